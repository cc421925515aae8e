#include <imgui.h>
#include <imgui_internal.h> // TempInputIsActive: whether the slider's text edit is open

#include <algorithm>
#include <cmath>

#include "game/day_clock.h"
#include "ui/panel_fit.h"
#include "ui/ui.h"
#include "world/block.h"

namespace ui {

void showOverlayPanel(const game::GameState& state, const OverlayInfo& info, bool* open) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.55f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                   ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("Overlay (F3)", open, flags)) {
        const game::Player& p = state.player;
        ImGui::Text("%.0f fps  frame %.2f ms", info.fps, info.frameMs);
        ImGui::Text("tick %.3f ms  render (cpu) %.2f ms", info.tickMs, info.renderCpuMs);
        ImGui::Text("chunks: %d loaded, %d meshed, %d drawn, %d pending", info.chunks.loaded, info.chunks.meshes,
                    info.chunks.drawn, info.chunks.pending);
        ImGui::Text("triangles %lld  meshing %.2f ms (%d this frame)", info.chunks.triangles, info.chunks.meshMs,
                    info.chunks.meshedThisFrame);
        ImGui::Separator();
        ImGui::Text("tick %llu  seed %llu", static_cast<unsigned long long>(state.tick),
                    static_cast<unsigned long long>(state.world.terrain().seed));
        ImGui::Text("pos %.2f %.2f %.2f", p.position.x, p.position.y, p.position.z);
        ImGui::Text("yaw %.1f pitch %.1f %s%s", p.yaw, p.pitch, p.onGround ? "on ground" : "airborne",
                    p.flying ? ", flying" : "");
        // What a click acts on now: the same target the break, place and panel actions use.
        const game::Target target = game::targetOf(state);
        switch (target.kind) {
        case game::Target::Kind::Block: {
            const auto& hit = target.block;
            ImGui::Text("target block %d %d %d (%.*s)", hit.block.x, hit.block.y, hit.block.z,
                        static_cast<int>(world::blockInfo(hit.type).name.size()),
                        world::blockInfo(hit.type).name.data());
            break;
        }
        case game::Target::Kind::PendulumSet:
            ImGui::Text("target pendulum set %zu, %.1f m", target.index, target.distance);
            break;
        case game::Target::Kind::HairBall:
            ImGui::Text("target hair ball %zu, %.1f m", target.index, target.distance);
            break;
        case game::Target::Kind::None:
            ImGui::TextUnformatted("target none");
            break;
        }
        ImGui::Text("edits %zu  gamepad %s", state.world.editCount(),
                    info.gamepad.empty() ? "none" : info.gamepad.c_str());
    }
    ImGui::End();
}

void showHelpPanel(bool* open) {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    fitNextWindowToDisplay();
    if (ImGui::Begin("Controls (F1)", open, kPanelFlags | ImGuiWindowFlags_AlwaysAutoResize)) {
        if (ImGui::BeginTable("controls", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
            ImGui::TableSetupColumn("Action");
            ImGui::TableSetupColumn("Keyboard and mouse");
            ImGui::TableSetupColumn("Gamepad");
            ImGui::TableHeadersRow();
            const char* rows[][3] = {
                {"Move", "W A S D", "Left stick"},
                {"Look", "Mouse", "Right stick"},
                {"Jump / fly up", "Space", "A"},
                {"Fly down", "Left Shift", "B"},
                {"Sprint", "Left Ctrl", "Left stick click"},
                {"Toggle fly", "F", "Y"},
                {"Break block", "Left click", "LB"},
                {"Place block", "Right click", "RB"},
                {"Pick targeted block or object", "Middle click", "X"},
                {"Panel of the object looked at", "E", "D-pad up"},
                {"Pick up / put down a hair ball", "Q", "Right stick click"},
                {"Select block", "1-9, mouse wheel", "LT / RT, d-pad"},
                {"Pause menu, back one level", "Esc", "Start"},
                {"Controls (this list)", "F1", "-"},
                {"Screenshot", "F2", "-"},
                {"Performance overlay, click target", "F3", "Back"},
            };
            for (const auto& r : rows) {
                ImGui::TableNextRow();
                for (int i = 0; i < 3; ++i) {
                    ImGui::TableSetColumnIndex(i);
                    ImGui::TextUnformatted(r[i]);
                }
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

PauseChoice showPausePanel(double& hours, PauseMenu& menu) {
    PauseChoice choice = PauseChoice::None;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::GetBackgroundDrawList()->AddRectFilled(ImVec2(0, 0), size, IM_COL32(0, 0, 0, 90));
    // A little above the middle where there is room; in the middle of a short frame, scrolling if need be.
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * (size.y >= 400.0f ? 0.4f : 0.5f)), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    fitNextWindowToDisplay();
    if (ImGui::Begin("Paused", nullptr, kPanelFlags | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove)) {
        const ImGuiStyle& style = ImGui::GetStyle();
        const ImVec2 button(std::min(220.0f, size.x - 20.0f - 2.0f * style.WindowPadding.x), 0);
        if (ImGui::Button("Resume", button)) choice = PauseChoice::Resume;
        if (ImGui::Button("Blocks", button)) choice = PauseChoice::Blocks;
        if (ImGui::Button("Worlds", button)) choice = PauseChoice::Worlds;
        if (ImGui::Button("Settings", button)) choice = PauseChoice::Settings;
        if (ImGui::Button("Controls", button)) choice = PauseChoice::Controls;
        if (ImGui::Button("Quit", button)) choice = PauseChoice::Quit;
        // The time of day, shown as a clock; the game's tick applies it (and a recording keeps it).
        // A typed hour is held here while its text edit is open: the slider shows it, the game does not have it.
        float slider = menu.typedHours.value_or(static_cast<float>(hours));
        const ImGuiID id = ImGui::GetID("##time");
        ImGui::SetNextItemWidth(button.x);
        const bool moved =
            ImGui::SliderFloat("##time", &slider, 0.0f, 23.99f, ("Time of day " + game::clockText(slider)).c_str());
        if (ImGui::TempInputIsActive(id)) {
            if (moved) menu.typedHours = slider;
        } else if (menu.typedHours) { // the text edit ended this frame: Esc cancels it, Return or a click keeps it
            if (!ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) {
                hours = static_cast<double>(*menu.typedHours);
                choice = PauseChoice::TimeOfDay;
            }
            menu.typedHours.reset();
        } else if (moved) {
            hours = static_cast<double>(slider);
            choice = PauseChoice::TimeOfDay;
        }
    }
    ImGui::End();
    return choice;
}

} // namespace ui
