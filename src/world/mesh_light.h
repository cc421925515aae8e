// Smooth light for the greedy mesher: the light words of a face's four corners, each the mean of the
// voxels around the corner that light can reach (docs/LIGHT.md, "Light in the mesh"). Included by
// mesher.cpp only, in an unnamed namespace like mesh_quads.h, so that faceLight inlines into the hot
// loop; the culled reference (mesh_culled.cpp) computes the same light voxel by voxel and must never use
// this file, so that tests can hold one against the other.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "world/block.h"
#include "world/light_level.h"
#include "world/mesh_quads.h"

namespace world {

namespace {

// A corner's mean of n voxels (1 to 4) rounded to the nearest, halves up, is (2 sum + n) / (2 n): here
// ((2 sum + n) * kReciprocal[n - 1]) >> 8 on four 16-bit lanes at once, exact for every sum of n levels up to
// kMaxLight (2 sum + n is at most 124; 43 / 256 stands for 1 / 6 below 131).
constexpr int kMaxCornerVoxels = 4;
constexpr std::uint64_t kReciprocal[kMaxCornerVoxels] = {128, 64, 43, 32};
static_assert([] {
    for (int n = 1; n <= kMaxCornerVoxels; ++n)
        for (int sum = 0; sum <= n * kMaxLight; ++sum)
            if ((2 * sum + n) / (2 * n) != static_cast<int>(((2 * sum + n) * kReciprocal[n - 1]) >> 8)) return false;
    return true;
}());
constexpr std::uint64_t kLaneOnes = 0x0001000100010001ull, kLaneLow = 0x00FF00FF00FF00FFull;

// Which voxels each corner averages besides the air-side one, per 3x3 solidity pattern: for corner
// k = cc + 2 * cb, bit 5k the one beside it along c, bit 5k + 1 the one beside it along b, bit 5k + 2 the
// diagonal one (when neither it nor both of those beside it are solid), and in bits 5k + 3 and 5k + 4 how
// many of the three are kept. The voxels kept are those that are not solid: light does not reach a corner
// through solid blocks.
constexpr std::array<std::uint32_t, 512> kCornerVoxels = [] {
    std::array<std::uint32_t, 512> t{};
    for (unsigned p = 0; p < 512; ++p) {
        std::uint32_t use = 0;
        for (int k = 0; k < 4; ++k) {
            const int sc = (k & 1) ? 2 : 0, sb = (k >> 1) ? 2 : 0; // (offset + 1) of the corner's side
            const bool sideC = (p >> (sc + 3) & 1u) != 0, sideB = (p >> (1 + 3 * sb) & 1u) != 0;
            const bool corner = (p >> (sc + 3 * sb) & 1u) != 0;
            const bool diagonal = !corner && !(sideB && sideC);
            const unsigned kept = unsigned{!sideC} + unsigned{!sideB} + unsigned{diagonal};
            use |= (unsigned{!sideC} | unsigned{!sideB} << 1 | unsigned{diagonal} << 2 | kept << 3) << (5 * k);
        }
        t[p] = use;
    }
    return t;
}();

// A light word spread for summing: its four nibbles (blue, green, red, sunlight from the low one up) in the four
// 16-bit lanes of a word, in two shift-and-mask steps.
[[gnu::always_inline]] inline std::uint64_t spreadLight(std::uint16_t level) {
    std::uint64_t x = level;
    x = (x | x << 24) & 0x000000FF000000FFull;    // bytes 0 and 1 to bits 0 and 32
    return (x | x << 12) & 0x000F000F000F000Full; // each byte's high nibble 16 bits up
}
// The inverse for four lanes of at most kMaxLight: back to a light word.
[[gnu::always_inline]] inline std::uint16_t packLanes(std::uint64_t lanes) {
    const std::uint64_t t = lanes | lanes >> 12;
    return static_cast<std::uint16_t>(t | t >> 24);
}

// Smooth light: the light words of a face's four corners (CornerLight), from the voxel on its air side (padded
// index q) and the 3x3 solidity pattern around it (kAoTable's). Each corner averages, channel by channel and
// rounded to the nearest level, the voxels that are not solid among q, the two beside the corner and the one
// diagonal to it (left out when both beside it are solid, as for occlusion): light does not reach a corner
// through solid blocks. The four channels are averaged at once, a 16-bit lane each.
template <int D>
[[gnu::always_inline]] inline CornerLight faceLight(const std::uint16_t* level, int q, unsigned pattern) {
    constexpr int sb = kStride[kDirs[D].b], sc = kStride[kDirs[D].c];
    // The nine voxels around the corners, all read, then kept or not by mask: no branch on the pattern.
    const std::uint64_t mid = spreadLight(level[q]);
    const std::uint64_t side[2][2] = {{spreadLight(level[q - sc]), spreadLight(level[q + sc])},  // along c
                                      {spreadLight(level[q - sb]), spreadLight(level[q + sb])}}; // along b
    const std::uint64_t diagonal[4] = {spreadLight(level[q - sc - sb]), spreadLight(level[q + sc - sb]),
                                       spreadLight(level[q - sc + sb]), spreadLight(level[q + sc + sb])};
    const std::uint32_t use = kCornerVoxels[pattern];
    CornerLight packed = 0;
    for (int k = 0; k < 4; ++k) {
        const std::uint32_t u = use >> (5 * k);
        const auto keep = [&](int bit) { return 0ull - (u >> bit & 1u); };
        const std::uint64_t sum =
            mid + (side[0][k & 1] & keep(0)) + (side[1][k >> 1] & keep(1)) + (diagonal[k] & keep(2));
        const unsigned n = (u >> 3 & 3u) + 1; // the voxels averaged
        const std::uint64_t mean = ((2 * sum + n * kLaneOnes) * kReciprocal[n - 1] >> 8) & kLaneLow;
        packed |= CornerLight{packLanes(mean)} << (16 * k);
    }
    return packed;
}

} // namespace

} // namespace world
