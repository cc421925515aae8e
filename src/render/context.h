// The places frames go: a window, or off-screen memory through OSMesa or EGL. Renderers draw into whichever
// is current and never know which. The off-screen backends implement RenderContext (offscreen.cpp) and own
// their GL context for their whole lifetime; the window is the platform layer's (platform/glfw_window.h),
// which render never includes: the window runner loads GL for its context (gl_loader.h) and drives it.
#pragma once
#include <glm/vec2.hpp>
#include <stdexcept>
#include <string>

namespace render {

// A failure to set up or use the renderer: no context, a missing shader or asset. Exit code 1.
class RenderError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class RenderContext {
public:
    virtual ~RenderContext() = default;
    virtual glm::ivec2 framebufferSize() const = 0;
    // Finishes the frame: swaps buffers in a window; off-screen, waits until every frame issued is drawn,
    // so the picture can be read back.
    virtual void present() = 0;
    // Hands the frame on without reading it back and keeps at most one frame in flight: off-screen it
    // returns once the frame before this one is drawn, so the caller prepares the next frame while
    // this one is rasterised (docs/ENGINE.md, "One frame in flight"). A window swaps, as present().
    virtual void submit() { present(); }
};

} // namespace render
