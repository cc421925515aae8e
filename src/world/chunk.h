// Chunks: 32^3 blocks stored as one flat array beside their occupancy bits, and the coordinate
// helpers between world block positions, chunk coordinates and chunk-local positions.
// A chunk is plain storage: it never generates terrain, knows nothing of its neighbours and never
// meshes itself. The world is kWorldHeight blocks tall; outside that, World defines what reads back.
#pragma once
#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "world/block.h"

namespace world {

inline constexpr int kChunkSize = 32;
inline constexpr int kChunkShift = 5; // log2(kChunkSize), for floor division by shifting
inline constexpr int kChunkVolume = kChunkSize * kChunkSize * kChunkSize;
inline constexpr int kWorldHeightChunks = 4;
inline constexpr int kWorldHeight = kWorldHeightChunks * kChunkSize; // y in [0, 128)
static_assert(1 << kChunkShift == kChunkSize);

struct ChunkCoord {
    int x = 0, y = 0, z = 0;
    auto operator<=>(const ChunkCoord&) const = default; // NOLINT(modernize-use-nullptr): clang-tidy 14 misreads it
};

struct ChunkCoordHash {
    std::size_t operator()(const ChunkCoord& c) const noexcept;
};

// Chebyshev distance in x and z, in chunks: how far apart two columns of chunks are.
constexpr int columnDistance(ChunkCoord a, ChunkCoord b) {
    const int dx = a.x > b.x ? a.x - b.x : b.x - a.x, dz = a.z > b.z ? a.z - b.z : b.z - a.z;
    return dx > dz ? dx : dz;
}

// a / b rounded down (b > 0 or b < 0): floorDiv(-1, 32) is -1, not 0.
inline int floorDiv(int a, int b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0); }

// Floor division: block -1 lies in chunk -1, not chunk 0.
inline ChunkCoord chunkOf(glm::ivec3 block) {
    // Arithmetic right shift of negative values is defined (as floor) since C++20.
    return {block.x >> kChunkShift, block.y >> kChunkShift, block.z >> kChunkShift};
}
// Always 0..31, also for negative positions.
inline glm::ivec3 localOf(glm::ivec3 block) {
    return {block.x & (kChunkSize - 1), block.y & (kChunkSize - 1), block.z & (kChunkSize - 1)};
}
inline glm::ivec3 chunkOrigin(ChunkCoord c) { return {c.x * kChunkSize, c.y * kChunkSize, c.z * kChunkSize}; }

class Chunk {
public:
    // x fastest, then z, then y: a horizontal layer is contiguous, which suits terrain filling.
    static constexpr int index(int x, int y, int z) { return x + kChunkSize * (z + kChunkSize * y); }

    // Occupancy: bit x of solidRow(y, z) is set when block (x, y, z) is solid. Kept in step with the
    // blocks by every writer, so the mesher reads solidity 32 blocks at a time and never scans bytes.
    static constexpr int rowIndex(int y, int z) { return z + kChunkSize * y; }

    BlockType get(int x, int y, int z) const { return m_blocks[static_cast<std::size_t>(index(x, y, z))]; }
    void set(int x, int y, int z, BlockType t) {
        m_blocks[static_cast<std::size_t>(index(x, y, z))] = t;
        std::uint32_t& row = m_solid[static_cast<std::size_t>(rowIndex(y, z))];
        row = (row & ~(1u << x)) | static_cast<std::uint32_t>(isSolid(t)) << x;
    }
    const BlockType* data() const { return m_blocks.data(); }
    std::uint32_t solidRow(int y, int z) const { return m_solid[static_cast<std::size_t>(rowIndex(y, z))]; }
    const std::uint32_t* solidRows() const { return m_solid.data(); }

    // Bulk writes go through here: `write(BlockType* blocks)` fills any of the chunk's bytes (in
    // index() order), then the occupancy is rebuilt from them (about 2 us).
    template <typename Write>
    void writeBlocks(Write&& write) {
        write(m_blocks.data());
        rebuildSolidRows();
    }

    void fill(BlockType t);
    bool isAllAir() const;

private:
    void rebuildSolidRows();

    std::array<BlockType, kChunkVolume> m_blocks{};               // all Air
    std::array<std::uint32_t, kChunkSize * kChunkSize> m_solid{}; // all clear
};

// Bit i of the result is set when bytes[i] is not Air (i < 32). SSE2 where available.
std::uint32_t solidMask32(const BlockType* bytes);

} // namespace world
