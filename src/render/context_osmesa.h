// Off-screen rendering through OSMesa (Mesa's llvmpipe on the CPU): a 3.3 core context drawing into a
// buffer in memory. Needs no display, so every feature can run in tests and scripts.
#pragma once
#include <cstdint>
#include <vector>

#include "render/context.h"

struct osmesa_context;

namespace render {

class OsMesaContext final : public RenderContext {
public:
    OsMesaContext(int width, int height); // throws RenderError
    ~OsMesaContext() override;
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;

    glm::ivec2 framebufferSize() const override { return {m_width, m_height}; }
    void present() override;

private:
    osmesa_context* m_context = nullptr;
    int m_width, m_height;
    std::vector<std::uint8_t> m_buffer;
};

} // namespace render
