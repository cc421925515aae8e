#include <algorithm>
#include <cstring>
#include <memory>
#include <thread>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "world/column_light.h"
#include "world/culling_data.h"
#include "world/level_of_detail.h"
#include "world/mesh_worker.h"

namespace {

using world::BlockType;
using world::ChunkCoord;
using world::MeshJob;
using world::MeshMode;

// A world with edits on a chunk's faces, edges and corner, on both sides of its borders.
world::World editedWorld(ChunkCoord& c) {
    world::World w(world::TerrainDef{6});
    c = world::chunkOf({70, world::surfaceHeight(w.terrain(), 70, 70), 70});
    const glm::ivec3 o = world::chunkOrigin(c);
    for (const glm::ivec3 d :
         {glm::ivec3(-1, 3, 3), glm::ivec3(32, 31, 0), glm::ivec3(0, -1, 31), glm::ivec3(-1, -1, -1),
          glm::ivec3(32, 32, 32), glm::ivec3(5, 5, 5), glm::ivec3(-2, 4, 4), glm::ivec3(33, 0, 0)}) {
        w.set(o + d, BlockType::Brick);
    }
    w.set(o + glm::ivec3(6, 6, 6), BlockType::Air);
    return w;
}

// The worker builds chunks without the World: from the terrain and the edits it was handed. That must
// give exactly the blocks (and solid rows) the World gives, edits across every border included.
TEST(MeshWorker, TerrainPlusEditsGatherLikeTheWorld) {
    ChunkCoord c;
    const world::World w = editedWorld(c);
    std::vector<world::BlockEdit> edits;
    w.editsAround(c, edits);
    EXPECT_EQ(edits.size(), 9u); // the column's light box holds them all, two blocks out too
    auto fromWorld = std::make_unique<world::PaddedChunk>(), fromTerrain = std::make_unique<world::PaddedChunk>();
    w.gatherPadded(c, *fromWorld);
    world::gatherPaddedFromTerrain(w.terrain(), c, edits, *fromTerrain);
    const world::PaddedChunk& a = *fromWorld;
    const world::PaddedChunk& b = *fromTerrain;
    ASSERT_FALSE(a.blocks.stale);
    ASSERT_FALSE(b.blocks.stale);
    EXPECT_EQ(std::memcmp(a.blocks.data(), b.blocks.data(), world::PaddedChunk::kVolume), 0);
    EXPECT_EQ(std::memcmp(a.solid, b.solid, sizeof a.solid), 0);
}

MeshJob jobFor(const world::World& w, ChunkCoord c, MeshMode mode, int cell) {
    MeshJob j;
    j.coord = c;
    j.revision = w.chunkRevision(c);
    j.mode = mode;
    j.cell = cell;
    w.editsAround(c, j.edits);
    return j;
}

// Every job comes back once, with the mesh the render thread would have built from the World.
TEST(MeshWorker, BuildsWhatTheRenderThreadWould) {
    ChunkCoord c;
    const world::World w = editedWorld(c);
    world::MeshWorker worker(w.terrain());
    std::vector<MeshJob> jobs;
    const struct {
        MeshMode mode;
        int cell;
    } details[] = {{MeshMode::Greedy, 1},
                   {MeshMode::GreedyStrips, 1},
                   {MeshMode::GreedyFlat, 1},
                   {MeshMode::GreedyFlat, 2},
                   {MeshMode::GreedyFlat, 4}};
    for (const auto& d : details) {
        for (int dx = 0; dx < 2; ++dx) jobs.push_back(jobFor(w, {c.x + dx, c.y, c.z}, d.mode, d.cell));
    }
    const std::size_t n = jobs.size();
    worker.submit(std::move(jobs));
    worker.waitIdle();
    EXPECT_EQ(worker.queued(), 0u);
    std::vector<world::MeshResult> results = worker.takeResults();
    ASSERT_EQ(results.size(), n);
    EXPECT_TRUE(worker.takeResults().empty()); // taken once
    auto padded = std::make_unique<world::PaddedChunk>(), coarse = std::make_unique<world::PaddedChunk>();
    for (const world::MeshResult& r : results) {
        EXPECT_TRUE(r.job.edits.empty()); // not kept once used
        w.gatherPadded(r.job.coord, *padded);
        std::vector<world::BlockEdit> edits;
        w.editsAround(r.job.coord, edits);
        world::lightPadded(w.terrain(), r.job.coord, edits, padded->light);
        world::ChunkMesh expected;
        world::meshAtDetail(*padded, r.job.mode, r.job.cell, *coarse, expected);
        ASSERT_GT(expected.quadCount(), 0u); // precondition: a chunk with something to draw
        // and some of it in the shade, so that a mesh built without light would differ
        ASSERT_TRUE(std::any_of(expected.vertices.begin(), expected.vertices.end(),
                                [](const world::ChunkVertex& v) { return world::sunlightOf(v) < world::kMaxLight; }));
        ASSERT_EQ(r.mesh.vertices.size(), expected.vertices.size());
        EXPECT_EQ(std::memcmp(r.mesh.vertices.data(), expected.vertices.data(),
                              expected.vertices.size() * sizeof(world::ChunkVertex)),
                  0);
        // And the culling data of the fine chunk, whatever the level of detail: occupancy for cell 1 only.
        const world::CullingData want = world::cullingDataOf(*padded, r.job.cell);
        // Precondition: ground solid through some column, so forgotten culling data (all clear) would show.
        ASSERT_TRUE(std::any_of(want.solid.layers.begin(), want.solid.layers.end(), [](auto l) { return l != 0; }));
        for (int f = 0; f < world::kFaceCount; ++f) EXPECT_EQ(r.culling.links.to[f], want.links.to[f]) << f;
        EXPECT_EQ(r.culling.solid.layers, want.solid.layers);
        ASSERT_EQ(r.culling.occupancy != nullptr, r.job.cell == 1);
        if (r.job.cell == 1) {
            EXPECT_EQ(r.culling.occupancy->rows, world::occupancyOf(*padded).rows);
        }
    }
}

// takeRegion takes every queued job of the first light region the worker is not in, so the caller and the worker
// never both light one region. 12 regions' chunks queued region by region; the caller takes regions until none is
// left to it: each call's jobs share a region, no region is both taken here and run by the worker, and every job
// comes back once. Preconditions: both the caller and the worker meshed some regions (the caller starts once the
// worker holds a job). Mutation caught: takeRegion taking the front region even when the worker is in it (a region
// meshed by both).
TEST(MeshWorker, TakeRegionLeavesTheWorkersRegionToIt) {
    const world::World w(world::TerrainDef{2});
    world::MeshWorker worker(w.terrain());
    worker.waitIdle();
    std::vector<MeshJob> jobs;
    const int side = world::kLightRegion;
    for (int r = 0; r < 12; ++r)
        for (int k = 0; k < side * side; ++k)
            for (int y = 0; y < world::kWorldHeightChunks; ++y)
                jobs.push_back(jobFor(w, {r * side + k % side, y, k / side}, MeshMode::Greedy, 1));
    const std::size_t total = jobs.size();
    worker.submit(std::move(jobs));
    // Wait until the worker holds a job (its region is then taken), not for a time: so the worker has a region
    // of its own whatever the load, and the caller's takes start beside it.
    while (worker.queued() == total) std::this_thread::yield();
    worker.hold(true); // it finishes the job in hand and starts no other: every other region is this thread's
    const auto regionOf = [](world::ChunkCoord c) { return world::lightRegionOf(c).x; }; // all in z region 0
    std::vector<int> takenRegions;
    std::vector<std::tuple<int, int, int>> all; // every job's chunk, taken or run
    for (std::vector<MeshJob> region = worker.takeRegion(); !region.empty(); region = worker.takeRegion()) {
        takenRegions.push_back(regionOf(region.front().coord));
        for (MeshJob& j : region) {
            EXPECT_EQ(regionOf(j.coord), takenRegions.back());
            all.emplace_back(j.coord.x, j.coord.y, j.coord.z);
            world::MeshWorker::run(w.terrain(), std::move(j)); // as the render thread does
        }
    }
    worker.hold(false); // the worker's own region is left to it
    worker.waitIdle();
    std::vector<int> workerRegions;
    for (const world::MeshResult& r : worker.takeResults()) {
        workerRegions.push_back(regionOf(r.job.coord));
        all.emplace_back(r.job.coord.x, r.job.coord.y, r.job.coord.z);
    }
    for (const int r : takenRegions) {
        EXPECT_EQ(std::count(workerRegions.begin(), workerRegions.end(), r), 0) << "region " << r << " meshed by both";
    }
    std::sort(all.begin(), all.end());
    ASSERT_EQ(all.size(), total);
    EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end()); // each job once
    EXPECT_EQ(takenRegions.size(), 11u);                              // all but the worker's
    EXPECT_GT(workerRegions.size(), 0u);
}

// The caller can take queued jobs itself, nearest (first given) first; a new submission replaces the
// queue. The worker is held (MeshWorker::hold), so the order and what is taken are exact on any machine.
TEST(MeshWorker, TakeJobFollowsTheQueueAndSubmitReplacesIt) {
    const world::World w(world::TerrainDef{2});
    world::MeshWorker worker(w.terrain());
    worker.waitIdle();
    worker.hold(true);
    std::vector<MeshJob> first, second;
    for (int i = 0; i < 400; ++i) first.push_back(jobFor(w, {i, 1, 0}, MeshMode::Greedy, 1));
    // The second list's chunks lie beyond the first's, so each job says which list it came from.
    for (int i = 0; i < 3; ++i) second.push_back(jobFor(w, {1000 + i, 1, 0}, MeshMode::Greedy, 1));
    worker.submit(std::move(first));
    ASSERT_EQ(worker.queued(), 400u);
    worker.submit(std::move(second)); // the first list is gone: this thread sees only the second
    std::vector<int> taken;
    while (const auto j = worker.takeJob()) taken.push_back(j->coord.x);
    worker.hold(false);
    worker.waitIdle();
    const std::vector<world::MeshResult> done = worker.takeResults();
    std::vector<int> all = taken;
    for (const auto& r : done) all.push_back(r.job.coord.x);
    std::sort(all.begin(), all.end());
    std::vector<int> fromFirst, fromSecond;
    for (const int x : all) (x >= 1000 ? fromSecond : fromFirst).push_back(x);
    EXPECT_EQ(fromSecond, (std::vector<int>{1000, 1001, 1002})); // each job of the new queue exactly once
    for (std::size_t i = 0; i < fromFirst.size(); ++i)
        EXPECT_EQ(fromFirst[i], static_cast<int>(i)) << "the first list's jobs done are its front, each once";
    EXPECT_TRUE(fromFirst.empty()) << "the first list was replaced before the held worker started it";
    for (const int x : taken) EXPECT_GE(x, 1000) << "this thread took a job of the replaced list";
    for (std::size_t i = 1; i < taken.size(); ++i) EXPECT_LT(taken[i - 1], taken[i]) << "front first";
}

// Dropping a worker with a long queue drops the queue and joins the thread (under the sanitizers:
// without a race or a leak); a hang here would stop the test at CTest's time limit.
TEST(MeshWorker, StopsWithALongQueue) {
    const world::World w(world::TerrainDef{3});
    auto worker = std::make_unique<world::MeshWorker>(w.terrain());
    std::vector<MeshJob> jobs;
    jobs.reserve(2000);
    for (int i = 0; i < 2000; ++i) jobs.push_back(jobFor(w, {i, 1, 0}, MeshMode::Greedy, 1));
    worker->hold(true); // so the whole queue is still waiting when it is dropped, on any machine
    worker->submit(std::move(jobs));
    ASSERT_EQ(worker->queued(), 2000u);
    worker->hold(false);
    worker.reset();
}

} // namespace

// A chunk whose result waits to be taken is still wanted by the render thread until it applies the result, so the
// next frame's queue names it again: the worker must not mesh it again (on the render thread, takeRegion would light
// its region a second time). Mutation caught: submit skipping only the running job (4 jobs queued again).
TEST(MeshWorkerQueue, DoneJobsWaitingToBeTakenAreNotQueuedAgain) {
    const world::World w(world::TerrainDef{3});
    world::MeshWorker worker(w.terrain());
    std::vector<world::MeshJob> jobs, again;
    for (int y = 0; y < world::kWorldHeightChunks; ++y) {
        jobs.push_back(jobFor(w, {0, y, 0}, MeshMode::Greedy, 1));
        again.push_back(jobFor(w, {0, y, 0}, MeshMode::Greedy, 1));
    }
    worker.submit(std::move(jobs));
    worker.waitIdle();
    worker.submit(std::move(again)); // the results are not taken yet
    EXPECT_EQ(worker.queued(), 0u);
    worker.waitIdle();
    EXPECT_EQ(worker.takeResults().size(), static_cast<std::size_t>(world::kWorldHeightChunks)); // each once
}
