#include "session/diagnostics.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>
#include <numeric>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/log.h"
#include "core/thread_clock.h"
#include "world/column_light.h"

namespace session {

namespace {

int methodIndex(physics::Method m) {
    return m == physics::Method::Exact             ? 0
           : m == physics::Method::SymplecticEuler ? 1
           : m == physics::Method::Verlet          ? 2
                                                   : -1;
}

double residentMiB() {
    long pages = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

std::string join(const std::set<std::string>& v) {
    std::string r;
    for (const auto& x : v) r += (r.empty() ? "" : ", ") + x;
    return r;
}

std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", v);
    return b;
}

} // namespace

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const auto i = static_cast<std::size_t>(
        std::min<double>(static_cast<double>(v.size() - 1), p * static_cast<double>(v.size() - 1) + 0.5));
    return v[i];
}

double SoakMonitor::threadCpuMs() { return core::threadCpuSeconds() * 1e3; }

void SoakMonitor::setUp(Session& session) {
    std::vector<game::PendulumCommand> commands;
    for (std::size_t i = 0; i < session.state().pendulumSets.size(); ++i) {
        game::PendulumSetDef def = session.state().pendulumSets[i].def();
        def.methods = {physics::Method::Exact, physics::Method::SymplecticEuler, physics::Method::Verlet,
                       physics::Method::Euler};
        commands.push_back({i, game::PendulumCommand::Op::SetDef, def});
        commands.push_back({i, game::PendulumCommand::Op::Release, def});
    }
    session.queue(commands);
}

void SoakMonitor::afterTick(const game::GameState& s, double tickMs) {
    m_longestMs = std::max(m_longestMs, tickMs);
    if (tickMs > m_budgetMs) m_overBudget.push_back({s.tick, tickMs});
    for (const auto& set : s.pendulumSets) {
        for (int i = 0; i < game::kPendulumSlots; ++i) {
            const physics::PendulumState st = set.slot(i).state();
            if (!std::isfinite(st.theta) || !std::isfinite(st.omega)) m_nan.insert("pendulum");
            const int m = methodIndex(set.slot(i).method());
            if (m >= 0 && !set.diverged(i)) {
                m_energy[m] = std::max(m_energy[m], std::abs(set.energyError(i)));
            }
        }
    }
    const game::Player& pl = s.player;
    if (!std::isfinite(pl.position.x + pl.position.y + pl.position.z + pl.velocity.x + pl.velocity.y + pl.velocity.z +
                       pl.yaw + pl.pitch)) {
        m_nan.insert("player");
    }
    for (const auto& ball : s.hairBalls) {
        const physics::HairSolver& h = ball.solver();
        const std::size_t n = static_cast<std::size_t>(h.strands()) * static_cast<std::size_t>(h.nodesPerStrand());
        float sum = 0.0f; // a NaN or inf anywhere makes the sum non-finite; positions are far below overflow
        for (std::size_t k = 0; k < n; ++k) sum += h.x()[k] * 0.0f + h.y()[k] * 0.0f + h.z()[k] * 0.0f;
        if (!std::isfinite(sum)) m_nan.insert("hair");
    }
    if (s.tick % m_ticksPerMinute == 0) closeMinute(s.tick);
}

bool SoakMonitor::finish(const std::string& path) {
    std::vector<std::string> failures;
    nlohmann::json minutes = nlohmann::json::array();
    std::array<double, 3> firstMinute{}, worst{};
    std::size_t warmup = std::min<std::size_t>(kWarmupMinutes, m_minutes.size() / 2);
    double rssAtWarmup = m_minutes.empty() ? 0.0 : m_minutes[warmup].rssMiB, rssMax = rssAtWarmup, longest = 0.0;
    for (std::size_t k = 0; k < m_minutes.size(); ++k) {
        const Minute& mm = m_minutes[k];
        if (k == 0) firstMinute = mm.energy;
        for (int m = 0; m < 3; ++m)
            worst[static_cast<std::size_t>(m)] =
                std::max(worst[static_cast<std::size_t>(m)], mm.energy[static_cast<std::size_t>(m)]);
        if (k >= warmup) rssMax = std::max(rssMax, mm.rssMiB);
        longest = std::max(longest, mm.longestMs);
        if (!mm.nan.empty()) failures.push_back("minute " + std::to_string(k + 1) + ": NaN or inf in " + join(mm.nan));
        nlohmann::json e;
        for (int m = 0; m < 3; ++m) e[kMethods[m]] = mm.energy[static_cast<std::size_t>(m)];
        minutes.push_back({{"minute", k + 1},
                           {"tick", mm.tick},
                           {"energy_error", e},
                           {"nan", join(mm.nan)},
                           {"rss_mib", mm.rssMiB},
                           {"longest_tick_ms", mm.longestMs}});
    }
    nlohmann::json bounds = {{"exact", kExactBound},
                             {"symplectic-euler", kSymplecticFactor * firstMinute[1]},
                             {"verlet", kSymplecticFactor * firstMinute[2]},
                             {"rss_growth_mib", kRssGrowthMiB},
                             {"tick_ms", m_budgetMs}};
    for (int m = 0; m < 3; ++m) {
        const double bound = bounds[kMethods[m]].get<double>();
        if (worst[static_cast<std::size_t>(m)] > bound) {
            failures.push_back(std::string(kMethods[m]) + " energy error " + fmt(worst[static_cast<std::size_t>(m)]) +
                               " over its bound " + fmt(bound));
        }
    }
    if (rssMax - rssAtWarmup > kRssGrowthMiB) {
        failures.push_back("resident memory grew from " + fmt(rssAtWarmup) + " MiB at minute " +
                           std::to_string(warmup + 1) + " to " + fmt(rssMax) + " MiB");
    }
    nlohmann::json overBudget = nlohmann::json::array();
    std::vector<std::string> overBudgetText;
    for (const auto& [tick, ms] : m_overBudget) {
        overBudget.push_back({{"tick", tick}, {"ms", ms}});
        overBudgetText.push_back("tick " + std::to_string(tick) + " (minute " +
                                 std::to_string((tick - 1) / m_ticksPerMinute + 1) + ") took " + fmt(ms) +
                                 " ms, over the " + fmt(m_budgetMs) + " ms budget");
    }
    if (m_overBudget.size() > kIsolatedOverBudget) {
        for (const auto& t : overBudgetText) failures.push_back(t);
    }
    if (m_minutes.empty()) failures.push_back("the run is shorter than one game minute: nothing was checked");
    nlohmann::json report = {
        {"minutes", minutes},
        {"bounds", bounds},
        {"max_energy_error", {{"exact", worst[0]}, {"symplectic-euler", worst[1]}, {"verlet", worst[2]}}},
        {"rss_mib_at_warmup", rssAtWarmup},
        {"rss_mib_max_after_warmup", rssMax},
        {"longest_tick_ms", longest},
        {"ticks_over_budget", overBudget},
        {"failures", failures},
        {"passed", failures.empty()}};
    core::AtomicFile out(path);
    out.stream() << report.dump(2) << '\n';
    out.commit();
    std::printf("soak %zu minutes: energy error exact %.3g, symplectic-euler %.3g, verlet %.3g; RSS %.1f -> %.1f MiB; "
                "longest tick %.2f ms -> %s\n",
                m_minutes.size(), worst[0], worst[1], worst[2], rssAtWarmup, rssMax, longest, path.c_str());
    if (m_overBudget.size() <= kIsolatedOverBudget) {
        for (const auto& t : overBudgetText) core::logWarn("soak: %s (isolated: allowed once an hour)", t.c_str());
    }
    for (const auto& f : failures) core::logError("soak check failed: %s", f.c_str());
    return failures.empty();
}

void SoakMonitor::closeMinute(std::uint64_t tick) {
    m_minutes.push_back({tick, m_energy, m_nan, residentMiB(), m_longestMs});
    m_energy = {};
    m_nan.clear();
    m_longestMs = 0.0;
}

namespace {

// Stretches of frames from the first with chunks pending to the first with none (inclusive): how long
// the view took to complete after the start or a teleport. A stretch still open at the end is listed
// with "complete": false.
nlohmann::json viewsCompleted(const std::vector<FrameSample>& samples) {
    nlohmann::json out = nlohmann::json::array();
    std::size_t begin = 0;
    bool open = false;
    double ms = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const FrameSample& f = samples[i];
        if (!open && f.pendingChunks > 0) {
            open = true;
            begin = i;
            ms = 0.0;
        }
        if (!open) continue;
        ms += f.frameMs;
        if (f.pendingChunks == 0) {
            out.push_back(
                {{"from_tick", samples[begin].tick}, {"frames", i - begin + 1}, {"ms", ms}, {"complete", true}});
            open = false;
        }
    }
    if (open) {
        out.push_back(
            {{"from_tick", samples[begin].tick}, {"frames", samples.size() - begin}, {"ms", ms}, {"complete", false}});
    }
    return out;
}

// How late edits reached the meshes: frames that ended with some chunk showing a mesh older than its blocks
// and light, the most at once, and the chunks the render thread meshed because they had waited too long.
nlohmann::json lateMeshes(const std::vector<FrameSample>& samples) {
    long long framesWithStale = 0, completedLate = 0;
    int most = 0;
    for (const FrameSample& f : samples) {
        framesWithStale += f.staleChunks > 0;
        most = std::max(most, f.staleChunks);
        completedLate += f.completedLate;
    }
    return {{"frames_with_stale", framesWithStale}, {"most_stale", most}, {"completed_late", completedLate}};
}

// Frame time over the frames after the view first completed (the first frame with no chunk pending):
// the loading at the start, whose frames views_completed lists, left out. Zero frames when the view
// never completed.
nlohmann::json afterLoad(const std::vector<FrameSample>& samples) {
    const auto loaded =
        std::find_if(samples.begin(), samples.end(), [](const FrameSample& f) { return f.pendingChunks == 0; });
    std::vector<double> ms;
    if (loaded != samples.end()) {
        for (auto it = std::next(loaded); it != samples.end(); ++it) ms.push_back(it->frameMs);
    }
    const double worst = ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end());
    const std::uint64_t fromTick = loaded != samples.end() ? loaded->tick + 1 : 0;
    return {{"from_tick", fromTick},
            {"frames", ms.size()},
            {"median_ms", percentile(ms, 0.5)},
            {"p99_ms", percentile(ms, 0.99)},
            {"worst_ms", worst}};
}

// The n slowest frames, slowest first, each with what it did: where a spike's time went.
nlohmann::json slowestFrames(const std::vector<FrameSample>& samples, std::size_t n) {
    std::vector<const FrameSample*> order;
    order.reserve(samples.size());
    for (const FrameSample& f : samples) order.push_back(&f);
    n = std::min(n, order.size());
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                      [](const FrameSample* a, const FrameSample* b) { return a->frameMs > b->frameMs; });
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t i = 0; i < n; ++i) {
        const FrameSample& f = *order[i];
        out.push_back({{"tick", f.tick},
                       {"frame_ms", f.frameMs},
                       {"mesh_ms", f.meshMs},
                       {"gpu_wait_ms", f.gpuWaitMs},
                       {"chunks_meshed", f.chunksMeshed},
                       {"triangles", f.triangles},
                       {"draw_calls", f.drawCalls},
                       {"fragments_per_pixel",
                        f.fragmentsPerPixel ? nlohmann::json(*f.fragmentsPerPixel) : nlohmann::json(nullptr)},
                       {"pending_chunks", f.pendingChunks}});
    }
    return out;
}

// Every frame in order, as columns (a few numbers a frame), so that a stretch of a run (a view, a
// stall) can be looked at on its own: scripts/frame_stats.py --stretch.
nlohmann::json perFrame(const std::vector<FrameSample>& samples) {
    nlohmann::json tick = nlohmann::json::array(), frameMs = nlohmann::json::array(),
                   triangles = nlohmann::json::array(), gpuWaitMs = nlohmann::json::array();
    for (const FrameSample& f : samples) {
        tick.push_back(f.tick);
        frameMs.push_back(f.frameMs);
        triangles.push_back(f.triangles);
        gpuWaitMs.push_back(f.gpuWaitMs);
    }
    return {{"tick", tick}, {"frame_ms", frameMs}, {"triangles", triangles}, {"gpu_wait_ms", gpuWaitMs}};
}

} // namespace

FrameStats::FrameStats() { world::countLightCost(true); }

void FrameStats::write(const std::string& path, int width, int height, int viewRadius) const {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto column = [&](double FrameSample::*field) {
        std::vector<double> v;
        v.reserve(m_samples.size());
        for (const FrameSample& f : m_samples) v.push_back(f.*field);
        return v;
    };
    const auto mean = [](const std::vector<double>& v) {
        return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    };
    const auto worst = [](const std::vector<double>& v) {
        return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
    };
    const auto spread = [&](const std::vector<double>& v) {
        return nlohmann::json{{"median", percentile(v, 0.5)}, {"p99", percentile(v, 0.99)}, {"worst", worst(v)}};
    };
    const std::vector<double> frameMs = column(&FrameSample::frameMs);
    std::vector<double> overdraw;
    for (const FrameSample& f : m_samples)
        if (f.fragmentsPerPixel) overdraw.push_back(*f.fragmentsPerPixel);
    nlohmann::json fragments = spread(overdraw);
    fragments["frames"] = overdraw.size();
    const std::vector<double> triangles = column(&FrameSample::triangles);
    // Light's CPU over the whole run (both threads), per voxel of the columns meshed: docs/LIGHT.md's costs.
    const world::LightCost light = world::lightCost();
    const double columnVoxels =
        static_cast<double>(light.columns) * world::kChunkSize * world::kChunkSize * world::kWorldHeight;
    const double lightNsPerVoxel = columnVoxels > 0 ? light.cpuSeconds * 1e9 / columnVoxels : 0.0;
    nlohmann::json stats = {
        {"frames", m_samples.size()},
        {"size", {width, height}},
        {"view_radius", viewRadius},
        {"mean_ms", mean(frameMs)},
        {"median_ms", percentile(frameMs, 0.5)},
        {"p99_ms", percentile(frameMs, 0.99)},
        {"worst_ms", worst(frameMs)},
        {"frames_over_50ms", std::count_if(frameMs.begin(), frameMs.end(), [](double v) { return v > 50.0; })},
        {"mean_triangles", mean(triangles)},
        {"mean_chunks_drawn", mean(column(&FrameSample::chunksDrawn))},
        {"triangles", spread(triangles)},
        {"draw_calls", spread(column(&FrameSample::drawCalls))},
        {"mesh_ms", spread(column(&FrameSample::meshMs))},
        {"gpu_wait_ms", spread(column(&FrameSample::gpuWaitMs))},
        {"fragments_per_pixel", fragments},
        {"views_completed", viewsCompleted(m_samples)},
        {"late_meshes", lateMeshes(m_samples)},
        {"after_load", afterLoad(m_samples)},
        {"peak_rss_mib", static_cast<double>(usage.ru_maxrss) / 1024.0},
        {"light",
         {{"cpu_ms", light.cpuSeconds * 1e3},
          {"regions_relit", light.relit},
          {"regions_repaired", light.repaired},
          {"columns", light.columns},
          {"regions", light.regions},
          {"relit_for_objects", light.relitForObjects},
          {"ns_per_column_voxel", lightNsPerVoxel}}},
        {"slowest", slowestFrames(m_samples, kSlowestListed)},
        {"per_frame", perFrame(m_samples)},
    };
    core::AtomicFile out(path);
    out.stream() << stats.dump(2) << '\n';
    out.commit();
    const nlohmann::json& played = stats["after_load"];
    std::printf("frames %zu: median %.2f ms, p99 %.2f ms, worst %.2f ms (after loading: %.2f, %.2f, %.2f); "
                "median %.0f triangles, %.0f draw calls, %.2f ms meshing, %.2f ms GPU wait, %.2f fragments per pixel; "
                "peak RSS %.0f MiB -> %s\n",
                m_samples.size(), stats["median_ms"].get<double>(), stats["p99_ms"].get<double>(),
                stats["worst_ms"].get<double>(), played["median_ms"].get<double>(), played["p99_ms"].get<double>(),
                played["worst_ms"].get<double>(), stats["triangles"]["median"].get<double>(),
                stats["draw_calls"]["median"].get<double>(), stats["mesh_ms"]["median"].get<double>(),
                stats["gpu_wait_ms"]["median"].get<double>(), stats["fragments_per_pixel"]["median"].get<double>(),
                stats["peak_rss_mib"].get<double>(), path.c_str());
    std::printf("light: %.1f ms CPU (%ld relights of %ld regions, %ld of them for objects; %ld repairs) for %ld "
                "columns: %.3f ns a voxel of them\n",
                light.cpuSeconds * 1e3, light.relit, light.regions, light.relitForObjects, light.repaired,
                light.columns, lightNsPerVoxel);
}

} // namespace session
