// The settings panel walked through every row of the settings table in a headless Dear ImGui context (no GL: the
// frame is laid out and ended, never drawn). Values in range and at both ends stay as they are; one past each end
// (what a ctrl+click typed value or an edited file can hold) is held to that end by the panel's clamps.
#include <gtest/gtest.h>

#include <imgui.h>

#include <algorithm>
#include <string>

#include "session/setting_table.h"
#include "ui/settings_panel.h"

namespace {

using session::SettingRow;
using session::SettingType;

class HeadlessImGui {
public:
    HeadlessImGui() {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(1280, 720);
        io.DeltaTime = 1.0f / 60.0f;
        io.IniFilename = nullptr;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h); // builds the font atlas, which a frame needs
    }
    ~HeadlessImGui() { ImGui::DestroyContext(); }
    HeadlessImGui(const HeadlessImGui&) = delete;
    HeadlessImGui& operator=(const HeadlessImGui&) = delete;

    // One frame of the panel with these settings; returns what the panel holds after it.
    static session::Settings frame(const session::Settings& edit, bool* changed = nullptr) {
        ui::SettingsPanel panel;
        panel.edit = edit;
        bool open = true;
        ImGui::NewFrame();
        ui::showSettingsPanel(panel, &open);
        ImGui::EndFrame();
        if (changed) *changed = panel.changed;
        return panel.edit;
    }
};

// The row's value `v` (Size: both sides) set straight into the settings, as a typed value lands before the clamp.
void set(const SettingRow& row, session::Settings& s, double v) {
    if (row.type == SettingType::Int) row.intRef(s) = static_cast<int>(v);
    if (row.type == SettingType::Float) row.floatRef(s) = static_cast<float>(v);
    if (row.type == SettingType::Size) row.sizeRef(s) = {static_cast<int>(v), static_cast<int>(v)};
}

// Catches a panel with its own ranges (the issue found view_radius's 2..32 written in four places) or without a
// clamp: with the clamp removed, every "past" value stays past its end.
TEST(SettingsPanel, EveryRowIsHeldToItsRangeAndValuesInsideItAreLeftAlone) {
    HeadlessImGui imgui;
    int walked = 0;
    for (const SettingRow& row : session::kSettingRows) {
        if (row.type == SettingType::Bool) continue;
        SCOPED_TRACE(std::string(row.key));
        const double step = row.type == SettingType::Float ? (row.hi - row.lo) * 1e-3 : 1.0;
        for (const double inside : {row.lo, (row.lo + row.hi) / 2, row.hi}) {
            session::Settings s;
            set(row, s, row.type == SettingType::Float ? inside : std::floor(inside));
            // The one rule across rows keeps the trigger's release below its press: let the press allow every value.
            if (row.key == "trigger_release") s.input.triggerPress = 1.0f, set(row, s, std::min(inside, 0.95));
            bool changed = true;
            const session::Settings after = HeadlessImGui::frame(s, &changed);
            EXPECT_EQ(session::settingText(row, after), session::settingText(row, s)) << inside;
            EXPECT_FALSE(changed);
        }
        for (const auto& [past, end] : {std::pair{row.lo - step, row.lo}, std::pair{row.hi + step, row.hi}}) {
            session::Settings s, expected;
            set(row, s, past);
            set(row, expected, end);
            if (row.key == "trigger_release") s.input.triggerPress = expected.input.triggerPress = 1.0f;
            session::clampSettings(expected); // the rule across rows, where it applies
            const session::Settings after = HeadlessImGui::frame(s);
            EXPECT_EQ(session::settingText(row, after), session::settingText(row, expected)) << past;
        }
        ++walked;
    }
    EXPECT_GE(walked, 11); // the precondition: every numeric row of the table was walked
}

} // namespace
