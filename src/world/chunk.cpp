#include "world/chunk.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/rng.h"

namespace world {

std::size_t ChunkCoordHash::operator()(const ChunkCoord& c) const noexcept {
    // Neighbouring chunks differ in the low bits only; a full mix keeps unordered_map buckets even.
    const auto h = core::hashCoords(0x6368756E6B, c.x, c.y, c.z);
    return static_cast<std::size_t>(h);
}

void Chunk::fill(BlockType t) { std::fill(m_blocks.begin(), m_blocks.end(), t); }

bool Chunk::isAllAir() const {
    static_assert(sizeof(BlockType) == 1 && static_cast<int>(BlockType::Air) == 0);
    // OR whole words without an early exit: the loop vectorises and costs about a microsecond.
    std::uint64_t any = 0;
    for (std::size_t i = 0; i < m_blocks.size(); i += sizeof(std::uint64_t)) {
        std::uint64_t w;
        std::memcpy(&w, m_blocks.data() + i, sizeof w);
        any |= w;
    }
    return any == 0;
}

} // namespace world
