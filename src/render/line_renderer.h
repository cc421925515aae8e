// Thin coloured lines in world space (camera-relative): the outline of the targeted block. One dynamic buffer,
// refilled per batch.
#pragma once
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "render/gl.h"
#include "render/shader.h"

namespace render {

// The vertex of everything drawn with shaders/line.*: a camera-relative position and a colour.
struct ColouredVertex {
    glm::vec3 position;
    glm::vec4 color;
};
// Describes ColouredVertex attributes (0: position, 1: colour) for the bound VAO and array buffer.
void describeColouredVertices();

class LineRenderer {
public:
    explicit LineRenderer(const std::filesystem::path& dataDir);
    ~LineRenderer();
    LineRenderer(const LineRenderer&) = delete;
    LineRenderer& operator=(const LineRenderer&) = delete;

    // The 12 edges of a box, points relative to the camera.
    void addBox(const glm::vec3& min, const glm::vec3& max, const glm::vec4& color);
    void addSegment(const glm::vec3& a, const glm::vec3& b, const glm::vec4& color);
    // Draws and clears everything added since the last flush.
    // tint: the light the lines are seen in, by colour (1: their own colours).
    void flush(const glm::mat4& viewProjection, const glm::vec3& tint = glm::vec3(1.0f));

private:
    ShaderProgram m_shader;
    using Vertex = ColouredVertex;
    GLint m_uViewProj, m_uTint;
    GLuint m_vao = 0, m_vbo = 0;
    std::vector<Vertex> m_points;
};

} // namespace render
