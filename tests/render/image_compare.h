// Golden-image comparison for render tests: a tolerance on the mean difference and on the share of
// pixels that differ visibly, so rasteriser rounding passes and a missing face or wrong colour fails.
// On failure the actual image and a diff image (differences amplified) are written for a person to look at.
#pragma once
#include <filesystem>
#include <string>

#include "render/screenshot.h"

namespace testing_support {

struct CompareResult {
    bool ok = false;
    double meanAbsDiff = 0.0;   // per channel, 0..255
    double badPixelShare = 0.0; // pixels whose largest channel difference exceeds 24
    std::string message;
};

render::Image loadPng(const std::filesystem::path& path); // empty image if missing
// meanAbsDiff and badPixelShare of two images of one size (ok and message left unset); `diff`, if
// given, receives the differences amplified eight times.
CompareResult compareImages(const render::Image& actual, const render::Image& expected, render::Image* diff = nullptr);
// Compares with golden `name`.png; regenerates it instead when MINECRAPPY_UPDATE_GOLDENS=1.
CompareResult compareWithGolden(const render::Image& actual, const std::string& name);

} // namespace testing_support
