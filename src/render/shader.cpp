#include "render/shader.h"

#include <fstream>
#include <sstream>
#include <string>

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

// Where `object`'s `status` (GL_COMPILE_STATUS of a shader, GL_LINK_STATUS of a program) is false: deletes it
// and throws RenderError(`what` + its info log). `getiv`, `getLog` and `destroy` are the shader's or the
// program's entry points.
template <class GetIv, class GetLog, class Destroy>
void throwUnlessOk(GLuint object, GLenum status, GetIv getiv, GetLog getLog, Destroy destroy, const std::string& what) {
    GLint ok = GL_FALSE;
    getiv(object, status, &ok);
    if (!ok) {
        char log[2048] = {};
        getLog(object, sizeof log, nullptr, log);
        destroy(object);
        throw RenderError(what + log);
    }
}

GLuint compile(GLenum type, const std::filesystem::path& path) {
    const std::string source = readFile(path);
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    throwUnlessOk(shader, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader,
                  "shader " + path.string() + " does not compile: ");
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
    throwUnlessOk(m_program, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram,
                  "shaders " + vertexFile.string() + " + " + fragmentFile.string() + " do not link: ");
}

ShaderProgram::~ShaderProgram() { glDeleteProgram(m_program); }

} // namespace render
