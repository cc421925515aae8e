#include "render/gl_loader.h"

#include "render/gl.h"
// glew.h undefines GLAPI at its end; the forwarders below are declared with it.
#ifndef GLAPI
#define GLAPI extern
#endif
#include <dlfcn.h>

#include <atomic>
#include <cstdint>
#include <string_view>
#include <utility>

namespace {

using ProcFn = render::ProcFn;
using GlxLookupFn = ProcFn (*)(const GLubyte*);

std::atomic<render::GlBackend> g_backend{render::GlBackend::Glx};
// Draw calls through the forwarders below: every draw of the project's own renderers (render thread only).
std::uint64_t g_drawCalls = 0;
constexpr bool isDrawCall(std::string_view name) { return name == "glDrawArrays" || name == "glDrawElements"; }
render::ProcLookup g_offscreenLookup; // set by loadGl for OSMesa and EGL; used on the thread that draws

ProcFn realGlxLookup(const GLubyte* name) {
    static const auto real = reinterpret_cast<GlxLookupFn>(dlsym(RTLD_NEXT, "glXGetProcAddressARB"));
    return real ? real(name) : nullptr;
}

ProcFn lookup(const char* name) {
    if (g_backend.load() != render::GlBackend::Glx) {
        // No GLX under an off-screen context: glewInit then stops before glxewInit asks GLX for a display
        // (under EGL, glvnd's GLX would answer from EGL's thread state and crash; seen with Mesa 22.3).
        if (std::string_view(name).substr(0, 3) == "glX" || !g_offscreenLookup) return nullptr;
        return g_offscreenLookup(name);
    }
    return realGlxLookup(reinterpret_cast<const GLubyte*>(name));
}

// The GL 1.0/1.1 functions that the renderers and Dear ImGui's backend call.
#define MC_GL11_FUNCTIONS(X)                                                                                           \
    X(void, glBindTexture, (GLenum a, GLuint b), (a, b))                                                               \
    X(void, glBlendFunc, (GLenum a, GLenum b), (a, b))                                                                 \
    X(void, glClear, (GLbitfield a), (a))                                                                              \
    X(void, glClearColor, (GLfloat a, GLfloat b, GLfloat c, GLfloat d), (a, b, c, d))                                  \
    X(void, glClearDepth, (GLclampd a), (a))                                                                           \
    X(void, glColorMask, (GLboolean a, GLboolean b, GLboolean c, GLboolean d), (a, b, c, d))                           \
    X(void, glCullFace, (GLenum a), (a))                                                                               \
    X(void, glDeleteTextures, (GLsizei a, const GLuint* b), (a, b))                                                    \
    X(void, glDepthFunc, (GLenum a), (a))                                                                              \
    X(void, glDepthMask, (GLboolean a), (a))                                                                           \
    X(void, glDisable, (GLenum a), (a))                                                                                \
    X(void, glDrawArrays, (GLenum a, GLint b, GLsizei c), (a, b, c))                                                   \
    X(void, glDrawBuffer, (GLenum a), (a))                                                                             \
    X(void, glDrawElements, (GLenum a, GLsizei b, GLenum c, const void* d), (a, b, c, d))                              \
    X(void, glEnable, (GLenum a), (a))                                                                                 \
    X(void, glFinish, (void), ())                                                                                      \
    X(void, glFlush, (void), ())                                                                                       \
    X(void, glFrontFace, (GLenum a), (a))                                                                              \
    X(void, glGenTextures, (GLsizei a, GLuint * b), (a, b))                                                            \
    X(void, glGetBooleanv, (GLenum a, GLboolean * b), (a, b))                                                          \
    X(GLenum, glGetError, (void), ())                                                                                  \
    X(void, glGetFloatv, (GLenum a, GLfloat * b), (a, b))                                                              \
    X(void, glGetIntegerv, (GLenum a, GLint * b), (a, b))                                                              \
    X(const GLubyte*, glGetString, (GLenum a), (a))                                                                    \
    X(void, glHint, (GLenum a, GLenum b), (a, b))                                                                      \
    X(GLboolean, glIsEnabled, (GLenum a), (a))                                                                         \
    X(void, glLineWidth, (GLfloat a), (a))                                                                             \
    X(void, glPixelStorei, (GLenum a, GLint b), (a, b))                                                                \
    X(void, glPolygonMode, (GLenum a, GLenum b), (a, b))                                                               \
    X(void, glPolygonOffset, (GLfloat a, GLfloat b), (a, b))                                                           \
    X(void, glReadBuffer, (GLenum a), (a))                                                                             \
    X(void, glReadPixels, (GLint a, GLint b, GLsizei c, GLsizei d, GLenum e, GLenum f, void* g),                       \
      (a, b, c, d, e, f, g))                                                                                           \
    X(void, glScissor, (GLint a, GLint b, GLsizei c, GLsizei d), (a, b, c, d))                                         \
    X(void, glTexImage2D,                                                                                              \
      (GLenum a, GLint b, GLint c, GLsizei d, GLsizei e, GLint f, GLenum g, GLenum h, const void* i),                  \
      (a, b, c, d, e, f, g, h, i))                                                                                     \
    X(void, glTexParameteri, (GLenum a, GLenum b, GLint c), (a, b, c))                                                 \
    X(void, glTexSubImage2D,                                                                                           \
      (GLenum a, GLint b, GLint c, GLint d, GLsizei e, GLsizei f, GLenum g, GLenum h, const void* i),                  \
      (a, b, c, d, e, f, g, h, i))                                                                                     \
    X(void, glViewport, (GLint a, GLint b, GLsizei c, GLsizei d), (a, b, c, d))

// NOLINTNEXTLINE(bugprone-macro-parentheses): the arguments are a type and a parameter list
#define MC_DECLARE_POINTER(ret, name, params, args) ret(*p_##name) params = nullptr;
MC_GL11_FUNCTIONS(MC_DECLARE_POINTER)
#undef MC_DECLARE_POINTER

bool bindGl11() {
    bool ok = true;
#define MC_BIND(ret, name, params, args)                                                                               \
    p_##name = reinterpret_cast<ret(*) params>(lookup(#name)); /* NOLINT(bugprone-macro-parentheses) */                \
    ok = ok && p_##name != nullptr;
    MC_GL11_FUNCTIONS(MC_BIND)
#undef MC_BIND
    return ok;
}

} // namespace

extern "C" {

// Interposes the GLX lookup that GLEW calls (see gl_loader.h).
ProcFn glXGetProcAddressARB(const GLubyte* name) { return lookup(reinterpret_cast<const char*>(name)); }

#define MC_FORWARD(ret, name, params, args)                                                                            \
    GLAPI ret name params {                                                                                            \
        if constexpr (isDrawCall(#name)) ++g_drawCalls;                                                                \
        return p_##name args;                                                                                          \
    }
MC_GL11_FUNCTIONS(MC_FORWARD)
#undef MC_FORWARD

} // extern "C"

namespace render {

std::uint64_t drawCallsIssued() { return g_drawCalls; }
void countDrawCalls(std::uint64_t n) { g_drawCalls += n; }

std::string loadGl(GlBackend backend, ProcLookup lookup) {
    g_offscreenLookup = std::move(lookup);
    g_backend = backend;
    if (!bindGl11()) return "the current context does not provide the OpenGL 1.1 entry points";
    glewExperimental = GL_TRUE;
    (void)glewInit(); // its return code reflects GLX, not whether the core functions loaded
    if (!GLEW_VERSION_3_3) {
        const GLubyte* version = glGetString(GL_VERSION);
        return std::string("OpenGL 3.3 core is required; this context offers ") +
               (version ? reinterpret_cast<const char*>(version) : "nothing usable");
    }
    return {};
}

} // namespace render
