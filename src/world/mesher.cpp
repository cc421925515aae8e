#include "world/mesher.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// How the greedy mesher works, in short:
// 1. One pass turns the padded block bytes into solidity bit rows along x (S[y][z], 34 bits each).
// 2. For each face direction and slice, visible faces are rows of bits: solid here, air on the far
//    side. Y and Z faces come straight out of the x rows; X faces are scattered into slices (their
//    count is proportional to the surface, not to the volume).
// 3. A face whose 3x3 neighbourhood on the air side is empty has all four corners fully lit; that is
//    a few bit operations per row, and covers most faces. Only the others get a per-face look-up of
//    their occlusion, and if their four corners are equal they still merge, keyed by (tile, ao).
// 4. Greedy rectangles per slice: widest run of equal keys along the bits, then grow along the rows.

namespace world {

namespace {

constexpr int kP = PaddedChunk::kSize; // 34
constexpr int kN = kChunkSize;         // 32
using Row = std::uint64_t;
constexpr Row kRowMask = (Row{1} << kP) - 1;
constexpr Row kInner = kRowMask & ~Row{1} & ~(Row{1} << (kP - 1)); // padded bits 1..32

// Solidity of the padded chunk: bit x of s[y][z] is set when block (x, y, z) is solid.
using SolidRows = Row[kP][kP];
static_assert(std::is_same_v<SolidRows, decltype(PaddedChunk::solid)>);

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
constexpr std::uint32_t kLightOpen = 0x01010101u * kOpenSkyLight; // every corner under the open sky

// Whether the four corners' light bytes are equal.
constexpr bool evenLight(std::uint32_t light) { return light == (light & 255u) * 0x01010101u; }

// What the greedy mesher merges: Flat (no occlusion, each face lit flat by its air-side voxel,
// MeshMode::GreedyFlat), Uniform (faces whose four corners are equal, MeshMode::Greedy) or Strips (besides,
// MeshMode::GreedyStrips).
enum class Shading { Flat, Uniform, Strips };

bool uniformAo(unsigned packed) { return packed == (packed & 3u) * 0x55u; }

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
    // aoPacked: two bits per corner, corner (cc, cb) at bit 2 * (cc + 2 * cb). light: a light byte per
    // corner (sunlight << 4 | block light), corner (cc, cb) at byte cc + 2 * cb.
    template <int D>
    void quad(int a, int b, int c, int h, int w, unsigned tile, unsigned aoPacked, std::uint32_t light) {
        if (m_n + 4 > m_out.size()) grow();
        constexpr const DirInfo& di = kDirs[D];
        using U = std::uint64_t;
        // A vertex is eight bytes built in one word; no field exceeds 64, so adding never carries.
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
    void unitQuad(const UnitWords& words, int a, int b, int c, unsigned tile, unsigned aoPacked, std::uint32_t light) {
        if (m_n + 4 > m_out.size()) grow();
        constexpr const DirInfo& di = kDirs[D];
        using U = std::uint64_t;
        U base = U(a + (di.positive ? 1 : 0)) << byteShift(di.a) | U(b) << byteShift(di.b) | U(c) << byteShift(di.c) |
                 U(D) << byteShift(3) | U(tile) << byteShift(6);
        const U* w = words.w[aoPacked & 255u];
        ChunkVertex* dst = m_out.data() + m_n;
        if (!evenLight(light)) { // smooth light that varies across the face: a word per corner
            const std::uint8_t* corner = words.corner[aoPacked & 255u];
            for (int k = 0; k < 4; ++k) store(dst + k, base + w[k] + lightWord(light >> (8 * corner[k]) & 255u));
            m_n += 4;
            return;
        }
        base += lightWord(light & 255u);
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
    // The vertex bits of a light byte: sunlight's shortfall in the high half of the face byte, block light
    // in the high half of the occlusion byte (ChunkVertex); both 0 under the open sky.
    static std::uint64_t lightWord(unsigned byte) {
        return std::uint64_t(kMaxLight - (byte >> 4)) << (byteShift(3) + 4) | std::uint64_t(byte & 15u)
                                                                                  << (byteShift(7) + 4);
    }
    template <int D, int K>
    static std::uint64_t lightOf(std::uint32_t light) {
        constexpr int cc = kDirs[D].order[K][0], cb = kDirs[D].order[K][1];
        return lightWord(light >> (8 * (cc + 2 * cb)) & 255u);
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

// ---------------------------------------------------------------------------------------------------
// Greedy

} // namespace

namespace {

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

} // namespace

void PaddedChunk::rebuildSolid() {
    solidFromBytes(*this, solid);
    blocks.stale = false;
}

void PaddedLight::fillOpenSky() {
    level.fill(kOpenSkyLight);
    std::memset(shade, 0, sizeof shade);
}

void PaddedLight::rebuildShade() {
    const std::uint8_t* p = level.data();
#if defined(__SSE2__)
    const __m128i open = _mm_set1_epi8(static_cast<char>(kOpenSkyLight));
    const auto openBits = [&](const std::uint8_t* at) {
        return static_cast<Row>(static_cast<unsigned>(
            _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at)), open))));
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

namespace {

Row spread(Row r) { return r | (r << 1) | (r >> 1); }

// The 3x3 pattern (see kAoTable) around the air-side block of the faces in row b of slice a of
// direction D. Prepared once per row: for Y and Z faces the three neighbouring x rows already hold
// the pattern bits side by side, for X faces the bit column at the air-side x is fixed.
template <int D>
class RowNeighbours {
public:
    RowNeighbours(const SolidRows& s, int a, int b) {
        constexpr const DirInfo& di = kDirs[D];
        const int qa = a + 1 + (di.positive ? 1 : -1), qb = b + 1;
        if constexpr (di.c == 0) {
            for (int db = 0; db < 3; ++db) m_rows[db] = di.a == 1 ? s[qa][qb + db - 1] : s[qb + db - 1][qa];
        } else {
            m_below = &s[qb - 1][0];
            m_x = qa;
        }
    }
    // Whether any of the 3x3 bits of face c is set: pattern(c) != 0, with fewer operations.
    bool any(int c) const {
        if constexpr (kDirs[D].c == 0) {
            return ((m_rows[0] | m_rows[1] | m_rows[2]) >> c & 7u) != 0;
        } else {
            Row r = 0;
            for (int db = 0; db < 3; ++db) {
                const Row* z = m_below + db * kP + c;
                r |= z[0] | z[1] | z[2];
            }
            return (r >> m_x & 1u) != 0;
        }
    }
    unsigned pattern(int c) const {
        if constexpr (kDirs[D].c == 0) {
            // Face c sits at padded bit c + 1, so its neighbours are bits c .. c + 2.
            return static_cast<unsigned>((m_rows[0] >> c) & 7u) | static_cast<unsigned>((m_rows[1] >> c) & 7u) << 3 |
                   static_cast<unsigned>((m_rows[2] >> c) & 7u) << 6;
        } else {
            unsigned p = 0;
            for (int db = 0; db < 3; ++db) {
                const Row* z = m_below + db * kP + c; // padded z = c .. c + 2 around the face's c + 1
                const unsigned bits =
                    static_cast<unsigned>(((z[0] >> m_x) & 1u) | ((z[1] >> m_x) & 1u) << 1 | ((z[2] >> m_x) & 1u) << 2);
                p |= bits << (3 * db);
            }
            return p;
        }
    }

private:
    Row m_rows[3] = {0, 0, 0};    // Y and Z faces: the x rows at db = -1, 0, +1
    const Row* m_below = nullptr; // X faces: row y - 1 of the padded solidity (z = 0)
    int m_x = 0;                  // X faces: air-side x
};

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

// A light byte spread for summing: sunlight in the low half, block light in the high half.
inline std::uint32_t spreadLight(std::uint8_t level) { return (level >> 4) | std::uint32_t(level & 15u) << 16; }

// Smooth light: the light bytes of a face's four corners (corner (cc, cb) at byte cc + 2 * cb), from the
// voxel on its air side (padded index q) and the 3x3 solidity pattern around it (kAoTable's). Each corner
// averages, channel by channel and rounded to the nearest level, the voxels that are not solid among q,
// the two beside the corner and the one diagonal to it (left out when both beside it are solid, as for
// occlusion): light does not reach a corner through solid blocks.
template <int D>
std::uint32_t faceLight(const std::uint8_t* level, int q, unsigned pattern) {
    constexpr int sb = kStride[kDirs[D].b], sc = kStride[kDirs[D].c];
    // The nine voxels around the corners, all read, then kept or not by mask: no branch on the pattern.
    const std::uint32_t mid = spreadLight(level[q]);
    const std::uint32_t side[2][2] = {{spreadLight(level[q - sc]), spreadLight(level[q + sc])},  // along c
                                      {spreadLight(level[q - sb]), spreadLight(level[q + sb])}}; // along b
    const std::uint32_t diagonal[4] = {spreadLight(level[q - sc - sb]), spreadLight(level[q + sc - sb]),
                                       spreadLight(level[q - sc + sb]), spreadLight(level[q + sc + sb])};
    const std::uint32_t use = kCornerVoxels[pattern];
    std::uint32_t packed = 0;
    for (int k = 0; k < 4; ++k) {
        const std::uint32_t u = use >> (5 * k);
        const auto keep = [&](int bit) { return 0u - (u >> bit & 1u); };
        const std::uint32_t sum =
            mid + (side[0][k & 1] & keep(0)) + (side[1][k >> 1] & keep(1)) + (diagonal[k] & keep(2));
        const auto& mean = kRoundedMean[u >> 3 & 3u];
        packed |= (unsigned{mean[sum & 0xFFFFu]} << 4 | mean[sum >> 16]) << (8 * k);
    }
    return packed;
}

// Merges set bits of equal key into rectangles: widest run along c first, then as many rows as match.
// keyAt(b, c) gives the key of a face; same(key, b, c) whether face (b, c) has that key; both are only
// asked of set bits. `live`: bit b set where rows[b] may be non-zero. Consumes `rows` (all zero after).
template <typename KeyAt, typename Same, typename Emit>
void greedyMerge(std::uint32_t (&rows)[kN], std::uint32_t live, KeyAt&& keyAt, Same&& same, Emit&& emit) {
    for (; live != 0; live &= live - 1) {
        const int b = std::countr_zero(live);
        while (rows[b] != 0) {
            const std::uint32_t m = rows[b];
            const int c = std::countr_zero(m);
            const auto key = keyAt(b, c);
            const int run = std::countr_one(m >> c);
            int w = 1;
            while (w < run && same(key, b, c + w)) ++w;
            const std::uint32_t span = (w == kN ? ~0u : ((1u << w) - 1u)) << c;
            rows[b] = m & ~span;
            int h = 1;
            while (b + h < kN && (rows[b + h] & span) == span) {
                int i = 0;
                while (i < w && same(key, b + h, c + i)) ++i;
                if (i < w) break;
                rows[b + h] &= ~span;
                ++h;
            }
            emit(b, c, h, w, key);
        }
    }
}

// A face's block byte and tile. Faces of the same block byte have the same tile, so the byte decides
// most comparisons and the tile table is read only for the first face and where bytes differ.
struct TileKey {
    unsigned char block;
    std::uint8_t tile;
};

// Bit i set where a[i] == b[i], i < 32.
std::uint32_t equalBytes32(const unsigned char* a, const unsigned char* b) {
#if defined(__SSE2__)
    const auto half = [&](int at) {
        const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + at));
        const __m128i y = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + at));
        return static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(x, y)));
    };
    return half(0) | half(16) << 16;
#else
    std::uint32_t m = 0;
    for (int i = 0; i < 32; ++i) m |= static_cast<std::uint32_t>(a[i] == b[i]) << i;
    return m;
#endif
}

// Faces of equal tile merged with bit operations, for directions whose bit axis is x (Y and Z faces):
// the 32 block bytes under a row of faces are contiguous, so one compare of a row with itself shifted
// by a byte says which neighbours along the row are equal, and one with the next row which are equal
// across. Where bytes differ but tiles agree (grass and dirt seen from below) the tile table decides,
// so the rectangles are exactly those of greedyMerge with tile keys. Consumes `rows`.
template <int D, typename Emit>
void bitwiseTileMerge(const unsigned char* blocks, const std::uint8_t* tiles, int a, std::uint32_t (&rows)[kN],
                      std::uint32_t live, Emit&& emit) {
    static_assert(kDirs[D].c == 0);
    const auto rowBytes = [&](int b) { return blocks + paddedIndex<D>(a, b, 0); };
    // right[b] bit c: faces (b, c) and (b, c + 1) have the same tile; down[b] bit c: (b, c) and (b + 1, c).
    // Only rows in `live` are written or read (a rectangle grows down only through live rows).
    std::uint32_t right[kN], down[kN];
    for (std::uint32_t l = live; l != 0; l &= l - 1) {
        const int b = std::countr_zero(l);
        const std::uint32_t m = rows[b];
        down[b] = 0;
        const unsigned char* p = rowBytes(b);
        const std::uint32_t pairs = m & (m >> 1);
        std::uint32_t r = equalBytes32(p, p + 1) & pairs;
        for (std::uint32_t d = pairs & ~r; d != 0; d &= d - 1) {
            const int c = std::countr_zero(d);
            if (tiles[p[c]] == tiles[p[c + 1]]) r |= 1u << c;
        }
        right[b] = r;
        if (b + 1 == kN || (live >> (b + 1) & 1u) == 0) continue;
        const unsigned char* n = rowBytes(b + 1);
        const std::uint32_t both = m & rows[b + 1];
        std::uint32_t dn = equalBytes32(p, n) & both;
        for (std::uint32_t d = both & ~dn; d != 0; d &= d - 1) {
            const int c = std::countr_zero(d);
            if (tiles[p[c]] == tiles[n[c]]) dn |= 1u << c;
        }
        down[b] = dn;
    }
    for (; live != 0; live &= live - 1) {
        const int b = std::countr_zero(live);
        while (rows[b] != 0) {
            const std::uint32_t m = rows[b];
            const int c = std::countr_zero(m);
            // Rectangles grown down from earlier rows may have taken faces of this one since `right`
            // was computed: chain only through faces still here.
            const int w = 1 + std::countr_one((right[b] & (m >> 1)) >> c);
            const std::uint32_t span = (w == kN ? ~0u : ((1u << w) - 1u)) << c;
            rows[b] = m & ~span;
            int h = 1;
            while (b + h < kN && (rows[b + h] & span) == span && (down[b + h - 1] & span) == span) {
                rows[b + h] &= ~span;
                ++h;
            }
            emit(b, c, h, w, TileKey{0, tiles[rowBytes(b)[c]]});
        }
    }
}

// Shading::Strips: a face whose occlusion changes across the c axis only (a floor along a wall) is
// shaded constant along c and linear along b, and so is a run of such faces along c with equal
// corners and tile: one quad one face high shades them exactly as they shade themselves. Likewise
// along b. Faces arrive row by row (b ascending), c ascending within a row, so one run along c is open
// at a time, and one run along b per column.
template <int D>
class StripRuns {
public:
    StripRuns(QuadSink& out, const QuadSink::UnitWords& words, int a) : m_out(out), m_words(words), m_a(a) {}
    StripRuns(const StripRuns&) = delete;
    StripRuns& operator=(const StripRuns&) = delete;

    // Takes face (b, c), of one light byte at every corner, when its (non-uniform) occlusion is constant
    // along c or along b.
    bool add(int b, int c, unsigned tile, unsigned ao, unsigned light) {
        const unsigned key = tile | ao << 8 | light << 16;
        if (((ao ^ (ao >> 2)) & 0x33u) == 0) { // corners (0, cb) and (1, cb) equal
            if (m_rowW > 0 && m_rowB == b && m_rowC + m_rowW == c && m_rowKey == key) {
                ++m_rowW;
                return true;
            }
            if (m_rowW > 0) emit(m_rowB, m_rowC, 1, m_rowW, m_rowKey);
            m_rowB = b, m_rowC = c, m_rowW = 1, m_rowKey = key;
            return true;
        }
        if (((ao ^ (ao >> 4)) & 0x0Fu) == 0) { // corners (cc, 0) and (cc, 1) equal
            Column& col = m_cols[c];
            if ((m_openCols >> c & 1u) != 0) {
                if (col.b + col.h == b && col.key == key) {
                    ++col.h;
                    return true;
                }
                emit(col.b, c, col.h, 1, col.key);
            }
            col = {b, 1, key};
            m_openCols |= 1u << c;
            return true;
        }
        return false;
    }
    // Emits the runs still open.
    void finish() {
        if (m_rowW > 0) emit(m_rowB, m_rowC, 1, m_rowW, m_rowKey);
        m_rowW = 0;
        for (; m_openCols != 0; m_openCols &= m_openCols - 1) {
            const int c = std::countr_zero(m_openCols);
            emit(m_cols[c].b, c, m_cols[c].h, 1, m_cols[c].key);
        }
    }

private:
    void emit(int b, int c, int h, int w, unsigned key) {
        const std::uint32_t light = (key >> 16) * 0x01010101u;
        if (h * w == 1) {
            m_out.unitQuad<D>(m_words, m_a, b, c, key & 255u, key >> 8 & 255u, light);
        } else {
            m_out.quad<D>(m_a, b, c, h, w, key & 255u, key >> 8 & 255u, light);
        }
    }
    struct Column {
        int b, h;
        unsigned key;
    };
    QuadSink& m_out;
    const QuadSink::UnitWords& m_words;
    int m_a;
    int m_rowB = 0, m_rowC = 0, m_rowW = 0; // the open run along c
    unsigned m_rowKey = 0;
    std::uint32_t m_openCols = 0; // bit c: m_cols[c] holds an open run along b
    Column m_cols[kN];
};

// One slice of direction D. `open`: faces whose air-side neighbourhood is empty and under the open sky
// (all corners lit, no shade); `other`: the remaining visible faces (with Shading::Flat, those whose
// air-side voxel is not under the open sky, lit flat by it). Both are consumed (left all zero).
// liveOpen, liveOther: bit b set where open[b], other[b] may be non-zero.
template <int D, Shading S, bool Lit>
void meshSlice(const PaddedChunk& in, const SolidRows& s, const SolidRows& shade, QuadSink& out, int a, std::uint32_t (&open)[kN],
               std::uint32_t (&other)[kN], std::uint32_t liveOpen, std::uint32_t liveOther) {
    const auto* blocks = reinterpret_cast<const unsigned char*>(in.blocks.data());
    const std::uint8_t* tiles = faceTiles().t[D];
    const auto blockAt = [&](int b, int c) { return blocks[paddedIndex<D>(a, b, c)]; };
    const auto keyAt = [&](int b, int c) {
        const unsigned char block = blockAt(b, c);
        return TileKey{block, tiles[block]};
    };
    const auto same = [&](TileKey key, int b, int c) {
        const unsigned char block = blockAt(b, c);
        return block == key.block || tiles[block] == key.tile;
    };
    const auto emitOpen = [&](int b, int c, int h, int w, TileKey key) {
        out.quad<D>(a, b, c, h, w, key.tile, kAoOpen, kLightOpen);
    };
    const std::uint8_t* level = in.light.level.data();
    constexpr int kFront = (kDirs[D].positive ? 1 : -1) * kStride[kDirs[D].a]; // to the air-side voxel
    const auto mergeOpen = [&] {
        if constexpr (kDirs[D].c == 0) {
            bitwiseTileMerge<D>(blocks, tiles, a, open, liveOpen, emitOpen);
        } else {
            greedyMerge(open, liveOpen, keyAt, same, emitOpen);
        }
    };
    if constexpr (S == Shading::Flat) {
        mergeOpen();
        if (!Lit || liveOther == 0) return;
        // Flat light, from the air-side voxel: faces merge by tile and that light.
        std::uint16_t flat[kN][kN];
        for (std::uint32_t l = liveOther; l != 0; l &= l - 1) {
            const int b = std::countr_zero(l);
            for (std::uint32_t m = other[b]; m != 0; m &= m - 1) {
                const int c = std::countr_zero(m);
                const int at = paddedIndex<D>(a, b, c);
                flat[b][c] = static_cast<std::uint16_t>(tiles[blocks[at]] | level[at + kFront] << 8);
            }
        }
        greedyMerge(
            other, liveOther, [&](int b, int c) { return flat[b][c]; },
            [&](std::uint16_t key, int b, int c) { return flat[b][c] == key; },
            [&](int b, int c, int h, int w, std::uint16_t key) {
                out.quad<D>(a, b, c, h, w, key & 255u, kAoOpen, (key >> 8) * 0x01010101u);
            });
        return;
    }

    const QuadSink::UnitWords& unitWords = QuadSink::unitWords<D>();
    std::uint32_t uniform[kN] = {};
    std::uint16_t keys[kN][kN]; // tile | ao << 4 | light << 8, valid where `uniform` has the bit
    std::uint32_t liveUniform = 0;
    StripRuns<D> strips(out, unitWords, a);
    for (; liveOther != 0; liveOther &= liveOther - 1) {
        const int b = std::countr_zero(liveOther);
        const RowNeighbours<D> around(s, a, b);
        const RowNeighbours<D> shaded(shade, a, b);
        for (std::uint32_t m = other[b]; m != 0; m &= m - 1) {
            const int c = std::countr_zero(m);
            const unsigned pattern = around.pattern(c);
            const unsigned ao = kAoTable[pattern];
            const int at = paddedIndex<D>(a, b, c);
            const std::uint8_t tile = tiles[blocks[at]];
            // Every corner averages open-sky voxels only, unless a voxel of the 3x3 has other light.
            const std::uint32_t light =
                Lit && shaded.any(c) ? faceLight<D>(level, at + kFront, pattern) : kLightOpen;
            const bool even = evenLight(light);
            if (even && uniformAo(ao)) {
                uniform[b] |= 1u << c;
                keys[b][c] = static_cast<std::uint16_t>(tile | (ao & 3u) << 4 | (light & 255u) << 8);
                liveUniform |= 1u << b;
            } else if (S != Shading::Strips || !even || !strips.add(b, c, tile, ao, light & 255u)) {
                out.unitQuad<D>(unitWords, a, b, c, tile, ao, light);
            }
        }
        other[b] = 0;
    }
    mergeOpen();
    if constexpr (S == Shading::Strips) strips.finish();
    if (liveUniform != 0) {
        // Faces with no uniform neighbour in the slice cannot merge: emit them straight away (this is
        // every face of the checkerboard worst case).
        std::uint32_t isolated[kN];
        for (int b = 0; b < kN; ++b) {
            const std::uint32_t u = uniform[b];
            const std::uint32_t around =
                (u << 1) | (u >> 1) | (b > 0 ? uniform[b - 1] : 0u) | (b + 1 < kN ? uniform[b + 1] : 0u);
            isolated[b] = u & ~around;
        }
        for (int b = 0; b < kN; ++b) {
            uniform[b] &= ~isolated[b];
            for (std::uint32_t m = isolated[b]; m != 0; m &= m - 1) {
                const int c = std::countr_zero(m);
                const unsigned key = keys[b][c];
                out.unitQuad<D>(unitWords, a, b, c, key & 15u, (key >> 4 & 3u) * 0x55u, (key >> 8) * 0x01010101u);
            }
        }
        greedyMerge(
            uniform, liveUniform, [&](int b, int c) { return keys[b][c]; },
            [&](std::uint16_t key, int b, int c) { return keys[b][c] == key; },
            [&](int b, int c, int h, int w, std::uint16_t key) {
                out.quad<D>(a, b, c, h, w, key & 15u, (key >> 4 & 3u) * 0x55u, (key >> 8) * 0x01010101u);
            });
    }
}

// What each horizontal layer (padded y, one bit each) can hold, so that layers of only air or only
// solid (most of a terrain chunk above or below the surface) are skipped whole.
struct Layers {
    std::uint64_t withSolid = 0;  // the inner 32 x 32 has a solid block: faces can start here
    std::uint64_t innerFull = 0;  // the inner 32 x 32 is all solid: no Y face can open onto it
    std::uint64_t paddedFull = 0; // all 34 x 34 solid: no X or Z face in this layer
    std::uint64_t sides() const { return withSolid & ~paddedFull; }
};

Layers layersOf(const SolidRows& s) {
    Layers l;
    for (int y = 0; y < kP; ++y) {
        Row any = 0, inner = kRowMask, all = kRowMask;
        for (int z = 1; z <= kN; ++z) {
            any |= s[y][z];
            inner &= s[y][z] | ~kInner;
            all &= s[y][z];
        }
        all &= s[y][0] & s[y][kP - 1];
        const std::uint64_t bit = std::uint64_t{1} << y;
        if ((any & kInner) != 0 && y >= 1 && y <= kN) l.withSolid |= bit;
        if ((inner & kRowMask) == kRowMask) l.innerFull |= bit;
        if (all == kRowMask) l.paddedFull |= bit;
    }
    return l;
}

// Bit b set where rows[b] != 0.
std::uint32_t nonZeroRows(const std::uint32_t (&rows)[kN]) {
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    std::uint32_t empty = 0;
    for (int b = 0; b < kN; b += 4) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(rows + b));
        empty |= static_cast<std::uint32_t>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(v, zero)))) << b;
    }
    return ~empty;
#else
    std::uint32_t live = 0;
    for (int b = 0; b < kN; ++b) live |= static_cast<std::uint32_t>(rows[b] != 0) << b;
    return live;
#endif
}

// Y and Z faces: their slices are read directly from the x rows.
template <int D, Shading S, bool Lit>
void meshYZ(const PaddedChunk& in, const SolidRows& s, const SolidRows& sh, QuadSink& out, const Layers& layers) {
    constexpr DirInfo di = kDirs[D];
    static_assert(di.c == 0);
    constexpr int step = di.positive ? 1 : -1;
    // Y: slices (padded y) with solid blocks whose neighbouring layer is not all solid. Z: rows
    // (padded y) whose layer has both solid and air.
    const std::uint64_t yOpenBelowOrAbove = step > 0 ? ~(layers.innerFull >> 1) : ~(layers.innerFull << 1);
    const std::uint64_t ySlices = di.a == 1 ? (layers.withSolid & yOpenBelowOrAbove) >> 1 : 0;
    const auto zRows = static_cast<std::uint32_t>(layers.sides() >> 1);
    if (di.a == 1 ? ySlices == 0 : zRows == 0) return;
    for (int a = 0; a < kN; ++a) {
        if (di.a == 1 && (ySlices >> a & 1u) == 0) continue;
        // Every row is written (a Z row outside zRows has no face either: its layer is all air inside
        // or all solid), branch-free so that the compiler vectorises the loop.
        std::uint32_t open[kN], other[kN];
        const int pa = a + 1;
        for (int b = 0; b < kN; ++b) {
            const int pb = b + 1;
            // near: where the air side's neighbourhood is not all open air under the open sky (with
            // Shading::Flat, where the air-side voxel is not under the open sky).
            Row face, near;
            if constexpr (di.a == 1) { // Y: slice y, rows z
                face = s[pa][pb] & ~s[pa + step][pb] & kInner;
                if constexpr (S != Shading::Flat) {
                    near = s[pa + step][pb - 1] | s[pa + step][pb] | s[pa + step][pb + 1];
                    if constexpr (Lit) near |= sh[pa + step][pb - 1] | sh[pa + step][pb] | sh[pa + step][pb + 1];
                    near = spread(near);
                } else {
                    near = Lit ? sh[pa + step][pb] : 0;
                }
            } else { // Z: slice z, rows y
                face = s[pb][pa] & ~s[pb][pa + step] & kInner;
                if constexpr (S != Shading::Flat) {
                    near = s[pb - 1][pa + step] | s[pb][pa + step] | s[pb + 1][pa + step];
                    if constexpr (Lit) near |= sh[pb - 1][pa + step] | sh[pb][pa + step] | sh[pb + 1][pa + step];
                    near = spread(near);
                } else {
                    near = Lit ? sh[pb][pa + step] : 0;
                }
            }
            open[b] = static_cast<std::uint32_t>((face & ~near) >> 1);
            other[b] = static_cast<std::uint32_t>((face & near) >> 1);
        }
        const std::uint32_t liveOpen = nonZeroRows(open);
        const std::uint32_t liveOther = nonZeroRows(other);
        if ((liveOpen | liveOther) != 0) meshSlice<D, S, Lit>(in, s, sh, out, a, open, other, liveOpen, liveOther);
    }
}

// X faces: found along the x rows, then scattered into x slices (rows y, bits z). meshSlice leaves
// every slice it consumes zeroed, so the workspace is cleared once per thread, not once per chunk.
struct XSlices {
    std::uint32_t open[2][kN][kN];
    std::uint32_t other[2][kN][kN];
};

// Sets bit zBit of row b in the slice of each face in `bits` (padded x).
void scatterBits(Row bits, std::uint32_t (&slices)[kN][kN], int b, std::uint32_t zBit) {
    for (; bits != 0; bits &= bits - 1) slices[std::countr_zero(bits) - 1][b] |= zBit;
}

template <Shading S, bool Lit>
void meshX(const PaddedChunk& in, const SolidRows& s, const SolidRows& sh, QuadSink& out, XSlices& xs,
           const Layers& layers) {
    Row used[2] = {0, 0}; // padded bit x: slice x - 1 has faces
    for (std::uint64_t ys = layers.sides(); ys != 0; ys &= ys - 1) {
        const int py = std::countr_zero(ys);
        for (int pz = 1; pz <= kN; ++pz) {
            const Row row = s[py][pz];
            const Row pos = row & ~(row >> 1) & kInner;
            const Row neg = row & ~(row << 1) & kInner;
            if ((pos | neg) == 0) continue;
            used[0] |= pos;
            used[1] |= neg;
            const std::uint32_t zBit = 1u << (pz - 1);
            Row near = 0; // as in meshYZ, the air side's column at each x (shifted to the face's x below)
            if constexpr (S == Shading::Flat) {
                near = Lit ? sh[py][pz] : 0;
            } else {
                for (int dy = -1; dy <= 1; ++dy) {
                    near |= s[py + dy][pz - 1] | s[py + dy][pz] | s[py + dy][pz + 1];
                    if constexpr (Lit) near |= sh[py + dy][pz - 1] | sh[py + dy][pz] | sh[py + dy][pz + 1];
                }
            }
            scatterBits(pos & ~(near >> 1), xs.open[0], py - 1, zBit);
            scatterBits(pos & (near >> 1), xs.other[0], py - 1, zBit);
            scatterBits(neg & ~(near << 1), xs.open[1], py - 1, zBit);
            scatterBits(neg & (near << 1), xs.other[1], py - 1, zBit);
        }
    }
    for (Row m = used[0]; m != 0; m &= m - 1) {
        const int x = std::countr_zero(m) - 1;
        meshSlice<kFacePosX, S, Lit>(in, s, sh, out, x, xs.open[0][x], xs.other[0][x], nonZeroRows(xs.open[0][x]),
                                nonZeroRows(xs.other[0][x]));
    }
    for (Row m = used[1]; m != 0; m &= m - 1) {
        const int x = std::countr_zero(m) - 1;
        meshSlice<kFaceNegX, S, Lit>(in, s, sh, out, x, xs.open[1][x], xs.other[1][x], nonZeroRows(xs.open[1][x]),
                                nonZeroRows(xs.other[1][x]));
    }
}

struct Workspace {
    XSlices x;
    SolidRows solid; // only for a PaddedChunk whose blocks are stale
    SolidRows shade; // the light's shade rows where the blocks are air: what meshing reads
};

template <Shading S, bool Lit>
void meshFaces(const PaddedChunk& in, const SolidRows& s, Workspace& ws, QuadSink& out, const Layers& layers) {
    meshX<S, Lit>(in, s, ws.shade, out, ws.x, layers);
    meshYZ<kFacePosY, S, Lit>(in, s, ws.shade, out, layers);
    meshYZ<kFaceNegY, S, Lit>(in, s, ws.shade, out, layers);
    meshYZ<kFacePosZ, S, Lit>(in, s, ws.shade, out, layers);
    meshYZ<kFaceNegZ, S, Lit>(in, s, ws.shade, out, layers);
}

template <Shading S>
void meshGreedy(const PaddedChunk& in, QuadSink& out) {
    // About 25 KB of scratch, zero between calls: kept per thread rather than on the caller's stack.
    thread_local Workspace ws{};
    if (in.blocks.stale) solidFromBytes(in, ws.solid); // bytes were written directly (tests do)
    const SolidRows& s = in.blocks.stale ? ws.solid : in.solid;
    const Layers layers = layersOf(s);
    if (layers.withSolid == 0) return; // nothing solid inside, nothing to draw
    // Light is read only from voxels that are not solid (a face's air side and the corners' open voxels), and
    // the light inside solid blocks is 0, not the open sky's: left in, it would send every face along the
    // ground down the per-face light path. Masked here, faces beside nothing but sunlit air merge as before light.
    const SolidRows& sh = in.light.shade;
    // A chunk with no such voxel (most of the world's, under the open sky) is meshed by a copy of the mesher
    // that reads no light at all.
    Row anyShade = 0;
    for (int y = 0; y < kP; ++y) {
        for (int z = 0; z < kP; ++z) {
            ws.shade[y][z] = sh[y][z] & ~s[y][z];
            anyShade |= ws.shade[y][z];
        }
    }
    if (anyShade != 0) {
        meshFaces<S, true>(in, s, ws, out, layers);
    } else {
        meshFaces<S, false>(in, s, ws, out, layers);
    }
}

// ---------------------------------------------------------------------------------------------------
// Culled: deliberately the plain per-voxel loop, sharing nothing with the bit tricks above except the
// vertex layout, so that tests can hold the greedy mesher against it.

template <int D>
void emitCulledFace(const PaddedChunk& in, QuadSink& out, int x, int y, int z, BlockType t) {
    constexpr DirInfo di = kDirs[D];
    const int* n = kFaceNormals[D];
    const int q[3] = {x + n[0], y + n[1], z + n[2]};
    if (isSolid(in.get(q[0], q[1], q[2]))) return;
    unsigned pattern = 0;
    for (int db = -1; db <= 1; ++db) {
        for (int dc = -1; dc <= 1; ++dc) {
            int p[3] = {q[0], q[1], q[2]};
            p[di.b] += db;
            p[di.c] += dc;
            if (isSolid(in.get(p[0], p[1], p[2]))) pattern |= 1u << ((dc + 1) + 3 * (db + 1));
        }
    }
    // Smooth light, written out voxel by voxel: per corner, the mean of the voxels that are not solid among
    // the air-side one, the two beside the corner and the diagonal one (not when both beside it are solid).
    const auto lightAt = [&](const int(&p)[3]) {
        return in.light.level[static_cast<std::size_t>(PaddedChunk::index(p[0], p[1], p[2]))];
    };
    std::uint32_t light = 0;
    for (int cb = 0; cb < 2; ++cb) {
        for (int cc = 0; cc < 2; ++cc) {
            int sideC[3] = {q[0], q[1], q[2]}, sideB[3] = {q[0], q[1], q[2]}, diagonal[3] = {q[0], q[1], q[2]};
            sideC[di.c] += 2 * cc - 1;
            sideB[di.b] += 2 * cb - 1;
            diagonal[di.c] += 2 * cc - 1;
            diagonal[di.b] += 2 * cb - 1;
            const bool solidC = isSolid(in.get(sideC[0], sideC[1], sideC[2]));
            const bool solidB = isSolid(in.get(sideB[0], sideB[1], sideB[2]));
            const bool solidD = isSolid(in.get(diagonal[0], diagonal[1], diagonal[2]));
            int sun = lightAt(q) >> 4, block = lightAt(q) & 15, count = 1;
            if (!solidC) sun += lightAt(sideC) >> 4, block += lightAt(sideC) & 15, ++count;
            if (!solidB) sun += lightAt(sideB) >> 4, block += lightAt(sideB) & 15, ++count;
            if (!solidD && !(solidB && solidC)) sun += lightAt(diagonal) >> 4, block += lightAt(diagonal) & 15, ++count;
            const auto mean = [&](int sum) { return static_cast<std::uint32_t>(std::lround(double(sum) / count)); };
            light |= (mean(sun) << 4 | mean(block)) << (8 * (cc + 2 * cb));
        }
    }
    const int pos[3] = {x - 1, y - 1, z - 1};
    out.quad<D>(pos[di.a], pos[di.b], pos[di.c], 1, 1, faceTiles().t[D][static_cast<std::uint8_t>(t)],
                kAoTable[pattern], light);
}

void meshCulled(const PaddedChunk& in, QuadSink& out) {
    for (int y = 1; y <= kN; ++y) {
        for (int z = 1; z <= kN; ++z) {
            for (int x = 1; x <= kN; ++x) {
                const BlockType t = in.get(x, y, z);
                if (!isSolid(t)) continue;
                emitCulledFace<kFacePosX>(in, out, x, y, z, t);
                emitCulledFace<kFaceNegX>(in, out, x, y, z, t);
                emitCulledFace<kFacePosY>(in, out, x, y, z, t);
                emitCulledFace<kFaceNegY>(in, out, x, y, z, t);
                emitCulledFace<kFacePosZ>(in, out, x, y, z, t);
                emitCulledFace<kFaceNegZ>(in, out, x, y, z, t);
            }
        }
    }
}

} // namespace

void coarsenPadded(const PaddedChunk& fine, int factor, PaddedChunk& out) {
    if (factor != 2 && factor != 4) throw std::invalid_argument("coarsenPadded: factor must be 2 or 4");
    if (fine.blocks.stale) throw std::invalid_argument("coarsenPadded: the fine chunk's solid rows are stale");
    std::memcpy(out.blocks.untrackedData(), fine.blocks.data(), PaddedChunk::kVolume);
    std::memcpy(out.solid, fine.solid, sizeof out.solid);
    out.light = fine.light; // the fine voxels' light: a coarse face's air side is air in the fine chunk too
    out.blocks.stale = false;
    const auto* in = reinterpret_cast<const unsigned char*>(fine.blocks.data());
    auto* to = reinterpret_cast<unsigned char*>(out.blocks.untrackedData());
    const Row cellBits = (Row{1} << factor) - 1;
    for (int cy = 1; cy <= kN; cy += factor) {
        for (int cz = 1; cz <= kN; cz += factor) {
            for (int cx = 1; cx <= kN; cx += factor) {
                const Row mask = cellBits << cx;
                unsigned char type = 0; // Air
                for (int y = cy + factor - 1; y >= cy && type == 0; --y) {
                    for (int z = cz; z < cz + factor; ++z) {
                        const Row hit = fine.solid[y][z] & mask;
                        if (hit != 0) {
                            type = in[PaddedChunk::index(std::countr_zero(hit), y, z)];
                            break;
                        }
                    }
                }
                for (int y = cy; y < cy + factor; ++y) {
                    for (int z = cz; z < cz + factor; ++z) {
                        std::memset(to + PaddedChunk::index(cx, y, z), type, static_cast<std::size_t>(factor));
                        out.solid[y][z] = type != 0 ? out.solid[y][z] | mask : out.solid[y][z] & ~mask;
                    }
                }
            }
        }
    }
}

void meshAtDetail(const PaddedChunk& fine, MeshMode mode, int cell, PaddedChunk& scratch, ChunkMesh& out) {
    if (cell > 1) coarsenPadded(fine, cell, scratch);
    meshChunk(cell > 1 ? scratch : fine, out, mode);
}

PlaneOrder sortByPlane(const ChunkMesh& mesh, std::vector<ChunkVertex>& sorted) {
    constexpr int kPlanes = PlaneOrder::kPlanes;
    // Key of a quad: face * kPlanes + plane, from its first vertex (all four share the plane).
    const auto keyOf = [&](std::size_t q) {
        const ChunkVertex& v = mesh.vertices[q * 4];
        const int face = faceOf(v);
        const int axis = face / 2;
        const int plane = axis == 0 ? v.x : axis == 1 ? v.y : v.z;
        if (face >= kFaceCount || plane >= kPlanes) throw std::invalid_argument("sortByPlane: vertex out of range");
        return face * kPlanes + PlaneOrder::slotOf(face, plane);
    };
    PlaneOrder order;
    std::array<int, kFaceCount * kPlanes + 1> next{};
    for (std::size_t q = 0; q < mesh.quadCount(); ++q) ++next[static_cast<std::size_t>(keyOf(q)) + 1];
    for (std::size_t k = 1; k < next.size(); ++k) next[k] += next[k - 1];
    order.start = next;
    sorted.resize(mesh.quadCount() * 4);
    for (std::size_t q = 0; q < mesh.quadCount(); ++q) {
        const auto slot = static_cast<std::size_t>(next[static_cast<std::size_t>(keyOf(q))]++);
        std::memcpy(&sorted[slot * 4], &mesh.vertices[q * 4], 4 * sizeof(ChunkVertex));
    }
    return order;
}

PlaneOrder::Range PlaneOrder::visible(int face, float t) const {
    // Clamped as floats first, so that any camera position converts to an int safely.
    const float c = std::clamp(t, -1.0f, static_cast<float>(kPlanes));
    // Seen from the front are planes p <= floor(t) of a positive face and p >= ceil(t) of a negative
    // one: in slot order, both a run that ends at the last slot.
    const int from = face % 2 == 0 ? std::clamp(kPlanes - 1 - static_cast<int>(std::floor(c)), 0, kPlanes)
                                   : std::clamp(static_cast<int>(std::ceil(c)), 0, kPlanes);
    return {at(face, from), at(face, kPlanes)}; // empty when from == kPlanes
}

void meshChunk(const PaddedChunk& in, ChunkMesh& out, MeshMode mode) {
    out.vertices.clear();
    QuadSink sink(out.vertices);
    if (mode == MeshMode::Culled) {
        meshCulled(in, sink);
    } else {
        if (mode == MeshMode::GreedyStrips) {
            meshGreedy<Shading::Strips>(in, sink);
        } else if (mode == MeshMode::Greedy) {
            meshGreedy<Shading::Uniform>(in, sink);
        } else {
            meshGreedy<Shading::Flat>(in, sink);
        }
    }
}

} // namespace world
