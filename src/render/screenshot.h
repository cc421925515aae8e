// Reads the current framebuffer back and writes it as a PNG (stb_image_write). Writes to a temporary
// file beside the target and renames it, so a failed or interrupted write never leaves half a PNG.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

namespace render {

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba; // top row first
};

Image readFramebuffer(int width, int height);
// Throws RenderError naming the path on failure.
void writePng(const Image& image, const std::filesystem::path& path);
// A fresh name screenshots/minecrappy-YYYYmmdd-HHMMSS[-N].png that does not exist yet.
std::filesystem::path nextScreenshotPath(const std::filesystem::path& folder);

} // namespace render
