#include "world/terrain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <stb/stb_perlin.h>

#include "core/rng.h"

namespace world {

namespace {

// Heights stay inside [kMinHeight, kMaxHeight] so the tallest tree (trunk 6, leaves one above)
// always fits below kWorldHeight and the bottom layer is never exposed.
constexpr int kMinHeight = 6;
constexpr int kMaxHeight = 116;
constexpr int kSandBelow = 34; // columns lower than this are beach
constexpr int kSnowLine = 80;  // plus a per-column jitter of 0..3, so the snowline is ragged
constexpr float kHillScale = 1.0f / 192.0f;
constexpr float kGravelScale = 1.0f / 24.0f;
constexpr float kGravelThreshold = 0.42f;

// Trees: at most one per kTreeCell x kTreeCell cell, rooted at an offset 0..kTreeJitter-1 inside it,
// so two trunks are always at least two columns apart and never touch, not even diagonally.
constexpr int kTreeCell = 5;
constexpr int kTreeJitter = 4;
static_assert(kTreeJitter <= kTreeCell - 1, "trunks in neighbouring cells must keep a gap");
constexpr int kTreeChancePercent = 38;
constexpr int kMinTrunk = 4;
constexpr int kMaxTrunk = 6;
constexpr int kLeafRadius = 2;     // how far leaves reach sideways from the trunk
constexpr int kLeafAboveTrunk = 1; // leaves reach one block above the top log
static_assert(kMaxHeight + kMaxTrunk + kLeafAboveTrunk < kWorldHeight);

// Salts keep the per-purpose hash streams independent of each other.
constexpr std::uint64_t kSaltFrame = 0x7465727261696E31ull;
constexpr std::uint64_t kSaltColumn = 0x636F6C756D6E7331ull;
constexpr std::uint64_t kSaltTree = 0x7472656573313233ull;
constexpr std::uint64_t kSaltLeaf = 0x6C65617665733132ull;

// stb_perlin repeats every 256 units and its seed argument keeps only 8 bits, so the seed instead
// picks where in that period we sample: offsets in x and z, and which 2D slice (y) of the 3D noise.
struct NoiseFrame {
    float hillX, hillY, hillZ;
    float gravelX, gravelY, gravelZ;
};

float periodOffset(std::uint64_t bits) {
    return static_cast<float>(bits & 0xFFFFFu) * (256.0f / 1048576.0f); // [0, 256), 20 bits
}

NoiseFrame noiseFrame(std::uint64_t seed) {
    const std::uint64_t a = core::mix64(seed ^ kSaltFrame);
    const std::uint64_t b = core::mix64(a);
    return {periodOffset(a), periodOffset(a >> 20), periodOffset(a >> 40),
            periodOffset(b), periodOffset(b >> 20), periodOffset(b >> 40)};
}

struct Column {
    int height; // y of the top block
    BlockType top;
    BlockType filler; // the layer under the top, fillerDepth blocks thick; stone below
    int fillerDepth;
};

// Out of line on purpose: every caller must get bit-identical floats for the same column, which an
// inlined copy compiled with different contraction or vectorisation might not give.
[[gnu::noinline]] int hillHeight(const NoiseFrame& f, int x, int z) {
    const float fx = static_cast<float>(x) * kHillScale + f.hillX;
    const float fz = static_cast<float>(z) * kHillScale + f.hillZ;
    const float n = stb_perlin_fbm_noise3(fx, f.hillY, fz, 2.0f, 0.5f, 5);
    // Lowlands stay gentle; the square of the positive part lifts hills into mountains.
    const float lifted = n + 0.9f * std::max(n, 0.0f) * std::max(n, 0.0f);
    const int h = static_cast<int>(std::floor(53.0f + 40.0f * lifted));
    return std::clamp(h, kMinHeight, kMaxHeight);
}

[[gnu::noinline]] bool gravelPatch(const NoiseFrame& f, int x, int z) {
    const float fx = static_cast<float>(x) * kGravelScale + f.gravelX;
    const float fz = static_cast<float>(z) * kGravelScale + f.gravelZ;
    return stb_perlin_noise3(fx, f.gravelY, fz, 0, 0, 0) > kGravelThreshold;
}

Column column(const TerrainDef& def, const NoiseFrame& f, int x, int z) {
    if (def.kind == TerrainKind::Flat) return {kFlatSurface, BlockType::Grass, BlockType::Dirt, 3};
    const int h = hillHeight(f, x, z);
    const std::uint64_t r = core::hashCoords(def.seed ^ kSaltColumn, x, 0, z);
    const int dirtDepth = 3 + static_cast<int>(r & 1u);
    if (h < kSandBelow) return {h, BlockType::Sand, BlockType::Sand, 3};
    if (h >= kSnowLine + static_cast<int>((r >> 1) & 3u)) return {h, BlockType::Snow, BlockType::Dirt, dirtDepth};
    if (gravelPatch(f, x, z)) return {h, BlockType::Gravel, BlockType::Gravel, 2};
    return {h, BlockType::Grass, BlockType::Dirt, dirtDepth};
}

// The columns of a box's footprint in x and z. Every chunk of one column of the world (kWorldHeightChunks
// of them, generated at different times, by the mesh worker as padded boxes or by the World as chunks)
// has the same footprint, and the columns' noise is most of the cost of generating one, so the last
// few footprints are kept per thread and a box stacked on one of them reuses its columns. A pure
// function of the terrain and the footprint: a kept one is exactly what computing it again gives.
struct Footprint {
    std::uint64_t seed = 0;
    TerrainKind kind = TerrainKind::Default;
    int x = 0, z = 0, sizeX = 0, sizeZ = 0;
    std::uint64_t lastUse = 0;   // 0: empty
    int minHeight = 0;           // of the columns' tops
    int maxHeight = 0;           // of the columns' tops: above it, air
    int stoneBelow = 0;          // the lowest top of a filler layer: below it, stone
    std::vector<Column> columns; // x + sizeX * z
    // The same columns by field, a byte each, for generateBox's rows: one more than the height and than where
    // the filler starts, clamped to [0, kWorldHeight + 1] (no y of the world tells those apart from the true
    // values), and the top and filler blocks.
    std::vector<std::uint8_t> heights, fillerFrom;
    std::vector<BlockType> tops, fillers;
};
constexpr int kKeptFootprints = 64;    // 16 were too few for a queue that reached a column's chunks apart
constexpr int kKeepFromArea = 16 * 16; // single blocks and one-block slabs are not kept
// Nor a light region's box (94 x 94 columns, 141 KB), generated once a relight: 64 of them kept were 9 MB a
// thread of columns that the tiles hold anyway. Footprints this large or larger are copied from the tiles into
// one slot of their own.
constexpr int kKeepBelowArea = 48 * 48;

// The columns of one chunk column's footprint (a tile, kChunkSize square, aligned): a footprint's columns are
// copied from the tiles it overlaps, so the noise of a column is computed about once however many boxes overlap
// it (a light region's box spans sixteen tiles, and its neighbours' share twelve of them). Tiles are kept for all
// threads together (the mesh worker and the render thread stream the same view, and with a cache each they
// computed most tiles twice: 4.5 times the tiles of a radius-32 view in all), set-associative: kWays slots in
// each of kSets sets, the one used longest ago replaced. A tile is a pure function of the terrain and its place,
// so whichever thread computed a kept tile, its columns are what computing them again gives; two threads missing
// the same tile at once both compute it, and either copy is kept.
struct SharedTiles {
    static constexpr int kWays = 4;
    static constexpr int kSets = 256; // 1,024 tiles of 12 KB: 12 MB
    struct Slot {
        std::uint64_t seed = 0;
        TerrainKind kind = TerrainKind::Default;
        int x = 0, z = 0;                                   // in tiles
        std::uint64_t lastUse = 0;                          // 0: empty
        std::shared_ptr<const std::vector<Column>> columns; // x + kChunkSize * z
    };
    std::mutex mutex;
    std::uint64_t clock = 0;
    std::array<Slot, static_cast<std::size_t>(kWays) * kSets> slots;
};

std::shared_ptr<const std::vector<Column>> tileAt(const TerrainDef& def, const NoiseFrame& frame, int tx, int tz) {
    static SharedTiles shared;
    const std::uint64_t h = core::hashCoords(def.seed ^ static_cast<std::uint64_t>(def.kind), tx, 0, tz);
    SharedTiles::Slot* const set = &shared.slots[static_cast<std::size_t>(h % SharedTiles::kSets) * SharedTiles::kWays];
    const auto matches = [&](const SharedTiles::Slot& s) {
        return s.lastUse != 0 && s.seed == def.seed && s.kind == def.kind && s.x == tx && s.z == tz;
    };
    {
        const std::lock_guard lock(shared.mutex);
        for (int w = 0; w < SharedTiles::kWays; ++w) {
            if (matches(set[w])) {
                set[w].lastUse = ++shared.clock;
                return set[w].columns;
            }
        }
    }
    // Computed outside the lock: the noise is the cost, and the other thread may need another tile meanwhile.
    auto columns = std::make_shared<std::vector<Column>>(static_cast<std::size_t>(kChunkSize) * kChunkSize);
    for (int z = 0; z < kChunkSize; ++z) {
        for (int x = 0; x < kChunkSize; ++x) {
            (*columns)[static_cast<std::size_t>(x) +
                       static_cast<std::size_t>(kChunkSize) * static_cast<std::size_t>(z)] =
                column(def, frame, tx * kChunkSize + x, tz * kChunkSize + z);
        }
    }
    const std::lock_guard lock(shared.mutex);
    SharedTiles::Slot* slot = &set[0];
    for (int w = 0; w < SharedTiles::kWays; ++w) {
        if (matches(set[w])) { // the other thread kept it meanwhile: the same columns
            slot = &set[w];
            break;
        }
        if (set[w].lastUse < slot->lastUse) slot = &set[w];
    }
    *slot = {def.seed, def.kind, tx, tz, ++shared.clock, columns};
    return columns;
}

const Footprint& footprint(const TerrainDef& def, const NoiseFrame& frame, int x0, int z0, int sizeX, int sizeZ) {
    // kept[kKeptFootprints]: small footprints, not kept; kept[kKeptFootprints + 1]: large ones, not kept.
    thread_local std::array<Footprint, kKeptFootprints + 2> kept;
    thread_local std::uint64_t clock = 0;
    const bool large = sizeX * sizeZ >= kKeepBelowArea;
    Footprint* f = &kept[large ? kKeptFootprints + 1 : kKeptFootprints];
    if (sizeX * sizeZ >= kKeepFromArea && !large) {
        Footprint* oldest = &kept[0];
        for (int i = 0; i < kKeptFootprints; ++i) {
            Footprint& k = kept[static_cast<std::size_t>(i)];
            if (k.lastUse != 0 && k.seed == def.seed && k.kind == def.kind && k.x == x0 && k.z == z0 &&
                k.sizeX == sizeX && k.sizeZ == sizeZ) {
                k.lastUse = ++clock;
                return k;
            }
            if (k.lastUse < oldest->lastUse) oldest = &k;
        }
        f = oldest;
    }
    f->lastUse = 0; // empty until its columns are all computed: a throw below leaves no wrong slot
    const std::size_t area = static_cast<std::size_t>(sizeX) * static_cast<std::size_t>(sizeZ);
    f->columns.resize(area);
    f->heights.resize(area);
    f->fillerFrom.resize(area);
    f->tops.resize(area);
    f->fillers.resize(area);
    f->minHeight = f->stoneBelow = kWorldHeight;
    f->maxHeight = -1;
    const auto put = [&](int x, int z, const Column& c) {
        const std::size_t i =
            static_cast<std::size_t>(x) + static_cast<std::size_t>(sizeX) * static_cast<std::size_t>(z);
        const auto clamped = [](int y) { return static_cast<std::uint8_t>(std::clamp(y + 1, 0, kWorldHeight + 1)); };
        static_assert(kWorldHeight + 1 <= 255);
        f->columns[i] = c;
        f->heights[i] = clamped(c.height);
        f->fillerFrom[i] = clamped(c.height - c.fillerDepth);
        f->tops[i] = c.top;
        f->fillers[i] = c.filler;
        f->minHeight = std::min(f->minHeight, c.height);
        f->maxHeight = std::max(f->maxHeight, c.height);
        f->stoneBelow = std::min(f->stoneBelow, c.height - c.fillerDepth);
    };
    if (f == &kept[kKeptFootprints]) { // a small box: its own columns
        for (int z = 0; z < sizeZ; ++z) {
            for (int x = 0; x < sizeX; ++x) put(x, z, column(def, frame, x0 + x, z0 + z));
        }
    } else { // from the tiles it overlaps
        for (int tz = floorDiv(z0, kChunkSize); tz <= floorDiv(z0 + sizeZ - 1, kChunkSize); ++tz) {
            for (int tx = floorDiv(x0, kChunkSize); tx <= floorDiv(x0 + sizeX - 1, kChunkSize); ++tx) {
                const std::shared_ptr<const std::vector<Column>> tile = tileAt(def, frame, tx, tz);
                const int ox = tx * kChunkSize, oz = tz * kChunkSize;
                for (int z = std::max(z0, oz); z < std::min(z0 + sizeZ, oz + kChunkSize); ++z) {
                    for (int x = std::max(x0, ox); x < std::min(x0 + sizeX, ox + kChunkSize); ++x) {
                        const auto at = static_cast<std::size_t>(x - ox) +
                                        static_cast<std::size_t>(kChunkSize) * static_cast<std::size_t>(z - oz);
                        put(x - x0, z - z0, (*tile)[at]);
                    }
                }
            }
        }
    }
    f->seed = def.seed;
    f->kind = def.kind;
    f->x = x0, f->z = z0, f->sizeX = sizeX, f->sizeZ = sizeZ;
    if (f < &kept[kKeptFootprints]) f->lastUse = ++clock;
    return *f;
}

struct Tree {
    int x, z;   // trunk column
    int ground; // y of the grass block the trunk stands on
    int trunk;  // number of log blocks
};

// The tree whose root lies in cell (cx, cz), if any. `columnAt` supplies column data so callers that
// already computed a column do not pay for the noise twice.
template <typename ColumnAt>
std::optional<Tree> treeInCell(const TerrainDef& def, int cx, int cz, ColumnAt&& columnAt) {
    const std::uint64_t r = core::hashCoords(def.seed ^ kSaltTree, cx, 0, cz);
    if (r % 100u >= static_cast<std::uint64_t>(kTreeChancePercent)) return std::nullopt;
    const int x = cx * kTreeCell + static_cast<int>((r >> 8) % kTreeJitter);
    const int z = cz * kTreeCell + static_cast<int>((r >> 16) % kTreeJitter);
    const Column c = columnAt(x, z);
    if (c.top != BlockType::Grass) return std::nullopt;
    return Tree{x, z, c.height, kMinTrunk + static_cast<int>((r >> 24) % (kMaxTrunk - kMinTrunk + 1))};
}

// What the tree puts at offset (dx, y, dz) from its trunk column, or Air. Corners of the lower leaf
// layer are dropped by a positional hash, so crowns vary without any state.
BlockType treeBlock(const TerrainDef& def, const Tree& t, int dx, int y, int dz) {
    const int top = t.ground + t.trunk;
    if (dx == 0 && dz == 0 && y > t.ground && y <= top) return BlockType::Log;
    const int ax = dx < 0 ? -dx : dx, az = dz < 0 ? -dz : dz;
    const int ly = y - top;
    bool leaf = false;
    if (ly == -2 || ly == -1) {
        leaf = ax <= 2 && az <= 2;
        if (ax == 2 && az == 2) {
            leaf = ly == -2 && (core::hashCoords(def.seed ^ kSaltLeaf, t.x + dx, y, t.z + dz) & 1u) != 0;
        }
    } else if (ly == 0) {
        leaf = ax <= 1 && az <= 1;
    } else if (ly == 1) {
        leaf = ax + az <= 1;
    }
    return leaf ? BlockType::Leaves : BlockType::Air;
}

} // namespace

std::optional<TerrainKind> terrainFromName(std::string_view name) {
    if (name == "default") return TerrainKind::Default;
    if (name == "flat") return TerrainKind::Flat;
    return std::nullopt;
}

std::string_view terrainName(TerrainKind kind) {
    switch (kind) {
    case TerrainKind::Default:
        return "default";
    case TerrainKind::Flat:
        return "flat";
    }
    return "default";
}

void generateBox(const TerrainDef& def, glm::ivec3 origin, glm::ivec3 size, BlockType* out) {
    if (size.x <= 0 || size.y <= 0 || size.z <= 0) return;
    const NoiseFrame frame = noiseFrame(def.seed);
    const auto at = [&](int x, int y, int z) -> BlockType& {
        return out[static_cast<std::size_t>(x + size.x * (z + size.z * y))];
    };

    // Columns once per box, not per voxel: the noise is the expensive part.
    const Footprint& foot = footprint(def, frame, origin.x, origin.z, size.x, size.z);
    const std::vector<Column>& columns = foot.columns;
    const int minHeight = foot.minHeight;

    for (int y = 0; y < size.y; ++y) {
        const int wy = origin.y + y;
        for (int z = 0; z < size.z; ++z) {
            BlockType* dst = &at(0, y, z);
            if (wy < 0 || wy < foot.stoneBelow) { // under every column's filler
                std::fill(dst, dst + size.x, BlockType::Stone);
            } else if (wy >= kWorldHeight || wy > foot.maxHeight) { // over every column's top
                std::fill(dst, dst + size.x, BlockType::Air);
            } else {
                // What each column holds at this height: air above its top, its top block, its filler for
                // fillerDepth blocks under that, stone below. As selects the compiler vectorises: which of
                // them a column has is unpredictable along an uneven surface.
                const std::size_t at = static_cast<std::size_t>(size.x) * static_cast<std::size_t>(z);
                const std::uint8_t* __restrict height = foot.heights.data() + at; // one more than the heights
                const std::uint8_t* __restrict fillerFrom = foot.fillerFrom.data() + at;
                const auto* __restrict top = reinterpret_cast<const std::uint8_t*>(foot.tops.data() + at);
                const auto* __restrict filler = reinterpret_cast<const std::uint8_t*>(foot.fillers.data() + at);
                auto* __restrict bytes = reinterpret_cast<std::uint8_t*>(dst);
                const auto y = static_cast<std::uint8_t>(wy + 1); // wy is inside the world here
                for (int x = 0; x < size.x; ++x) {
                    const auto mask = [](bool b) { return static_cast<std::uint8_t>(0u - static_cast<unsigned>(b)); };
                    const std::uint8_t inFiller = mask(y >= fillerFrom[x]), atTop = mask(y == height[x]);
                    const std::uint8_t below = mask(y <= height[x]);
                    const auto stone = static_cast<std::uint8_t>(BlockType::Stone);
                    std::uint8_t b = static_cast<std::uint8_t>((filler[x] & inFiller) | (stone & ~inFiller));
                    b = static_cast<std::uint8_t>((top[x] & atTop) | (b & ~atTop));
                    static_assert(static_cast<int>(BlockType::Air) == 0);
                    bytes[x] = static_cast<std::uint8_t>(b & below); // air above the top
                }
            }
        }
    }

    // Trees only fill air above their own ground, so a box that is solid terrain all the way up
    // cannot contain any part of one.
    if (def.kind == TerrainKind::Flat) return;
    const int boxTop = std::min(origin.y + size.y, kWorldHeight) - 1;
    if (boxTop <= minHeight) return;

    const auto columnAt = [&](int wx, int wz) {
        const int lx = wx - origin.x, lz = wz - origin.z;
        if (lx >= 0 && lx < size.x && lz >= 0 && lz < size.z)
            return columns[static_cast<std::size_t>(lx) +
                           static_cast<std::size_t>(size.x) * static_cast<std::size_t>(lz)];
        return column(def, frame, wx, wz);
    };
    const int cx0 = floorDiv(origin.x - kLeafRadius, kTreeCell);
    const int cx1 = floorDiv(origin.x + size.x - 1 + kLeafRadius, kTreeCell);
    const int cz0 = floorDiv(origin.z - kLeafRadius, kTreeCell);
    const int cz1 = floorDiv(origin.z + size.z - 1 + kLeafRadius, kTreeCell);
    for (int cz = cz0; cz <= cz1; ++cz) {
        for (int cx = cx0; cx <= cx1; ++cx) {
            // Cheap rejections (hash, root position) before the column noise inside treeInCell.
            const std::uint64_t r = core::hashCoords(def.seed ^ kSaltTree, cx, 0, cz);
            if (r % 100u >= static_cast<std::uint64_t>(kTreeChancePercent)) continue;
            const std::optional<Tree> tree = treeInCell(def, cx, cz, columnAt);
            if (!tree) continue;
            const int x0 = std::max(tree->x - kLeafRadius, origin.x),
                      x1 = std::min(tree->x + kLeafRadius, origin.x + size.x - 1);
            const int z0 = std::max(tree->z - kLeafRadius, origin.z),
                      z1 = std::min(tree->z + kLeafRadius, origin.z + size.z - 1);
            const int y0 = std::max(tree->ground + 1, origin.y);
            const int y1 = std::min(tree->ground + tree->trunk + kLeafAboveTrunk, boxTop);
            for (int wy = y0; wy <= y1; ++wy) {
                for (int wz = z0; wz <= z1; ++wz) {
                    for (int wx = x0; wx <= x1; ++wx) {
                        const BlockType b = treeBlock(def, *tree, wx - tree->x, wy, wz - tree->z);
                        if (b == BlockType::Air) continue;
                        BlockType& cell = at(wx - origin.x, wy - origin.y, wz - origin.z);
                        // Logs beat leaves and leaves fill only air: the result is the same in any
                        // order, so overlapping crowns from neighbouring chunks agree.
                        if (cell == BlockType::Air || (b == BlockType::Log && cell == BlockType::Leaves)) cell = b;
                    }
                }
            }
        }
    }
}

void generateChunk(const TerrainDef& def, ChunkCoord coord, Chunk& out) {
    out.writeBlocks([&](BlockType* blocks) { generateBox(def, chunkOrigin(coord), glm::ivec3(kChunkSize), blocks); });
}

BlockType terrainBlock(const TerrainDef& def, glm::ivec3 pos) {
    if (pos.y < 0) return BlockType::Stone;
    if (pos.y >= kWorldHeight) return BlockType::Air;
    BlockType b = BlockType::Air;
    generateBox(def, pos, glm::ivec3(1), &b);
    return b;
}

int surfaceHeight(const TerrainDef& def, int x, int z) {
    if (def.kind == TerrainKind::Flat) return kFlatSurface;
    return hillHeight(noiseFrame(def.seed), x, z);
}

} // namespace world
