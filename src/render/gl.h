// The one way the render layer includes OpenGL: GLEW for every entry point, 3.3 core; and the one draw call
// the batch renderers share.
#pragma once
#include <GL/glew.h>

#include <vector>

namespace render {

// Uploads `vertices` into the array buffer `vbo` (GL_STREAM_DRAW, replacing what it held) and draws them all as
// `mode` with the vertex array `vao`, which is left unbound. The program and its uniforms are the caller's.
template <class Vertex>
void streamAndDraw(GLuint vao, GLuint vbo, const std::vector<Vertex>& vertices, GLenum mode) {
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)), vertices.data(),
                 GL_STREAM_DRAW);
    glDrawArrays(mode, 0, static_cast<GLsizei>(vertices.size()));
    glBindVertexArray(0);
}

} // namespace render
