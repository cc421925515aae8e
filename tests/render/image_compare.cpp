#include "image_compare.h"

#include <stb/stb_image.h>

#include <cmath>
#include <cstdlib>
#include <memory>

namespace testing_support {

render::Image loadPng(const std::filesystem::path& path) {
    render::Image img;
    int channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load(path.c_str(), &img.width, &img.height, &channels, 4),
                                                 stbi_image_free);
    if (!px) return {};
    img.rgba.assign(px.get(), px.get() + static_cast<std::size_t>(img.width) * img.height * 4);
    return img;
}

CompareResult compareImages(const render::Image& actual, const render::Image& expected, render::Image* diff) {
    if (diff) *diff = actual;
    double sum = 0.0;
    std::size_t bad = 0;
    const std::size_t pixels = static_cast<std::size_t>(actual.width) * actual.height;
    for (std::size_t p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(actual.rgba[p * 4 + c]) - int(expected.rgba[p * 4 + c]));
            sum += d;
            worst = std::max(worst, d);
            if (diff) diff->rgba[p * 4 + c] = static_cast<std::uint8_t>(std::min(255, d * 8));
        }
        if (diff) diff->rgba[p * 4 + 3] = 255;
        if (worst > 24) ++bad;
    }
    CompareResult r;
    r.meanAbsDiff = sum / (3.0 * static_cast<double>(pixels));
    r.badPixelShare = static_cast<double>(bad) / static_cast<double>(pixels);
    return r;
}

CompareResult compareWithGolden(const render::Image& actual, const std::string& name) {
    const std::filesystem::path golden = std::filesystem::path(MC_GOLDEN_DIR) / (name + ".png");
    const std::filesystem::path outDir = MC_RENDER_OUT;
    std::filesystem::create_directories(outDir);
    CompareResult r;
    if (const char* update = std::getenv("MINECRAPPY_UPDATE_GOLDENS"); update && std::string(update) == "1") {
        render::writePng(actual, golden);
        r.ok = true;
        r.message = "regenerated " + golden.string();
        return r;
    }
    const render::Image expected = loadPng(golden);
    render::writePng(actual, outDir / (name + ".actual.png"));
    if (expected.rgba.empty()) {
        r.message = "missing golden " + golden.string() + " (actual written to " + (outDir / name).string() +
                    ".actual.png; regenerate goldens with scripts/update-goldens.sh)";
        return r;
    }
    if (expected.width != actual.width || expected.height != actual.height) {
        r.message = "size differs from golden " + golden.string();
        return r;
    }
    render::Image diff;
    const CompareResult measured = compareImages(actual, expected, &diff);
    r.meanAbsDiff = measured.meanAbsDiff;
    r.badPixelShare = measured.badPixelShare;
    // Tolerances: llvmpipe on another CPU may round a few edge pixels differently; a wrong texture,
    // a missing face or a moved camera changes far more than this.
    r.ok = r.meanAbsDiff < 1.0 && r.badPixelShare < 0.005;
    if (!r.ok) {
        render::writePng(diff, outDir / (name + ".diff.png"));
        r.message = "differs from " + golden.string() + ": mean |diff| " + std::to_string(r.meanAbsDiff) +
                    ", visibly different pixels " + std::to_string(r.badPixelShare * 100.0) + "%; see " +
                    (outDir / name).string() + ".{actual,diff}.png";
    }
    return r;
}

} // namespace testing_support
