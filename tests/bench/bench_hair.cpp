// Wall time of HairSolver::step() for a default ball (512 strands x 12 nodes, default iterations, ball collision)
// and for a big one (65,536 x 16) on one and two threads. Ratios against the naive and limit kernels are
// measured by minecrappy-lab hair-bench, in one run.
#include <benchmark/benchmark.h>

#include "physics/hair.h"

namespace {

void stepBench(benchmark::State& state, int strands, int nodes, int threads) {
    physics::HairParams params;
    params.strands = strands;
    params.nodesPerStrand = nodes;
    params.sleepSpeed = 0.0f; // time the work, not the sleeping shortcut
    const physics::HostPose pose{{0.0f, 2.0f, 0.0f}, {}};
    physics::HairSolver hair(params, 0.25f, pose);
    for (auto _ : state) {
        const auto stats = hair.step(pose, 1.0f / 60.0f, {}, nullptr, threads);
        benchmark::DoNotOptimize(stats);
    }
    state.counters["node_steps_per_s"] =
        benchmark::Counter(static_cast<double>(strands) * nodes, benchmark::Counter::kIsIterationInvariantRate);
}

} // namespace

BENCHMARK_CAPTURE(stepBench, default_ball, 512, 12, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(stepBench, big_65536x16_1thread, 65536, 16, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(stepBench, big_65536x16_2threads, 65536, 16, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

// A whole game tick with many default hair balls that never sleep (the worst case: sleeping balls cost
// nothing), packed as tightly as the space rules allow (spheres touching, 0.6 m apart, hair tangled) or
// spread 4 m apart; with the default hair budget and without one. docs/HAIR.md: the ballsTick table.
#include <cmath>
#include <cstdint>
#include <limits>

#include "game/game_state.h"

namespace {

void ballsTickBench(benchmark::State& state) {
    const int count = static_cast<int>(state.range(0));
    const float spacing = static_cast<float>(state.range(1)) / 10.0f;
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    if (state.range(2) == 0) def.hairBudget = std::numeric_limits<std::int64_t>::max();
    game::GameState s(def);
    game::HairBallDef ball;
    ball.hair.sleepSpeed = 0.0f;
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    for (int i = 0; i < count; ++i) {
        const int row = i / side, column = i % side; // a square grid, row by row
        const float x = 3.0f + spacing * static_cast<float>(column), z = -3.0f - spacing * static_cast<float>(row);
        s.hairBalls.emplace_back(glm::vec3(x, 36.0f, z), ball);
    }
    for (int t = 0; t < 30; ++t) game::tick(s, {}, 1.0 / 60.0); // the hair falls and tangles first
    for (auto _ : state) game::tick(s, {}, 1.0 / 60.0);
}

void ballsArgs(benchmark::internal::Benchmark* b) {
    for (const int budget : {1, 0}) {
        for (const int spacing : {6, 40}) {
            for (const int count : {1, 10, 40, 100}) b->Args({count, spacing, budget});
        }
    }
    b->ArgNames({"balls", "spacing_dm", "budget"});
}

} // namespace

BENCHMARK(ballsTickBench)->Apply(ballsArgs)->Unit(benchmark::kMillisecond)->MinTime(0.5);

// What the state hash costs now that it reads every hair node: game::stateHash of a state with 1, 10 and 100
// default balls (512 x 12 nodes each), against one tick of the same state measured in the same run
// (counter hash_per_tick). A session hashes only on the ticks a recording writes or a replay checks (every
// 10th), so a tenth of this ratio is its share of a recorded tick. docs/WORLDS.md quotes it.
#include <chrono>

#include "game/state_io.h"

namespace {

void stateHashBench(benchmark::State& state) {
    const int count = static_cast<int>(state.range(0));
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    game::GameState s(def);
    game::HairBallDef ball;
    ball.hair.sleepSpeed = 0.0f;
    for (int i = 0; i < count; ++i) {
        const int row = i / 10, column = i % 10; // rows of ten, 4 m apart
        const float x = 3.0f + 4.0f * static_cast<float>(column), z = -3.0f - 4.0f * static_cast<float>(row);
        s.hairBalls.emplace_back(glm::vec3(x, 36.0f, z), ball);
    }
    for (int t = 0; t < 10; ++t) game::tick(s, {}, 1.0 / 60.0);
    const auto secondsEach = [](int n, auto&& f) {
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < n; ++i) f();
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / n;
    };
    const double tick = secondsEach(20, [&] { game::tick(s, {}, 1.0 / 60.0); });
    const double hash = secondsEach(20, [&] { benchmark::DoNotOptimize(game::stateHash(s)); });
    for (auto _ : state) benchmark::DoNotOptimize(game::stateHash(s));
    state.counters["tick_ms"] = tick * 1e3;
    state.counters["hash_per_tick"] = hash / tick;
}

} // namespace

BENCHMARK(stateHashBench)->Arg(1)->Arg(10)->Arg(100)->ArgName("balls")->Unit(benchmark::kMicrosecond);

// What an autosave costs: on the main thread save::takeSnapshot (save:0), a plain copy of the state, hair
// included (221 KB a default ball), and its state hash, of a world with 2,000 edits, the demo's pendulum set
// and three default balls; on the autosaver's thread the save itself (save:1). docs/WORLDS.md quotes both.
#include <filesystem>
#include <system_error>

#include "save/world_store.h"

namespace {

void snapshotBench(benchmark::State& state) {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    game::GameState s(def);
    for (int i = 0; i < 2000; ++i) s.world.set({i % 40, 40 + i / 400, (i / 40) % 10}, world::BlockType::Brick);
    while (s.hairBalls.size() < 3)
        s.hairBalls.emplace_back(glm::vec3(3.0f * static_cast<float>(s.hairBalls.size()), 36.0f, -3.0f));
    for (int t = 0; t < 10; ++t) game::tick(s, {}, 1.0 / 60.0);
    if (state.range(0) == 0) {
        for (auto _ : state) benchmark::DoNotOptimize(save::takeSnapshot(s));
        return;
    }
    // The autosaver thread's part: one save of that snapshot (a transaction, synchronous=FULL) to a file in the
    // temporary folder, so it measures that disk.
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "minecrappy-bench-save.mcworld";
    std::error_code ec;
    save::removeWorldFiles(file, ec);
    auto store = save::WorldStore::open(file, true);
    const save::Snapshot snap = save::takeSnapshot(s);
    for (auto _ : state) store->save(snap);
    store.reset();
    save::removeWorldFiles(file, ec);
}

} // namespace

BENCHMARK(snapshotBench)->Arg(0)->Arg(1)->ArgName("save")->Unit(benchmark::kMillisecond);
