#include "world/column_light.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <tuple>

#include "core/thread_clock.h"
#include "world/light.h"

namespace world {

namespace {

// Repairing more edits than this costs about what a relight does.
constexpr std::size_t kMostRepairs = 256;
// Regions kept per thread, about 3.4 MB each (94 x 128 x 94 voxels, a block byte and two light bytes). A view
// streams in a region at a time (render/chunk_streaming.cpp), so streaming needs one; an edit changes the light of at
// most the 2 x 2 regions around it (light reaches 14 blocks, a region is 64 wide), so four keep every chunk an edit
// bumps repairable. Eight would keep 27 MB more (computed), and cost a tenth more of the CPU of streaming a view in
// (measured with white light's smaller regions; pages first touched: a region's fields are allocated once and then
// reused).
constexpr std::size_t kKeptRegions = 4;

struct KeptRegion {
    TerrainDef def;
    int x = 0, z = 0;             // lightRegionOf its columns
    std::vector<BlockEdit> edits; // sorted by position, each once (the last of equal positions wins)
    std::unique_ptr<LightField> field;
    unsigned long lastUse = 0;
    bool valid = false; // the field holds the light of (def, x, z, edits)
};

struct Cache {
    std::vector<KeptRegion> regions;
    unsigned long clock = 0;
    ColumnLightStats stats;
};
thread_local Cache t_cache;

// The process's LightCost: CPU time and counts added by every thread, and the columns seen, while `on`.
struct Cost {
    std::atomic<bool> on{false};
    std::atomic<long long> ns{0};
    std::atomic<long> relit{0}, relitForObjects{0}, repaired{0};
    std::mutex columnsMutex;
    std::set<std::tuple<std::uint64_t, int, int, int>> columns, regions; // terrain seed and kind, x, z
};
Cost& cost() {
    static Cost c;
    return c;
}

// The thread's CPU time in nanoseconds while counting, 0 otherwise (a system call each: kept off the edit path).
long long costClock() {
    return cost().on.load(std::memory_order_relaxed) ? static_cast<long long>(core::threadCpuSeconds() * 1e9) : 0;
}
void addCost(long long start, std::atomic<long>& count) {
    Cost& c = cost();
    if (!c.on.load(std::memory_order_relaxed)) return;
    c.ns += costClock() - start;
    ++count;
}

void countColumn(const TerrainDef& def, ChunkCoord coord) {
    Cost& c = cost();
    if (!c.on.load(std::memory_order_relaxed)) return;
    const std::lock_guard<std::mutex> lock(c.columnsMutex);
    c.columns.emplace(def.seed, static_cast<int>(def.kind), coord.x, coord.z);
    const ChunkCoord region = lightRegionOf(coord);
    c.regions.emplace(def.seed, static_cast<int>(def.kind), region.x, region.z);
}

// The edits in `box`, sorted by position, one per position.
std::vector<BlockEdit> editsIn(const LightBox& box, const std::vector<BlockEdit>& edits) {
    std::vector<BlockEdit> out;
    for (const BlockEdit& e : edits) {
        if (box.contains(e.pos)) out.push_back(e);
    }
    std::stable_sort(out.begin(), out.end(), positionLess);
    // Of equal positions the last given wins, as when the edits are applied in order.
    std::vector<BlockEdit> unique;
    unique.reserve(out.size());
    for (const BlockEdit& e : out) {
        if (!unique.empty() && unique.back().pos == e.pos) {
            unique.back() = e;
        } else {
            unique.push_back(e);
        }
    }
    return unique;
}

void relight(const TerrainDef& def, const LightBox& box, const std::vector<BlockEdit>& edits, LightField& field) {
    long long start = 0;
    field.fillAndRelight([&](LightField& f, std::vector<BlockType>& blocks) {
        generateBox(def, box.origin, box.size, blocks.data());
        for (const BlockEdit& e : edits) blocks[f.index(e.pos)] = e.block;
        start = costClock(); // the light from here on
    });
    addCost(start, cost().relit);
}

// Brings `field`, lit with `from`, to the blocks of `to` (both sorted). False when that takes more than
// kMostRepairs edits (the field is then left as it was).
bool repair(const TerrainDef& def, const std::vector<BlockEdit>& from, const std::vector<BlockEdit>& to,
            LightField& field) {
    std::vector<BlockEdit> changes;
    auto a = from.begin(), b = to.begin();
    while (a != from.end() || b != to.end()) {
        if (b == to.end() || (a != from.end() && positionLess(*a, *b))) { // an edit gone: back to the terrain
            changes.push_back({a->pos, terrainBlock(def, a->pos)});
            ++a;
        } else if (a == from.end() || positionLess(*b, *a)) {
            changes.push_back(*b++);
        } else {
            if (a->block != b->block) changes.push_back(*b);
            ++a, ++b;
        }
        if (changes.size() > kMostRepairs) return false;
    }
    const long long start = costClock();
    for (const BlockEdit& c : changes) {
        if (field.block(c.pos) != c.block) field.setBlock(c.pos, c.block);
    }
    addCost(start, cost().repaired);
    return true;
}

const LightField& columnField(const TerrainDef& def, ChunkCoord coord, const std::vector<BlockEdit>& given) {
    Cache& cache = t_cache;
    const LightBox box = lightBoxOf(coord);
    const ChunkCoord region = lightRegionOf(coord);
    std::vector<BlockEdit> edits = editsIn(box, given);
    ++cache.clock;
    KeptRegion* kept = nullptr;
    for (KeptRegion& c : cache.regions) {
        if (c.valid && c.x == region.x && c.z == region.z && c.def.seed == def.seed && c.def.kind == def.kind)
            kept = &c;
    }
    if (kept) {
        kept->lastUse = cache.clock;
        if (kept->edits == edits) {
            ++cache.stats.reused;
            return *kept->field;
        }
        kept->valid = false; // until the field matches its edits again: a throw below leaves no wrong column
        if (repair(def, kept->edits, edits, *kept->field)) {
            ++cache.stats.repaired;
        } else {
            relight(def, box, edits, *kept->field);
            ++cache.stats.relit;
        }
        kept->edits = std::move(edits);
        kept->valid = true;
        return *kept->field;
    }
    if (cache.regions.size() < kKeptRegions) {
        cache.regions.push_back({});
        kept = &cache.regions.back();
        kept->field = std::make_unique<LightField>(box.origin, box.size);
    } else { // the one used longest ago makes room
        kept = &*std::min_element(cache.regions.begin(), cache.regions.end(),
                                  [](const KeptRegion& l, const KeptRegion& r) { return l.lastUse < r.lastUse; });
        kept->valid = false;
        kept->field->moveTo(box.origin); // the same size: its storage is reused, its contents relit below
    }
    kept->lastUse = cache.clock;
    relight(def, box, edits, *kept->field);
    kept->def = def;
    kept->x = region.x;
    kept->z = region.z;
    kept->edits = std::move(edits);
    kept->valid = true;
    ++cache.stats.relit;
    return *kept->field;
}

} // namespace

ChunkCoord lightRegionOf(ChunkCoord coord) {
    return {floorDiv(coord.x, kLightRegion), 0, floorDiv(coord.z, kLightRegion)};
}

LightBox lightBoxOf(ChunkCoord coord) {
    const ChunkCoord r = lightRegionOf(coord);
    const glm::ivec3 o = chunkOrigin({r.x * kLightRegion, 0, r.z * kLightRegion});
    constexpr int kWidth = kLightRegion * kChunkSize + 2 * kLightBorder;
    return {o - glm::ivec3(kLightBorder, 0, kLightBorder), glm::ivec3(kWidth, kWorldHeight, kWidth)};
}

namespace {

// The padded light of chunk `coord` cut out of its column's field, and with `blocks` its padded blocks too.
void cutPadded(const LightField& field, ChunkCoord coord, PaddedLight& out, PaddedBlocks* blocks) {
    const glm::ivec3 low = chunkOrigin(coord) - glm::ivec3(1);
    constexpr int kP = PaddedLight::kSize;
    constexpr auto kLayer = static_cast<std::size_t>(kP) * kP;
    static_assert(sizeof(BlockType) == 1);
    for (int y = 0; y < kP; ++y) {
        std::uint16_t* layer = out.level.data() + kLayer * static_cast<std::size_t>(y);
        auto* blockLayer =
            blocks ? reinterpret_cast<unsigned char*>(blocks->untrackedData()) + kLayer * static_cast<std::size_t>(y)
                   : nullptr;
        const int wy = low.y + y;
        if (wy < 0 || wy >= kWorldHeight) { // below the world: stone, dark; above it: the open sky
            std::fill(layer, layer + kLayer, wy < 0 ? std::uint16_t{0} : kOpenSkyLight);
            if (blockLayer) {
                std::memset(blockLayer, static_cast<int>(wy < 0 ? BlockType::Stone : BlockType::Air), kLayer);
            }
            continue;
        }
        for (int z = 0; z < kP; ++z) {
            const std::size_t at = field.index({low.x, wy, low.z + z});
            std::memcpy(layer + kP * z, field.packedLevels() + at, sizeof(std::uint16_t) * kP);
            if (blockLayer) std::memcpy(blockLayer + kP * z, field.blocks() + at, static_cast<std::size_t>(kP));
        }
    }
    out.rebuildShade();
}

} // namespace

void lightPadded(const TerrainDef& def, ChunkCoord coord, const std::vector<BlockEdit>& edits, PaddedLight& out) {
    countColumn(def, coord);
    cutPadded(columnField(def, coord, edits), coord, out, nullptr);
}

void gatherAndLight(const TerrainDef& def, ChunkCoord coord, const std::vector<BlockEdit>& edits, PaddedChunk& out) {
    countColumn(def, coord);
    cutPadded(columnField(def, coord, edits), coord, out.light, &out.blocks);
    out.rebuildSolid();
}

LocalLight lightAt(const World& w, glm::ivec3 pos) {
    if (pos.y >= kWorldHeight) return {};
    if (pos.y < 0) return {0, 0, 0, 0};
    // Objects stand still mostly: what was asked since the world last changed is answered from a memo, so a
    // frame's objects touch the kept regions (shared with the meshes this thread builds) only when they move.
    thread_local struct Memo {
        std::uint64_t world = 0, revision = 0;
        std::map<std::tuple<int, int, int>, LocalLight> light;
    } memo;
    if (memo.world != w.identity() || memo.revision != w.revision() || memo.light.size() > 256) {
        memo = {w.identity(), w.revision(), {}};
    }
    if (const auto it = memo.light.find({pos.x, pos.y, pos.z}); it != memo.light.end()) return it->second;
    thread_local std::vector<BlockEdit> edits;
    w.editsAround(chunkOf(pos), edits);
    const long relitBefore = t_cache.stats.relit;
    const LightField& field = columnField(w.terrain(), chunkOf(pos), edits);
    if (cost().on.load(std::memory_order_relaxed) && t_cache.stats.relit != relitBefore) ++cost().relitForObjects;
    const auto at = [&](glm::ivec3 p) {
        return LocalLight{field.level(LightChannel::Sun, p), field.level(LightChannel::Red, p),
                          field.level(LightChannel::Green, p), field.level(LightChannel::Blue, p)};
    };
    LocalLight l = at(pos);
    if (isSolid(field.block(pos))) { // inside a block (a ball pressed into a wall): the light at its faces
        for (const glm::ivec3 step : {glm::ivec3(1, 0, 0), glm::ivec3(-1, 0, 0), glm::ivec3(0, 1, 0),
                                      glm::ivec3(0, -1, 0), glm::ivec3(0, 0, 1), glm::ivec3(0, 0, -1)}) {
            const glm::ivec3 n = pos + step;
            if (n.y >= kWorldHeight) { // the open sky above the world
                l.sun = kMaxLight;
                continue;
            }
            if (!field.contains(n)) continue;
            const LocalLight o = at(n);
            l.sun = std::max(l.sun, o.sun);
            l.red = std::max(l.red, o.red);
            l.green = std::max(l.green, o.green);
            l.blue = std::max(l.blue, o.blue);
        }
    }
    memo.light.emplace(std::tuple{pos.x, pos.y, pos.z}, l);
    return l;
}

ColumnLightStats columnLightStats() { return t_cache.stats; }

void clearColumnLight() { t_cache = Cache{}; }

void countLightCost(bool on) { cost().on = on; }

LightCost lightCost() {
    Cost& c = cost();
    LightCost out;
    out.cpuSeconds = static_cast<double>(c.ns.load()) * 1e-9;
    out.relit = c.relit.load();
    out.relitForObjects = c.relitForObjects.load();
    out.repaired = c.repaired.load();
    const std::lock_guard<std::mutex> lock(c.columnsMutex);
    out.columns = static_cast<long>(c.columns.size());
    out.regions = static_cast<long>(c.regions.size());
    return out;
}

} // namespace world
