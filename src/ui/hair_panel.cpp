#include <imgui.h>

#include <algorithm>

#include "ui/ui.h"

namespace ui {

void showHairPanel(HairPanel& panel, bool* open) {
    const game::HairBall& ball = *panel.ball;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    // The window fits its content, and every slider has one fixed width with its label beside it: a
    // fixed window width cut the longest labels ("constraint iteratic"). Long enough for "R:255" in
    // each of the colour's three fields. The height is capped by the screen (it scrolls when smaller).
    const float sliderWidth = std::max(ImGui::GetFontSize() * 16.0f, ImGui::CalcTextSize("R:255").x * 4.0f);
    ImGui::SetNextWindowPos(ImVec2(display.x - 10.0f, 10.0f), ImGuiCond_Appearing, ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowSizeConstraints(
        ImVec2(0.0f, 0.0f), ImVec2(std::max(display.x - 20.0f, 100.0f), std::max(display.y - 20.0f, 100.0f)));
    if (!ImGui::Begin("Hair ball", open, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::End();
        return;
    }
    ImGui::PushItemWidth(sliderWidth);
    const physics::HairSolver& solver = ball.solver();
    ImGui::Text("at %.1f %.1f %.1f  %s", ball.centre().x, ball.centre().y, ball.centre().z,
                solver.sleeping() ? "asleep" : "awake");
    ImGui::Text("%d of %d strands simulated, %d nodes each", solver.activeStrands(), solver.strands(),
                solver.nodesPerStrand());
    ImGui::Text("largest segment length error %.2e", static_cast<double>(ball.lastStats().maxSegmentError));
    ImGui::Separator();

    game::HairBallDef& d = panel.edit;
    bool changed = false;
    changed |= ImGui::ColorEdit3("colour", &d.colour[0]);
    changed |= ImGui::SliderFloat("radius (m)", &d.radius, 0.1f, 1.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderInt("strands", &d.hair.strands, 16, 8192, "%d",
                                ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderInt("nodes per strand", &d.hair.nodesPerStrand, 3, 32, "%d", ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderFloat("strand length (m)", &d.hair.strandLength, 0.05f, 1.5f, "%.2f",
                                  ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderFloat("damping (1/s)", &d.hair.dampingPerSecond, 0.0f, 20.0f, "%.2f",
                                  ImGuiSliderFlags_AlwaysClamp);
    float patchDegrees = d.hair.patchHalfAngle * 57.29578f;
    if (ImGui::SliderFloat("patch half-angle (deg)", &patchDegrees, 5.0f, 180.0f, "%.0f",
                           ImGuiSliderFlags_AlwaysClamp)) {
        d.hair.patchHalfAngle = patchDegrees / 57.29578f;
        changed = true;
    }
    changed |= ImGui::SliderFloat("spin (rad/s)", &d.spinRate, -6.0f, 6.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderInt("constraint iterations", &d.hair.iterations, 1, 20, "%d", ImGuiSliderFlags_AlwaysClamp);
    ImGui::PopItemWidth();
    if (changed) panel.commands.push_back({panel.index, d});
    ImGui::TextDisabled("Q picks the ball up and puts it down; E or Esc closes");
    ImGui::End();
}

} // namespace ui
