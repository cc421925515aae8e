// Nanoseconds per step for every pendulum method, each on the same swing (60 degrees, h = 1/60 s).
// The exact solution is timed per evaluation of the closed form at a new time.
#include <benchmark/benchmark.h>

#include "physics/pendulum.h"

namespace {

void stepBench(benchmark::State& state, physics::Method method) {
    const physics::PendulumParams params;
    physics::Pendulum p(method, params, {60.0 * 3.14159265358979323846 / 180.0, 0.0});
    const double h = 1.0 / 60.0;
    for (auto _ : state) {
        p.step(h);
        benchmark::DoNotOptimize(p.state());
    }
    state.counters["evals_per_step"] = physics::evaluationsPerStep(method);
}

} // namespace

BENCHMARK_CAPTURE(stepBench, euler, physics::Method::Euler);
BENCHMARK_CAPTURE(stepBench, euler_cartesian, physics::Method::EulerCartesian);
BENCHMARK_CAPTURE(stepBench, midpoint, physics::Method::Midpoint);
BENCHMARK_CAPTURE(stepBench, trapezoid, physics::Method::Trapezoid);
BENCHMARK_CAPTURE(stepBench, symplectic_euler, physics::Method::SymplecticEuler);
BENCHMARK_CAPTURE(stepBench, verlet, physics::Method::Verlet);
BENCHMARK_CAPTURE(stepBench, rk4, physics::Method::Rk4);
BENCHMARK_CAPTURE(stepBench, exact, physics::Method::Exact);
