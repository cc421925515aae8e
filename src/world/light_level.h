// A voxel's light: sunlight and block light, 0..kMaxLight each, in one byte (sunlight in the high four bits,
// block light in the low four). The one place that knows the layout: the light field, the padded light, the
// mesher's corner averages, the culled reference and the vertices' light words pack and unpack through it, so
// that a wider format (coloured block light) changes this file and what must store more, not shifts written out
// by hand. Arrays of light stay arrays of bytes (LightLevel::bits), which the SIMD code compares whole.
#pragma once
#include <cstdint>

#include "world/block.h"

namespace world {

struct LightLevel {
    static constexpr int kSunShift = 4;
    static constexpr std::uint8_t kSunBits = 0xF0, kBlockBits = 0x0F; // each channel's bits in the byte
    static_assert(kMaxLight == 15, "each channel is four bits");

    std::uint8_t bits = 0;

    static constexpr LightLevel of(int sun, int block) {
        return {static_cast<std::uint8_t>(static_cast<unsigned>(sun) << kSunShift | static_cast<unsigned>(block))};
    }
    constexpr int sun() const { return bits >> kSunShift; }
    constexpr int block() const { return bits & kBlockBits; }
    friend constexpr bool operator==(LightLevel, LightLevel) = default;
};

// Full sunlight, no block light: the open sky.
inline constexpr LightLevel kOpenSky = LightLevel::of(kMaxLight, 0);

} // namespace world
