#include "render/screenshot.h"

#include "core/atomic_file.h"

#include <stb/stb_image_write.h>

#include <ctime>
#include <system_error>

#include "render/context.h"
#include "render/gl.h"

namespace render {

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
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    try {
        core::writeFileAtomically(path, [&](const std::filesystem::path& temp) {
            return stbi_write_png(temp.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4) != 0;
        });
    } catch (const std::runtime_error& e) {
        throw RenderError(std::string("cannot write PNG: ") + e.what());
    }
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
