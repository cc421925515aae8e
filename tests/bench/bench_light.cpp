// Light propagation on the game's terrain (world/light.h): relighting one chunk column over its light box
// (what streaming a new column costs), one edit at the surface (a block placed and broken, a lamp placed and
// taken), what a mesh job pays for its chunk's light (world/column_light.h), and what storing the light of a
// view would take.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <set>
#include <tuple>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/common.hpp>

#include "world/column_light.h"
#include "world/light.h"
#include "world/light_level.h"
#include "world/world.h"

namespace {

using world::BlockType;
using world::LightField;

// The blocks of `w` in the field's box, copied chunk by chunk (the world generates them as needed).
void fillFromWorld(const world::World& w, LightField& f) {
    const glm::ivec3 lo = f.origin(), hi = f.origin() + f.size() - glm::ivec3(1);
    const world::ChunkCoord a = world::chunkOf(lo), b = world::chunkOf(hi);
    f.fillAndRelight([&](LightField& field, std::vector<BlockType>& blocks) {
        for (int cy = a.y; cy <= b.y; ++cy)
            for (int cz = a.z; cz <= b.z; ++cz)
                for (int cx = a.x; cx <= b.x; ++cx) {
                    const world::Chunk& c = w.chunk({cx, cy, cz});
                    const glm::ivec3 o = world::chunkOrigin({cx, cy, cz});
                    const glm::ivec3 from = glm::max(lo, o), to = glm::min(hi, o + glm::ivec3(world::kChunkSize - 1));
                    for (int y = from.y; y <= to.y; ++y)
                        for (int z = from.z; z <= to.z; ++z)
                            for (int x = from.x; x <= to.x; ++x)
                                blocks[field.index({x, y, z})] = c.get(x - o.x, y - o.y, z - o.z);
                }
    });
}

// Column (0, 0) of the default world, seed 1, over its light box (world/column_light.h: the blocks its padded
// light depends on, world::kLightBorder around it; light loses a level a step sideways, so nothing farther
// reaches it).
const LightField& columnField() {
    static const std::unique_ptr<LightField> f = [] {
        const world::LightBox box = world::lightBoxOf({0, 0, 0});
        auto out = std::make_unique<LightField>(box.origin, box.size);
        fillFromWorld(world::World(world::TerrainDef{1}), *out);
        return out;
    }();
    return *f;
}

void lightRelightColumn(benchmark::State& state) {
    LightField f = columnField();
    std::size_t visited = 0;
    for (auto _ : state) {
        visited = f.relightAll();
        benchmark::ClobberMemory();
    }
    state.counters["visited_voxels"] = static_cast<double>(visited);
    state.counters["chunks"] = static_cast<double>(world::kWorldHeightChunks);
}
BENCHMARK(lightRelightColumn)->Unit(benchmark::kMicrosecond);

// Chunks of the field whose light differs between two fields.
int chunksTouched(const LightField& a, const LightField& b) {
    std::set<std::tuple<int, int, int>> chunks;
    const std::size_t n = static_cast<std::size_t>(a.size().x) * a.size().y * a.size().z;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::ivec3 p = a.position(i);
        if (a.packedLevels()[i] != b.packedLevels()[i]) {
            const world::ChunkCoord c = world::chunkOf(p);
            chunks.insert({c.x, c.y, c.z});
        }
    }
    return static_cast<int>(chunks.size());
}

// One edit at the surface of the column's middle and its undoing, each timed: range 0 places a stone block
// on the ground (a shadow, the sky cut off below it), range 1 a (white) lamp, 2 a red lamp (one channel), 3 an
// orange lamp (two channels, 15 and 8).
void lightEditAtTheSurface(benchmark::State& state) {
    LightField f = columnField();
    const BlockType kinds[] = {BlockType::Stone, BlockType::Lamp, BlockType::RedLamp, BlockType::OrangeLamp};
    const BlockType placed = kinds[state.range(0)];
    int ground = world::kWorldHeight - 1;
    while (ground > 0 && f.block({16, ground, 16}) == BlockType::Air) --ground;
    const glm::ivec3 at(16, ground + 2, 16); // one block of air between it and the ground
    const LightField before = f;
    f.setBlock(at, placed);
    const int touched = chunksTouched(before, f);
    f.setBlock(at, BlockType::Air);
    std::size_t visited = 0;
    for (auto _ : state) {
        visited = f.setBlock(at, placed);
        visited += f.setBlock(at, BlockType::Air);
        benchmark::ClobberMemory();
    }
    state.counters["edits"] = benchmark::Counter(2.0 * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["visited_voxels_per_edit"] = static_cast<double>(visited) / 2.0;
    state.counters["chunks_touched"] = touched;
}
BENCHMARK(lightEditAtTheSurface)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

// What a mesh job pays for light (world/column_light.h), on the surface chunk of column (0, 0). Range 0: a
// column streamed in, lit from scratch (the kept columns forgotten first): the terrain of its light box
// generated and relit, then the chunk's padded light cut out. Range 1: an edit, a lamp placed on the ground
// and taken away in turn, repaired in the kept column, then the padded light cut out (what each chunk whose
// revision the edit bumped pays; `chunks_bumped` counts them).
void columnLight(benchmark::State& state) {
    const world::TerrainDef def{1};
    const int ground = world::surfaceHeight(def, 16, 16);
    const world::ChunkCoord c = world::chunkOf({16, ground, 16});
    const std::vector<world::BlockEdit> none, lamp{{{16, ground + 2, 16}, BlockType::Lamp}};
    auto out = std::make_unique<world::PaddedLight>();
    world::clearColumnLight();
    world::lightPadded(def, c, none, *out);
    bool placed = false;
    for (auto _ : state) {
        if (state.range(0) == 0) world::clearColumnLight();
        placed = !placed;
        world::lightPadded(def, c, state.range(0) == 1 && placed ? lamp : none, *out);
        benchmark::DoNotOptimize(out->level.data());
    }
    const world::ColumnLightStats stats = world::columnLightStats();
    state.counters["relit"] = static_cast<double>(stats.relit);
    state.counters["repaired"] = static_cast<double>(stats.repaired);
    if (state.range(0) == 1) {
        world::World w(def);
        const std::uint64_t before = w.revision();
        w.set(lamp[0].pos, BlockType::Lamp);
        int bumped = 0;
        for (int cz = c.z - 2; cz <= c.z + 2; ++cz)
            for (int cx = c.x - 2; cx <= c.x + 2; ++cx)
                for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) bumped += w.chunkRevision({cx, cy, cz}) != 0;
        state.counters["chunks_bumped"] = bumped;
        benchmark::DoNotOptimize(before);
    }
}
BENCHMARK(columnLight)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The light of every chunk within a view radius of the origin (range: 8 or 32 columns), computed a row of
// columns at a time (each with a 16-block margin, more than light reaches), and what keeping it would cost: dense (a
// byte a voxel), a byte for a chunk of uniform light and dense otherwise, and a chunk's voxels whose light differs from
// what its blocks alone say (full sunlight where the sky is open straight above, none elsewhere) kept sparse at three
// bytes each (dense where that is smaller).
void lightMemory(benchmark::State& state) {
    const int radius = static_cast<int>(state.range(0));
    const int columns = 2 * radius + 1;
    double dense = 0, uniform = 0, sparse = 0;
    long long uniformChunks = 0, chunks = 0;
    for (auto _ : state) {
        dense = uniform = sparse = 0;
        uniformChunks = chunks = 0;
        world::World w(world::TerrainDef{1});
        for (int cz = -radius; cz <= radius; ++cz) {
            LightField f({-radius * world::kChunkSize - 16, 0, cz * world::kChunkSize - 16},
                         {columns * world::kChunkSize + 32, world::kWorldHeight, world::kChunkSize + 32});
            fillFromWorld(w, f);
            w.unloadOutside({0, 0, cz + 1}, radius + 1); // keep the rows still needed, at most three
            // Per column of the field, the lowest height from which nothing but clear blocks lie above.
            std::vector<int> openFrom(static_cast<std::size_t>(f.size().x) * static_cast<std::size_t>(f.size().z));
            const auto columnOf = [&](int x, int z) {
                return static_cast<std::size_t>(x) + static_cast<std::size_t>(f.size().x) * static_cast<std::size_t>(z);
            };
            for (int z = 0; z < f.size().z; ++z)
                for (int x = 0; x < f.size().x; ++x) {
                    int y = world::kWorldHeight;
                    while (y > 0 && world::blockInfo(f.block(f.origin() + glm::ivec3(x, y - 1, z))).lightOpacity == 0)
                        --y;
                    openFrom[columnOf(x, z)] = y;
                }
            for (int cx = -radius; cx <= radius; ++cx) {
                for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
                    const glm::ivec3 o = world::chunkOrigin({cx, cy, cz});
                    std::uint16_t first = 0;
                    bool same = true;
                    long long exceptions = 0;
                    for (int y = 0; y < world::kChunkSize; ++y)
                        for (int z = 0; z < world::kChunkSize; ++z)
                            for (int x = 0; x < world::kChunkSize; ++x) {
                                const glm::ivec3 p = o + glm::ivec3(x, y, z);
                                const std::uint16_t value = f.packedLevels()[f.index(p)];
                                if (x == 0 && y == 0 && z == 0) first = value;
                                same = same && value == first;
                                const glm::ivec3 l = p - f.origin();
                                const bool openSky = p.y >= openFrom[columnOf(l.x, l.z)];
                                exceptions += value != (openSky ? world::kOpenSky.bits : 0);
                            }
                    ++chunks;
                    dense += world::kChunkVolume;
                    uniformChunks += same;
                    uniform += same ? 1.0 : world::kChunkVolume;
                    sparse += std::min(3.0 * static_cast<double>(exceptions), double(world::kChunkVolume));
                }
            }
        }
    }
    state.counters["chunks"] = static_cast<double>(chunks);
    state.counters["uniform_chunks"] = static_cast<double>(uniformChunks);
    state.counters["dense_MB"] = dense / 1e6;
    state.counters["uniform_or_dense_MB"] = uniform / 1e6;
    state.counters["sparse_MB"] = sparse / 1e6;
}
BENCHMARK(lightMemory)->Arg(8)->Arg(32)->Iterations(1)->Unit(benchmark::kSecond);

} // namespace
