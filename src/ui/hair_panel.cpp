#include <imgui.h>

#include "ui/ui.h"

namespace ui {

void showHairPanel(HairPanel& panel, bool* open) {
    const game::HairBall& ball = *panel.ball;
    ImGui::SetNextWindowSize(ImVec2(420, 0), ImGuiCond_Appearing);
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 430, 10), ImGuiCond_Appearing);
    if (!ImGui::Begin("Hair ball", open, ImGuiWindowFlags_NoCollapse)) {
        ImGui::End();
        return;
    }
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
    if (changed) panel.commands.push_back({panel.index, d});
    ImGui::TextDisabled("Q picks the ball up and puts it down; E or Esc closes");
    ImGui::End();
}

} // namespace ui
