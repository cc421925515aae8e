#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ui/ui.h"

namespace ui {

namespace {

ImU32 colourOf(physics::Method m, float alpha = 1.0f) {
    const glm::vec3 c = game::methodColour(m);
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha));
}

// One plot: the trace's samples oldest to newest, each series a polyline, optional reference drawn
// first in white, the y range fitted to what is shown (symmetric around zero).
void plotTraces(const char* label, const game::PendulumTrace& trace,
                const std::array<const std::vector<float>*, 4>& series, const std::array<physics::Method, 4>& methods,
                const std::vector<float>* reference, ImVec2 size) {
    ImGui::TextUnformatted(label);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 a = ImGui::GetCursorScreenPos();
    const ImVec2 b(a.x + size.x, a.y + size.y);
    ImGui::Dummy(size);
    dl->AddRectFilled(a, b, IM_COL32(20, 22, 28, 255));
    dl->AddRect(a, b, IM_COL32(90, 90, 100, 255));
    const std::size_t n = trace.size;
    if (n < 2) return;
    const auto at = [&](const std::vector<float>& v, std::size_t k) {
        return v[(trace.head + game::PendulumTrace::kSamples - n + k) % game::PendulumTrace::kSamples];
    };
    float range = 1e-9f;
    for (const auto* s : series) {
        for (std::size_t k = 0; k < n; ++k) {
            const float v = at(*s, k);
            if (std::isfinite(v)) range = std::max(range, std::abs(v));
        }
    }
    if (reference) {
        for (std::size_t k = 0; k < n; ++k) range = std::max(range, std::abs(at(*reference, k)));
    }
    range *= 1.1f;
    const float t0 = at(trace.time, 0), t1 = std::max(at(trace.time, n - 1), t0 + 1e-6f);
    const auto point = [&](std::size_t k, float v) {
        const float x = a.x + (at(trace.time, k) - t0) / (t1 - t0) * size.x;
        const float y = a.y + size.y * 0.5f - std::clamp(v / range, -1.0f, 1.0f) * size.y * 0.5f;
        return ImVec2(x, y);
    };
    dl->AddLine(ImVec2(a.x, a.y + size.y * 0.5f), ImVec2(b.x, a.y + size.y * 0.5f), IM_COL32(70, 70, 80, 255));
    std::vector<ImVec2> pts(n);
    if (reference) {
        for (std::size_t k = 0; k < n; ++k) pts[k] = point(k, at(*reference, k));
        dl->AddPolyline(pts.data(), static_cast<int>(n), IM_COL32(255, 255, 255, 110), 0, 3.0f);
    }
    for (std::size_t i = 0; i < series.size(); ++i) {
        for (std::size_t k = 0; k < n; ++k)
            pts[k] = point(k, std::isfinite(at(*series[i], k)) ? at(*series[i], k) : 0.0f);
        dl->AddPolyline(pts.data(), static_cast<int>(n), colourOf(methods[i]), 0, 1.5f);
    }
    char text[64];
    std::snprintf(text, sizeof text, "%+.3g", static_cast<double>(range));
    dl->AddText(ImVec2(a.x + 3, a.y + 1), IM_COL32(200, 200, 200, 255), text);
    std::snprintf(text, sizeof text, "t = %.1f .. %.1f s", static_cast<double>(t0), static_cast<double>(t1));
    dl->AddText(ImVec2(a.x + 3, b.y - 15), IM_COL32(200, 200, 200, 255), text);
}

} // namespace

void showPendulumPanel(PendulumPanel& panel, bool* open) {
    const game::PendulumSet& set = *panel.set;
    ImGui::SetNextWindowSize(ImVec2(560, 0), ImGuiCond_Appearing);
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 570, 10), ImGuiCond_Appearing);
    if (!ImGui::Begin("Pendulum set", open, ImGuiWindowFlags_NoCollapse)) {
        ImGui::End();
        return;
    }
    const game::PendulumSetDef& def = set.def();
    ImGui::Text("at %d %d %d   t = %.2f s   step h = %.4f s (%.2f x tick)%s", set.base().x, set.base().y, set.base().z,
                set.time(), panel.tickSeconds * def.stepMultiplier, def.stepMultiplier,
                set.released() ? "" : "   held");
    if (ImGui::BeginTable("slots", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("slot");
        ImGui::TableSetupColumn("method");
        ImGui::TableSetupColumn("theta (deg)");
        ImGui::TableSetupColumn("omega (rad/s)");
        ImGui::TableSetupColumn("(E-E0)/mgL");
        ImGui::TableHeadersRow();
        for (int i = 0; i < game::kPendulumSlots; ++i) {
            const physics::Method m = def.methods[static_cast<std::size_t>(i)];
            const physics::PendulumState s = set.slot(i).state();
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(std::string(game::compassName(i)).c_str());
            ImGui::TableSetColumnIndex(1);
            ImGui::PushID(i);
            int current = static_cast<int>(panel.edit.methods[static_cast<std::size_t>(i)]);
            ImGui::PushStyleColor(ImGuiCol_Text, colourOf(m));
            ImGui::SetNextItemWidth(-1);
            if (ImGui::BeginCombo("##method", std::string(physics::methodName(m)).c_str())) {
                for (int k = 0; k < physics::kMethodCount; ++k) {
                    const auto mk = static_cast<physics::Method>(k);
                    if (ImGui::Selectable(std::string(physics::methodName(mk)).c_str(), k == current)) {
                        panel.edit.methods[static_cast<std::size_t>(i)] = mk;
                        panel.commands.push_back({panel.index, game::PendulumCommand::Op::SetDef, panel.edit});
                    }
                }
                ImGui::EndCombo();
            }
            ImGui::PopStyleColor();
            ImGui::PopID();
            ImGui::TableSetColumnIndex(2);
            if (set.diverged(i)) {
                ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "diverged");
            } else {
                ImGui::Text("%.3f", s.theta * 180.0 / 3.14159265358979323846);
            }
            ImGui::TableSetColumnIndex(3);
            ImGui::Text("%.4f", s.omega);
            ImGui::TableSetColumnIndex(4);
            ImGui::Text("%+.2e", set.energyError(i));
        }
        ImGui::EndTable();
    }

    const game::PendulumTrace& trace = set.trace();
    std::array<const std::vector<float>*, 4> theta{}, energy{};
    for (std::size_t i = 0; i < 4; ++i) {
        theta[i] = &trace.theta[i];
        energy[i] = &trace.energyError[i];
    }
    const float width = ImGui::GetContentRegionAvail().x;
    plotTraces("theta (rad); exact solution in white", trace, theta, def.methods, &trace.exactTheta,
               ImVec2(width, 120));
    plotTraces("energy error (E - E0) / mgL", trace, energy, def.methods, nullptr, ImVec2(width, 100));

    bool changed = false;
    float release = static_cast<float>(panel.edit.releaseDegrees);
    float length = static_cast<float>(panel.edit.length);
    float multiplier = static_cast<float>(panel.edit.stepMultiplier);
    changed |= ImGui::SliderFloat("release angle (deg)", &release, 1.0f, 179.0f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderFloat("length (m)", &length, 0.25f, 3.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderFloat("step multiplier", &multiplier, 0.1f, 30.0f, "%.2f x",
                                  ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    if (changed) {
        panel.edit.releaseDegrees = release;
        panel.edit.length = length;
        panel.edit.stepMultiplier = multiplier;
        panel.commands.push_back({panel.index, game::PendulumCommand::Op::SetDef, panel.edit});
    }
    if (ImGui::Button("Reset (hold)")) panel.commands.push_back({panel.index, game::PendulumCommand::Op::Reset, {}});
    ImGui::SameLine();
    if (ImGui::Button("Release")) panel.commands.push_back({panel.index, game::PendulumCommand::Op::Release, {}});
    ImGui::SameLine();
    ImGui::TextDisabled("(E or Esc closes)");
    ImGui::End();
}

void drawPendulumLabels(const game::GameState& state, const render::SceneRenderer& scene, float alpha) {
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    for (const auto& set : state.pendulumSets) {
        for (int i = 0; i < game::kPendulumSlots; ++i) {
            const physics::PendulumState s = set.drawnState(i, alpha);
            const glm::vec3 at = set.bobPosition(i, s.theta) + glm::vec3(0.0f, 0.25f, 0.0f);
            const auto screen = scene.project(at);
            if (!screen) continue;
            const float distance = glm::length(at - render::interpolatedCamera(state, alpha).eye);
            if (distance > 24.0f) continue; // unreadable farther away
            const physics::Method m = set.def().methods[static_cast<std::size_t>(i)];
            std::string text(physics::methodName(m));
            if (set.diverged(i)) text += " (diverged)";
            const ImVec2 ts = ImGui::CalcTextSize(text.c_str());
            const ImVec2 p(screen->x - ts.x * 0.5f, screen->y - ts.y);
            dl->AddRectFilled(ImVec2(p.x - 3, p.y - 1), ImVec2(p.x + ts.x + 3, p.y + ts.y + 1), IM_COL32(0, 0, 0, 140),
                              3.0f);
            dl->AddText(p, colourOf(m), text.c_str());
        }
    }
}

} // namespace ui
