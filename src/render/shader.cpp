#include "render/shader.h"

#include <fstream>
#include <sstream>

#include "render/context.h"

namespace render {

namespace {
std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw RenderError("missing shader " + path.string());
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

GLuint compile(GLenum type, const std::filesystem::path& path) {
    const std::string source = readFile(path);
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw RenderError("shader " + path.string() + " does not compile: " + log);
    }
    return shader;
}
} // namespace

ShaderProgram::ShaderProgram(const std::filesystem::path& vertexFile, const std::filesystem::path& fragmentFile) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertexFile);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragmentFile);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    m_program = glCreateProgram();
    glAttachShader(m_program, vs);
    glAttachShader(m_program, fs);
    glLinkProgram(m_program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(m_program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(m_program, sizeof log, nullptr, log);
        glDeleteProgram(m_program);
        throw RenderError("shaders " + vertexFile.string() + " + " + fragmentFile.string() + " do not link: " + log);
    }
}

ShaderProgram::~ShaderProgram() { glDeleteProgram(m_program); }

} // namespace render
