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
