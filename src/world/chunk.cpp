#include "world/chunk.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/rng.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace world {

std::size_t ChunkCoordHash::operator()(const ChunkCoord& c) const noexcept {
    // Neighbouring chunks differ in the low bits only; a full mix keeps unordered_map buckets even.
    const auto h = core::hashCoords(0x6368756E6B, c.x, c.y, c.z);
    return static_cast<std::size_t>(h);
}

std::uint32_t solidMask32(const BlockType* bytes) {
    static_assert(sizeof(BlockType) == 1 && static_cast<int>(BlockType::Air) == 0);
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    const auto airBits = [&](int at) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(bytes + at));
        return static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, zero)));
    };
    return ~(airBits(0) | airBits(16) << 16);
#else
    std::uint32_t m = 0;
    for (int i = 0; i < 32; ++i) m |= static_cast<std::uint32_t>(isSolid(bytes[i])) << i;
    return m;
#endif
}

void Chunk::rebuildSolidRows() {
    static_assert(kChunkSize == 32);
    for (int r = 0; r < kChunkSize * kChunkSize; ++r) {
        m_solid[static_cast<std::size_t>(r)] = solidMask32(m_blocks.data() + r * kChunkSize);
    }
}

void Chunk::fill(BlockType t) {
    std::fill(m_blocks.begin(), m_blocks.end(), t);
    m_solid.fill(isSolid(t) ? ~0u : 0u);
}

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
