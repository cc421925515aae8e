#include "render/context_osmesa.h"

#include "render/gl.h"
#include "render/gl_loader.h"
#ifndef GLAPI
#define GLAPI extern
#endif
#include <GL/osmesa.h>

namespace render {

OsMesaContext::OsMesaContext(int width, int height) : m_width(width), m_height(height) {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
        throw RenderError("off-screen size " + std::to_string(width) + "x" + std::to_string(height) +
                          " is out of range (1..16384)");
    }
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_STENCIL_BITS,
                           8,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    m_context = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!m_context) throw RenderError("OSMesa could not create an OpenGL 3.3 core context");
    m_buffer.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    if (!OSMesaMakeCurrent(m_context, m_buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
        OSMesaDestroyContext(m_context);
        throw RenderError("OSMesa could not make its context current");
    }
    const std::string error = loadGl(GlBackend::OsMesa);
    if (!error.empty()) {
        OSMesaDestroyContext(m_context);
        throw RenderError("OSMesa: " + error);
    }
}

OsMesaContext::~OsMesaContext() {
    if (m_context) OSMesaDestroyContext(m_context);
}

void OsMesaContext::present() { glFinish(); }

} // namespace render
