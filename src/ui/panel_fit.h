// Every panel fits the frame it is drawn in: at most the display less a margin each way, scrolling (both
// ways) what does not fit, so that at the smallest window the settings allow (320 px) and the smallest render
// size (160x90) every control can still be reached. `PanelFit.*` in tests/render checks each panel.
#pragma once
#include <imgui.h>

#include <algorithm>

namespace ui {

inline constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_HorizontalScrollbar;

// Call before ImGui::Begin: the window's size is capped by the display (less `margin` on each side).
inline void fitNextWindowToDisplay(float margin = 10.0f) {
    const ImVec2 d = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowSizeConstraints(
        ImVec2(0.0f, 0.0f), ImVec2(std::max(d.x - 2.0f * margin, 60.0f), std::max(d.y - 2.0f * margin, 40.0f)));
}

} // namespace ui
