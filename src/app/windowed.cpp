// The window runner: frames at the display's pace, input from GLFW events and the gamepad, ticks from a
// fixed-step clock. What is drawn and how menus act is Frontend's, the same as headless.
#include <algorithm>
#include <dlfcn.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <variant>

#include "app/frontend.h"
#include "app/runners.h"
#include "core/atomic_file.h"
#include "core/fixed_step.h"
#include "core/frame_rate.h"
#include "core/log.h"
#include "input/gamepad_mappings.h"
#include "input/keys.h"
#include "input/script.h"
#include "platform/glfw_window.h"
#include "render/context.h"
#include "render/gl_loader.h"
#include "render/screenshot.h"
#include "session/paths.h"
#include "session/recording.h"
#include "session/timeline.h"
#include "ui/timeline_bar.h"

namespace app {

namespace {

// A window is opened at least this many pixels a side, whatever the frame size asks (it goes down to 16 for
// headless pictures): below it the pause menu and the panels do not fit, and a typing slip would leave a window
// that no menu can be reached in to fix it.
constexpr int kSmallestWindow = 320;
// SIGTERM or SIGINT (Ctrl+C in the terminal) end the game like closing the window: state is written.
volatile std::sig_atomic_t g_stopRequested = 0;
void onStopSignal(int) { g_stopRequested = 1; }

// A lost display (X server gone) ends the process inside Xlib, which calls exit() after its I/O error
// handler returns, so no destructor runs. Our handler saves the world first. It is looked up at run
// time: GLFW already loaded libX11, and the game does not link it itself.
session::Session* g_sessionForDisplayLoss = nullptr;
int onDisplayLost(void*) {
    core::logError("the connection to the display was lost; saving the world and exiting");
    if (g_sessionForDisplayLoss) {
        try {
            g_sessionForDisplayLoss->finishRecording();
        } catch (const std::exception& e) {
            core::logError("%s", e.what());
        }
    }
    if (g_sessionForDisplayLoss && g_sessionForDisplayLoss->hasWorld()) {
        const auto errors = g_sessionForDisplayLoss->saveNow();
        for (const auto& e : errors) core::logError("save failed: %s", e.c_str());
        if (errors.empty()) core::logNote("saved %s", g_sessionForDisplayLoss->worldPath().c_str());
    }
    std::_Exit(1);
}
void saveWorldIfDisplayIsLost(session::Session& session) {
    g_sessionForDisplayLoss = &session;
    using Handler = int (*)(void*);
    using Setter = Handler (*)(Handler);
    if (auto set = reinterpret_cast<Setter>(dlsym(RTLD_DEFAULT, "XSetIOErrorHandler"))) set(onDisplayLost);
}

// While a menu is open the mouse belongs to the menu: only keys reach the game, so Esc still resumes.
bool reachesGame(const input::InputEvent& e, bool captured) {
    if (captured) return true;
    return std::holds_alternative<input::KeyEvent>(e) || std::holds_alternative<input::GamepadButtonEvent>(e) ||
           std::holds_alternative<input::GamepadAxisEvent>(e);
}

// Window events and the gamepad go through the same mapper as script lines; a binding being changed takes
// the next key or button instead of the game, and Esc goes back one level before it pauses or resumes.
bool swallowedPause = false; // the pause key's press went back a level: its release is not the game's either
bool shiftHeld = false;      // for the timeline's Shift+Left / Right
// While a replay's timeline is active its keys (ui::timelineKey) and F2 are its, and nothing reaches the game:
// returns whether F2 asked for a screenshot.
bool routeInput(platform::GlfwWindow& window, session::Session& session, Frontend& frontend, bool captured,
                session::Timeline* timeline) {
    bool screenshot = false;
    for (const auto& e : window.pollEvents()) {
        if (const auto* key = std::get_if<input::KeyEvent>(&e)) frontend.noteKey(key->key, key->down);
        if (const auto* key = std::get_if<input::KeyEvent>(&e);
            key && (key->key == input::key::LeftShift || key->key == input::key::RightShift))
            shiftHeld = key->down;
        if (timeline && timeline->active()) { // a T in this batch ends it: the events after it are the game's
            const auto* key = std::get_if<input::KeyEvent>(&e);
            if (!key || !key->down) continue;
            if (key->key == session.mapper().config().keys.pause) {
                frontend.goBack();
            } else if (key->key == input::key::F2) {
                screenshot = true;
            } else if (!ui::timelineKey(*timeline, key->key, shiftHeld, session.options().settings.tickRate) &&
                       key->key == session.mapper().config().keys.interact) { // the timeline's keys come first
                frontend.toggleObjectPanel();
            }
            continue;
        }
        if (const auto* key = std::get_if<input::KeyEvent>(&e); key && key->down && frontend.rebinding()) {
            frontend.feedRebindKey(key->key);
            continue;
        }
        // The pause key goes back one level first (a panel, a page of the pause menu, the controls list);
        // only with nothing open does it reach the game, which pauses or resumes. Its release follows it.
        if (const auto* key = std::get_if<input::KeyEvent>(&e);
            key && key->key == session.mapper().config().keys.pause) {
            if (key->down && frontend.goBack()) {
                swallowedPause = true;
                continue;
            }
            if (!key->down && std::exchange(swallowedPause, false)) continue;
        }
        if (reachesGame(e, captured)) session.mapper().handle(e);
    }
    const input::GamepadState pad = window.pollGamepad();
    if (timeline) return screenshot;
    if (frontend.rebinding()) {
        for (int b = 0; b < static_cast<int>(input::GamepadButton::Count); ++b) {
            if (pad.buttons[static_cast<std::size_t>(b)]) frontend.feedRebindButton(b);
        }
    } else {
        session.mapper().setGamepadState(pad);
    }
    return screenshot;
}

// Adds the player's gamepad mappings (--gamepad-mappings, else the config folder's gamecontrollerdb.txt when it
// exists). A malformed line is reported by its number and skipped; the rest load; the game starts either way.
void loadGamepadMappings(platform::GlfwWindow& window, const session::Options& o) {
    const std::filesystem::path path =
        o.gamepadMappings.empty() ? session::defaultGamepadMappingsPath() : std::filesystem::path(o.gamepadMappings);
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (!o.gamepadMappings.empty()) core::logWarn("%s: cannot read the gamepad mappings", path.c_str());
        return;
    }
    std::stringstream text;
    text << in.rdbuf();
    const input::GamepadMappings parsed = input::parseGamepadMappings(text.str(), path.string());
    for (const auto& p : parsed.problems) core::logWarn("%s (line skipped)", p.c_str());
    const std::vector<std::string> refused = window.addGamepadMappings(parsed.lines);
    for (const auto& r : refused) core::logWarn("%s: GLFW refused the mapping %s", path.c_str(), r.c_str());
    core::logNote("added %zu gamepad mapping%s from %s", parsed.lines.size() - refused.size(),
                  parsed.lines.size() - refused.size() == 1 ? "" : "s", path.c_str());
}

} // namespace

int runWindowed(const session::Options& options) {
    session::Options o = options;
    const std::filesystem::path worldsFolder =
        o.worldsFolder.empty() ? session::defaultWorldsFolder() : std::filesystem::path(o.worldsFolder);
    // The window always plays a saved world unless told not to: a player's work is never lost. A replay plays its
    // recording's start world instead (a file that cannot be read is reported by the session).
    bool replaying = o.replay;
    if (!replaying && !o.script.empty()) {
        try {
            replaying = session::isRecording(input::readScriptText(o.script));
        } catch (const std::exception&) {}
    }
    if (o.world.empty() && !replaying) {
        std::error_code ec;
        std::filesystem::create_directories(worldsFolder, ec);
        o.world = (worldsFolder / "default.mcworld").string();
    } else if (o.world == "none") {
        o.world.clear();
    }
    session::Session session(o);
    platform::WindowDef def;
    def.width = std::max(o.settings.size.width, kSmallestWindow);
    def.height = std::max(o.settings.size.height, kSmallestWindow);
    def.vsync = o.settings.vsync;
    platform::GlfwWindow window(def);
    // The window's context is current; render loads GL's entry points for it through GLX. On failure the
    // window is closed as the error leaves.
    if (const std::string error = render::loadGl(render::GlBackend::Glx); !error.empty()) {
        throw render::RenderError("window: " + error);
    }
    loadGamepadMappings(window, o);
    Frontend frontend(session, window.handle(), worldsFolder, o.settingsFile);
    saveWorldIfDisplayIsLost(session);
    // --replay: the recording plays as a timeline until the player takes over (session/timeline.h).
    std::optional<session::Timeline> timeline;
    if (o.replay)
        timeline.emplace(session, static_cast<std::uint64_t>(o.settings.keyframeInterval),
                         std::size_t(o.settings.keyframeBudgetMiB) << 20);
    frontend.setTimeline(timeline ? &*timeline : nullptr);

    core::FixedStepDef clockDef;
    clockDef.tickSeconds = session.tickSeconds();
    core::FixedStepClock clock(clockDef);
    double last = window.time();
    core::FrameRate frameRate; // F3: frames of the last second, averaged by time
    bool wasFocused = true;

    std::signal(SIGTERM, onStopSignal);
    std::signal(SIGINT, onStopSignal);
    while (!window.shouldClose() && !g_stopRequested) {
        const double now = window.time();
        const double frameSeconds = now - last;
        last = now;
        frameRate.addFrame(frameSeconds);

        const bool focused = window.focused();
        // A timeline's replay is the recording's alone: losing focus neither pauses it nor lets go of its keys.
        if (wasFocused && !focused && !(timeline && timeline->active())) {
            session.mapper().releaseAll();
            if (!session.state().paused) session.requestPauseToggle();
        }
        wasFocused = focused;
        session::Timeline* const playing = timeline && timeline->active() ? &*timeline : nullptr;
        const bool captured = !playing && !session.state().paused && focused && !frontend.panelOpen();
        window.setCursorCaptured(captured);
        bool screenshot = routeInput(window, session, frontend, captured, playing);

        // Fixed ticks; a timeline moves the replay itself (a take-over then starts the clock afresh).
        const bool wasPlaying = playing != nullptr;
        if (playing) playing->advance(frameSeconds);
        if (wasPlaying && !playing->active()) {
            clockDef.tickSeconds = session.tickSeconds(); // a replay opened from the menu has its recording's rate
            clock = core::FixedStepClock(clockDef);
        }
        const int ticks = playing ? 0 : clock.advance(frameSeconds);
        const auto simStart = std::chrono::steady_clock::now();
        for (int i = 0; i < ticks; ++i) screenshot |= frontend.afterTick(session.step());
        const double tickMs =
            ticks > 0
                ? std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - simStart).count() / ticks
                : 0.0;
        frontend.age(frameSeconds);
        frontend.reportSaveErrors(); // keep playing: the last good save stays on disk

        // Draw between the last two ticks.
        FrameRequest frame;
        frame.size = window.framebufferSize();
        if (frame.size.x > 0 && frame.size.y > 0) {
            frame.alpha = playing ? 1.0f : static_cast<float>(clock.alpha()); // a timeline shows its tick itself
            frame.look = session.state().paused ? glm::vec2(0.0f) : session.mapper().pendingLook();
            frame.seconds = frameSeconds;
            frame.timing = {frameRate.fps(), frameRate.frameMs(), tickMs, window.gamepadName()};
            frontend.draw(frame);
            if (frontend.takeReplayOpened()) { // Worlds > Recordings > Play
                timeline.emplace(session, static_cast<std::uint64_t>(session.options().settings.keyframeInterval),
                                 std::size_t(session.options().settings.keyframeBudgetMiB) << 20);
                frontend.setTimeline(&*timeline);
            }
            if (frontend.quitRequested()) window.requestClose();
            if (const auto changed = frontend.takeWindowSettings()) {
                window.setSize(std::max(changed->size.width, kSmallestWindow),
                               std::max(changed->size.height, kSmallestWindow));
                window.setVsync(changed->vsync);
            }
            if (screenshot) frontend.screenshot(render::nextScreenshotPath(o.screenshotDir), frame, o.screenshotScale);
        }
        window.present();
    }
    // A timeline's jump still catching up when the window closes is finished first: the state written is the one
    // at the tick the timeline was asked for (as a take-over does). A replay that stopped where it left its
    // recording makes no more progress, and the loop ends there.
    for (std::uint64_t last = ~std::uint64_t{0};
         timeline && timeline->active() && timeline->catchingUp() && timeline->tick() != last;) {
        last = timeline->tick();
        timeline->advance(0.0);
    }
    // Every output is tried even when one fails; a recording, a save or a dump that could not be written (a full
    // disk; the previous files are kept) is exit 2, as headless.
    int exitCode = 0;
    try {
        session.finishRecording();
    } catch (const core::OutputError& e) {
        core::logError("%s", e.what());
        exitCode = 2;
    }
    if (session.hasWorld()) {
        const auto errors = session.saveNow();
        for (const auto& e : errors) core::logError("save failed: %s", e.c_str());
        if (errors.empty()) std::printf("saved %s\n", session.worldPath().c_str());
        if (!errors.empty()) exitCode = 2;
    }
    if (!o.dumpState.empty()) {
        try {
            session.writeDump(o.dumpState);
        } catch (const core::OutputError& e) {
            core::logError("%s", e.what());
            exitCode = 2;
        }
    }
    return exitCode;
}

} // namespace app
