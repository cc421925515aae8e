// Reads the current framebuffer back and writes it as a PNG (stb_image_write). Writes to a temporary
// file beside the target and renames it, so a failed or interrupted write never leaves half a PNG.
#pragma once
#include <cstdint>
#include <filesystem>
#include <glm/vec2.hpp>
#include <vector>

namespace render {

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba; // top row first
};

Image readFramebuffer(int width, int height);

// A framebuffer object drawn into instead of the window or context's own (RGBA8 with depth and stencil), bound
// while it exists; the previous binding and viewport come back when it goes. For frames larger than the
// context: draw a tile, then readInto the whole image.
class OffscreenTarget {
public:
    explicit OffscreenTarget(glm::ivec2 size); // throws RenderError when GL cannot make it
    ~OffscreenTarget();
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;
    // Copies the bottom-left `size` pixels drawn into `image` (top row first) at `origin` (y down).
    void readInto(Image& image, glm::ivec2 origin, glm::ivec2 size) const;
    // The largest side the current context allows for both a renderbuffer and a viewport (16384 on llvmpipe):
    // no target, nor a tile drawn into one, may be larger.
    static int largestSide();

private:
    void release();
    unsigned m_fbo = 0, m_color = 0, m_depth = 0;
    int m_previous = 0;
    int m_viewport[4] = {0, 0, 0, 0};
};
// Throws RenderError naming the path on failure.
void writePng(const Image& image, const std::filesystem::path& path);
// A fresh name screenshots/minecrappy-YYYYmmdd-HHMMSS[-N].png that does not exist yet.
std::filesystem::path nextScreenshotPath(const std::filesystem::path& folder);

} // namespace render
