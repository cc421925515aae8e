// The pendulum studies of minecrappy-lab, as library functions so that tests can run them on tiny
// inputs: one run written as CSV, work-precision (accuracy against cost), stability limits as first
// failures on a fine grid, and the seed write-up's figures redone against the exact solution.
// Every function takes its sizes and durations as parameters; the defaults are the full studies.
// It must never touch a terminal or exit: progress goes through a callback, results are returned,
// and files are written whole (temporary file + rename) or not at all.
// This header holds what they share; each study has its own: lab/pendulum_run.h, lab/work_precision.h,
// lab/stability.h, lab/stability_map.h and lab/seed_figures.h.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

using Progress = std::function<void(const std::string& line)>;

// Every method that takes steps (all but Exact), in enum order.
std::vector<physics::Method> steppedMethods();
// Every stepped method but the adaptive one (dopri5 picks its own steps, so every output step is bounded: its
// stability scan and map would be one verdict and cost as much as three others).
std::vector<physics::Method> fixedStepMethods();
// A fixed colour per method, shared by all charts so a method looks the same everywhere.
int methodColour(physics::Method method);
// Angle difference wrapped to (-pi, pi]: a pendulum one turn ahead is in the same place.
double wrapAngle(double radians);

inline constexpr std::int64_t kMaxSteps = 50'000'000; // ~5 GB of CSV; more is refused, not attempted

// Steps needed to reach `seconds`: the last one may end past it, but 10 / 0.001 is 10000, not 10001.
// Returns -1 when the count is not finite or does not fit.
std::int64_t stepCount(double seconds, double dt);

// Helpers that several studies' files share; not part of the lab's interface.
namespace detail {

inline double degToRad(double deg) { return deg * std::numbers::pi / 180.0; }

inline std::string name(physics::Method m) { return std::string(physics::methodName(m)); }

inline double mgl(const physics::PendulumParams& p) { return p.mass * p.gravity * p.length; }

// The methods of `points`, each once, in the order they first appear (the charts' legend order).
template <typename Point>
std::vector<physics::Method> methodsInOrder(const std::vector<Point>& points) {
    std::vector<physics::Method> seen;
    for (const auto& p : points) {
        if (std::find(seen.begin(), seen.end(), p.method) == seen.end()) seen.push_back(p.method);
    }
    return seen;
}

// Method `m`'s series in its colour: the point (x(p), y(p)) of each of `points` that `m` made, in order.
template <typename Point, typename X, typename Y>
Series methodSeries(const std::vector<Point>& points, physics::Method m, X x, Y y) {
    Series s{name(m), {}, {}, methodColour(m), true, false, true};
    for (const auto& p : points) {
        if (p.method != m) continue;
        s.x.push_back(x(p));
        s.y.push_back(y(p));
    }
    return s;
}

// Runs job(i) for i in [0, count) on `threads` threads (0: one per hardware thread); each i exactly once.
template <typename Job>
void parallelFor(std::size_t count, int threads, Job&& job) {
    std::size_t n = threads > 0 ? static_cast<std::size_t>(threads) : std::thread::hardware_concurrency();
    n = std::clamp<std::size_t>(n, 1, std::max<std::size_t>(count, 1));
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto worker = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < count;) {
            try {
                job(i);
            } catch (...) {
                const std::lock_guard lock(failureMutex);
                if (!failure) failure = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

} // namespace detail

} // namespace lab
