// A linked GLSL program built from two files under shaders/. Compile and link errors are thrown as
// RenderError with the file name and the driver's log, never printed and ignored.
#pragma once
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <string>

#include "render/gl.h"

namespace render {

class ShaderProgram {
public:
    ShaderProgram(const std::filesystem::path& vertexFile, const std::filesystem::path& fragmentFile);
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    void use() const { glUseProgram(m_program); }
    GLint uniform(const char* name) const { return glGetUniformLocation(m_program, name); }

private:
    GLuint m_program = 0;
};

} // namespace render
