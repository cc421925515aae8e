// Nanoseconds per step for every pendulum method, each on the same swing (60 degrees, h = 1/60 s; dopri5 at
// its default tolerance, stepping to each tick).
// The exact solution is timed per evaluation of the closed form at a new time.
#include <benchmark/benchmark.h>

#include "physics/pendulum.h"

#include <algorithm>
#include <cstdint>

namespace {

void stepBench(benchmark::State& state, physics::Method method) {
    const physics::PendulumParams params;
    physics::Pendulum p(method, params, {60.0 * 3.14159265358979323846 / 180.0, 0.0});
    const double h = 1.0 / 60.0;
    for (auto _ : state) {
        p.step(h);
        benchmark::DoNotOptimize(p.state());
    }
    // Counted, not looked up: implicit-midpoint's Newton iterations and dopri5's steps vary.
    state.counters["evals_per_step"] =
        static_cast<double>(p.evaluations()) / static_cast<double>(std::max<std::int64_t>(state.iterations(), 1));
}

} // namespace

BENCHMARK_CAPTURE(stepBench, euler, physics::Method::Euler);
BENCHMARK_CAPTURE(stepBench, euler_cartesian, physics::Method::EulerCartesian);
BENCHMARK_CAPTURE(stepBench, midpoint, physics::Method::Midpoint);
BENCHMARK_CAPTURE(stepBench, trapezoid, physics::Method::Trapezoid);
BENCHMARK_CAPTURE(stepBench, symplectic_euler, physics::Method::SymplecticEuler);
BENCHMARK_CAPTURE(stepBench, verlet, physics::Method::Verlet);
BENCHMARK_CAPTURE(stepBench, rk4, physics::Method::Rk4);
BENCHMARK_CAPTURE(stepBench, implicit_midpoint, physics::Method::ImplicitMidpoint);
BENCHMARK_CAPTURE(stepBench, yoshida4, physics::Method::Yoshida4);
BENCHMARK_CAPTURE(stepBench, dopri5, physics::Method::Dopri5);
BENCHMARK_CAPTURE(stepBench, exact, physics::Method::Exact);
