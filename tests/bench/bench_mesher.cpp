// Mesher throughput: greedy against the culled reference in the same run, on a typical terrain
// surface chunk and on the checkerboard worst case. Items are voxels, so items_per_second and the
// ns_per_voxel counter compare directly with other voxel meshers; `quads` is the output size.
#include <memory>

#include <benchmark/benchmark.h>

#include "world/mesher.h"
#include "world/world.h"

namespace {

using world::MeshMode;
using world::PaddedChunk;

// The chunk holding the ground at the origin of the default world, seed 1, with its real neighbours.
const PaddedChunk& terrainChunk() {
    static const std::unique_ptr<PaddedChunk> p = [] {
        auto out = std::make_unique<PaddedChunk>();
        const world::World w(world::TerrainDef{1});
        const int h = world::surfaceHeight(w.terrain(), 16, 16);
        w.gatherPadded(world::chunkOf({16, h, 16}), *out);
        return out;
    }();
    return *p;
}

// Every other voxel solid: every solid voxel shows six faces and nothing can merge.
const PaddedChunk& checkerboardChunk() {
    static const std::unique_ptr<PaddedChunk> p = [] {
        auto out = std::make_unique<PaddedChunk>();
        for (int y = 0; y < PaddedChunk::kSize; ++y)
            for (int z = 0; z < PaddedChunk::kSize; ++z)
                for (int x = 0; x < PaddedChunk::kSize; ++x)
                    if ((x + y + z) % 2 == 1) out->set(x, y, z, world::BlockType::Stone);
        return out;
    }();
    return *p;
}

void meshBench(benchmark::State& state, const PaddedChunk& (*chunk)(), MeshMode mode) {
    const PaddedChunk& in = chunk();
    world::ChunkMesh mesh;
    world::meshChunk(in, mesh, mode); // warm the output capacity, as a renderer reusing its mesh would
    for (auto _ : state) {
        world::meshChunk(in, mesh, mode);
        benchmark::DoNotOptimize(mesh.vertices.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * world::kChunkVolume);
    state.counters["quads"] = static_cast<double>(mesh.quadCount());
    state.counters["ns_per_voxel"] =
        benchmark::Counter(static_cast<double>(world::kChunkVolume),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(meshBench, terrain_greedy, &terrainChunk, MeshMode::Greedy);
BENCHMARK_CAPTURE(meshBench, terrain_greedy_unlit, &terrainChunk, MeshMode::GreedyUnlit);
BENCHMARK_CAPTURE(meshBench, terrain_culled, &terrainChunk, MeshMode::Culled);
BENCHMARK_CAPTURE(meshBench, checkerboard_greedy, &checkerboardChunk, MeshMode::Greedy);
BENCHMARK_CAPTURE(meshBench, checkerboard_culled, &checkerboardChunk, MeshMode::Culled);

} // namespace

namespace {

// What a renderer pays before meshing: the padded copy when the neighbours are loaded (the common
// case) and when none of them is (border slabs generated from terrain).
void gatherBench(benchmark::State& state, bool neighboursLoaded) {
    const world::World w(world::TerrainDef{1});
    const int h = world::surfaceHeight(w.terrain(), 16, 16);
    const world::ChunkCoord c = world::chunkOf({16, h, 16});
    if (neighboursLoaded) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
                for (int dx = -1; dx <= 1; ++dx) w.chunk({c.x + dx, c.y + dy, c.z + dz});
    }
    auto out = std::make_unique<PaddedChunk>();
    for (auto _ : state) {
        w.gatherPadded(c, *out);
        benchmark::DoNotOptimize(out->blocks.data());
    }
    state.SetItemsProcessed(state.iterations() * PaddedChunk::kVolume);
}
BENCHMARK_CAPTURE(gatherBench, neighbours_loaded, true);
BENCHMARK_CAPTURE(gatherBench, neighbours_unloaded, false);

} // namespace
