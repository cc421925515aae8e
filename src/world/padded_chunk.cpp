#include "world/padded_chunk.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace world {

namespace {

constexpr int kP = PaddedChunk::kSize; // 34
using Row = std::uint64_t;
constexpr Row kRowMask = (Row{1} << kP) - 1;

// Solidity of the padded chunk: bit x of s[y][z] is set when block (x, y, z) is solid.
using SolidRows = Row[kP][kP];
static_assert(std::is_same_v<SolidRows, decltype(PaddedChunk::solid)>);

} // namespace

// Solidity rows from block bytes: one SSE2 compare per 16 bytes, then the 34-bit rows cut out.
void solidFromBytes(const PaddedChunk& in, SolidRows& s) {
    constexpr int kBytes = PaddedChunk::kVolume;
    constexpr int kWords = (kBytes + 63) / 64;
    static_assert(kBytes % 8 == 0);
    static_assert(static_cast<int>(BlockType::Air) == 0 && sizeof(BlockType) == 1);
    std::uint64_t bits[kWords + 1];
    const auto* p = reinterpret_cast<const unsigned char*>(in.blocks.data());
    int i = 0, w = 0;
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    const auto airMask = [&](int at) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + at));
        return static_cast<std::uint64_t>(static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, zero))));
    };
    for (; i + 64 <= kBytes; i += 64, ++w) {
        bits[w] = ~(airMask(i) | airMask(i + 16) << 16 | airMask(i + 32) << 32 | airMask(i + 48) << 48);
    }
#endif
    // Portable tail (and whole body without SSE2): flag non-zero bytes, gather the 8 flags by a multiply.
    for (; i < kBytes; i += 64, ++w) {
        std::uint64_t word = 0;
        for (int j = 0; j < 64 && i + j < kBytes; j += 8) {
            std::uint64_t flags = 0;
            if constexpr (std::endian::native == std::endian::little) {
                std::uint64_t v;
                std::memcpy(&v, p + i + j, 8);
                const std::uint64_t t =
                    (v | ((v & 0x7F7F7F7F7F7F7F7Full) + 0x7F7F7F7F7F7F7F7Full)) & 0x8080808080808080ull;
                flags = ((t >> 7) * 0x0102040810204080ull) >> 56;
            } else {
                for (int k = 0; k < 8; ++k) flags |= static_cast<std::uint64_t>(p[i + j + k] != 0) << k;
            }
            word |= flags << j;
        }
        bits[w] = word;
    }
    bits[kWords] = 0;

    Row* rows = &s[0][0];
    for (int r = 0; r < kP * kP; ++r) {
        const int bit = r * kP;
        const int wi = bit >> 6, sh = bit & 63;
        Row v = bits[wi] >> sh;
        if (sh > 64 - kP) v |= bits[wi + 1] << (64 - sh);
        rows[r] = v & kRowMask;
    }
}

void PaddedChunk::rebuildSolid() {
    solidFromBytes(*this, solid);
    blocks.stale = false;
}

void PaddedLight::fillOpenSky() {
    level.fill(kOpenSkyLight);
    std::memset(shade, 0, sizeof shade);
}

void PaddedLight::rebuildShade() {
    const std::uint16_t* p = level.data();
#if defined(__SSE2__)
    const __m128i open = _mm_set1_epi16(static_cast<short>(kOpenSkyLight));
    // Bit k of the result: word k of the 16 at `at` is the open sky's.
    const auto openBits = [&](const std::uint16_t* at) {
        const __m128i a = _mm_cmpeq_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at)), open);
        const __m128i b = _mm_cmpeq_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at + 8)), open);
        return static_cast<Row>(static_cast<unsigned>(_mm_movemask_epi8(_mm_packs_epi16(a, b))));
    };
#endif
    for (int y = 0; y < kP; ++y) {
        for (int z = 0; z < kP; ++z, p += kP) {
            Row row = 0;
#if defined(__SSE2__)
            row = ~(openBits(p) | openBits(p + 16) << 16 | Row{p[32] == kOpenSkyLight} << 32 |
                    Row{p[33] == kOpenSkyLight} << 33) &
                  kRowMask;
#else
            for (int x = 0; x < kP; ++x) row |= Row{p[x] != kOpenSkyLight} << x;
#endif
            shade[y][z] = row;
        }
    }
}

} // namespace world
