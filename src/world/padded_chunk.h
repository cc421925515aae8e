// A chunk as the mesher reads it: its blocks, their solidity as 64-bit rows and their light, each with a
// one-voxel border taken from the neighbouring chunks, so that faces against those chunks are culled and
// occlusion and light are seamless across chunk borders. Plain data: World::gatherPadded and
// world/column_light.h fill it; it never reads the world itself and knows nothing of meshes or GL.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "world/block.h"
#include "world/chunk.h"
#include "world/light_level.h"

namespace world {

// The padded block bytes. Reading is free; any non-const access (operator[], data(), begin(), end(),
// fill()) marks the occupancy rows stale, so bytes written behind PaddedChunk::set's back can never be
// meshed with old solidity: meshChunk then derives the rows from the bytes itself (about 3 us).
struct PaddedBlocks : std::array<BlockType, (kChunkSize + 2) * (kChunkSize + 2) * (kChunkSize + 2)> {
    using Base = std::array<BlockType, (kChunkSize + 2) * (kChunkSize + 2) * (kChunkSize + 2)>;
    const BlockType* data() const { return Base::data(); }
    BlockType* data() { return stale = true, Base::data(); }
    const_reference operator[](size_type i) const { return Base::operator[](i); }
    reference operator[](size_type i) { return stale = true, Base::operator[](i); }
    const_iterator begin() const { return Base::begin(); }
    iterator begin() { return stale = true, Base::begin(); }
    const_iterator end() const { return Base::end(); }
    iterator end() { return stale = true, Base::end(); }
    void fill(BlockType t) { stale = true, Base::fill(t); }
    // For writers that keep PaddedChunk::solid in step themselves (set(), World::gatherPadded).
    BlockType* untrackedData() { return Base::data(); }

    bool stale = false;
};

// The open sky's light word (world/light_level.h): full sunlight, no block light.
inline constexpr std::uint16_t kOpenSkyLight = kOpenSky.bits;

// The light of the padded voxels, for smooth lighting: what a chunk's faces are lit by. Starts as open sky
// everywhere, which meshes exactly as a chunk without light did.
struct PaddedLight {
    static constexpr int kSize = kChunkSize + 2;
    static constexpr int kVolume = kSize * kSize * kSize;
    PaddedLight() { fillOpenSky(); }
    void fillOpenSky();
    // Recomputes `shade` from `level`; call after writing `level`.
    void rebuildShade();

    std::array<std::uint16_t, kVolume> level; // LightLevel::bits of each voxel, in PaddedChunk::index order
    // Bit x of shade[y][z] is set where level differs from kOpenSkyLight. A face whose 3x3 neighbourhood
    // on the air side has no such bit is lit as under the open sky at every corner, and merges by tile alone.
    std::uint64_t shade[kSize][kSize];
};

struct PaddedChunk {
    static constexpr int kSize = kChunkSize + 2;
    static constexpr int kVolume = kSize * kSize * kSize;
    // Padded coordinates 0..33; the chunk's own block (x, y, z) is at (x + 1, y + 1, z + 1).
    // Same order as Chunk: x fastest, then z, then y.
    static constexpr int index(int x, int y, int z) { return x + kSize * (z + kSize * y); }
    BlockType get(int x, int y, int z) const { return blocks[static_cast<std::size_t>(index(x, y, z))]; }
    void set(int x, int y, int z, BlockType t) {
        blocks.untrackedData()[index(x, y, z)] = t;
        std::uint64_t& row = solid[y][z];
        row = (row & ~(std::uint64_t{1} << x)) | std::uint64_t{isSolid(t)} << x;
    }
    bool solidAt(int x, int y, int z) const { return (solid[y][z] >> x & 1u) != 0; }
    // Recomputes `solid` from `blocks` and clears blocks.stale.
    void rebuildSolid();

    // Unless blocks.stale: bit x of solid[y][z] is set exactly when blocks[index(x, y, z)] is solid,
    // and bits 34..63 are clear. The mesher reads solidity only from these 64-bit rows (culling,
    // merging and ambient occlusion) and block bytes only for the tiles of visible faces.
    PaddedBlocks blocks{};               // all Air
    std::uint64_t solid[kSize][kSize]{}; // all clear
    PaddedLight light;                   // all open sky
};
static_assert(sizeof(PaddedBlocks::Base) == PaddedChunk::kVolume);

// Solidity rows from block bytes, in PaddedChunk::solid's layout (bit x of s[y][z], bits 34..63 clear):
// what rebuildSolid stores, and what the greedy mesher derives for itself when in.blocks is stale, as
// bytes written behind PaddedChunk::set's back leave it. Reads only in.blocks (about 3 us).
void solidFromBytes(const PaddedChunk& in, std::uint64_t (&s)[PaddedChunk::kSize][PaddedChunk::kSize]);

} // namespace world
