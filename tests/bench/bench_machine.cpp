// The machine's own stalls, a control for reading frame times: the same fixed piece of arithmetic
// (8-9 ms on the development machines; no memory traffic, no system calls), timed 300 times in a row
// while a second thread keeps the other core busy, as llvmpipe's rasterising threads do while the game
// thread issues a frame. Any run slower than the fastest is time the machine took away (another
// thread, the host of a virtual machine), not work: where the worst run takes 40 ms longer than the
// fastest, a frame can too, whatever the game does. `scripts/frame_stats.py` prints these figures
// beside its frame table (docs/ENGINE.md, "Speed").
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

namespace {

// A dependent chain of multiplies and adds: its time is cycles, whatever the caches hold.
std::uint64_t fixedWork(std::uint64_t x) {
    constexpr int kSteps = 6'000'000;
    for (int i = 0; i < kSteps; ++i) x = x * 6364136223846793005ull + 1442695040888963407ull;
    return x;
}

void machineStalls(benchmark::State& state) {
    constexpr int kRuns = 300;
    std::atomic<bool> stop{false};
    std::thread sibling([&] {
        std::uint64_t y = 1;
        while (!stop.load(std::memory_order_relaxed)) y = fixedWork(y) | 1u;
        benchmark::DoNotOptimize(y);
    });
    std::vector<double> ms;
    ms.reserve(kRuns);
    std::uint64_t x = 1;
    for (auto _ : state) {
        ms.clear();
        for (int i = 0; i < kRuns; ++i) {
            const auto a = std::chrono::steady_clock::now();
            x = fixedWork(x);
            benchmark::DoNotOptimize(x);
            const auto b = std::chrono::steady_clock::now();
            ms.push_back(std::chrono::duration<double, std::milli>(b - a).count());
        }
    }
    stop = true;
    sibling.join();
    std::sort(ms.begin(), ms.end());
    const auto at = [&](double q) { return ms[static_cast<std::size_t>(q * static_cast<double>(ms.size() - 1))]; };
    state.counters["fastest_ms"] = ms.front();
    state.counters["median_ms"] = at(0.5);
    state.counters["p99_ms"] = at(0.99);
    state.counters["worst_ms"] = ms.back();
    // Time taken away from the slowest run, and how many runs lost more than 5 ms.
    state.counters["worst_stall_ms"] = ms.back() - ms.front();
    state.counters["runs_over_5ms_late"] =
        static_cast<double>(std::count_if(ms.begin(), ms.end(), [&](double v) { return v > ms.front() + 5.0; }));
}
BENCHMARK(machineStalls)->Iterations(1)->Unit(benchmark::kMillisecond);

} // namespace
