#include "ui/settings_panel.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "input/action_table.h"
#include "input/events.h"
#include "input/keys.h"
#include "ui/panel_fit.h"

namespace ui {
namespace {

// The rows are the actions of input/action_table.h, in its order, with its labels.
constexpr const auto& kKeyRows = input::kKeyActions;
constexpr const auto& kPadRows = input::kPadActions;

void label(std::string_view text) { ImGui::TextUnformatted(text.data(), text.data() + text.size()); }

std::string keyLabel(int key) {
    const std::string_view name = input::keyName(key);
    return name.empty() ? std::string("(none)") : std::string(name);
}

std::string padLabel(input::GamepadButton button) {
    const std::string_view name = input::gamepadButtonName(button);
    return name.empty() ? std::string("(none)") : std::string(name);
}

// With the GLFW backend, ImGui 1.86's KeysDown[] is indexed by GLFW key code, so a press can be read
// here without the window's help; headless frames have no backend and rely on feedSettingsPanelKey.
void pollImGuiKeys(SettingsPanel& panel) {
    if (panel.capturingKey < 0 || panel.capturedKey) return;
    for (int k = 0; k <= input::kKeyLast; ++k) {
        if (ImGui::IsKeyPressed(k, false)) {
            panel.capturedKey = k;
            return;
        }
    }
}

// Applies a captured key or button to the binding that waits for it. Escape cancels a key rebind
// (so Escape itself cannot be bound from here; "Reset" restores it for the pause menu).
void applyCapture(SettingsPanel& panel) {
    if (panel.capturingKey >= 0 && panel.capturedKey) {
        const int key = *panel.capturedKey;
        if (key != input::key::Escape && key >= 0 && key <= input::kKeyLast) {
            panel.edit.input.keys.*kKeyRows[static_cast<std::size_t>(panel.capturingKey)].key = key;
            panel.changed = true;
        }
        panel.capturingKey = -1;
    }
    if (panel.capturingPad >= 0 && panel.capturedKey && *panel.capturedKey == input::key::Escape) {
        panel.capturingPad = -1;
    }
    if (panel.capturingPad >= 0 && panel.capturedButton) {
        const int b = *panel.capturedButton;
        if (b >= 0 && b < static_cast<int>(input::kGamepadButtonCount)) {
            panel.edit.input.pad.*kPadRows[static_cast<std::size_t>(panel.capturingPad)].button =
                static_cast<input::GamepadButton>(b);
            panel.changed = true;
        }
        panel.capturingPad = -1;
    }
    panel.capturedKey.reset();
    panel.capturedButton.reset();
}

void graphicsSection(SettingsPanel& p) {
    session::Settings& s = p.edit;
    bool c = false;
    c |= ImGui::SliderFloat("Field of view", &s.fov, 30.0f, 120.0f, "%.0f deg");
    c |= ImGui::SliderInt("View radius", &s.viewRadius, 2, 32, "%d chunks");
    const char* detail[] = {"Low (1/4 of the strands)", "Half of the strands", "Full"};
    s.hairDetail = std::clamp(s.hairDetail, 0, 2);
    c |= ImGui::Combo("Hair detail", &s.hairDetail, detail, 3);
    c |= ImGui::SliderInt("Hair budget", &s.hairBudgetThousands, 100, 100000, "%d thousand node passes a tick",
                          ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    c |= ImGui::Checkbox("Vsync", &s.vsync);
    int size[2] = {s.windowWidth, s.windowHeight};
    if (ImGui::InputInt2("Window size", size, ImGuiInputTextFlags_EnterReturnsTrue)) {
        s.windowWidth = std::clamp(size[0], 320, 16384);
        s.windowHeight = std::clamp(size[1], 320, 16384);
        c = true;
    }
    c |= ImGui::SliderInt("Tick rate", &s.tickRate, 10, 1000, "%d per second", ImGuiSliderFlags_Logarithmic);
    // Sliders accept typed values (ctrl+click) outside their range; the file's ranges hold here too.
    s.fov = std::clamp(s.fov, 30.0f, 120.0f);
    s.viewRadius = std::clamp(s.viewRadius, 2, 32);
    s.tickRate = std::clamp(s.tickRate, 10, 1000);
    p.changed |= c;
}

void controlsSection(SettingsPanel& p) {
    input::InputConfig& in = p.edit.input;
    bool c = false;
    c |= ImGui::SliderFloat("Mouse sensitivity", &in.mouseDegreesPerPixel, 0.001f, 10.0f, "%.3f deg/px",
                            ImGuiSliderFlags_Logarithmic);
    c |= ImGui::Checkbox("Invert Y (mouse and right stick)", &in.invertY);
    c |= ImGui::SliderFloat("Stick deadzone", &in.stickDeadzone, 0.0f, 0.9f, "%.2f");
    c |= ImGui::SliderFloat("Stick look speed", &in.lookStickDegreesPerSecond, 1.0f, 2000.0f, "%.0f deg/s",
                            ImGuiSliderFlags_Logarithmic);
    c |= ImGui::SliderFloat("Trigger press", &in.triggerPress, 0.05f, 1.0f, "%.2f");
    c |= ImGui::SliderFloat("Trigger release", &in.triggerRelease, 0.0f, 0.95f, "%.2f");
    in.mouseDegreesPerPixel = std::clamp(in.mouseDegreesPerPixel, 0.001f, 10.0f);
    in.stickDeadzone = std::clamp(in.stickDeadzone, 0.0f, 0.9f);
    in.lookStickDegreesPerSecond = std::clamp(in.lookStickDegreesPerSecond, 1.0f, 2000.0f);
    in.triggerPress = std::clamp(in.triggerPress, 0.05f, 1.0f);
    // Release must stay below press or a resting trigger would step the hotbar every tick.
    in.triggerRelease = std::clamp(in.triggerRelease, 0.0f, in.triggerPress - 0.05f);
    ImGui::TextDisabled("Release must stay below press: a pull counts again only after falling below it.");
    p.changed |= c;
}

// One row of a bindings table: the action's name, its binding on a button (click to rebind), and a note when
// another action shares the binding. Returns whether the button was clicked.
bool bindingRow(std::size_t i, std::string_view name, const std::string& binding, bool shared) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    label(name);
    ImGui::TableSetColumnIndex(1);
    ImGui::PushID(static_cast<int>(i));
    const bool clicked = ImGui::Button(binding.c_str(), ImVec2(200, 0));
    if (shared) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1.0f, 0.7f, 0.2f, 1.0f), "also bound elsewhere");
    }
    ImGui::PopID();
    return clicked;
}

void keysSection(SettingsPanel& p) {
    const input::Bindings& keys = p.edit.input.keys;
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
        for (std::size_t i = 0; i < kKeyRows.size(); ++i) {
            const int key = keys.*kKeyRows[i].key;
            const bool waiting = p.capturingKey == static_cast<int>(i);
            const bool shared =
                key >= 0 && std::count_if(kKeyRows.begin(), kKeyRows.end(),
                                          [&](const input::KeyAction& r) { return keys.*r.key == key; }) > 1;
            if (bindingRow(i, kKeyRows[i].label, waiting ? "press a key (Esc cancels)" : keyLabel(key), shared)) {
                p.capturingKey = waiting ? -1 : static_cast<int>(i);
                p.capturingPad = -1;
                p.capturedKey.reset();
            }
        }
        ImGui::EndTable();
    }
    if (ImGui::Button("Reset keys")) {
        p.edit.input.keys = input::Bindings{};
        p.capturingKey = -1;
        p.changed = true;
    }
}

void padSection(SettingsPanel& p) {
    const input::GamepadBindings& pad = p.edit.input.pad;
    if (ImGui::BeginTable("pad", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
        for (std::size_t i = 0; i < kPadRows.size(); ++i) {
            const input::GamepadButton button = pad.*kPadRows[i].button;
            const bool waiting = p.capturingPad == static_cast<int>(i);
            const bool shared = button != input::GamepadButton::Count &&
                                std::count_if(kPadRows.begin(), kPadRows.end(),
                                              [&](const input::PadAction& r) { return pad.*r.button == button; }) > 1;
            if (bindingRow(i, kPadRows[i].label, waiting ? "press a button (Esc cancels)" : padLabel(button), shared)) {
                p.capturingPad = waiting ? -1 : static_cast<int>(i);
                p.capturingKey = -1;
                p.capturedButton.reset();
            }
        }
        ImGui::EndTable();
    }
    ImGui::TextDisabled("Sticks move and look; the triggers step the hotbar.");
    if (ImGui::Button("Reset buttons")) {
        p.edit.input.pad = input::GamepadBindings{};
        p.capturingPad = -1;
        p.changed = true;
    }
}

} // namespace

bool feedSettingsPanelKey(SettingsPanel& panel, int glfwKey) {
    // Escape also cancels a pad rebind, so it is taken while either waits.
    if (!settingsPanelCapturing(panel)) return false;
    panel.capturedKey = glfwKey;
    return true;
}

bool feedSettingsPanelButton(SettingsPanel& panel, int gamepadButton) {
    if (panel.capturingPad < 0) return false;
    panel.capturedButton = gamepadButton;
    return true;
}

bool settingsPanelCapturing(const SettingsPanel& panel) { return panel.capturingKey >= 0 || panel.capturingPad >= 0; }

void showSettingsPanel(SettingsPanel& panel, bool* open) {
    pollImGuiKeys(panel);
    applyCapture(panel);

    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(520, 560), ImGuiCond_FirstUseEver);
    fitNextWindowToDisplay();
    if (ImGui::Begin("Settings", open, kPanelFlags)) {
        if (ImGui::BeginTabBar("settings_tabs")) {
            if (ImGui::BeginTabItem("Graphics")) {
                graphicsSection(panel);
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Controls")) {
                controlsSection(panel);
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Keys")) {
                keysSection(panel);
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Gamepad")) {
                padSection(panel);
                ImGui::EndTabItem();
            }
            ImGui::EndTabBar();
        }
        ImGui::Separator();
        if (!panel.overriddenNote.empty()) ImGui::TextWrapped("%s", panel.overriddenNote.c_str());
        ImGui::BeginDisabled(panel.filePath.empty());
        if (ImGui::Button("Save")) panel.saveRequested = true;
        ImGui::EndDisabled();
        ImGui::SameLine();
        if (ImGui::Button("Defaults")) {
            panel.edit = session::Settings{};
            panel.capturingKey = panel.capturingPad = -1;
            panel.changed = true;
        }
        if (panel.filePath.empty()) {
            ImGui::TextWrapped("Not saved: started with --settings none.");
        } else {
            ImGui::TextWrapped("File: %s", panel.filePath.c_str());
        }
        if (!panel.status.empty()) ImGui::TextWrapped("%s", panel.status.c_str());
    }
    ImGui::End();
    // Closing the panel drops a rebind in progress, so keys go back to the game.
    if (open && !*open) panel.capturingKey = panel.capturingPad = -1;
}

} // namespace ui
