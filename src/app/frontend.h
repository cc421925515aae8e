// What the player sees and works, shared by both runners: the scene, the Dear ImGui layer, the object
// panels, the pause menu with its world list and settings panel, the overlay and help, HUD messages,
// settings applied live, and screenshots. The runners differ only in where frames and input come from:
// the window (app/windowed.cpp) draws every frame at its own clock and feeds live events; the headless
// runner (app/headless.cpp) draws only the frames it is asked for, in an OSMesa buffer, from a script.
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include <glm/vec2.hpp>

#include "app/object_panels.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"
#include "session/session.h"
#include "session/settings.h"
#include "session/timeline.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"

struct GLFWwindow;

namespace app {

// What the runner measured about its frames, for the F3 overlay. The headless runner leaves it empty:
// its pictures must not depend on how fast this machine is.
struct FrameTiming {
    double fps = 0.0, frameMs = 0.0;
    double tickMs = 0.0; // mean simulation time per tick over the last frame
    std::string gamepad; // connected pad name, empty if none
};

struct FrameRequest {
    glm::ivec2 size{0, 0}; // framebuffer pixels
    float alpha = 1.0f;    // where the frame lies between the last two ticks (0..1)
    glm::vec2 look{0.0f};  // mouse motion not consumed by a tick yet: the camera turns now, not next tick
    double seconds = 0.0;  // since the previous frame (Dear ImGui's clock)
    FrameTiming timing;
    // A frame with none before it (a headless screenshot): the UI is laid out once without drawing first,
    // because Dear ImGui sizes auto-fitting windows on their first frame and shows them from the second.
    bool layoutFirst = false;
};

class Frontend {
public:
    // The settings are the session's (its options'). window: the GLFW window for Dear ImGui's platform backend,
    // nullptr headless. settingsFile: where the settings panel's Save writes (none: --settings none). Needs a
    // current GL context.
    Frontend(session::Session& session, GLFWwindow* window, std::filesystem::path worldsFolder,
             std::optional<std::filesystem::path> settingsFile);

    // The program's part of a tick's actions: overlay, help, the object panel. Returns whether the tick
    // asked for a screenshot.
    bool afterTick(const session::AppRequests& requests);
    // Autosave problems since the last call: printed and shown; play goes on (the last good save stays).
    void reportSaveErrors();
    // Time passes for the HUD message.
    void age(double seconds) { m_message.secondsLeft -= seconds; }

    // Draws the state, then the HUD, labels, panels and menus; carries out what the player chose in them.
    void draw(const FrameRequest& frame);
    // Every picture the runners write comes from here (screenshots, --screenshot, --capture-every frames):
    // at scale 1 the framebuffer of the frame just drawn (draw `frame` first); at 2..8 (--screenshot-scale)
    // the frame drawn that many times larger off-screen, in tiles where GL limits require, HUD scaled alike.
    // Written as a PNG of frame.size x scale; throws what render::writePng throws (core::OutputError).
    void writePicture(const std::filesystem::path& path, const FrameRequest& frame, int scale);
    // writePicture as the player's screenshot: its folder created, the path printed and shown on the HUD.
    // Returns the problem, empty when written; a failure is shown too.
    std::string screenshot(const std::filesystem::path& path, const FrameRequest& frame, int scale);

    // For the window's input routing.
    bool panelOpen() const { return m_panels.anyOpen(); }
    // A replay's timeline: the interact key opens (read only) the panel of the object the replayed player looks at,
    // or closes the open one.
    void toggleObjectPanel() { m_panels.interact(m_session.state()); }
    // The pause key (Esc) goes back one level: it closes an open object panel, a page of the pause menu
    // (back to its list) or the controls list. True when it did; false when nothing was open, so the key
    // pauses or, from the pause menu's list, resumes. An open pop-up or text edit takes it first: ImGui closes
    // or cancels it, and the level stays.
    bool goBack();
    void noteKey(int key, bool down) { m_imgui.noteKey(key, down); }
    bool rebinding() const { return ui::settingsPanelCapturing(m_settingsPanel); }
    void feedRebindKey(int key) { ui::feedSettingsPanelKey(m_settingsPanel, key); }
    void feedRebindButton(int button) { ui::feedSettingsPanelButton(m_settingsPanel, button); }
    // The pause menu's Quit.
    bool quitRequested() const { return m_quit; }
    // The settings the window applies itself (size, vsync), once after the player changed any setting.
    std::optional<session::Settings> takeWindowSettings();

    // A replay played in the window: its timeline's bar is drawn while it is active (nullptr: none).
    void setTimeline(session::Timeline* timeline) { m_timeline = timeline; }
    // Worlds > Recordings > Play made the session a replay (Session::openReplay): once true, the runner starts its
    // timeline.
    bool takeReplayOpened() { return std::exchange(m_replayOpened, false); }

    render::SceneSettings& sceneSettings() { return m_sceneSettings; }
    const render::SceneRenderer& scene() const { return m_scene; }

private:
    void drawMenus();
    void layoutUi(const FrameRequest& frame, float framebufferScale);
    // Writes picture() as a PNG and says so (stdout and HUD); a failure is logged and shown, and returned.
    render::Image drawLarge(const FrameRequest& frame, int scale);
    void applySettings();
    void setSceneSettings(const session::Settings& s);
    static std::string overriddenNote(const session::Options& o);
    void handleWorldRequest();

    session::Session& m_session;
    session::Settings m_settings;
    std::optional<std::filesystem::path> m_settingsFile;
    render::SceneRenderer m_scene;
    ui::ImGuiLayer m_imgui;
    render::SceneSettings m_sceneSettings;
    ObjectPanels m_panels;
    ui::SettingsPanel m_settingsPanel;
    ui::WorldPanel m_worldPanel;
    ui::RecordingsPanel m_recordingsPanel;
    ui::BlocksPanel m_blocksPanel;
    bool m_replayOpened = false;
    ui::HudMessage m_message;
    // The pause menu shows its list or one page in its place, never one over the other.
    enum class MenuPage { List, Blocks, Worlds, Recordings, Settings, Controls };
    MenuPage m_page = MenuPage::List;
    ui::PauseMenu m_pauseMenu;
    bool m_wasPaused = false;
    bool m_overlay = false, m_help = false, m_quit = false;
    std::optional<session::Settings> m_windowSettings;
    session::Timeline* m_timeline = nullptr;
};

} // namespace app
