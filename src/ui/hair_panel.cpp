#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "ui/panel_fit.h"
#include "ui/ui.h"

namespace ui {

namespace {

// One line on what each solver does (physics/hair.h has the whole story), under the solver combo.
const char* solverSummary(physics::HairMethod m) {
    switch (m) {
    case physics::HairMethod::Ftl:
        return "follow-the-leader: exact lengths in one pass; a free strand loses energy";
    case physics::HairMethod::Dftl:
        return "follow-the-leader with velocity correction: tips calm down, hair settles";
    case physics::HairMethod::Pbd:
        return "Gauss-Seidel length constraints: exact only with many iterations";
    case physics::HairMethod::XpbdSubsteps:
        return "small substeps of one PBD pass each";
    case physics::HairMethod::Shake:
        return "each strand's lengths solved together (Newton): exact, no FTL energy loss";
    case physics::HairMethod::Count:
        break;
    }
    return "";
}

} // namespace

void showHairPanel(HairPanel& panel, bool* open) {
    const game::HairBall& ball = *panel.ball;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    // The window fits its content, and every slider has one fixed width with its label beside it: a
    // fixed window width cut the longest labels ("constraint iteratic"). Long enough for "R:255" in
    // each of the colour's three fields. The height is capped by the screen (it scrolls when smaller).
    const float sliderWidth = std::max(ImGui::GetFontSize() * 16.0f, ImGui::CalcTextSize("R:255").x * 4.0f);
    ImGui::SetNextWindowPos(ImVec2(display.x - 10.0f, 10.0f), ImGuiCond_Appearing, ImVec2(1.0f, 0.0f));
    fitNextWindowToDisplay();
    if (!ImGui::Begin("Hair ball", open, kPanelFlags | ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::End();
        return;
    }
    ImGui::PushItemWidth(sliderWidth);
    const physics::HairSolver& solver = ball.solver();
    const bool asleep = solver.sleeping();
    ImGui::Text("at %.1f %.1f %.1f  %s", ball.centre().x, ball.centre().y, ball.centre().z,
                asleep ? "asleep" : "awake");
    ImGui::Text("%d of %d strands simulated, %d nodes each", solver.activeStrands(), solver.strands(),
                solver.nodesPerStrand());
    // Live: the largest |segment / rest length - 1| of the ball's last step, as a percentage. A sleeping
    // ball does no steps; it keeps the figure of its last awake one, and says so.
    {
        char text[128];
        std::snprintf(text, sizeof text, "segment length error %.3g %%",
                      100.0 * static_cast<double>(ball.lastStats().maxSegmentError));
        ImGui::TextUnformatted(text);
        if (asleep) {
            ImGui::SameLine();
            ImGui::TextDisabled("(asleep: its last awake step)");
        }
    }
    ImGui::Separator();

    game::HairBallDef& d = panel.edit;
    bool changed = false;
    ImGui::BeginDisabled(panel.readOnly); // a replay's ball is the recording's: shown, not edited

    // The solver. Switching starts from that solver's own iterations and substeps (hairMethodDefaults keeps
    // every other parameter), then rebuilds the ball like any other edit.
    const physics::HairMethod current = d.hair.method;
    if (ImGui::BeginCombo("solver", std::string(physics::hairMethodName(current)).c_str())) {
        for (int k = 0; k < physics::kHairMethodCount; ++k) {
            const auto mk = static_cast<physics::HairMethod>(k);
            if (ImGui::Selectable(std::string(physics::hairMethodName(mk)).c_str(), mk == current) && mk != current) {
                d.hair = physics::hairMethodDefaults(mk, d.hair);
                changed = true;
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", solverSummary(mk));
        }
        ImGui::EndCombo();
    }
    ImGui::TextDisabled("%s", solverSummary(d.hair.method));
    // What iterations and substeps mean depends on the solver: only the controls it uses, named for it.
    constexpr int maxIterations = 20;
    const auto iterations = [&](const char* label) {
        return ImGui::SliderInt(label, &d.hair.iterations, 1, maxIterations, "%d", ImGuiSliderFlags_AlwaysClamp);
    };
    switch (d.hair.method) {
    case physics::HairMethod::Ftl:
    case physics::HairMethod::Dftl:
        changed |= iterations("follow-the-leader passes");
        break;
    case physics::HairMethod::Pbd:
        changed |= iterations("Gauss-Seidel iterations");
        break;
    case physics::HairMethod::Shake:
        changed |= iterations("Newton iterations");
        break;
    case physics::HairMethod::XpbdSubsteps: // one PBD pass a substep: iterations do not apply
    case physics::HairMethod::Count:
        break;
    }
    changed |= ImGui::SliderInt(d.hair.method == physics::HairMethod::XpbdSubsteps ? "substeps (one pass each)"
                                                                                   : "substeps per tick",
                                &d.hair.substeps, 1, game::kMaxHairSubsteps, "%d", ImGuiSliderFlags_AlwaysClamp);
    if (d.hair.method == physics::HairMethod::Dftl) {
        changed |= ImGui::SliderFloat("velocity correction", &d.hair.velocityCorrection, 0.0f, 1.0f, "%.2f",
                                      ImGuiSliderFlags_AlwaysClamp);
    }
    ImGui::TextDisabled("%d constraint projections per node a step (more substeps on long ticks)",
                        physics::hairProjectionsPerNode(d.hair));
    ImGui::Separator();

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
    ImGui::PopItemWidth();
    ImGui::EndDisabled();
    if (changed && !panel.readOnly) panel.commands.push_back({panel.index, d});
    ImGui::TextDisabled(panel.readOnly ? "A replay: read only (T takes over); E or Esc closes"
                                       : "Q picks the ball up and puts it down; E or Esc closes");
    ImGui::End();
}

} // namespace ui
