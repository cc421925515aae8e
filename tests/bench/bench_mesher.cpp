// Mesher throughput: greedy against the culled reference in the same run, on a typical terrain
// surface chunk and on the checkerboard worst case. Items are voxels, so items_per_second and the
// ns_per_voxel counter compare directly with other voxel meshers; `quads` is the output size.
// `vsBaseline` runs our mesher and the binary greedy anchor (binary_greedy_baseline.h) on the same 64^3
// region of terrain and prints the ratio of their times per voxel, with warm and with cold caches.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_regions.h"
#include "binary_greedy_baseline.h"
#include "world/column_light.h"
#include "world/culling_data.h"
#include "world/mesh_worker.h"
#include "world/mesher.h"
#include "world/terrain.h"
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
BENCHMARK_CAPTURE(meshBench, terrain_greedy_strips, &terrainChunk, MeshMode::GreedyStrips);
BENCHMARK_CAPTURE(meshBench, terrain_greedy_flat, &terrainChunk, MeshMode::GreedyFlat);
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

// The blocks of a light region's box (world/column_light.h: 94 x 128 x 94 around 2 x 2 columns) from the terrain,
// its columns' noise kept from the first run (as when streaming reaches the box's region after its neighbours'):
// what a worker pays for blocks before lighting them, once for four columns.
void terrainBoxBench(benchmark::State& state) {
    const world::TerrainDef def{1};
    const world::LightBox box = world::lightBoxOf({0, 0, 0});
    std::vector<world::BlockType> blocks(static_cast<std::size_t>(box.size.x) * box.size.y * box.size.z);
    for (auto _ : state) {
        world::generateBox(def, box.origin, box.size, blocks.data());
        benchmark::DoNotOptimize(blocks.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(blocks.size()));
}
BENCHMARK(terrainBoxBench)->Unit(benchmark::kMicrosecond);

} // namespace

namespace {

using bench::coveredFaces;
using bench::Region;
using bench::region;

// Each iteration times both meshers twice over. Warm: each mesher runs kWarmRuns times in a row after
// one untimed run, so its input, output and scratch are in the caches, as in the game, where a mesh
// worker meshes the chunk it has just gathered into a buffer it reuses. Cold: one run of each, turn
// about, so that each starts on caches the other has just filled (a megabyte of L2 holds one of the
// two working sets, about 0.7 MB ours and 0.5 MB the anchor's, not both). `ratio` is the warm ratio,
// `ratio_cold` the cold one; both are ours over the anchor's time per voxel. `lit`: our mesher meshes the
// region under its real light (what the game meshes), otherwise under the open sky (as before light).
void vsBaseline(benchmark::State& state, MeshMode mode, bool lit) {
    constexpr int kWarmRuns = 3;
    const int seed = static_cast<int>(state.range(0));
    const Region& r = region(seed);
    const auto& chunks = lit ? r.lit : r.chunks;
    using Clock = std::chrono::steady_clock;
    bench::BinaryGreedyBaseline anchor;
    std::vector<std::uint64_t> anchorQuads;
    std::vector<world::ChunkMesh> meshes(chunks.size());
    // Precondition: the anchor does the whole job (every visible face of its region, once).
    anchor.mesh(r.bytes.data(), r.columns.data(), anchorQuads);
    if (bench::BinaryGreedyBaseline::coveredFaces(anchorQuads) != r.anchorVisibleFaces) {
        std::fprintf(stderr, "binary greedy anchor covers %lld faces, the region shows %lld\n",
                     bench::BinaryGreedyBaseline::coveredFaces(anchorQuads), r.anchorVisibleFaces);
        std::abort();
    }
    const auto meshOurs = [&] {
        for (std::size_t i = 0; i < chunks.size(); ++i) world::meshChunk(*chunks[i], meshes[i], mode);
        benchmark::ClobberMemory();
    };
    // And ours does the whole job too: its quads cover as many faces as the culled mesher finds.
    meshOurs();
    long long oursCovered = 0, visible = 0;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        oursCovered += coveredFaces(meshes[i]);
        world::ChunkMesh culled;
        world::meshChunk(*chunks[i], culled, MeshMode::Culled);
        visible += static_cast<long long>(culled.quadCount());
    }
    if (oursCovered != visible) {
        std::fprintf(stderr, "our mesher covers %lld faces, the chunks show %lld\n", oursCovered, visible);
        std::abort();
    }
    const auto meshAnchor = [&] {
        anchor.mesh(r.bytes.data(), r.columns.data(), anchorQuads);
        benchmark::ClobberMemory();
    };
    const auto seconds = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double>(b - a).count();
    };

    double ours = 0, theirs = 0, oursCold = 0, theirsCold = 0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        meshOurs();
        const auto t1 = Clock::now();
        meshAnchor();
        const auto t2 = Clock::now();
        meshOurs();
        const auto t3 = Clock::now();
        for (int k = 0; k < kWarmRuns; ++k) meshOurs();
        const auto t4 = Clock::now();
        meshAnchor();
        const auto t5 = Clock::now();
        for (int k = 0; k < kWarmRuns; ++k) meshAnchor();
        const auto t6 = Clock::now();
        oursCold += seconds(t0, t1);
        theirsCold += seconds(t1, t2);
        ours += seconds(t3, t4) / kWarmRuns;
        theirs += seconds(t5, t6) / kWarmRuns;
        state.SetIterationTime(seconds(t3, t4) / kWarmRuns);
    }
    std::size_t quads = 0;
    for (const auto& m : meshes) quads += m.quadCount();
    const double n = static_cast<double>(state.iterations());
    const double ourVoxels = 8.0 * world::kChunkVolume;
    const double anchorVoxels = double(bench::BinaryGreedyBaseline::kInner * bench::BinaryGreedyBaseline::kInner *
                                       bench::BinaryGreedyBaseline::kInner);
    state.counters["ours_ns_per_voxel"] = ours / n * 1e9 / ourVoxels;
    state.counters["anchor_ns_per_voxel"] = theirs / n * 1e9 / anchorVoxels;
    state.counters["ratio"] = (ours / ourVoxels) / (theirs / anchorVoxels);
    state.counters["ratio_cold"] = (oursCold / ourVoxels) / (theirsCold / anchorVoxels);
    state.counters["ours_quads"] = static_cast<double>(quads);
    state.counters["anchor_quads"] = static_cast<double>(anchorQuads.size());
}

// Lit meshing against meshing the same blocks under the open sky (what the mesher did before light: the same
// quads it made then), on the vsBaseline region, turn about in one run: `ratio` is lit over open-sky time,
// warm as in vsBaseline. The quad counts of both are printed.
void litVsOpenSky(benchmark::State& state, MeshMode mode) {
    constexpr int kRuns = 3;
    const Region& r = region(static_cast<int>(state.range(0)));
    using Clock = std::chrono::steady_clock;
    std::vector<world::ChunkMesh> meshes(r.chunks.size());
    const auto meshAll = [&](const std::vector<std::unique_ptr<world::PaddedChunk>>& chunks) {
        for (std::size_t i = 0; i < chunks.size(); ++i) world::meshChunk(*chunks[i], meshes[i], mode);
        benchmark::ClobberMemory();
    };
    const auto quadsOf = [&](const std::vector<std::unique_ptr<world::PaddedChunk>>& chunks) {
        meshAll(chunks);
        std::size_t q = 0;
        for (const auto& m : meshes) q += m.quadCount();
        return q;
    };
    const std::size_t openQuads = quadsOf(r.chunks), litQuads = quadsOf(r.lit);
    double open = 0, lit = 0;
    for (auto _ : state) {
        meshAll(r.chunks);
        const auto t0 = Clock::now();
        for (int k = 0; k < kRuns; ++k) meshAll(r.chunks);
        const auto t1 = Clock::now();
        meshAll(r.lit);
        const auto t2 = Clock::now();
        for (int k = 0; k < kRuns; ++k) meshAll(r.lit);
        const auto t3 = Clock::now();
        open += std::chrono::duration<double>(t1 - t0).count() / kRuns;
        lit += std::chrono::duration<double>(t3 - t2).count() / kRuns;
        state.SetIterationTime(std::chrono::duration<double>(t3 - t2).count() / kRuns);
    }
    const double n = static_cast<double>(state.iterations()), voxels = 8.0 * world::kChunkVolume;
    state.counters["lit_ns_per_voxel"] = lit / n * 1e9 / voxels;
    state.counters["open_sky_ns_per_voxel"] = open / n * 1e9 / voxels;
    state.counters["ratio"] = lit / open;
    state.counters["lit_quads"] = static_cast<double>(litQuads);
    state.counters["open_sky_quads"] = static_cast<double>(openQuads);
}
BENCHMARK_CAPTURE(litVsOpenSky, greedy_ao, MeshMode::Greedy)->DenseRange(1, 3)->UseManualTime();
BENCHMARK_CAPTURE(litVsOpenSky, greedy_strips, MeshMode::GreedyStrips)->DenseRange(1, 3)->UseManualTime();
BENCHMARK_CAPTURE(litVsOpenSky, greedy_flat, MeshMode::GreedyFlat)->DenseRange(1, 3)->UseManualTime();

BENCHMARK_CAPTURE(vsBaseline, greedy_flat, MeshMode::GreedyFlat, false)->DenseRange(1, 3)->UseManualTime();
BENCHMARK_CAPTURE(vsBaseline, greedy_ao, MeshMode::Greedy, false)->DenseRange(1, 3)->UseManualTime();
BENCHMARK_CAPTURE(vsBaseline, greedy_strips, MeshMode::GreedyStrips, false)->DenseRange(1, 3)->UseManualTime();
BENCHMARK_CAPTURE(vsBaseline, lit_flat, MeshMode::GreedyFlat, true)->DenseRange(1, 3)->UseManualTime();
BENCHMARK_CAPTURE(vsBaseline, lit_ao, MeshMode::Greedy, true)->DenseRange(1, 3)->UseManualTime();
BENCHMARK_CAPTURE(vsBaseline, lit_strips, MeshMode::GreedyStrips, true)->DenseRange(1, 3)->UseManualTime();

} // namespace

namespace {

// What one worker job costs: the padded chunk from the terrain (34^3 blocks) and its mesh, against the
// render thread's own path when the neighbours are loaded (gatherBench plus meshBench above). A job cuts its
// chunk out of its light region's box, which the thread keeps while it meshes the region's columns, and the
// terrain keeps the tiles of columns it computed (terrain.cpp), so a job on the same columns again would find
// them computed. The jobs go light region by light region, the region's columns one after another, as
// streaming orders them (ChunkStreaming::orderCandidates), over 32 x 32 columns (more tiles than the terrain
// keeps): `first_of_column` runs the surface chunk of each column, the first job of its column;
// `whole_column` runs the four chunks of each column one after the other, the best case (the game's queue
// reaches them among other columns' chunks); per_chunk is the time per chunk. Both go on through the columns
// where the last run stopped, so no run starts on columns an earlier one left kept.
void workerJobBench(benchmark::State& state, bool wholeColumn) {
    const world::TerrainDef def{1};
    constexpr int kRegionsAcross = 16; // 32 x 32 columns, whose light boxes span 34 x 34 tiles
    std::vector<world::ChunkCoord> surface;
    for (int r = 0; r < kRegionsAcross * kRegionsAcross; ++r) {
        for (int k = 0; k < world::kLightRegion * world::kLightRegion; ++k) {
            const int cx = (r % kRegionsAcross) * world::kLightRegion + k % world::kLightRegion;
            const int cz = (r / kRegionsAcross) * world::kLightRegion + k / world::kLightRegion;
            const int x = 32 * cx + 16, z = 32 * cz + 16;
            surface.push_back(world::chunkOf({x, world::surfaceHeight(def, x, z), z}));
        }
    }
    world::MeshJob job;
    job.mode = MeshMode::GreedyStrips;
    static std::size_t next = 0;
    std::size_t chunks = 0;
    for (auto _ : state) {
        const world::ChunkCoord c = surface[next];
        next = (next + 1) % surface.size();
        const int bottom = wholeColumn ? 0 : c.y, top = wholeColumn ? world::kWorldHeightChunks - 1 : c.y;
        for (int y = bottom; y <= top; ++y) {
            job.coord = {c.x, y, c.z};
            world::MeshResult r = world::MeshWorker::run(def, job);
            benchmark::DoNotOptimize(r.mesh.vertices.data());
            ++chunks;
        }
    }
    state.counters["per_chunk"] =
        benchmark::Counter(static_cast<double>(chunks), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK_CAPTURE(workerJobBench, first_of_column, false);
BENCHMARK_CAPTURE(workerJobBench, whole_column, true);

} // namespace

namespace {

// The face links of a chunk (occlusion culling's input), computed when it is meshed.
void faceLinksBench(benchmark::State& state, const PaddedChunk& (*chunk)()) {
    const PaddedChunk& in = chunk();
    for (auto _ : state) {
        world::FaceLinks l = world::faceLinks(in);
        benchmark::DoNotOptimize(l);
    }
}
BENCHMARK_CAPTURE(faceLinksBench, terrain, &terrainChunk);
BENCHMARK_CAPTURE(faceLinksBench, checkerboard, &checkerboardChunk);

} // namespace
