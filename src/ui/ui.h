// Dear ImGui on top of the 3D frame: the HUD (crosshair, hotbar, messages), the F3 overlay, the F1
// controls list and the pause menu. Panels follow `void showXxxPanel(Xxx&, bool* open)`. The same code
// draws in the window and in headless frames (there without a platform backend).
#pragma once
#include <cstdint>
#include <filesystem>
#include <glm/vec2.hpp>
#include <optional>
#include <string>
#include <vector>

#include "game/game_state.h"
#include "render/scene_renderer.h"
#include "render/texture.h"

struct GLFWwindow;

namespace ui {

class ImGuiLayer {
public:
    // window == nullptr: headless, input and display size come from the caller.
    explicit ImGuiLayer(GLFWwindow* window);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    // framebufferScale: the frame is drawn this many times larger than it is laid out (large screenshots),
    // the way a HiDPI display scales it; the HUD keeps its proportions.
    void beginFrame(glm::ivec2 displaySize, float deltaSeconds, float framebufferScale = 1.0f);
    void endFrame();
    // For a frame drawn in tiles: finishes the layout without drawing, then draws the part of the UI that falls
    // in each tile (framebuffer pixels, y down, the tile's own viewport).
    void finishLayout();
    void drawTile(glm::ivec2 tileOrigin, glm::ivec2 tileSize);
    void discardFrame(); // ends a frame without drawing it (layout only)
    bool wantsMouse() const;
    bool wantsKeyboard() const;
    // Every key event the window reported, in order. ImGui 1.86 reads a key as held or not when a frame begins,
    // so a key pressed and released between two frames (a quick tap on a slow frame) never reached it: Esc left
    // a text edit open, Return sometimes did not end one. Such a key is held down for ImGui for one frame.
    void noteKey(int key, bool down);
    // A pop-up (a drop-down, a modal) or a text edit is open: Esc is ImGui's, to close or cancel it.
    bool ownsEscape() const;

private:
    void updateModifiers();

    bool m_glfw;
    std::vector<int> m_pressedSinceFrame, m_heldForOneFrame;
};

struct HudMessage {
    std::string text;
    double secondsLeft = 0.0;
};

// Crosshair, hotbar with tile icons and the selected slot, fly/pause badges and a transient message.
void drawHud(const game::GameState& state, const render::BlockAtlas& atlas, const HudMessage& message);

struct OverlayInfo {
    double fps = 0.0;
    double frameMs = 0.0;
    double tickMs = 0.0; // mean simulation time per tick over the last frame
    double renderCpuMs = 0.0;
    render::ChunkStats chunks;
    std::string gamepad; // connected pad name, empty if none
};
void showOverlayPanel(const game::GameState& state, const OverlayInfo& info, bool* open);
void showHelpPanel(bool* open);

// The panel of one pendulum set: live traces of theta and energy for the four slots (the exact
// solution as a white reference), and the set's controls. Changes come back as commands, applied by
// the next tick like any other input.
struct PendulumPanel {
    const game::PendulumSet* set = nullptr;
    std::size_t index = 0;     // of the set in GameState::pendulumSets
    game::PendulumSetDef edit; // what the controls show
    double tickSeconds = 1.0 / 60.0;
    std::vector<game::PendulumCommand> commands; // filled by the panel, drained by the caller
    bool readOnly = false; // a replay's timeline: the figures at the tick on screen, the controls disabled
};
void showPendulumPanel(PendulumPanel& panel, bool* open);
// Names in the world, within reading distance and in sight, laid out together so that none covers another
// (ui/label_layout.h): each pendulum bob's method in its colour, next to it, and each hair ball's solver
// ("dftl", "shake", ...) above its hair (not the carried ball's).
void drawObjectLabels(const game::GameState& state, const render::SceneRenderer& scene, float alpha);
// The labels drawObjectLabels considers, on screen and within reading distance: `hidden` when a block stands
// between the eye and the label's point (the line of sight is cast through the blocks, world/raycast.h).
struct ObjectLabel {
    std::string text;
    glm::vec3 at{0.0f};     // the point in the world the label names
    glm::vec2 screen{0.0f}; // where it projects, pixels
    float distance = 0.0f;  // from the eye
    unsigned colour = 0;    // ImU32
    bool hidden = false;
};
std::vector<ObjectLabel> objectLabels(const game::GameState& state, const render::SceneRenderer& scene, float alpha);

// The panel of one hair ball: its solver (switching starts from that solver's iterations and substeps) with
// the controls that solver uses, named for it; colour, size, strands, damping, patch, spin; all edited live.
// It shows the ball's segment-length error live (the last awake step's while the ball sleeps).
struct HairPanel {
    const game::HairBall* ball = nullptr;
    std::size_t index = 0; // of the ball in GameState::hairBalls
    game::HairBallDef edit;
    std::vector<game::HairCommand> commands;
    bool readOnly = false; // a replay's timeline: the figures at the tick on screen, the controls disabled
};
void showHairPanel(HairPanel& panel, bool* open);

// The world list: every saved world in a folder, load, delete (confirmed), create.
struct WorldPanel {
    std::filesystem::path folder;
    std::string current; // the world being played (full path), empty if unsaved
    char newName[64] = "new world";
    std::uint64_t newSeed = 1;
    bool newFlat = false;
    std::optional<std::filesystem::path> pendingDelete;
    std::string status; // the last outcome, shown under the list
    enum class Request { None, Load, Create, Delete, Recordings };
    Request request = Request::None; // set for one frame when the player asks for something
    std::filesystem::path target;
};
void showWorldPanel(WorldPanel& panel, bool* open);

// Worlds > Recordings: the recordings (--record's files, FILE.mcscript) in the worlds folder, newest first, each
// with its ticks; Play replays one in the window as a timeline.
struct RecordingsPanel {
    std::filesystem::path folder;
    std::string status; // the last outcome (a recording that could not be played: why)
    bool play = false;  // set for one frame when the player asks to play `target`
    std::filesystem::path target;
};
void showRecordingsPanel(RecordingsPanel& panel, bool* open);

enum class PauseChoice { None, Resume, Blocks, Worlds, Settings, Controls, Quit, TimeOfDay };
// The pause menu's own state between frames: an hour typed into the time slider (Ctrl+click) and not yet
// confirmed.
struct PauseMenu {
    std::optional<float> typedHours;
};
// `hours`: the time of day, shown on a slider. Dragged, each new hour is the choice TimeOfDay at once; typed, it
// waits for Return (or a click elsewhere) and Esc drops it.
PauseChoice showPausePanel(double& hours, PauseMenu& menu);

// The block picker (a page of the pause menu): every block and lab object, as the hotbar shows them. `chosen` is
// what was clicked this frame, for the player's selected slot; `hovered` the name last pointed at or focused.
struct BlocksPanel {
    std::optional<game::Item> chosen;
    std::string hovered;
};
void showBlocksPanel(BlocksPanel& panel, const game::Player& player, const render::BlockAtlas& atlas, bool* open);

} // namespace ui
