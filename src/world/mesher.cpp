#include "world/mesher.h"

#include <bit>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "world/mesh_culled.h"
#include "world/mesh_light.h"
#include "world/mesh_quads.h"

// How the greedy mesher works, in short:
// 1. One pass turns the padded block bytes into solidity bit rows along x (S[y][z], 34 bits each),
//    which PaddedChunk keeps (padded_chunk.h).
// 2. For each face direction and slice, visible faces are rows of bits: solid here, air on the far
//    side. Y and Z faces come straight out of the x rows; X faces are scattered into slices (their
//    count is proportional to the surface, not to the volume).
// 3. A face whose 3x3 neighbourhood on the air side is empty has all four corners fully lit; that is
//    a few bit operations per row, and covers most faces. Only the others get a per-face look-up of
//    their occlusion, and if their four corners are equal they still merge, keyed by (tile, ao).
// 4. Greedy rectangles per slice: widest run of equal keys along the bits, then grow along the rows.

namespace world {

namespace {

using Row = std::uint64_t;
constexpr Row kRowMask = (Row{1} << kP) - 1;
constexpr Row kInner = kRowMask & ~Row{1} & ~(Row{1} << (kP - 1)); // padded bits 1..32

// Solidity of the padded chunk: bit x of s[y][z] is set when block (x, y, z) is solid.
using SolidRows = Row[kP][kP];
static_assert(std::is_same_v<SolidRows, decltype(PaddedChunk::solid)>);

// What the greedy mesher merges: Flat (no occlusion, each face lit flat by its air-side voxel,
// MeshMode::GreedyFlat), Uniform (faces whose four corners are equal, MeshMode::Greedy) or Strips (besides,
// MeshMode::GreedyStrips).
enum class Shading { Flat, Uniform, Strips };

bool uniformAo(unsigned packed) { return packed == (packed & 3u) * 0x55u; }

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

    // Takes face (b, c), of one light word at every corner, when its (non-uniform) occlusion is constant
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
        const CornerLight light = evenCorners(key >> 16);
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
void meshSlice(const PaddedChunk& in, const SolidRows& s, const SolidRows& shade, QuadSink& out, int a,
               std::uint32_t (&open)[kN], std::uint32_t (&other)[kN], std::uint32_t liveOpen, std::uint32_t liveOther) {
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
    const std::uint16_t* level = in.light.level.data();
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
        std::uint32_t flat[kN][kN]; // tile | light << 16
        for (std::uint32_t l = liveOther; l != 0; l &= l - 1) {
            const int b = std::countr_zero(l);
            for (std::uint32_t m = other[b]; m != 0; m &= m - 1) {
                const int c = std::countr_zero(m);
                const int at = paddedIndex<D>(a, b, c);
                flat[b][c] = tiles[blocks[at]] | std::uint32_t{level[at + kFront]} << 16;
            }
        }
        greedyMerge(
            other, liveOther, [&](int b, int c) { return flat[b][c]; },
            [&](std::uint32_t key, int b, int c) { return flat[b][c] == key; },
            [&](int b, int c, int h, int w, std::uint32_t key) {
                out.quad<D>(a, b, c, h, w, key & 255u, kAoOpen, evenCorners(key >> 16));
            });
        return;
    }

    const QuadSink::UnitWords& unitWords = QuadSink::unitWords<D>();
    std::uint32_t uniform[kN] = {};
    std::uint32_t keys[kN][kN]; // tile | ao << 8 | light << 16, valid where `uniform` has the bit
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
            const CornerLight light = Lit && shaded.any(c) ? faceLight<D>(level, at + kFront, pattern) : kLightOpen;
            const bool even = evenLight(light);
            if (even && uniformAo(ao)) {
                uniform[b] |= 1u << c;
                keys[b][c] = tile | (ao & 3u) << 8 | static_cast<std::uint32_t>(light & 0xFFFFu) << 16;
                liveUniform |= 1u << b;
            } else if (S != Shading::Strips || !even || !strips.add(b, c, tile, ao, light & 0xFFFFu)) {
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
                const std::uint32_t key = keys[b][c];
                out.unitQuad<D>(unitWords, a, b, c, key & 255u, (key >> 8 & 3u) * 0x55u, evenCorners(key >> 16));
            }
        }
        greedyMerge(
            uniform, liveUniform, [&](int b, int c) { return keys[b][c]; },
            [&](std::uint32_t key, int b, int c) { return keys[b][c] == key; },
            [&](int b, int c, int h, int w, std::uint32_t key) {
                out.quad<D>(a, b, c, h, w, key & 255u, (key >> 8 & 3u) * 0x55u, evenCorners(key >> 16));
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

// Aligned explicitly: GCC vectorises the loops over these rows assuming the alignment it gives large objects
// (16 or 32 bytes) while the thread-local section it emits for them asked only for the members' 8, and the
// -march=x86-64-v3 build then faulted on an aligned store into `shade` (meshBench, seed 1).
struct alignas(64) Workspace {
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
    // ground down the per-face light path. Masked here, faces beside nothing but sunlit air merge by tile alone.
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

} // namespace

void meshChunk(const PaddedChunk& in, ChunkMesh& out, MeshMode mode) {
    out.vertices.clear();
    if (mode == MeshMode::Culled) {
        detail::meshCulled(in, out.vertices); // mesh_culled.cpp, with a QuadSink of its own
    } else {
        QuadSink sink(out.vertices);
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
