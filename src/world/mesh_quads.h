// How the mesher's two translation units write vertices: the slice layout of each face direction, the
// occlusion table, the face tiles and QuadSink, which packs quads straight into a ChunkMesh. Shared by the
// greedy mesher (mesher.cpp) and the culled reference (mesh_culled.cpp) so that both write the same
// vertices, and by nothing else: no other file, and no other layer, may include it.
// Everything is in an unnamed namespace on purpose: each of the two files compiles its own copy, with
// internal linkage as when this was part of mesher.cpp, so that the compiler inlines and specialises it
// freely in the greedy mesher's hot loops.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "world/block.h"
#include "world/chunk.h"
#include "world/chunk_vertex.h"
#include "world/light_level.h"
#include "world/padded_chunk.h"

namespace world {

namespace {

constexpr int kP = PaddedChunk::kSize; // 34
constexpr int kN = kChunkSize;         // 32

// Slice layout of each face direction: a = normal axis, b = row axis, c = bit axis (0 x, 1 y, 2 z).
// order[k] = (cc, cb): which end of the c and b extents vertex k sits at; the orders are counter-
// clockwise seen from outside. uFlip/vFlip make u grow to the right seen from outside and v grow
// downward on side faces.
struct DirInfo {
    int a, b, c;
    bool positive;
    std::uint8_t order[4][2];
    bool uFlip, vFlip;
};
constexpr DirInfo kDirs[kFaceCount] = {
    {0, 1, 2, true, {{0, 0}, {0, 1}, {1, 1}, {1, 0}}, true, true},    // +X: b = y, c = z
    {0, 1, 2, false, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, false, true},  // -X
    {1, 2, 0, true, {{0, 0}, {0, 1}, {1, 1}, {1, 0}}, false, false},  // +Y: b = z, c = x
    {1, 2, 0, false, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, false, false}, // -Y
    {2, 1, 0, true, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, false, true},   // +Z: b = y, c = x
    {2, 1, 0, false, {{0, 0}, {0, 1}, {1, 1}, {1, 0}}, true, true},   // -Z
};

// Occlusion of the four corners from the 3x3 solidity pattern on the air side of a face. Pattern bit
// (dc + 1) + 3 * (db + 1) is the block offset by dc along c and db along b. Result: two bits per
// corner, corner (cc, cb) at bit 2 * (cc + 2 * cb).
constexpr std::array<std::uint8_t, 512> kAoTable = [] {
    std::array<std::uint8_t, 512> t{};
    for (unsigned p = 0; p < 512; ++p) {
        unsigned packed = 0;
        for (int cb = 0; cb < 2; ++cb) {
            for (int cc = 0; cc < 2; ++cc) {
                const int sc = cc ? 2 : 0, sb = cb ? 2 : 0; // (offset + 1) of the corner's side
                const unsigned sideB = (p >> (1 + 3 * sb)) & 1u;
                const unsigned sideC = (p >> (sc + 3)) & 1u;
                const unsigned corner = (p >> (sc + 3 * sb)) & 1u;
                const unsigned ao = (sideB && sideC) ? 0u : 3u - (sideB + sideC + corner);
                packed |= ao << (2 * (cc + 2 * cb));
            }
        }
        t[p] = static_cast<std::uint8_t>(packed);
    }
    return t;
}();
constexpr std::uint8_t kAoOpen = 0xFF;
// A face's light: the light word (LightLevel::bits) of each of its four corners, corner (cc, cb) at bits
// 16 * (cc + 2 * cb).
using CornerLight = std::uint64_t;
constexpr CornerLight kEachCorner = 0x0001000100010001ull;
// A face of one light word at every corner.
constexpr CornerLight evenCorners(unsigned word) { return CornerLight{word} * kEachCorner; }
constexpr CornerLight kLightOpen = evenCorners(kOpenSkyLight); // every corner under the open sky

// Whether the four corners' light words are equal.
constexpr bool evenLight(CornerLight light) { return light == evenCorners(light & 0xFFFFu); }

// tile[face][block byte]; sized for every byte so that a corrupt block value cannot index out of range.
struct FaceTiles {
    std::uint8_t t[kFaceCount][256];
};
const FaceTiles& faceTiles() {
    static const FaceTiles tiles = [] {
        FaceTiles f{};
        for (int face = 0; face < kFaceCount; ++face) {
            for (int b = 0; b < 256; ++b) {
                const BlockInfo& info = blockInfo(static_cast<BlockType>(b));
                f.t[face][b] = face == kFacePosY ? info.tileTop : face == kFaceNegY ? info.tileBottom : info.tileSide;
            }
        }
        return f;
    }();
    return tiles;
}

// Steps between neighbouring padded voxels along x, y and z.
constexpr int kStride[3] = {1, kP* kP, kP};

// Padded array index of inner slice coordinates (a, b, c) of direction D.
template <int D>
constexpr int paddedIndex(int a, int b, int c) {
    int p[3];
    p[kDirs[D].a] = a + 1;
    p[kDirs[D].b] = b + 1;
    p[kDirs[D].c] = c + 1;
    return PaddedChunk::index(p[0], p[1], p[2]);
}

constexpr int byteShift(int i) { return 8 * (std::endian::native == std::endian::little ? i : 7 - i); }

// The vertex bits of a light word (ChunkVertex): sunlight's shortfall in the high half of the face byte, red in
// the high half of the occlusion byte, green in the top two bits of x (low) and y (high), blue in those of z and
// u; all 0 under the open sky. Tables by the word's high byte (sunlight, red) and its low byte (green, blue): two
// look-ups a word.
constexpr std::uint64_t colourVertexBits(unsigned word) {
    const LightLevel l{static_cast<std::uint16_t>(word)};
    using U = std::uint64_t;
    const auto g = static_cast<U>(l.green()), b = static_cast<U>(l.blue());
    return U(l.red()) << (byteShift(7) + 4) | (g & 3u) << (byteShift(0) + 6) | (g >> 2) << (byteShift(1) + 6) |
           (b & 3u) << (byteShift(2) + 6) | (b >> 2) << (byteShift(4) + 6);
}
struct VertexLight {
    std::uint64_t high[256], low[256];
};
constexpr VertexLight kVertexLight = [] {
    VertexLight t{};
    for (unsigned b = 0; b < 256; ++b) {
        t.high[b] = colourVertexBits(b << 8) | std::uint64_t(kMaxLight - (b >> 4)) << (byteShift(3) + 4);
        t.low[b] = colourVertexBits(b);
    }
    return t;
}();

// Quads are written straight into the mesh: its vector is grown ahead when a quad would not fit
// (VertexList leaves new elements unwritten, so growing into capacity it has costs nothing) and cut
// back to what was written at the end, so the hot loop checks one count per quad and never copies.
class QuadSink {
public:
    explicit QuadSink(VertexList& out) : m_out(out), m_n(out.size()) {}
    QuadSink(const QuadSink&) = delete;
    QuadSink& operator=(const QuadSink&) = delete;
    ~QuadSink() { m_out.resize(m_n); }

    // Quad of direction D on slice a covering rows [b, b + h) and bits [c, c + w) of that slice.
    // aoPacked: two bits per corner, corner (cc, cb) at bit 2 * (cc + 2 * cb). light: CornerLight.
    template <int D>
    void quad(int a, int b, int c, int h, int w, unsigned tile, unsigned aoPacked, CornerLight light) {
        if (m_n + 4 > m_out.size()) grow();
        constexpr const DirInfo& di = kDirs[D];
        using U = std::uint64_t;
        // A vertex is eight bytes built in one word; no position or texture field exceeds 32 (six bits, under
        // the light bits above them), so adding never carries.
        const Steps st{U(a + (di.positive ? 1 : 0)) << byteShift(di.a) | U(b) << byteShift(di.b) |
                           U(c) << byteShift(di.c) | U(D) << byteShift(3) | U(tile) << byteShift(6),
                       U(h) << byteShift(di.b), U(w) << byteShift(di.c), U(w) << byteShift(4), U(h) << byteShift(5)};
        const U v0 = vertex<D, 0>(st, aoPacked) + lightOf<D, 0>(light);
        const U v1 = vertex<D, 1>(st, aoPacked) + lightOf<D, 1>(light);
        const U v2 = vertex<D, 2>(st, aoPacked) + lightOf<D, 2>(light);
        const U v3 = vertex<D, 3>(st, aoPacked) + lightOf<D, 3>(light);
        // Split along the diagonal whose corners are brighter in sum; rotating keeps the winding.
        const bool rotate = aoOf<D, 0>(aoPacked) + aoOf<D, 2>(aoPacked) < aoOf<D, 1>(aoPacked) + aoOf<D, 3>(aoPacked);
        // Four separate word stores: staging them in an array first makes the compiler reload them as
        // one wide load, which stalls on store forwarding.
        ChunkVertex* dst = m_out.data() + m_n;
        store(dst + 0, rotate ? v1 : v0);
        store(dst + 1, rotate ? v2 : v1);
        store(dst + 2, rotate ? v3 : v2);
        store(dst + 3, rotate ? v0 : v3);
        m_n += 4;
    }

    // The four vertex words of a 1x1 quad of direction D, relative to its base word, for each packed
    // occlusion, in emission order (diagonal rotation applied): what quad() computes, read from a table.
    struct UnitWords {
        std::uint64_t w[256][4];
        std::uint8_t corner[256][4]; // the corner (cc + 2 * cb) of each emitted vertex
    };
    template <int D>
    static const UnitWords& unitWords() {
        static const UnitWords table = [] {
            UnitWords t{};
            using U = std::uint64_t;
            constexpr const DirInfo& di = kDirs[D];
            const Steps st{0, U(1) << byteShift(di.b), U(1) << byteShift(di.c), U(1) << byteShift(4),
                           U(1) << byteShift(5)};
            for (unsigned ao = 0; ao < 256; ++ao) {
                const U v[4] = {vertex<D, 0>(st, ao), vertex<D, 1>(st, ao), vertex<D, 2>(st, ao), vertex<D, 3>(st, ao)};
                const bool rotate = aoOf<D, 0>(ao) + aoOf<D, 2>(ao) < aoOf<D, 1>(ao) + aoOf<D, 3>(ao);
                for (int k = 0; k < 4; ++k) {
                    const int from = (k + (rotate ? 1 : 0)) % 4;
                    t.w[ao][k] = v[from];
                    t.corner[ao][k] = static_cast<std::uint8_t>(di.order[from][0] + 2 * di.order[from][1]);
                }
            }
            return t;
        }();
        return table;
    }
    // A 1x1 quad (a face with uneven occlusion, which merges with nothing): quad(a, b, c, 1, 1, ...)
    // with the per-vertex work looked up. `words` is unitWords<D>(), fetched once by the caller.
    template <int D>
    void unitQuad(const UnitWords& words, int a, int b, int c, unsigned tile, unsigned aoPacked, CornerLight light) {
        if (m_n + 4 > m_out.size()) grow();
        constexpr const DirInfo& di = kDirs[D];
        using U = std::uint64_t;
        U base = U(a + (di.positive ? 1 : 0)) << byteShift(di.a) | U(b) << byteShift(di.b) | U(c) << byteShift(di.c) |
                 U(D) << byteShift(3) | U(tile) << byteShift(6);
        const U* w = words.w[aoPacked & 255u];
        ChunkVertex* dst = m_out.data() + m_n;
        if (!evenLight(light)) { // smooth light that varies across the face: a word per corner
            const std::uint8_t* corner = words.corner[aoPacked & 255u];
            for (int k = 0; k < 4; ++k) store(dst + k, base + w[k] + lightWord(light >> (16 * corner[k]) & 0xFFFFu));
            m_n += 4;
            return;
        }
        base += lightWord(light & 0xFFFFu);
#if defined(__SSE2__)
        // Two vertices to a store: the base added to two table words at once.
        const __m128i b2 = _mm_set1_epi64x(static_cast<long long>(base));
        const auto* from = reinterpret_cast<const __m128i*>(w);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm_add_epi64(b2, _mm_loadu_si128(from)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + 2), _mm_add_epi64(b2, _mm_loadu_si128(from + 1)));
#else
        store(dst + 0, base + w[0]);
        store(dst + 1, base + w[1]);
        store(dst + 2, base + w[2]);
        store(dst + 3, base + w[3]);
#endif
        m_n += 4;
    }

private:
    static void store(ChunkVertex* dst, std::uint64_t word) { std::memcpy(dst, &word, sizeof word); }
    struct Steps {
        std::uint64_t base, stepB, stepC, stepU, stepV;
    };
    [[gnu::always_inline]] static std::uint64_t lightWord(unsigned word) {
        return kVertexLight.high[word >> 8 & 255u] | kVertexLight.low[word & 255u];
    }
    template <int D, int K>
    static std::uint64_t lightOf(CornerLight light) {
        constexpr int cc = kDirs[D].order[K][0], cb = kDirs[D].order[K][1];
        return lightWord(light >> (16 * (cc + 2 * cb)) & 0xFFFFu);
    }
    template <int D, int K>
    static unsigned aoOf(unsigned aoPacked) {
        constexpr int cc = kDirs[D].order[K][0], cb = kDirs[D].order[K][1];
        return (aoPacked >> (2 * (cc + 2 * cb))) & 3u;
    }
    // Vertex K of a quad, everything but the quad's own numbers known at compile time.
    template <int D, int K>
    static std::uint64_t vertex(const Steps& st, unsigned aoPacked) {
        constexpr const DirInfo& di = kDirs[D];
        constexpr int cc = di.order[K][0], cb = di.order[K][1];
        std::uint64_t v = st.base + (std::uint64_t(aoOf<D, K>(aoPacked)) << byteShift(7));
        if constexpr (cb != 0) v += st.stepB;
        if constexpr (cc != 0) v += st.stepC;
        if constexpr ((di.uFlip ? 1 - cc : cc) != 0) v += st.stepU;
        if constexpr ((di.vFlip ? 1 - cb : cb) != 0) v += st.stepV;
        return v;
    }

    void grow() { m_out.resize(std::max<std::size_t>({m_out.capacity(), 2 * m_out.size(), 4096})); }

    static_assert(sizeof(ChunkVertex) == sizeof(std::uint64_t));
    VertexList& m_out;
    std::size_t m_n; // vertices written; m_out.size() is how far it may write
};

} // namespace

} // namespace world
