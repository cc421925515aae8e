// The headless runner: the game without a window. A script is the input, an OSMesa buffer the screen, and
// frames are drawn only when asked for (a screenshot, --frame-stats); everything else is Frontend's.
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>

#include "app/frontend.h"
#include "app/instruments.h"
#include "app/runners.h"
#include "core/atomic_file.h"
#include "core/log.h"
#include "input/script.h"
#include "render/gl_loader.h"
#include "render/offscreen.h"
#include "session/paths.h"

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

// Script lines that a run of `ticks` ticks from `startTick` never reaches are most likely a mistake
// (a --ticks too small for the script): say so once, before the run.
void warnAboutLateEvents(const session::Options& o, std::uint64_t ticks, const std::vector<input::ScriptEvent>& events,
                         std::uint64_t startTick) {
    if (o.script.empty()) return;
    const std::uint64_t end = startTick > UINT64_MAX - ticks ? UINT64_MAX : startTick + ticks;
    const input::LateEvents late = input::eventsFrom(events, end);
    if (late.count == 0) return;
    std::string from;
    if (startTick > 0) from = " from tick " + std::to_string(startTick) + " of the world";
    core::logWarn("%s: %zu event%s at tick >= %llu will not run (--ticks %llu%s); the first is line %d",
                  o.script.c_str(), late.count, late.count == 1 ? "" : "s", static_cast<unsigned long long>(end),
                  static_cast<unsigned long long>(ticks), from.c_str(), late.firstLine);
}

const char* signalName(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

// A screenshot asked for at tick T is named after T; a second one of the same tick gets "-2", and so on.
std::filesystem::path tickScreenshotPath(const std::string& folder, std::uint64_t tick) {
    char name[64];
    std::snprintf(name, sizeof name, "minecrappy-tick-%06llu", static_cast<unsigned long long>(tick));
    std::filesystem::path path = std::filesystem::path(folder) / (std::string(name) + ".png");
    for (int n = 2; std::filesystem::exists(path); ++n) {
        path = std::filesystem::path(folder) / (std::string(name) + "-" + std::to_string(n) + ".png");
    }
    return path;
}

// --seek, in slices, so that a signal ends a long seek too (at a tick boundary, as it ends the run).
void seekFirst(session::Session& session, std::uint64_t target) {
    std::optional<session::Session::Restore> from; // what the first slice restored
    try {
        for (bool first = true;; first = false) {
            const bool done = session.seekToward(target, 0.05);
            if (first) from = session.lastRestore();
            if (done || g_stopSignal != 0) break;
        }
    } catch (const session::SeekError& e) {
        throw session::SeekError("--seek " + std::to_string(target) + ": " + e.what());
    }
    const auto tick = static_cast<unsigned long long>(session.state().tick);
    if (session.state().tick != target)
        std::printf("the seek stopped at tick %llu of %llu\n", tick, static_cast<unsigned long long>(target));
    else if (from)
        std::printf("at tick %llu (restored tick %llu from %s, then stepped)\n", tick,
                    static_cast<unsigned long long>(from->tick), from->source);
    else
        std::printf("at tick %llu\n", tick);
}

} // namespace

int runHeadless(const session::Options& o) {
    // Installed first, so a signal during start-up (loading a world) also ends the run cleanly.
    g_stopSignal = 0;
    std::signal(SIGTERM, onStopSignal);
    std::signal(SIGINT, onStopSignal);
    session::Session session(o);
    for (const auto& w : session.loadWarnings()) core::logWarn("%s", w.c_str());
    if (session.hasWorld())
        std::printf("world: %s (tick %llu)\n", session.worldPath().c_str(),
                    static_cast<unsigned long long>(session.state().tick));
    // A test waits for the line above before it signals the run.
    std::fflush(stdout);
    // --seek: the run starts at that tick (no picture, screenshot or capture on the way), and --ticks counts from it.
    if (o.seek) seekFirst(session, *o.seek);
    // A replay without --ticks runs to the recording's end; with --seek it stops there.
    const std::uint64_t ticks =
        o.ticks == 0 && session.replayEndTick() && !o.seek
            ? *session.replayEndTick() - std::min(*session.replayEndTick(), session.state().tick)
            : o.ticks;
    if (!(o.seek && o.ticks == 0)) warnAboutLateEvents(o, ticks, session.script(), session.state().tick); // asked
    const auto contextOwner = render::makeOffscreenContext(*render::offscreenBackendFromName(o.glBackend),
                                                           o.settings.size.width, o.settings.size.height);
    render::RenderContext& context = *contextOwner;
    const std::filesystem::path worlds =
        o.worldsFolder.empty() ? session::defaultWorldsFolder() : std::filesystem::path(o.worldsFolder);
    Frontend frontend(session, nullptr, worlds, o.settingsFile);
    const glm::ivec2 size = context.framebufferSize();
    // Headless has no time between ticks (alpha 1) and no unconsumed mouse motion.
    FrameRequest lone;
    lone.size = size;
    lone.seconds = session.tickSeconds();
    lone.layoutFirst = true;
    // Screenshots must not depend on how fast this machine meshes: stream everything in range first (the
    // frame statistics' frames stream with the window's budget: app/instruments.cpp).
    const auto drawFrame = [&](const FrameRequest& f, double meshBudgetSeconds) {
        frontend.sceneSettings().meshBudgetSeconds = meshBudgetSeconds;
        frontend.draw(f);
        context.present();
    };
    if (o.captureEvery > 0) std::filesystem::create_directories(o.captureDir); // checked writable at start
    const std::vector<std::unique_ptr<Instrument>> instruments = makeInstruments(o, session, size);

    int exitCode = 0;
    std::uint64_t ticksRun = 0, captured = 0;
    double captureMs = 0.0;
    for (; ticksRun < ticks && g_stopSignal == 0; ++ticksRun) {
        for (const auto& i : instruments) i->beforeStep();
        // Events of tick T are applied in the step that starts at state tick T; a screenshot they ask
        // for is named after that tick, as the script format says (docs/SCRIPTS.md).
        const std::uint64_t eventTick = session.state().tick;
        const session::AppRequests r = session.step();
        for (const auto& i : instruments) i->afterStep(session);
        frontend.reportSaveErrors(); // keep playing: the last good save stays on disk
        const bool screenshot = frontend.afterTick(r);
        frontend.age(session.tickSeconds());
        for (const auto& i : instruments) i->afterTick(frontend, context, session);
        if (o.captureEvery > 0 && session.state().tick % o.captureEvery == 0) {
            const auto start = std::chrono::steady_clock::now();
            drawFrame(lone, 0.0);
            char name[40];
            std::snprintf(name, sizeof name, "frame-%06llu.png", static_cast<unsigned long long>(session.state().tick));
            frontend.writePicture(std::filesystem::path(o.captureDir) / name, lone, 1);
            captureMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            ++captured;
        }
        if (screenshot) {
            const std::filesystem::path path = tickScreenshotPath(o.screenshotDir, eventTick);
            if (o.screenshotScale > 1) {
                frontend.sceneSettings().meshBudgetSeconds = 0.0;
            } else {
                drawFrame(lone, 0.0);
            }
            if (!frontend.screenshot(path, lone, o.screenshotScale).empty()) exitCode = 1;
        }
    }

    const int stopSignal = g_stopSignal;
    if (stopSignal != 0) {
        core::logError("interrupted by %s at tick %llu of %llu", signalName(stopSignal),
                       static_cast<unsigned long long>(ticksRun), static_cast<unsigned long long>(ticks));
        exitCode = 128 + stopSignal; // as the shell reports a process the signal ended
    }
    if (captured > 0)
        std::printf("captured %llu frames into %s (%.1f ms a frame, drawing and writing)\n",
                    static_cast<unsigned long long>(captured), o.captureDir.c_str(),
                    captureMs / static_cast<double>(captured));
    // Every output is tried even when one fails (a full disk must not cost the world's save), and the first
    // failure is reported again at the end: exit 2 for an output that could not be written.
    std::string outputFailure;
    const auto attempt = [&](const std::function<void()>& write) {
        try {
            write();
        } catch (const core::OutputError& e) {
            core::logError("%s", e.what());
            if (outputFailure.empty()) outputFailure = e.what();
        }
    };
    if (!o.screenshot.empty()) {
        attempt([&] {
            if (o.screenshotScale > 1) {
                frontend.sceneSettings().meshBudgetSeconds = 0.0;
            } else {
                drawFrame(lone, 0.0);
            }
            frontend.writePicture(o.screenshot, lone, o.screenshotScale);
            std::printf("wrote %s\n", o.screenshot.c_str());
        });
    }
    // The recording is put in place here rather than by the session's destructor, so that one that cannot be
    // written is an output failure (exit 2) like the others.
    attempt([&] { session.finishRecording(); });
    // An interrupted run saves even without --save: the ticks since the last autosave would be lost. A save that
    // fails (a full disk; the previous save is kept) is a write that failed: exit 2.
    if ((o.saveAtEnd || stopSignal != 0) && session.hasWorld()) {
        const auto errors = session.saveNow();
        for (const auto& e : errors) core::logError("save failed: %s", e.c_str());
        if (errors.empty()) {
            std::printf("saved %s\n", session.worldPath().c_str());
        } else if (outputFailure.empty()) {
            outputFailure = "save failed: " + errors.front();
        }
    }
    if (!o.dumpState.empty()) {
        attempt([&] {
            session.writeDump(o.dumpState);
            std::printf("wrote %s\n", o.dumpState.c_str());
        });
    }
    for (const auto& i : instruments) {
        attempt([&] {
            if (!i->finish() && stopSignal == 0) exitCode = 1;
        });
    }
    if (!outputFailure.empty() && stopSignal == 0) {
        core::logError("not every output was written (the first failure is above)");
        exitCode = 2;
    }
    return exitCode;
}

} // namespace app
