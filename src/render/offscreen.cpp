#include "render/offscreen.h"

#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/gl.h"
#include "render/gl_loader.h"
#include "render/screenshot.h"

namespace render {

namespace {

std::atomic<const char*> g_current{""};

void checkSize(int width, int height) {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
        throw RenderError("off-screen size " + std::to_string(width) + "x" + std::to_string(height) +
                          " is out of range (1..16384)");
    }
}

// A library opened once for the process (the GL driver must outlive every context).
void* openLibrary(const char* name, std::string& why) {
    void* handle = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* error = dlerror();
        why = error ? error : (std::string(name) + ": cannot be loaded");
    }
    return handle;
}

template <typename F>
F symbol(void* library, const char* name) {
    return reinterpret_cast<F>(dlsym(library, name));
}

// ---- Where off-screen frames are drawn --------------------------------------------------------------------
// Both backends draw into a framebuffer object of the context's size instead of the context's own buffer.
// Under llvmpipe a flush of OSMesa's own buffer (the caller's memory) waits until the frame is rasterised,
// while a flush of a framebuffer object only hands the frame to llvmpipe's rasterising threads: measured,
// glFlush after 60 screen-sized blended quads took 99-125 ms on OSMesa's buffer and 0.2-5 ms on a
// framebuffer object, whose frame then finished while the caller's thread went on. submit() uses that to
// keep one frame in flight (docs/ENGINE.md, "One frame in flight"). readFramebuffer reads the bound
// framebuffer, which is this one.
class FrameTarget {
public:
    // The context must be current, and stay current until the FrameTarget is destroyed.
    FrameTarget(int width, int height) : m_buffer({width, height}) {}
    ~FrameTarget() { forget(); }
    FrameTarget(const FrameTarget&) = delete;
    FrameTarget& operator=(const FrameTarget&) = delete;

    // Waits until every frame issued so far is drawn.
    void finish() {
        glFinish();
        forget();
    }
    // Hands the frame just issued to the renderer and waits only for the one before it.
    void submit() {
        GLsync frame = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        glFlush();
        if (m_inFlight) {
            GLenum r = GL_TIMEOUT_EXPIRED;
            while (r == GL_TIMEOUT_EXPIRED) r = glClientWaitSync(m_inFlight, 0, 1'000'000'000); // 1 s a try
            forget();
            if (r == GL_WAIT_FAILED) glFinish();
        }
        m_inFlight = frame;
        if (!m_inFlight) glFinish(); // no fence: leave nothing in flight to wait for later
    }

private:
    void forget() {
        if (m_inFlight) glDeleteSync(m_inFlight);
        m_inFlight = nullptr;
    }
    OffscreenTarget m_buffer;
    GLsync m_inFlight = nullptr; // the fence after the frame submitted last, until it is waited for
};

// ---- OSMesa ---------------------------------------------------------------------------------------------
// The few OSMesa values used (GL/osmesa.h, which needs the library's link line, is not included).
constexpr int kOsMesaRgba = 0x1908, kOsMesaFormat = 0x22, kOsMesaDepthBits = 0x30, kOsMesaStencilBits = 0x31,
              kOsMesaProfile = 0x33, kOsMesaCoreProfile = 0x34, kOsMesaMajor = 0x36, kOsMesaMinor = 0x37;

struct OsMesaApi {
    void* (*createContextAttribs)(const int*, void*) = nullptr;
    GLboolean (*makeCurrent)(void*, void*, GLenum, GLsizei, GLsizei) = nullptr;
    void (*destroyContext)(void*) = nullptr;
    void* (*getCurrentContext)() = nullptr;
    void (*(*getProcAddress)(const char*))() = nullptr;
};

const OsMesaApi* osMesa(std::string& why) {
    static OsMesaApi api;
    static std::string error;
    static const bool loaded = [] {
        void* lib = openLibrary("libOSMesa.so.8", error);
        if (!lib) return false;
        api.createContextAttribs = symbol<decltype(api.createContextAttribs)>(lib, "OSMesaCreateContextAttribs");
        api.makeCurrent = symbol<decltype(api.makeCurrent)>(lib, "OSMesaMakeCurrent");
        api.destroyContext = symbol<decltype(api.destroyContext)>(lib, "OSMesaDestroyContext");
        api.getCurrentContext = symbol<decltype(api.getCurrentContext)>(lib, "OSMesaGetCurrentContext");
        api.getProcAddress = symbol<decltype(api.getProcAddress)>(lib, "OSMesaGetProcAddress");
        if (!api.createContextAttribs || !api.makeCurrent || !api.destroyContext || !api.getCurrentContext ||
            !api.getProcAddress) {
            error = "libOSMesa.so.8 lacks OSMesaCreateContextAttribs (Mesa older than 12?)";
            return false;
        }
        return true;
    }();
    why = error;
    return loaded ? &api : nullptr;
}

class OsMesaContext final : public RenderContext {
public:
    OsMesaContext(const OsMesaApi& api, int width, int height) : m_api(api), m_width(width), m_height(height) {
        const int attribs[] = {kOsMesaFormat,
                               kOsMesaRgba,
                               kOsMesaDepthBits, // the context's own buffer is not drawn into (FrameTarget)
                               0,
                               kOsMesaStencilBits,
                               0,
                               kOsMesaProfile,
                               kOsMesaCoreProfile,
                               kOsMesaMajor,
                               3,
                               kOsMesaMinor,
                               3,
                               0};
        m_context = m_api.createContextAttribs(attribs, nullptr);
        if (!m_context) throw RenderError("OSMesa could not create an OpenGL 3.3 core context");
        m_buffer.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
        if (!m_api.makeCurrent(m_context, m_buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
            m_api.destroyContext(m_context);
            throw RenderError("OSMesa could not make its context current");
        }
        const OsMesaApi* a = &m_api;
        const std::string error = loadGl(GlBackend::OsMesa, [a](const char* name) {
            return a->getCurrentContext() ? a->getProcAddress(name) : nullptr;
        });
        if (!error.empty()) {
            m_api.destroyContext(m_context);
            throw RenderError("OSMesa: " + error);
        }
        try {
            m_target.emplace(width, height);
        } catch (...) {
            m_api.destroyContext(m_context);
            throw;
        }
    }
    ~OsMesaContext() override {
        m_target.reset(); // while the context is current
        m_api.destroyContext(m_context);
    }
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;
    glm::ivec2 framebufferSize() const override { return {m_width, m_height}; }
    void present() override { m_target->finish(); }
    void submit() override { m_target->submit(); }

private:
    const OsMesaApi& m_api;
    void* m_context = nullptr;
    int m_width, m_height;
    std::vector<std::uint8_t> m_buffer; // OSMesa's own buffer: made current, never drawn into
    std::optional<FrameTarget> m_target;
};

// ---- EGL ------------------------------------------------------------------------------------------------
struct EglApi {
    decltype(&eglGetProcAddress) getProcAddress = nullptr;
    decltype(&eglInitialize) initialize = nullptr;
    decltype(&eglTerminate) terminate = nullptr;
    decltype(&eglBindAPI) bindApi = nullptr;
    decltype(&eglChooseConfig) chooseConfig = nullptr;
    decltype(&eglCreatePbufferSurface) createPbufferSurface = nullptr;
    decltype(&eglCreateContext) createContext = nullptr;
    decltype(&eglMakeCurrent) makeCurrent = nullptr;
    decltype(&eglDestroyContext) destroyContext = nullptr;
    decltype(&eglDestroySurface) destroySurface = nullptr;
    decltype(&eglGetError) getError = nullptr;
    decltype(&eglQueryString) queryString = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
};

const EglApi* egl(std::string& why) {
    static EglApi api;
    static std::string error;
    static const bool loaded = [] {
        void* lib = openLibrary("libEGL.so.1", error);
        if (!lib) return false;
        api.getProcAddress = symbol<decltype(api.getProcAddress)>(lib, "eglGetProcAddress");
        api.initialize = symbol<decltype(api.initialize)>(lib, "eglInitialize");
        api.terminate = symbol<decltype(api.terminate)>(lib, "eglTerminate");
        api.bindApi = symbol<decltype(api.bindApi)>(lib, "eglBindAPI");
        api.chooseConfig = symbol<decltype(api.chooseConfig)>(lib, "eglChooseConfig");
        api.createPbufferSurface = symbol<decltype(api.createPbufferSurface)>(lib, "eglCreatePbufferSurface");
        api.createContext = symbol<decltype(api.createContext)>(lib, "eglCreateContext");
        api.makeCurrent = symbol<decltype(api.makeCurrent)>(lib, "eglMakeCurrent");
        api.destroyContext = symbol<decltype(api.destroyContext)>(lib, "eglDestroyContext");
        api.destroySurface = symbol<decltype(api.destroySurface)>(lib, "eglDestroySurface");
        api.getError = symbol<decltype(api.getError)>(lib, "eglGetError");
        api.queryString = symbol<decltype(api.queryString)>(lib, "eglQueryString");
        if (!api.getProcAddress || !api.initialize || !api.bindApi || !api.chooseConfig || !api.createContext ||
            !api.makeCurrent || !api.createPbufferSurface || !api.destroyContext || !api.destroySurface ||
            !api.terminate || !api.getError || !api.queryString) {
            error = "libEGL.so.1 lacks the EGL 1.4 functions";
            return false;
        }
        api.getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(api.getProcAddress("eglGetPlatformDisplayEXT"));
        if (!api.getPlatformDisplay) {
            error = "EGL has no eglGetPlatformDisplayEXT (EGL_EXT_platform_base)";
            return false;
        }
        return true;
    }();
    why = error;
    return loaded ? &api : nullptr;
}

std::string eglErrorText(const EglApi& api, const char* what) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(api.getError()));
    return std::string("EGL: ") + what + " (error " + code + ")";
}

class EglContext final : public RenderContext {
public:
    EglContext(const EglApi& api, int width, int height) : m_api(api), m_width(width), m_height(height) {
        m_display = m_api.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (m_display == EGL_NO_DISPLAY || !m_api.initialize(m_display, &major, &minor))
            throw RenderError(eglErrorText(m_api, "no surfaceless display (EGL_MESA_platform_surfaceless)"));
        try {
            if (!m_api.bindApi(EGL_OPENGL_API)) throw RenderError(eglErrorText(m_api, "no desktop OpenGL API"));
            const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                            EGL_PBUFFER_BIT,
                                            EGL_RENDERABLE_TYPE,
                                            EGL_OPENGL_BIT,
                                            EGL_RED_SIZE,
                                            8,
                                            EGL_GREEN_SIZE,
                                            8,
                                            EGL_BLUE_SIZE,
                                            8,
                                            EGL_ALPHA_SIZE,
                                            8,
                                            EGL_DEPTH_SIZE,
                                            24,
                                            EGL_STENCIL_SIZE,
                                            8,
                                            EGL_NONE};
            EGLConfig config = nullptr;
            EGLint count = 0;
            if (!m_api.chooseConfig(m_display, configAttribs, &config, 1, &count) || count == 0)
                throw RenderError(eglErrorText(m_api, "no RGBA8 pbuffer config with depth and stencil"));
            const EGLint surfaceAttribs[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
            m_surface = m_api.createPbufferSurface(m_display, config, surfaceAttribs);
            if (m_surface == EGL_NO_SURFACE) throw RenderError(eglErrorText(m_api, "no pbuffer of that size"));
            const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                             3,
                                             EGL_CONTEXT_MINOR_VERSION,
                                             3,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                             EGL_NONE};
            m_context = m_api.createContext(m_display, config, EGL_NO_CONTEXT, contextAttribs);
            if (m_context == EGL_NO_CONTEXT) throw RenderError(eglErrorText(m_api, "no OpenGL 3.3 core context"));
            if (!m_api.makeCurrent(m_display, m_surface, m_surface, m_context))
                throw RenderError(eglErrorText(m_api, "could not make the context current"));
            const EglApi* a = &m_api;
            const std::string error = loadGl(GlBackend::Egl, [a](const char* name) { return a->getProcAddress(name); });
            if (!error.empty()) throw RenderError("EGL: " + error);
            m_target.emplace(width, height);
        } catch (...) {
            release();
            throw;
        }
    }
    ~EglContext() override { release(); }
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;
    glm::ivec2 framebufferSize() const override { return {m_width, m_height}; }
    void present() override { m_target->finish(); }
    void submit() override { m_target->submit(); }

private:
    void release() {
        m_target.reset(); // while the context is current
        m_api.makeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (m_context != EGL_NO_CONTEXT) m_api.destroyContext(m_display, m_context);
        if (m_surface != EGL_NO_SURFACE) m_api.destroySurface(m_display, m_surface);
        m_api.terminate(m_display);
        m_context = EGL_NO_CONTEXT;
        m_surface = EGL_NO_SURFACE;
    }
    const EglApi& m_api;
    EGLDisplay m_display = EGL_NO_DISPLAY;
    EGLSurface m_surface = EGL_NO_SURFACE;
    EGLContext m_context = EGL_NO_CONTEXT;
    int m_width, m_height;
    std::optional<FrameTarget> m_target;
};

std::unique_ptr<RenderContext> tryOsMesa(int width, int height) {
    std::string why;
    const OsMesaApi* api = osMesa(why);
    if (!api) throw RenderError("OSMesa: " + why);
    auto context = std::make_unique<OsMesaContext>(*api, width, height);
    g_current = "osmesa";
    return context;
}

std::unique_ptr<RenderContext> tryEgl(int width, int height) {
    std::string why;
    const EglApi* api = egl(why);
    if (!api) throw RenderError("EGL: " + why);
    auto context = std::make_unique<EglContext>(*api, width, height);
    g_current = "egl";
    return context;
}

} // namespace

// In the order of OffscreenBackend.
constexpr std::array<std::string_view, 3> kBackendNames{"auto", "osmesa", "egl"};

std::optional<OffscreenBackend> offscreenBackendFromName(std::string_view name) {
    const auto it = std::find(kBackendNames.begin(), kBackendNames.end(), name);
    if (it == kBackendNames.end()) return std::nullopt;
    return static_cast<OffscreenBackend>(it - kBackendNames.begin());
}

std::string_view offscreenBackendName(OffscreenBackend backend) {
    return kBackendNames.at(static_cast<std::size_t>(backend));
}

std::unique_ptr<RenderContext> makeOffscreenContext(OffscreenBackend backend, int width, int height) {
    checkSize(width, height);
    switch (backend) {
    case OffscreenBackend::OsMesa:
        return tryOsMesa(width, height);
    case OffscreenBackend::Egl:
        return tryEgl(width, height);
    case OffscreenBackend::Auto:
        break;
    }
    std::string osmesaWhy;
    try {
        return tryOsMesa(width, height);
    } catch (const RenderError& e) {
        osmesaWhy = e.what();
    }
    try {
        return tryEgl(width, height);
    } catch (const RenderError& e) {
        throw RenderError("no off-screen OpenGL: " + osmesaWhy + "; " + e.what() +
                          ". Install either: on Debian and Ubuntu libosmesa6 or libegl-mesa0, on Fedora "
                          "mesa-libOSMesa or mesa-libEGL, on Arch mesa (EGL)");
    }
}

std::string_view currentOffscreenBackend() { return g_current.load(); }

} // namespace render
