#include "render/screenshot.h"

#include "core/atomic_file.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <ctime>
#include <string>
#include <system_error>

#include "render/context.h"
#include "render/gl.h"

namespace render {

OffscreenTarget::OffscreenTarget(glm::ivec2 size) {
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &m_previous);
    glGetIntegerv(GL_VIEWPORT, m_viewport);
    glGenFramebuffers(1, &m_fbo);
    glGenRenderbuffers(1, &m_color);
    glGenRenderbuffers(1, &m_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, m_color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, size.x, size.y);
    glBindRenderbuffer(GL_RENDERBUFFER, m_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, size.x, size.y);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m_color);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, m_depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        release();
        throw RenderError("cannot make an off-screen buffer of " + std::to_string(size.x) + "x" +
                          std::to_string(size.y) + " pixels");
    }
}

OffscreenTarget::~OffscreenTarget() { release(); }

int OffscreenTarget::largestSide() {
    GLint maxRenderbuffer = 0, maxViewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    return std::min(
        {static_cast<int>(maxRenderbuffer), static_cast<int>(maxViewport[0]), static_cast<int>(maxViewport[1])});
}

void OffscreenTarget::release() {
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(m_previous));
    glViewport(m_viewport[0], m_viewport[1], m_viewport[2], m_viewport[3]);
    if (m_fbo) glDeleteFramebuffers(1, &m_fbo);
    if (m_color) glDeleteRenderbuffers(1, &m_color);
    if (m_depth) glDeleteRenderbuffers(1, &m_depth);
    m_fbo = m_color = m_depth = 0;
}

void OffscreenTarget::readInto(Image& image, glm::ivec2 origin, glm::ivec2 size) const {
    std::vector<std::uint8_t> rows(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    const std::size_t rowBytes = static_cast<std::size_t>(size.x) * 4;
    for (int y = 0; y < size.y; ++y) { // GL's rows start at the bottom
        const std::uint8_t* from = rows.data() + static_cast<std::size_t>(size.y - 1 - y) * rowBytes;
        std::uint8_t* to =
            image.rgba.data() + (static_cast<std::size_t>(origin.y + y) * static_cast<std::size_t>(image.width) +
                                 static_cast<std::size_t>(origin.x)) *
                                    4;
        std::copy(from, from + rowBytes, to);
        for (std::size_t i = 3; i < rowBytes; i += 4) to[i] = 255; // the PNG shows the frame, opaque
    }
}

Image readFramebuffer(int width, int height) {
    Image img;
    img.width = width;
    img.height = height;
    img.rgba.resize(static_cast<std::size_t>(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    // GL's rows start at the bottom; PNG's at the top. Alpha is forced opaque: the PNG shows the frame.
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height / 2; ++y) {
        std::swap_ranges(img.rgba.begin() + static_cast<std::ptrdiff_t>(y * row),
                         img.rgba.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                         img.rgba.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
    }
    for (std::size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
    return img;
}

void writePng(const Image& image, const std::filesystem::path& path) {
    // Encoded in memory first: stb's file writer ignores fwrite's errors, so a full disk made a short PNG.
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    if (stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0)
        throw RenderError("cannot encode the PNG for '" + path.string() + "'");
    core::writeOutput(path, bytes); // core::OutputError names the path and the system's reason
}

std::filesystem::path nextScreenshotPath(const std::filesystem::path& folder) {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    localtime_r(&now, &tm);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
    std::filesystem::path p = folder / (std::string("minecrappy-") + stamp + ".png");
    for (int n = 2; std::filesystem::exists(p); ++n) {
        p = folder / (std::string("minecrappy-") + stamp + "-" + std::to_string(n) + ".png");
    }
    return p;
}

} // namespace render
