#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <set>

#include "app/panels.h"
#include "app/runners.h"
#include "app/session.h"
#include "input/script.h"
#include "render/context_osmesa.h"
#include "render/data_dir.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"
#include "ui/ui.h"

namespace app {

namespace {

// SIGTERM or SIGINT end the run at the next tick boundary, and the run then finishes as if its ticks
// were done: screenshot, save, dump. The handler only records the signal; a second one kills at once
// (the default action is back), for a finish that hangs.
volatile std::sig_atomic_t g_stopSignal = 0;
void onStopSignal(int signal) {
    g_stopSignal = signal;
    std::signal(signal, SIG_DFL);
}

struct Frame {
    render::OsMesaContext& context;
    render::SceneRenderer& scene;
    ui::ImGuiLayer& imgui;
    ObjectPanels& panels;
};

// Draws the current state (alpha = 1: headless has no time between ticks) with the HUD. A lone frame
// (a screenshot) first lays the UI out once without drawing it: Dear ImGui sizes auto-fitting windows
// on their first frame and shows them from the second.
void drawFrame(Frame& f, Session& s, const render::SceneSettings& settings, const ui::HudMessage& message,
               bool& overlay, bool& help, bool lone) {
    const glm::ivec2 size = f.context.framebufferSize();
    f.scene.render(s.state(), render::interpolatedCamera(s.state(), 1.0f), size, settings);
    for (int pass = lone ? 0 : 1; pass < 2; ++pass) {
        f.imgui.beginFrame(size, static_cast<float>(s.tickSeconds()));
        ui::drawObjectLabels(s.state(), f.scene, 1.0f);
        ui::drawHud(s.state(), f.scene.atlas(), message);
        f.panels.show(s);
        if (overlay) {
            ui::OverlayInfo info;
            info.chunks = f.scene.stats().chunks;
            info.renderCpuMs = f.scene.stats().cpuMs;
            ui::showOverlayPanel(s.state(), info, &overlay);
        }
        if (help) ui::showHelpPanel(&help);
        if (s.state().paused) ui::showPausePanel(&help);
        if (pass == 0) {
            f.imgui.discardFrame();
        } else {
            f.imgui.endFrame();
        }
    }
    f.context.present();
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const auto i = static_cast<std::size_t>(
        std::min<double>(static_cast<double>(v.size() - 1), p * static_cast<double>(v.size() - 1) + 0.5));
    return v[i];
}

// --soak-report: checks a long run once per game minute. Per tick it only reads the state (energy
// errors of 4 slots, a finite check of every hair node: microseconds); /proc is read once a minute.
// Bounds: the exact slot to 1e-9 of m g L; symplectic-euler and verlet conserve a nearby energy, so
// their error stays within kSymplecticFactor x what they reached in the first minute (measured in
// the same run, not guessed); RSS may grow by kRssGrowthMiB after minute kWarmupMinutes; a tick
// (Session::step: script events and game::tick) must fit in its own period. Ticks are timed in this
// thread's CPU time, not wall time: on a shared machine preemption alone made wall-time ticks of
// 20-48 ms out of a 0.4 ms mean, which says nothing about the game. Even CPU time has one-off
// outliers there (one tick of 18 ms in CI beside a 1.6-3.9 ms worst when run alone; a parallel test or
// the hypervisor stalls the thread mid-tick). The script repeats the same minute 60 times, so a
// slow path of the game shows up in many minutes; the soak therefore allows one isolated tick
// over budget in the hour, reports it as a warning, and fails on a second one.
class SoakMonitor {
public:
    static constexpr double kExactBound = 1e-9, kSymplecticFactor = 2.0, kRssGrowthMiB = 4.0;
    static constexpr int kWarmupMinutes = 5;
    static constexpr std::size_t kIsolatedOverBudget = 1;
    static constexpr const char* kMethods[3] = {"exact", "symplectic-euler", "verlet"};

    static double threadCpuMs() {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
    }

    SoakMonitor(std::uint64_t ticksPerMinute, double budgetMs)
        : m_ticksPerMinute(ticksPerMinute), m_budgetMs(budgetMs) {}

    // Puts the methods the soak bounds into every set (exact, symplectic-euler, verlet) next to euler,
    // which blows up and must stay finite (marked diverged), and releases them.
    static void setUp(Session& session) {
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

    void afterTick(const game::GameState& s, double tickMs) {
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
        if (!std::isfinite(pl.position.x + pl.position.y + pl.position.z + pl.velocity.x + pl.velocity.y +
                           pl.velocity.z + pl.yaw + pl.pitch)) {
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

    // Writes the report, prints each failure; true when every check passed.
    bool finish(const std::string& path) {
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
            if (!mm.nan.empty())
                failures.push_back("minute " + std::to_string(k + 1) + ": NaN or inf in " + join(mm.nan));
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
                failures.push_back(std::string(kMethods[m]) + " energy error " +
                                   fmt(worst[static_cast<std::size_t>(m)]) + " over its bound " + fmt(bound));
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
        std::ofstream out(path);
        if (!out || !(out << report.dump(2) << '\n')) throw std::runtime_error("cannot write " + path);
        std::printf(
            "soak %zu minutes: energy error exact %.3g, symplectic-euler %.3g, verlet %.3g; RSS %.1f -> %.1f MiB; "
            "longest tick %.2f ms -> %s\n",
            m_minutes.size(), worst[0], worst[1], worst[2], rssAtWarmup, rssMax, longest, path.c_str());
        if (m_overBudget.size() <= kIsolatedOverBudget) {
            for (const auto& t : overBudgetText)
                std::fprintf(stderr, "minecrappy: soak warning: %s (isolated: allowed once an hour)\n", t.c_str());
        }
        for (const auto& f : failures) std::fprintf(stderr, "minecrappy: soak check failed: %s\n", f.c_str());
        return failures.empty();
    }

private:
    struct Minute {
        std::uint64_t tick;
        std::array<double, 3> energy;
        std::set<std::string> nan;
        double rssMiB, longestMs;
    };

    static int methodIndex(physics::Method m) {
        return m == physics::Method::Exact             ? 0
               : m == physics::Method::SymplecticEuler ? 1
               : m == physics::Method::Verlet          ? 2
                                                       : -1;
    }
    static double residentMiB() {
        long pages = 0, resident = 0;
        if (FILE* f = std::fopen("/proc/self/statm", "r")) {
            if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
            std::fclose(f);
        }
        return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
    }
    static std::string join(const std::set<std::string>& v) {
        std::string r;
        for (const auto& x : v) r += (r.empty() ? "" : ", ") + x;
        return r;
    }
    static std::string fmt(double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%.3g", v);
        return b;
    }
    void closeMinute(std::uint64_t tick) {
        m_minutes.push_back({tick, m_energy, m_nan, residentMiB(), m_longestMs});
        m_energy = {};
        m_nan.clear();
        m_longestMs = 0.0;
    }

    std::uint64_t m_ticksPerMinute;
    double m_budgetMs;
    std::array<double, 3> m_energy{};
    std::set<std::string> m_nan;
    double m_longestMs = 0.0;
    std::vector<Minute> m_minutes;
    std::vector<std::pair<std::uint64_t, double>> m_overBudget; // (tick, CPU ms) of every tick over budget
};

// Script lines that a run of `ticks` ticks from `startTick` never reaches are most likely a mistake
// (a --ticks too small for the script): say so once, before the run.
void warnAboutLateEvents(const Options& o, const std::vector<input::ScriptEvent>& events, std::uint64_t startTick) {
    if (o.script.empty()) return;
    const std::uint64_t end = startTick > UINT64_MAX - o.ticks ? UINT64_MAX : startTick + o.ticks;
    const input::LateEvents late = input::eventsFrom(events, end);
    if (late.count == 0) return;
    std::string from;
    if (startTick > 0) from = " from tick " + std::to_string(startTick) + " of the world";
    std::fprintf(stderr,
                 "minecrappy: warning: %s: %zu event%s at tick >= %llu will not run (--ticks %llu%s); the first is "
                 "line %d\n",
                 o.script.c_str(), late.count, late.count == 1 ? "" : "s", static_cast<unsigned long long>(end),
                 static_cast<unsigned long long>(o.ticks), from.c_str(), late.firstLine);
}

const char* signalName(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

} // namespace

int runHeadless(const Options& o, const Settings& userSettings) {
    // Installed first, so a signal during start-up (loading a world) also ends the run cleanly.
    g_stopSignal = 0;
    std::signal(SIGTERM, onStopSignal);
    std::signal(SIGINT, onStopSignal);
    Session session(o, userSettings);
    for (const auto& w : session.loadWarnings()) std::fprintf(stderr, "minecrappy: warning: %s\n", w.c_str());
    if (session.hasWorld())
        std::printf("world: %s (tick %llu)\n", session.worldPath().c_str(),
                    static_cast<unsigned long long>(session.state().tick));
    // A test waits for the line above before it signals the run.
    std::fflush(stdout);
    warnAboutLateEvents(o, session.script(), session.state().tick);
    render::OsMesaContext context(o.width, o.height);
    const auto data = render::dataDir();
    render::SceneRenderer scene(data);
    ui::ImGuiLayer imgui(nullptr);
    ObjectPanels panels;
    Frame frame{context, scene, imgui, panels};

    render::SceneSettings settings;
    settings.fovDegrees = o.fov;
    settings.viewRadius = o.viewRadius;
    // Screenshots must not depend on how fast this machine meshes: stream everything in range first.
    settings.meshBudgetSeconds = 0.0;

    const bool benchmark = !o.frameStats.empty();
    render::SceneSettings benchSettings = settings;
    benchSettings.meshBudgetSeconds = 0.004; // as the window does
    std::vector<double> frameMs;
    double trianglesSum = 0.0, drawnSum = 0.0;
    bool overlay = false, help = false;
    ui::HudMessage message;

    std::optional<SoakMonitor> soak;
    if (!o.soakReport.empty()) {
        soak.emplace(static_cast<std::uint64_t>(o.tickRate) * 60,
                     o.soakTickBudgetMs > 0.0 ? o.soakTickBudgetMs : 1000.0 * session.tickSeconds());
        SoakMonitor::setUp(session);
    }

    int exitCode = 0;
    std::uint64_t ticksRun = 0;
    for (; ticksRun < o.ticks && g_stopSignal == 0; ++ticksRun) {
        const double tickStart = soak ? SoakMonitor::threadCpuMs() : 0.0;
        // Events of tick T are applied in the step that starts at state tick T; a screenshot they ask
        // for is named after that tick, as the README's script example says.
        const std::uint64_t eventTick = session.state().tick;
        const AppRequests r = session.step();
        if (soak) soak->afterTick(session.state(), SoakMonitor::threadCpuMs() - tickStart);
        for (const auto& e : session.takeSaveErrors()) { // keep playing: the last good save stays on disk
            std::fprintf(stderr, "minecrappy: autosave failed: %s\n", e.c_str());
            message = {"Autosave failed: " + e, 5.0};
        }
        overlay ^= r.toggleOverlay;
        help ^= r.toggleHelp;
        if (r.interact) panels.interact(session.state());
        message.secondsLeft -= session.tickSeconds();
        if (benchmark) {
            const auto start = std::chrono::steady_clock::now();
            drawFrame(frame, session, benchSettings, message, overlay, help, false);
            frameMs.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            trianglesSum += static_cast<double>(scene.stats().chunks.triangles);
            drawnSum += scene.stats().chunks.drawn;
        }
        if (r.screenshot) {
            drawFrame(frame, session, settings, message, overlay, help, true);
            char name[64];
            std::snprintf(name, sizeof name, "minecrappy-tick-%06llu", static_cast<unsigned long long>(eventTick));
            std::filesystem::path path = std::filesystem::path(o.screenshotDir) / (std::string(name) + ".png");
            for (int n = 2; std::filesystem::exists(path); ++n) {
                path = std::filesystem::path(o.screenshotDir) / (std::string(name) + "-" + std::to_string(n) + ".png");
            }
            render::writePng(render::readFramebuffer(o.width, o.height), path);
            std::printf("screenshot: %s\n", path.c_str());
            message = {"Saved " + path.string(), 3.0};
        }
    }

    const int stopSignal = g_stopSignal;
    if (stopSignal != 0) {
        std::fprintf(stderr, "minecrappy: interrupted by %s at tick %llu of %llu\n", signalName(stopSignal),
                     static_cast<unsigned long long>(ticksRun), static_cast<unsigned long long>(o.ticks));
        exitCode = 128 + stopSignal; // as the shell reports a process the signal ended
    }
    if (!o.screenshot.empty()) {
        drawFrame(frame, session, settings, message, overlay, help, true);
        render::writePng(render::readFramebuffer(o.width, o.height), o.screenshot);
        std::printf("wrote %s\n", o.screenshot.c_str());
    }
    // An interrupted run saves even without --save: the ticks since the last autosave would be lost.
    if ((o.saveAtEnd || stopSignal != 0) && session.hasWorld()) {
        const auto errors = session.saveNow();
        for (const auto& e : errors) std::fprintf(stderr, "minecrappy: save failed: %s\n", e.c_str());
        if (errors.empty()) {
            std::printf("saved %s\n", session.worldPath().c_str());
        } else if (stopSignal == 0) {
            exitCode = 1;
        }
    }
    if (!o.dumpState.empty()) {
        session.writeDump(o.dumpState);
        std::printf("wrote %s\n", o.dumpState.c_str());
    }
    if (soak && !soak->finish(o.soakReport) && stopSignal == 0) exitCode = 1;
    if (benchmark) {
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        const double sum = std::accumulate(frameMs.begin(), frameMs.end(), 0.0);
        nlohmann::json stats = {
            {"frames", frameMs.size()},
            {"size", {o.width, o.height}},
            {"view_radius", o.viewRadius},
            {"mean_ms", frameMs.empty() ? 0.0 : sum / static_cast<double>(frameMs.size())},
            {"median_ms", percentile(frameMs, 0.5)},
            {"p99_ms", percentile(frameMs, 0.99)},
            {"worst_ms", frameMs.empty() ? 0.0 : *std::max_element(frameMs.begin(), frameMs.end())},
            {"frames_over_50ms", std::count_if(frameMs.begin(), frameMs.end(), [](double v) { return v > 50.0; })},
            {"mean_triangles", frameMs.empty() ? 0.0 : trianglesSum / static_cast<double>(frameMs.size())},
            {"mean_chunks_drawn", frameMs.empty() ? 0.0 : drawnSum / static_cast<double>(frameMs.size())},
            {"peak_rss_mib", static_cast<double>(usage.ru_maxrss) / 1024.0},
        };
        std::ofstream out(o.frameStats);
        if (!out || !(out << stats.dump(2) << '\n')) throw std::runtime_error("cannot write " + o.frameStats);
        std::printf("frames %zu: median %.2f ms, p99 %.2f ms, worst %.2f ms, %.0f triangles, peak RSS %.0f MiB -> %s\n",
                    frameMs.size(), stats["median_ms"].get<double>(), stats["p99_ms"].get<double>(),
                    stats["worst_ms"].get<double>(), stats["mean_triangles"].get<double>(),
                    stats["peak_rss_mib"].get<double>(), o.frameStats.c_str());
    }
    return exitCode;
}

} // namespace app
