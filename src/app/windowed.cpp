#include <chrono>
#include <csignal>
#include <cstdio>
#include <variant>

#include "app/panels.h"
#include "app/runners.h"
#include "app/session.h"
#include "core/fixed_step.h"
#include "input/keys.h"
#include "render/context_glfw.h"
#include "render/data_dir.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"
#include "ui/ui.h"

namespace app {

namespace {
// SIGTERM or SIGINT (Ctrl+C in the terminal) end the game like closing the window: state is written.
volatile std::sig_atomic_t g_stopRequested = 0;
void onStopSignal(int) { g_stopRequested = 1; }

// While a menu is open the mouse belongs to the menu: only keys reach the game, so Esc still resumes.
bool reachesGame(const input::InputEvent& e, bool captured) {
    if (captured) return true;
    return std::holds_alternative<input::KeyEvent>(e) || std::holds_alternative<input::GamepadButtonEvent>(e) ||
           std::holds_alternative<input::GamepadAxisEvent>(e);
}
} // namespace

int runWindowed(const Options& o) {
    Session session(o);
    render::WindowDef def;
    def.width = o.width;
    def.height = o.height;
    def.vsync = o.vsync;
    render::GlfwWindow window(def);
    const auto data = render::dataDir();
    render::SceneRenderer scene(data);
    ui::ImGuiLayer imgui(window.handle());

    render::SceneSettings settings;
    settings.fovDegrees = o.fov;
    settings.viewRadius = o.viewRadius;

    core::FixedStepDef clockDef;
    clockDef.tickSeconds = session.tickSeconds();
    core::FixedStepClock clock(clockDef);

    bool overlay = false, help = false;
    ObjectPanels panels;
    ui::HudMessage message;
    double last = window.time();
    double fps = 0.0, frameMs = 0.0;
    bool wasFocused = true;

    std::signal(SIGTERM, onStopSignal);
    std::signal(SIGINT, onStopSignal);
    while (!window.shouldClose() && !g_stopRequested) {
        const double now = window.time();
        const double frameSeconds = now - last;
        last = now;
        if (frameSeconds > 0.0) {
            fps = fps == 0.0 ? 1.0 / frameSeconds : fps * 0.95 + 0.05 / frameSeconds;
            frameMs = frameSeconds * 1000.0;
        }

        // Input: window events and the gamepad go through the same mapper as script lines.
        const bool focused = window.focused();
        if (wasFocused && !focused) {
            session.mapper().releaseAll();
            if (!session.state().paused) session.requestPauseToggle();
        }
        wasFocused = focused;
        const bool captured = !session.state().paused && focused && !panels.anyOpen();
        window.setCursorCaptured(captured);
        for (const auto& e : window.pollEvents()) {
            // Esc closes an open panel instead of pausing.
            if (const auto* key = std::get_if<input::KeyEvent>(&e); key && panels.anyOpen() && key->key == input::key::Escape) {
                if (key->down) panels.close();
                continue;
            }
            if (reachesGame(e, captured)) session.mapper().handle(e);
        }
        session.mapper().setGamepadState(window.pollGamepad());

        // Fixed ticks.
        const int ticks = clock.advance(frameSeconds);
        const auto simStart = std::chrono::steady_clock::now();
        bool screenshot = false;
        for (int i = 0; i < ticks; ++i) {
            const AppRequests r = session.step();
            overlay ^= r.toggleOverlay;
            help ^= r.toggleHelp;
            screenshot |= r.screenshot;
            if (r.interact) panels.interact(session.state());
        }
        const double tickMs = ticks > 0 ? std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - simStart).count() / ticks : 0.0;
        message.secondsLeft -= frameSeconds;

        // Draw between the last two ticks; unconsumed mouse motion turns the camera now, not next tick.
        const glm::ivec2 size = window.framebufferSize();
        if (size.x > 0 && size.y > 0) {
            const glm::vec2 look = session.state().paused ? glm::vec2(0.0f) : session.mapper().pendingLook();
            const float alpha = static_cast<float>(clock.alpha());
            scene.render(session.state(), render::interpolatedCamera(session.state(), alpha, look), size, settings, alpha);
            imgui.beginFrame(size, static_cast<float>(frameSeconds));
            ui::drawPendulumLabels(session.state(), scene, alpha);
            ui::drawHud(session.state(), scene.atlas(), message);
            panels.show(session);
            if (overlay) {
                ui::OverlayInfo info;
                info.fps = fps;
                info.frameMs = frameMs;
                info.tickMs = tickMs;
                info.renderCpuMs = scene.stats().cpuMs;
                info.chunks = scene.stats().chunks;
                info.gamepad = window.gamepadName();
                ui::showOverlayPanel(session.state(), info, &overlay);
            }
            if (session.state().paused) {
                switch (ui::showPausePanel(&help)) {
                case ui::PauseChoice::Resume: session.requestPauseToggle(); break;
                case ui::PauseChoice::Quit: window.requestClose(); break;
                case ui::PauseChoice::None: break;
                }
            }
            if (help) ui::showHelpPanel(&help);
            imgui.endFrame();
            if (screenshot) {
                try {
                    const auto path = render::nextScreenshotPath(o.screenshotDir);
                    render::writePng(render::readFramebuffer(size.x, size.y), path);
                    std::printf("screenshot: %s\n", path.c_str());
                    std::fflush(stdout);
                    message = {"Saved " + path.string(), 3.0};
                } catch (const render::RenderError& e) {
                    std::fprintf(stderr, "minecrappy: %s\n", e.what());
                    message = {e.what(), 5.0};
                }
            }
        }
        window.present();
    }
    if (!o.dumpState.empty()) session.writeDump(o.dumpState);
    return 0;
}

} // namespace app
