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

// kRoundedMean[n - 1][sum]: sum / n rounded to the nearest, halves up ((2 * sum + n) / (2 * n)), for the
// up to four voxels (n) a corner averages, each at most kMaxLight: a look-up instead of two divisions.
constexpr int kMaxCornerVoxels = 4;
constexpr auto kRoundedMean = [] {
    std::array<std::array<std::uint8_t, kMaxCornerVoxels * kMaxLight + 1>, kMaxCornerVoxels> t{};
    for (int n = 1; n <= kMaxCornerVoxels; ++n)
        for (int sum = 0; sum <= kMaxCornerVoxels * kMaxLight; ++sum)
            t[static_cast<std::size_t>(n - 1)][static_cast<std::size_t>(sum)] =
                static_cast<std::uint8_t>((2 * sum + n) / (2 * n));
    return t;
}();

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

// A light word spread for summing: sunlight, red, green and blue in 16-bit lanes from the low one up.
inline std::uint64_t spreadLight(std::uint16_t level) {
    const LightLevel l{level};
    return static_cast<std::uint64_t>(l.sun()) | static_cast<std::uint64_t>(l.red()) << 16 |
           static_cast<std::uint64_t>(l.green()) << 32 | static_cast<std::uint64_t>(l.blue()) << 48;
}

// Smooth light: the light words of a face's four corners (CornerLight), from the voxel on its air side (padded
// index q) and the 3x3 solidity pattern around it (kAoTable's). Each corner averages, channel by channel and
// rounded to the nearest level, the voxels that are not solid among q, the two beside the corner and the one
// diagonal to it (left out when both beside it are solid, as for occlusion): light does not reach a corner
// through solid blocks.
template <int D>
CornerLight faceLight(const std::uint16_t* level, int q, unsigned pattern) {
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
        const auto& mean = kRoundedMean[u >> 3 & 3u];
        const auto lane = [&](int i) { return mean[sum >> (16 * i) & 0xFFFFu]; };
        packed |= CornerLight{LightLevel::of(lane(0), lane(1), lane(2), lane(3)).bits} << (16 * k);
    }
    return packed;
}

} // namespace

} // namespace world
