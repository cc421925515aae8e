#include <dlfcn.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <variant>

#include "app/panels.h"
#include "app/runners.h"
#include "app/session.h"
#include "core/fixed_step.h"
#include "core/frame_rate.h"
#include "input/keys.h"
#include "render/context_glfw.h"
#include "render/data_dir.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"

namespace app {

namespace {
// SIGTERM or SIGINT (Ctrl+C in the terminal) end the game like closing the window: state is written.
volatile std::sig_atomic_t g_stopRequested = 0;
void onStopSignal(int) { g_stopRequested = 1; }

// A lost display (X server gone) ends the process inside Xlib, which calls exit() after its I/O error
// handler returns, so no destructor runs. Our handler saves the world first. It is looked up at run
// time: GLFW already loaded libX11, and the game does not link it itself.
Session* g_sessionForDisplayLoss = nullptr;
int onDisplayLost(void*) {
    std::fprintf(stderr, "minecrappy: the connection to the display was lost; saving the world and exiting\n");
    if (g_sessionForDisplayLoss && g_sessionForDisplayLoss->hasWorld()) {
        const auto errors = g_sessionForDisplayLoss->saveNow();
        for (const auto& e : errors) std::fprintf(stderr, "minecrappy: save failed: %s\n", e.c_str());
        if (errors.empty())
            std::fprintf(stderr, "minecrappy: saved %s\n", g_sessionForDisplayLoss->worldPath().c_str());
    }
    std::_Exit(1);
}
void saveWorldIfDisplayIsLost(Session& session) {
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
// Carries out what the world list asked for. Failures are shown in the list; the current world stays.
void handleWorldRequest(Session& session, ui::WorldPanel& panel, ObjectPanels& objects) {
    std::error_code ec;
    try {
        switch (panel.request) {
        case ui::WorldPanel::Request::None:
            return;
        case ui::WorldPanel::Request::Load:
            objects.close();
            session.openWorld(panel.target, 1, world::TerrainKind::Default);
            panel.status = "Loaded " + panel.target.stem().string();
            break;
        case ui::WorldPanel::Request::Create:
            std::filesystem::create_directories(panel.folder, ec);
            objects.close();
            session.openWorld(panel.target, panel.newSeed,
                              panel.newFlat ? world::TerrainKind::Flat : world::TerrainKind::Default);
            panel.status = "Created " + panel.target.stem().string();
            break;
        case ui::WorldPanel::Request::Delete:
            if (session.hasWorld() && std::filesystem::equivalent(panel.target, session.worldPath(), ec)) {
                panel.status = "The world being played cannot be deleted.";
                return;
            }
            std::filesystem::remove(panel.target, ec);
            for (const char* suffix : {"-journal", "-wal", "-shm"})
                std::filesystem::remove(panel.target.string() + suffix, ec);
            panel.status = ec ? "Could not delete: " + ec.message() : "Deleted " + panel.target.stem().string();
            break;
        }
    } catch (const std::exception& e) {
        panel.status = e.what();
    }
}

} // namespace

int runWindowed(const Options& options, const Settings& initialSettings) {
    Options o = options;
    const std::filesystem::path worldsFolder =
        o.worldsFolder.empty() ? ui::defaultWorldsFolder() : std::filesystem::path(o.worldsFolder);
    // The window always plays a saved world unless told not to: a player's work is never lost.
    if (o.world.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(worldsFolder, ec);
        o.world = (worldsFolder / "default.mcworld").string();
    } else if (o.world == "none") {
        o.world.clear();
    }
    Settings settings = initialSettings;
    Session session(o, settings);
    render::WindowDef def;
    def.width = o.width;
    def.height = o.height;
    def.vsync = o.vsync;
    render::GlfwWindow window(def);
    const auto data = render::dataDir();
    render::SceneRenderer scene(data);
    ui::ImGuiLayer imgui(window.handle());
    saveWorldIfDisplayIsLost(session);

    render::SceneSettings sceneSettings;
    sceneSettings.fovDegrees = o.fov;
    sceneSettings.viewRadius = o.viewRadius;

    core::FixedStepDef clockDef;
    clockDef.tickSeconds = session.tickSeconds();
    core::FixedStepClock clock(clockDef);

    bool overlay = false, help = false, worldsOpen = false, settingsOpen = false;
    ui::SettingsPanel settingsPanel;
    settingsPanel.edit = settings;
    settingsPanel.filePath = o.settingsFile ? o.settingsFile->string() : std::string();
    ObjectPanels panels;
    ui::WorldPanel worldPanel;
    worldPanel.folder = worldsFolder;
    ui::HudMessage message;
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
            // A binding being changed takes the next key instead of the game.
            if (const auto* key = std::get_if<input::KeyEvent>(&e);
                key && key->down && ui::settingsPanelCapturing(settingsPanel)) {
                ui::feedSettingsPanelKey(settingsPanel, key->key);
                continue;
            }
            // Esc closes an open panel instead of pausing.
            if (const auto* key = std::get_if<input::KeyEvent>(&e);
                key && panels.anyOpen() && key->key == input::key::Escape) {
                if (key->down) panels.close();
                continue;
            }
            if (reachesGame(e, captured)) session.mapper().handle(e);
        }
        const input::GamepadState pad = window.pollGamepad();
        if (ui::settingsPanelCapturing(settingsPanel)) {
            for (int b = 0; b < static_cast<int>(input::GamepadButton::Count); ++b) {
                if (pad.buttons[static_cast<std::size_t>(b)]) ui::feedSettingsPanelButton(settingsPanel, b);
            }
        } else {
            session.mapper().setGamepadState(pad);
        }

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
        const double tickMs =
            ticks > 0
                ? std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - simStart).count() / ticks
                : 0.0;
        message.secondsLeft -= frameSeconds;
        for (const auto& e : session.takeSaveErrors()) { // keep playing: the last good save stays on disk
            std::fprintf(stderr, "minecrappy: autosave failed: %s\n", e.c_str());
            message = {"Autosave failed: " + e, 6.0};
        }

        // Draw between the last two ticks; unconsumed mouse motion turns the camera now, not next tick.
        const glm::ivec2 size = window.framebufferSize();
        if (size.x > 0 && size.y > 0) {
            const glm::vec2 look = session.state().paused ? glm::vec2(0.0f) : session.mapper().pendingLook();
            const float alpha = static_cast<float>(clock.alpha());
            scene.render(session.state(), render::interpolatedCamera(session.state(), alpha, look), size, sceneSettings,
                         alpha);
            imgui.beginFrame(size, static_cast<float>(frameSeconds));
            ui::drawObjectLabels(session.state(), scene, alpha);
            ui::drawHud(session.state(), scene.atlas(), message);
            panels.show(session);
            if (overlay) {
                ui::OverlayInfo info;
                info.fps = frameRate.fps();
                info.frameMs = frameRate.frameMs();
                info.tickMs = tickMs;
                info.renderCpuMs = scene.stats().cpuMs;
                info.chunks = scene.stats().chunks;
                info.gamepad = window.gamepadName();
                ui::showOverlayPanel(session.state(), info, &overlay);
            }
            if (session.state().paused) {
                switch (ui::showPausePanel(&help)) {
                case ui::PauseChoice::Resume:
                    session.requestPauseToggle();
                    break;
                case ui::PauseChoice::Worlds:
                    worldsOpen = true;
                    break;
                case ui::PauseChoice::Settings:
                    settingsOpen = true;
                    break;
                case ui::PauseChoice::Quit:
                    window.requestClose();
                    break;
                case ui::PauseChoice::None:
                    break;
                }
                if (settingsOpen) {
                    ui::showSettingsPanel(settingsPanel, &settingsOpen);
                    if (settingsPanel.changed) { // live: input, view, window, hair detail
                        settingsPanel.changed = false;
                        settings = settingsPanel.edit;
                        session.mapper().config() = settings.input;
                        session.setHairDetail(hairDetailFraction(settings.hairDetail));
                        session.setHairBudget(hairBudgetPasses(settings));
                        sceneSettings.fovDegrees = settings.fov;
                        sceneSettings.viewRadius = settings.viewRadius;
                        window.setSize(settings.windowWidth, settings.windowHeight);
                        window.setVsync(settings.vsync);
                    }
                    if (settingsPanel.saveRequested) {
                        settingsPanel.saveRequested = false;
                        try {
                            if (!o.settingsFile)
                                throw std::runtime_error("settings are not saved in this run (--settings none)");
                            saveSettings(settingsPanel.edit, *o.settingsFile);
                            settingsPanel.status = "Saved " + o.settingsFile->string();
                        } catch (const std::exception& e) {
                            settingsPanel.status = e.what();
                        }
                    }
                }
                if (worldsOpen) {
                    worldPanel.current = session.hasWorld() ? session.worldPath().string() : std::string();
                    ui::showWorldPanel(worldPanel, &worldsOpen);
                    handleWorldRequest(session, worldPanel, panels);
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
    int exitCode = 0;
    if (session.hasWorld()) {
        const auto errors = session.saveNow();
        for (const auto& e : errors) std::fprintf(stderr, "minecrappy: save failed: %s\n", e.c_str());
        if (errors.empty()) std::printf("saved %s\n", session.worldPath().c_str());
        exitCode = errors.empty() ? 0 : 1;
    }
    if (!o.dumpState.empty()) session.writeDump(o.dumpState);
    return exitCode;
}

} // namespace app
