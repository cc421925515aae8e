#include "ui/settings_panel.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "input/action_table.h"
#include "input/events.h"
#include "input/keys.h"
#include "session/setting_table.h"
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

// The slider's number format: as many decimals as the range needs, then the unit ("%.2f of full travel").
std::string sliderFormat(const session::SettingRow& row) {
    std::string format = row.type == session::SettingType::Int ? "%d"
                         : row.hi - row.lo >= 10.0             ? "%.0f"
                         : row.lo > 0.0 && row.lo < 0.01       ? "%.3f"
                                                               : "%.2f";
    if (!row.unit.empty()) { // piecewise: GCC 12 warns falsely (-Wrestrict) on " " + std::string&&
        format += ' ';
        format += row.unit;
    }
    return format;
}

// A setting's label: its name, and when it applies if not at once.
std::string settingLabel(const session::SettingRow& row) {
    std::string label(row.label);
    if (!row.live) label += " (from the next start)";
    return label;
}

// One setting's widget, from its row (session/setting_table.h); true when it changed the value.
bool settingWidget(const session::SettingRow& row, session::Settings& s) {
    const std::string label = settingLabel(row);
    const ImGuiSliderFlags scale = row.scale == session::SettingScale::Logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
    bool changed = false;
    switch (row.type) {
    case session::SettingType::Int:
        if (!row.choices.empty()) {
            std::string items(row.choices); // ImGui's list: names ended by '\0', the list by a second
            std::replace(items.begin(), items.end(), '|', '\0');
            items += '\0';
            int& value = row.intRef(s);
            value = std::clamp(value, static_cast<int>(row.lo), static_cast<int>(row.hi));
            int index = value - static_cast<int>(row.lo);
            changed = ImGui::Combo(label.c_str(), &index, items.c_str());
            value = index + static_cast<int>(row.lo);
        } else {
            changed = ImGui::SliderInt(label.c_str(), &row.intRef(s), static_cast<int>(row.lo),
                                       static_cast<int>(row.hi), sliderFormat(row).c_str(), scale);
        }
        break;
    case session::SettingType::Float:
        changed = ImGui::SliderFloat(label.c_str(), &row.floatRef(s), static_cast<float>(row.lo),
                                     static_cast<float>(row.hi), sliderFormat(row).c_str(), scale);
        break;
    case session::SettingType::Bool:
        changed = ImGui::Checkbox(label.c_str(), &row.boolRef(s));
        break;
    case session::SettingType::Size: {
        session::PixelSize& size = row.sizeRef(s);
        int sides[2] = {size.width, size.height};
        if (ImGui::InputInt2(label.c_str(), sides, ImGuiInputTextFlags_EnterReturnsTrue)) {
            size = {sides[0], sides[1]};
            changed = true;
        }
        break;
    }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%.*s", static_cast<int>(row.help.size()), row.help.data());
    return changed;
}

// The settings of one tab: the rows of the sections given, in the table's order, then the table's clamps (sliders
// take typed values, ctrl+click, outside their range).
// The widgets leave room for the longest label beside them (ImGui's default, two thirds of the window, pushed
// "Tick rate (from the next start)" out of a 640x480 frame); below 120 px a widget scrolls instead.
void settingsSection(SettingsPanel& p, std::initializer_list<std::string_view> sections) {
    const auto inSection = [&](const session::SettingRow& row) {
        return std::find(sections.begin(), sections.end(), row.section) != sections.end();
    };
    float labelWidth = 0.0f;
    for (const session::SettingRow& row : session::kSettingRows)
        if (inSection(row)) labelWidth = std::max(labelWidth, ImGui::CalcTextSize(settingLabel(row).c_str()).x);
    const float width = ImGui::GetContentRegionAvail().x - labelWidth - ImGui::GetStyle().ItemInnerSpacing.x;
    ImGui::PushItemWidth(std::max(120.0f, width));
    bool c = false;
    for (const session::SettingRow& row : session::kSettingRows)
        if (inSection(row)) c |= settingWidget(row, p.edit);
    ImGui::PopItemWidth();
    session::clampSettings(p.edit);
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
                settingsSection(panel, {"graphics", "simulation"});
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Replay")) {
                settingsSection(panel, {"replay"});
                ImGui::TextDisabled("Applied from the next replay (--replay) or recording (--record).");
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Controls")) {
                settingsSection(panel, {"mouse", "gamepad_tuning"});
                ImGui::TextDisabled("Release must stay below press: a pull counts again only after falling below it.");
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
