// A voxel's light: sunlight and block light in three colour channels (red, green, blue), 0..kMaxLight each,
// in 16 bits: sunlight in the top four, then red, green and blue. The one place that knows the layout: the light
// field, the padded light, the mesher's corner averages, the culled reference and the vertices' light words pack
// and unpack through it. Arrays of light are arrays of LightLevel::bits, which the SIMD code compares whole.
#pragma once
#include <cstdint>

#include "world/block.h"

namespace world {

struct LightLevel {
    static constexpr int kSunShift = 12, kRedShift = 8, kGreenShift = 4, kBlueShift = 0;
    static constexpr std::uint16_t kSunBits = 0xF000, kColourBits = 0x0FFF; // sunlight's bits, block light's
    static_assert(kMaxLight == 15, "each channel is four bits");

    std::uint16_t bits = 0;

    static constexpr LightLevel of(int sun, int red, int green, int blue) {
        return {static_cast<std::uint16_t>(
            static_cast<unsigned>(sun) << kSunShift | static_cast<unsigned>(red) << kRedShift |
            static_cast<unsigned>(green) << kGreenShift | static_cast<unsigned>(blue) << kBlueShift)};
    }
    // White block light: every channel at `block`.
    static constexpr LightLevel of(int sun, int block) { return of(sun, block, block, block); }
    constexpr int sun() const { return bits >> kSunShift; }
    constexpr int red() const { return bits >> kRedShift & 15; }
    constexpr int green() const { return bits >> kGreenShift & 15; }
    constexpr int blue() const { return bits >> kBlueShift & 15; }
    // The brightest of the block light's channels.
    constexpr int block() const {
        const int r = red(), g = green(), b = blue();
        return r > g ? (r > b ? r : b) : (g > b ? g : b);
    }
    friend constexpr bool operator==(LightLevel, LightLevel) = default;
};

// Full sunlight, no block light: the open sky.
inline constexpr LightLevel kOpenSky = LightLevel::of(kMaxLight, 0);

} // namespace world
