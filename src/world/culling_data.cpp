// A chunk's culling data (culling_data.h). Face-to-face links through its air (FaceLinks): flood fills over
// the chunk's air blocks held as 32-bit rows (bit x of row (y, z)), 32 blocks a step.
#include "world/culling_data.h"

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>

namespace world {

namespace {

constexpr int kN = kChunkSize;
using Rows = std::array<std::uint32_t, kN * kN>; // index z + 32 * y
constexpr int at(int y, int z) { return z + kN * y; }

// Every bit of `open` joined along the row to a bit of `seed` through set bits of `open`
// (a Kogge-Stone fill in both directions; seed must be a subset of open).
std::uint32_t fillRow(std::uint32_t seed, std::uint32_t open) {
    std::uint32_t up = seed, pu = open, down = seed, pd = open;
    for (int k = 1; k < 32; k <<= 1) {
        up |= pu & (up << k);
        pu &= pu << k;
        down |= pd & (down >> k);
        pd &= pd >> k;
    }
    return up | down;
}

// The air joined to `reach` (a subset of air) through air, in place.
void flood(const Rows& air, Rows& reach) {
    bool changed = true;
    constexpr auto kRow = static_cast<std::size_t>(kN); // one step in y
    const auto visit = [&](int y, int z) {
        const auto i = static_cast<std::size_t>(at(y, z));
        std::uint32_t n = reach[i];
        if (y > 0) n |= reach[i - kRow];
        if (y < kN - 1) n |= reach[i + kRow];
        if (z > 0) n |= reach[i - 1];
        if (z < kN - 1) n |= reach[i + 1];
        n &= air[i];
        if (n == 0) return;
        n = fillRow(n, air[i]);
        if (n != reach[i]) {
            reach[i] = n;
            changed = true;
        }
    };
    // Sweeps forward and back use what they have just reached, so an air region that is not a maze
    // fills in a few sweeps.
    while (changed) {
        changed = false;
        for (int y = 0; y < kN; ++y)
            for (int z = 0; z < kN; ++z) visit(y, z);
        for (int y = kN - 1; y >= 0; --y)
            for (int z = kN - 1; z >= 0; --z) visit(y, z);
    }
}

// The cells of `rows` on face f, as a mask of the same shape.
Rows onFace(const Rows& rows, int f) {
    Rows out{};
    for (int y = 0; y < kN; ++y) {
        for (int z = 0; z < kN; ++z) {
            const std::uint32_t r = rows[static_cast<std::size_t>(at(y, z))];
            std::uint32_t m = 0;
            switch (f) {
            case kFacePosX:
                m = r & (1u << (kN - 1));
                break;
            case kFaceNegX:
                m = r & 1u;
                break;
            case kFacePosY:
                m = y == kN - 1 ? r : 0;
                break;
            case kFaceNegY:
                m = y == 0 ? r : 0;
                break;
            case kFacePosZ:
                m = z == kN - 1 ? r : 0;
                break;
            default:
                m = z == 0 ? r : 0;
                break;
            }
            out[static_cast<std::size_t>(at(y, z))] = m;
        }
    }
    return out;
}

bool any(const Rows& rows) {
    std::uint32_t a = 0;
    for (const std::uint32_t r : rows) a |= r;
    return a != 0;
}

} // namespace

FaceLinks FaceLinks::all() {
    FaceLinks l;
    for (auto& t : l.to) t = (1u << kFaceCount) - 1;
    return l;
}

FaceLinks faceLinks(const PaddedChunk& in) {
    if (in.blocks.stale) throw std::invalid_argument("faceLinks: the chunk's solid rows are stale");
    Rows air{};
    std::uint32_t anyAir = 0, anySolid = 0;
    for (int y = 0; y < kN; ++y) {
        for (int z = 0; z < kN; ++z) {
            const auto solid = static_cast<std::uint32_t>(in.solid[y + 1][z + 1] >> 1);
            air[static_cast<std::size_t>(at(y, z))] = ~solid;
            anyAir |= ~solid;
            anySolid |= solid;
        }
    }
    if (anySolid == 0) return FaceLinks::all();
    FaceLinks links;
    if (anyAir == 0) return links;
    std::array<Rows, kFaceCount> faceAir;
    for (int f = 0; f < kFaceCount; ++f) faceAir[static_cast<std::size_t>(f)] = onFace(air, f);
    std::uint8_t covered = 0; // faces whose air every flood so far has taken in
    for (int f = 0; f < kFaceCount; ++f) {
        if ((covered >> f & 1u) != 0 || !any(faceAir[static_cast<std::size_t>(f)])) continue;
        Rows reach = faceAir[static_cast<std::size_t>(f)];
        flood(air, reach);
        std::uint8_t touched = 0;
        for (int g = 0; g < kFaceCount; ++g) {
            const Rows& onG = faceAir[static_cast<std::size_t>(g)];
            bool some = false, every = true;
            for (std::size_t i = 0; i < onG.size(); ++i) {
                some = some || (onG[i] & reach[i]) != 0;
                every = every && (onG[i] & ~reach[i]) == 0;
            }
            if (some) touched |= static_cast<std::uint8_t>(1u << g);
            if (some && every) covered |= static_cast<std::uint8_t>(1u << g);
        }
        for (int g = 0; g < kFaceCount; ++g) {
            if ((touched >> g & 1u) != 0) links.to[g] |= touched;
        }
    }
    return links;
}

SolidColumns solidColumns(const PaddedChunk& in) {
    if (in.blocks.stale) throw std::invalid_argument("solidColumns: the chunk's solid rows are stale");
    SolidColumns out;
    constexpr int kCell = SolidColumns::kCell;
    for (int y = 0; y < kChunkSize; ++y) {
        for (int cz = 0; cz < SolidColumns::kCells; ++cz) {
            std::uint64_t all = ~std::uint64_t{0}; // the blocks solid in every row of the column's z range
            for (int z = cz * kCell; z < (cz + 1) * kCell; ++z) all &= in.solid[y + 1][z + 1];
            const auto own = static_cast<std::uint32_t>(all >> 1); // x = 0..31 of the chunk
            for (int cx = 0; cx < SolidColumns::kCells; ++cx) {
                if ((own >> (cx * kCell) & 0xFFu) == 0xFFu) out.layers[SolidColumns::index(cx, cz)] |= 1u << y;
            }
        }
    }
    return out;
}

ChunkOccupancy occupancyOf(const PaddedChunk& in) {
    if (in.blocks.stale) throw std::invalid_argument("occupancyOf: the chunk's solid rows are stale");
    ChunkOccupancy out;
    for (int y = 0; y < kChunkSize; ++y) {
        for (int z = 0; z < kChunkSize; ++z) {
            out.rows[static_cast<std::size_t>(y) * kChunkSize + static_cast<std::size_t>(z)] =
                static_cast<std::uint32_t>(in.solid[y + 1][z + 1] >> 1);
        }
    }
    return out;
}

CullingData cullingDataOf(const PaddedChunk& fine, int cell) {
    CullingData d;
    d.links = faceLinks(fine);
    d.solid = solidColumns(fine);
    if (cell == 1) d.occupancy = std::make_shared<const ChunkOccupancy>(occupancyOf(fine));
    return d;
}

} // namespace world
