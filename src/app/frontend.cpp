#include "app/frontend.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <functional>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "core/log.h"
#include "render/context.h"
#include "render/data_dir.h"
#include "render/screenshot.h"
#include "save/world_store.h"
#include "session/setting_table.h"
#include "ui/timeline_bar.h"

namespace app {

Frontend::Frontend(session::Session& session, GLFWwindow* window, std::filesystem::path worldsFolder,
                   std::optional<std::filesystem::path> settingsFile)
    : m_session(session), m_settings(session.options().settings), m_settingsFile(std::move(settingsFile)),
      m_scene(render::dataDir()), m_imgui(window) {
    setSceneSettings(m_settings);
    m_settingsPanel.edit = m_settings;
    m_settingsPanel.overriddenNote = overriddenNote(session.options());
    m_settingsPanel.filePath = m_settingsFile ? m_settingsFile->string() : std::string();
    m_worldPanel.folder = std::move(worldsFolder);
}

bool Frontend::afterTick(const session::AppRequests& r) {
    m_overlay ^= r.toggleOverlay;
    m_help ^= r.toggleHelp;
    if (r.interact) m_panels.interact(m_session.state());
    return r.screenshot;
}

void Frontend::reportSaveErrors() {
    for (const auto& e : m_session.takeSaveErrors()) {
        core::logError("autosave failed: %s", e.c_str());
        m_message = {"Autosave failed: " + e, 6.0};
    }
}

void Frontend::draw(const FrameRequest& f) {
    const game::GameState& state = m_session.state();
    m_scene.render(state, render::interpolatedCamera(state, f.alpha, f.look), f.size, m_sceneSettings, f.alpha);
    for (int pass = f.layoutFirst ? 0 : 1; pass < 2; ++pass) {
        layoutUi(f, 1.0f);
        if (pass == 0) {
            m_imgui.discardFrame();
        } else {
            m_imgui.endFrame();
        }
    }
}

void Frontend::layoutUi(const FrameRequest& f, float framebufferScale) {
    const game::GameState& state = m_session.state();
    m_imgui.beginFrame(f.size, static_cast<float>(f.seconds), framebufferScale);
    ui::drawObjectLabels(state, m_scene, f.alpha);
    ui::drawHud(state, m_scene.atlas(), m_message);
    if (m_timeline && m_timeline->active()) ui::drawTimeline(*m_timeline, state);
    m_panels.show(m_session, m_timeline && m_timeline->active());
    if (m_overlay) {
        ui::OverlayInfo info;
        info.fps = f.timing.fps;
        info.frameMs = f.timing.frameMs;
        info.tickMs = f.timing.tickMs;
        info.gamepad = f.timing.gamepad;
        info.renderCpuMs = m_scene.stats().cpuMs;
        info.chunks = m_scene.stats().chunks;
        ui::showOverlayPanel(state, info, &m_overlay);
    }
    // Resumed by any means (Esc from the list, the gamepad's Start, a script): the next pause opens the list.
    if (!state.paused && m_wasPaused) {
        m_page = MenuPage::List;
        m_pauseMenu = {}; // an hour typed and never confirmed is dropped
    }
    m_wasPaused = state.paused;
    // A timeline's replayed state may be paused (the recording paused): its menu is not the player's to use (it
    // would change the replay, or open a world the next restore would overwrite).
    if (state.paused && !(m_timeline && m_timeline->active())) drawMenus();
    if (m_help && !(state.paused && m_page == MenuPage::Controls)) ui::showHelpPanel(&m_help);
}

render::Image Frontend::drawLarge(const FrameRequest& f, int scale) {
    const game::GameState& state = m_session.state();
    const render::Camera camera = render::interpolatedCamera(state, f.alpha, f.look);
    const glm::ivec2 full = f.size * scale;
    // Tiles no larger than GL allows for a renderbuffer and a viewport (16384 on llvmpipe), nor than 4096 so
    // that a tile's buffers stay small.
    const int tileMax = std::max(64, std::min(4096, render::OffscreenTarget::largestSide()));
    const glm::ivec2 tile(std::min(full.x, tileMax), std::min(full.y, tileMax));
    render::OffscreenTarget target(tile);

    render::SceneSettings settings = m_sceneSettings;
    settings.frame = full;
    settings.labelSpace = f.size;
    settings.lineWidth = static_cast<float>(scale);
    render::Image image;
    image.width = full.x;
    image.height = full.y;
    image.rgba.resize(static_cast<std::size_t>(full.x) * static_cast<std::size_t>(full.y) * 4);
    bool laidOut = false;
    for (int y0 = 0; y0 < full.y; y0 += tile.y) {
        for (int x0 = 0; x0 < full.x; x0 += tile.x) {
            const glm::ivec2 size(std::min(tile.x, full.x - x0), std::min(tile.y, full.y - y0));
            settings.tileOrigin = {x0, y0};
            m_scene.render(state, camera, size, settings, f.alpha);
            if (!laidOut) { // the labels need the scene's projection, which the first tile has set
                if (f.layoutFirst) {
                    layoutUi(f, static_cast<float>(scale));
                    m_imgui.discardFrame();
                }
                layoutUi(f, static_cast<float>(scale));
                m_imgui.finishLayout();
                laidOut = true;
            }
            m_imgui.drawTile({x0, y0}, size);
            target.readInto(image, {x0, y0}, size);
        }
    }
    return image;
}

void Frontend::writePicture(const std::filesystem::path& path, const FrameRequest& frame, int scale) {
    if (scale > 1) {
        render::writePng(drawLarge(frame, scale), path);
    } else {
        render::writePng(render::readFramebuffer(frame.size.x, frame.size.y), path);
    }
}

bool Frontend::goBack() {
    if (m_imgui.ownsEscape()) return true; // ImGui closes the pop-up or cancels the edit; the level stays
    if (m_panels.anyOpen()) {
        m_panels.close();
        return true;
    }
    if (m_session.state().paused && m_page != MenuPage::List) {
        m_page = m_page == MenuPage::Recordings ? MenuPage::Worlds : MenuPage::List;
        return true;
    }
    if (m_help) {
        m_help = false;
        return true;
    }
    return false;
}

void Frontend::drawMenus() {
    bool open = true;
    switch (m_page) {
    case MenuPage::List: {
        double hours = m_session.state().day.hours;
        switch (ui::showPausePanel(hours, m_pauseMenu)) {
        case ui::PauseChoice::Resume:
            m_session.requestPauseToggle();
            break;
        case ui::PauseChoice::Blocks:
            m_page = MenuPage::Blocks;
            break;
        case ui::PauseChoice::Worlds:
            m_page = MenuPage::Worlds;
            break;
        case ui::PauseChoice::Settings:
            m_page = MenuPage::Settings;
            break;
        case ui::PauseChoice::Controls:
            m_page = MenuPage::Controls;
            break;
        case ui::PauseChoice::Quit:
            m_quit = true;
            break;
        case ui::PauseChoice::TimeOfDay:
            m_session.queueTimeOfDay(hours);
            break;
        case ui::PauseChoice::None:
            break;
        }
        break;
    }
    case MenuPage::Settings:
        ui::showSettingsPanel(m_settingsPanel, &open);
        if (m_settingsPanel.changed) applySettings();
        if (m_settingsPanel.saveRequested) {
            m_settingsPanel.saveRequested = false;
            try {
                if (!m_settingsFile) throw std::runtime_error("settings are not saved in this run (--settings none)");
                session::saveSettings(m_settingsPanel.edit, *m_settingsFile);
                m_settingsPanel.status = "Saved " + m_settingsFile->string();
            } catch (const std::exception& e) {
                m_settingsPanel.status = e.what();
            }
        }
        break;
    case MenuPage::Worlds:
        m_worldPanel.current = m_session.hasWorld() ? m_session.worldPath().string() : std::string();
        ui::showWorldPanel(m_worldPanel, &open);
        handleWorldRequest();
        break;
    case MenuPage::Recordings:
        ui::showRecordingsPanel(m_recordingsPanel, &open);
        if (m_recordingsPanel.play) {
            try {
                m_panels.close();
                m_session.openReplay(m_recordingsPanel.target);
                m_replayOpened = true;
                m_settings = m_session.options().settings; // the recording's simulation settings now
                m_settingsPanel.edit = m_settings;
                m_page = MenuPage::List;
            } catch (const std::exception& e) {
                m_recordingsPanel.status = e.what();
            }
        }
        break;
    case MenuPage::Controls:
        ui::showHelpPanel(&open);
        break;
    case MenuPage::Blocks:
        ui::showBlocksPanel(m_blocksPanel, m_session.state().player, m_scene.atlas(), &open);
        if (m_blocksPanel.chosen) m_session.queueHotbar(m_session.state().player.selectedSlot, *m_blocksPanel.chosen);
        break;
    }
    if (!open) m_page = MenuPage::List; // the page's close button: back to the list
}

// Live: input, view, hair detail and budget here; the window's size and vsync by the window. The tick rate
// (not live, session/setting_table.h) applies from the next start.
void Frontend::applySettings() {
    m_settingsPanel.changed = false;
    m_settings = m_settingsPanel.edit;
    const std::vector<std::string> kept = m_session.applySettings(m_settings);
    m_settingsPanel.status.clear();
    for (const std::string& label : kept)
        m_settingsPanel.status += label + " keeps its value until the recording ends (it changes the simulation). ";
    setSceneSettings(m_settings);
    m_windowSettings = m_settings;
}

void Frontend::setSceneSettings(const session::Settings& s) {
    m_sceneSettings.fovDegrees = s.fov;
    m_sceneSettings.viewRadius = s.viewRadius;
    m_sceneSettings.levelOfDetail = s.levelOfDetail;
    m_sceneSettings.occlusionCulling = s.occlusionCulling;
}

std::string Frontend::overriddenNote(const session::Options& o) {
    std::string flags;
    for (std::size_t i = 0; i < session::kSettingRows.size(); ++i) {
        if (!o.given.settings[i]) continue;
        const session::SettingRow& row = session::kSettingRows[i];
        if (!flags.empty()) flags += ", ";
        flags += std::string(row.flag) + " " + session::settingText(row, o.settings);
    }
    return flags.empty() ? flags
                         : "Given on the command line for this run: " + flags + ". Save writes them into the file.";
}

std::optional<session::Settings> Frontend::takeWindowSettings() {
    return std::exchange(m_windowSettings, std::nullopt);
}

// Carries out what the world list asked for. Failures are shown in the list; the current world stays.
void Frontend::handleWorldRequest() {
    ui::WorldPanel& panel = m_worldPanel;
    std::error_code ec;
    try {
        switch (panel.request) {
        case ui::WorldPanel::Request::None:
            return;
        case ui::WorldPanel::Request::Load:
            m_panels.close();
            m_session.openWorld(panel.target, 1, world::TerrainKind::Default);
            panel.status = "Loaded " + panel.target.stem().string();
            break;
        case ui::WorldPanel::Request::Create:
            std::filesystem::create_directories(panel.folder, ec);
            m_panels.close();
            m_session.openWorld(panel.target, panel.newSeed,
                                panel.newFlat ? world::TerrainKind::Flat : world::TerrainKind::Default);
            panel.status = "Created " + panel.target.stem().string();
            break;
        case ui::WorldPanel::Request::Recordings:
            m_page = MenuPage::Recordings;
            m_recordingsPanel.folder = panel.folder;
            m_recordingsPanel.status.clear();
            break;
        case ui::WorldPanel::Request::Delete:
            if (m_session.hasWorld() && std::filesystem::equivalent(panel.target, m_session.worldPath(), ec)) {
                panel.status = "The world being played cannot be deleted.";
                return;
            }
            save::removeWorldFiles(panel.target, ec);
            panel.status = ec ? "Could not delete: " + ec.message() : "Deleted " + panel.target.stem().string();
            break;
        }
    } catch (const std::exception& e) {
        panel.status = e.what();
    }
}

std::string Frontend::screenshot(const std::filesystem::path& path, const FrameRequest& frame, int scale) {
    try {
        // The screenshot folder (--screenshot-dir or its default) is named as a folder: it is created.
        std::error_code ec;
        if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
        writePicture(path, frame, scale);
    } catch (const std::runtime_error& e) { // render::RenderError, core::OutputError
        core::logError("%s", e.what());
        m_message = {e.what(), 5.0};
        return e.what();
    }
    std::printf("screenshot: %s\n", path.c_str());
    std::fflush(stdout);
    m_message = {"Saved " + path.string(), 3.0};
    return {};
}

} // namespace app
