#include <imgui.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ui/hotbar_layout.h"
#include "ui/label_layout.h"
#include "ui/panel_fit.h"
#include "ui/ui.h"
#include "world/raycast.h"

namespace ui {

namespace {

ImU32 colourOf(physics::Method m, float alpha = 1.0f) {
    const glm::vec3 c = game::methodColour(m);
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha));
}

// A plot's label above it, then its dark framed area (size pixels), reserved in the layout: where to draw.
struct PlotArea {
    ImDrawList* dl;
    ImVec2 a, b; // top left, bottom right (screen pixels)
};
PlotArea beginPlot(const char* label, ImVec2 size) {
    ImGui::TextUnformatted(label);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 a = ImGui::GetCursorScreenPos();
    const ImVec2 b(a.x + size.x, a.y + size.y);
    ImGui::Dummy(size);
    dl->AddRectFilled(a, b, IM_COL32(20, 22, 28, 255));
    dl->AddRect(a, b, IM_COL32(90, 90, 100, 255));
    return {dl, a, b};
}

// One plot: the trace's samples oldest to newest, each series a polyline, optional reference drawn
// first in white, the y range fitted to what is shown (symmetric around zero).
void plotTraces(const char* label, const game::PendulumTrace& trace,
                const std::array<const std::vector<float>*, 4>& series, const std::array<physics::Method, 4>& methods,
                const std::vector<float>* reference, ImVec2 size) {
    const PlotArea plot = beginPlot(label, size);
    ImDrawList* dl = plot.dl;
    const ImVec2 a = plot.a, b = plot.b;
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

// The work-precision chart of the lab, live: each stepped slot as a dot at (force evaluations per simulated
// second, angle error against the exact solution), log-log over fixed decades so the dots move, not the axes.
void plotWorkPrecision(const game::PendulumSet& set, ImVec2 size) {
    const PlotArea plot =
        beginPlot("work-precision now: angle error (rad) against evaluations per simulated second", size);
    ImDrawList* dl = plot.dl;
    const ImVec2 a = plot.a, b = plot.b;
    constexpr double kXMin = 1.0, kXMax = 6.0;   // log10 of evaluations per second: 10 .. 1e6
    constexpr double kYMin = -16.0, kYMax = 1.0; // log10 of the angle error (rad): 1e-16 .. 10
    const auto place = [&](double lx, double ly) {
        const float x = a.x + static_cast<float>((lx - kXMin) / (kXMax - kXMin)) * size.x;
        const float y = b.y - static_cast<float>((std::clamp(ly, kYMin, kYMax) - kYMin) / (kYMax - kYMin)) * size.y;
        return ImVec2(x, y);
    };
    char text[48];
    for (int d = static_cast<int>(kXMin); d <= static_cast<int>(kXMax); ++d) {
        const ImVec2 p = place(d, kYMin);
        dl->AddLine(ImVec2(p.x, a.y), ImVec2(p.x, b.y), IM_COL32(50, 50, 60, 255));
        // The corner belongs to the y axis' labels; the last decade's label goes inside, left of its line.
        if (d == static_cast<int>(kXMin)) continue;
        std::snprintf(text, sizeof text, "1e%d", d);
        const float width = ImGui::CalcTextSize(text).x;
        const float x = d == static_cast<int>(kXMax) ? p.x - width - 2.0f : p.x + 2.0f;
        dl->AddText(ImVec2(x, b.y - 15.0f), IM_COL32(150, 150, 160, 255), text);
    }
    for (int d = static_cast<int>(kYMin); d <= static_cast<int>(kYMax); d += 4) {
        const ImVec2 p = place(kXMin, d);
        dl->AddLine(ImVec2(a.x, p.y), ImVec2(b.x, p.y), IM_COL32(50, 50, 60, 255));
        if (d == static_cast<int>(kYMin)) continue; // the bottom line: the x axis' labels are there
        std::snprintf(text, sizeof text, "1e%d", d);
        dl->AddText(ImVec2(a.x + 2.0f, p.y - 14.0f), IM_COL32(150, 150, 160, 255), text);
    }
    // The dots, then their labels laid out so that none overlaps another (close methods put their dots on top
    // of each other); a label moved off its dot is joined to it by a thin line.
    std::vector<glm::vec2> dots, sizes;
    std::vector<std::string> texts;
    std::vector<ImU32> colours;
    for (int i = 0; i < game::kPendulumSlots; ++i) {
        const double error = set.angleError(i), cost = set.evaluationsPerSecond(i);
        if (!(cost > 0.0) || !std::isfinite(error)) continue; // the exact slot, a diverged one, or not started
        const ImVec2 p = place(std::clamp(std::log10(cost), kXMin, kXMax), std::log10(std::max(error, 1e-300)));
        const physics::Method m = set.def().methods[static_cast<std::size_t>(i)];
        dl->AddCircleFilled(p, 4.0f, colourOf(m));
        std::snprintf(text, sizeof text, "%s %.1e", std::string(physics::methodName(m)).c_str(), error);
        const ImVec2 measured = ImGui::CalcTextSize(text);
        dots.emplace_back(p.x - a.x, p.y - a.y);
        sizes.emplace_back(measured.x, measured.y);
        texts.emplace_back(text);
        colours.push_back(colourOf(m));
    }
    const std::vector<LabelPlacement> labels = layoutPointLabels(dots, sizes, {size.x, size.y});
    for (std::size_t k = 0; k < labels.size(); ++k) {
        if (!labels[k].shown) continue;
        const ImVec2 at(a.x + labels[k].topLeft.x, a.y + labels[k].topLeft.y);
        const float middle = labels[k].topLeft.y + sizes[k].y * 0.5f;
        if (std::abs(middle - dots[k].y) > sizes[k].y * 0.5f)
            dl->AddLine(ImVec2(a.x + dots[k].x, a.y + dots[k].y), ImVec2(at.x, at.y + sizes[k].y * 0.5f), colours[k]);
        dl->AddText(at, colours[k], texts[k].c_str());
    }
}

} // namespace

void showPendulumPanel(PendulumPanel& panel, bool* open) {
    const game::PendulumSet& set = *panel.set;
    const game::PendulumSetDef& def = set.def();
    const ImGuiStyle& style = ImGui::GetStyle();
    const ImVec2 display = ImGui::GetIO().DisplaySize;

    // Every width comes from the text it must hold (a fixed window width cut "midpoint" to "midpoi"),
    // and the window fits its content; its height is capped by the screen (it scrolls when smaller).
    static constexpr const char* kHeaders[5] = {"slot", "method", "theta (deg)", "omega (rad/s)", "(E-E0)/mgL"};
    std::array<std::array<std::string, 5>, game::kPendulumSlots> cells;
    for (int i = 0; i < game::kPendulumSlots; ++i) {
        const physics::PendulumState st = set.slot(i).state();
        char text[64];
        auto& row = cells[static_cast<std::size_t>(i)];
        row[0] = std::string(game::compassName(i));
        if (set.diverged(i)) {
            row[2] = "diverged";
        } else {
            std::snprintf(text, sizeof text, "%.3f", st.theta * 180.0 / 3.14159265358979323846);
            row[2] = text;
        }
        std::snprintf(text, sizeof text, "%.4f", st.omega);
        row[3] = text;
        std::snprintf(text, sizeof text, "%+.2e", set.energyError(i));
        row[4] = text;
    }
    float methodNameWidth = 0.0f;
    for (int k = 0; k < physics::kMethodCount; ++k) {
        const std::string name(physics::methodName(static_cast<physics::Method>(k)));
        methodNameWidth = std::max(methodNameWidth, ImGui::CalcTextSize(name.c_str()).x);
    }
    // A combo is its text, the frame padding on both sides and a square arrow button.
    const float comboWidth = methodNameWidth + 2.0f * style.FramePadding.x + ImGui::GetFrameHeight();
    std::array<float, 5> columnWidth{};
    for (std::size_t c = 0; c < 5; ++c) {
        columnWidth[c] = ImGui::CalcTextSize(kHeaders[c]).x;
        for (const auto& row : cells) columnWidth[c] = std::max(columnWidth[c], ImGui::CalcTextSize(row[c].c_str()).x);
    }
    columnWidth[1] = std::max(columnWidth[1], comboWidth);
    float contentWidth = 0.0f;
    for (const float w : columnWidth) contentWidth += w + 2.0f * style.CellPadding.x;
    static constexpr const char* kSliders[3] = {"release angle (deg)", "length (m)", "step multiplier"};
    float sliderLabelWidth = 0.0f;
    for (const char* label : kSliders) sliderLabelWidth = std::max(sliderLabelWidth, ImGui::CalcTextSize(label).x);
    // Sliders keep a usable length even when the table is narrow.
    const float sliderWidth =
        std::max(contentWidth - sliderLabelWidth - style.ItemInnerSpacing.x, ImGui::CalcTextSize("0000.00 x").x * 2.5f);
    contentWidth = std::max(contentWidth, sliderWidth + style.ItemInnerSpacing.x + sliderLabelWidth);
    // The plots take a share of the screen's height between readable and roomy.
    const float thetaPlotHeight = std::clamp(display.y * 0.17f, 60.0f, 160.0f);
    const float energyPlotHeight = thetaPlotHeight * 0.85f;

    ImGui::SetNextWindowPos(ImVec2(display.x - 10.0f, 10.0f), ImGuiCond_Appearing, ImVec2(1.0f, 0.0f));
    fitNextWindowToDisplay();
    if (!ImGui::Begin("Pendulum set", open, kPanelFlags | ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::End();
        return;
    }
    ImGui::Text("at %d %d %d   t = %.2f s   step h = %.4f s (%.2f x tick)%s", set.base().x, set.base().y, set.base().z,
                set.time(), panel.tickSeconds * def.stepMultiplier, def.stepMultiplier,
                set.released() ? "" : "   held");
    // Fixed columns at least as wide as their text now; not resizable, so they also grow to what they
    // held last frame if a value gets longer.
    if (ImGui::BeginTable("slots", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
        for (std::size_t c = 0; c < 5; ++c)
            ImGui::TableSetupColumn(kHeaders[c], ImGuiTableColumnFlags_WidthFixed, columnWidth[c]);
        ImGui::TableHeadersRow();
        for (int i = 0; i < game::kPendulumSlots; ++i) {
            const physics::Method m = def.methods[static_cast<std::size_t>(i)];
            const auto& row = cells[static_cast<std::size_t>(i)];
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::AlignTextToFramePadding();
            ImGui::TextUnformatted(row[0].c_str());
            ImGui::TableSetColumnIndex(1);
            ImGui::PushID(i);
            int current = static_cast<int>(panel.edit.methods[static_cast<std::size_t>(i)]);
            ImGui::PushStyleColor(ImGuiCol_Text, colourOf(m));
            ImGui::SetNextItemWidth(comboWidth);
            ImGui::BeginDisabled(panel.readOnly); // a replay's set is the recording's: shown, not edited
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
            ImGui::EndDisabled();
            ImGui::PopStyleColor();
            ImGui::PopID();
            ImGui::TableSetColumnIndex(2);
            ImGui::AlignTextToFramePadding();
            if (set.diverged(i)) {
                ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", row[2].c_str());
            } else {
                ImGui::TextUnformatted(row[2].c_str());
            }
            for (int c = 3; c < 5; ++c) {
                ImGui::TableSetColumnIndex(c);
                ImGui::AlignTextToFramePadding();
                ImGui::TextUnformatted(row[static_cast<std::size_t>(c)].c_str());
            }
        }
        ImGui::EndTable();
    }

    const game::PendulumTrace& trace = set.trace();
    std::array<const std::vector<float>*, 4> theta{}, energy{};
    for (std::size_t i = 0; i < 4; ++i) {
        theta[i] = &trace.theta[i];
        energy[i] = &trace.energyError[i];
    }
    // A fixed width, not the space left: in a window that fits its content that would feed back on itself.
    plotTraces("theta (rad); exact solution in white", trace, theta, def.methods, &trace.exactTheta,
               ImVec2(contentWidth, thetaPlotHeight));
    plotTraces("energy error (E - E0) / mgL", trace, energy, def.methods, nullptr,
               ImVec2(contentWidth, energyPlotHeight));
    plotWorkPrecision(set, ImVec2(contentWidth, energyPlotHeight));

    bool changed = false;
    ImGui::BeginDisabled(panel.readOnly);
    float release = static_cast<float>(panel.edit.releaseDegrees);
    float length = static_cast<float>(panel.edit.length);
    float multiplier = static_cast<float>(panel.edit.stepMultiplier);
    ImGui::PushItemWidth(sliderWidth);
    changed |= ImGui::SliderFloat(kSliders[0], &release, 1.0f, 179.0f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderFloat(kSliders[1], &length, 0.25f, 3.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    changed |= ImGui::SliderFloat(kSliders[2], &multiplier, 0.1f, 30.0f, "%.2f x",
                                  ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    ImGui::PopItemWidth();
    if (changed) {
        panel.edit.releaseDegrees = release;
        panel.edit.length = length;
        panel.edit.stepMultiplier = multiplier;
        panel.commands.push_back({panel.index, game::PendulumCommand::Op::SetDef, panel.edit});
    }
    if (ImGui::Button("Reset (hold)")) panel.commands.push_back({panel.index, game::PendulumCommand::Op::Reset, {}});
    ImGui::SameLine();
    if (ImGui::Button("Release")) panel.commands.push_back({panel.index, game::PendulumCommand::Op::Release, {}});
    ImGui::EndDisabled();
    if (panel.readOnly) panel.commands.clear(); // nothing a replay did not do
    ImGui::SameLine();
    ImGui::TextDisabled(panel.readOnly ? "(a replay: read only, T takes over; E or Esc closes)" : "(E or Esc closes)");
    ImGui::End();
}

std::vector<ObjectLabel> objectLabels(const game::GameState& state, const render::SceneRenderer& scene, float alpha) {
    std::vector<ObjectLabel> labels;
    const glm::vec3 eye = render::interpolatedCamera(state, alpha).eye;
    const auto add = [&](glm::vec3 at, std::string text, ImU32 colour) {
        const auto screen = scene.project(at);
        if (!screen) return;
        const float distance = glm::length(at - eye);
        if (!(distance <= 24.0f)) return; // unreadable farther away (and NaN is no distance)
        // In sight when no block lies between the eye and the point (the point itself is in the air above an
        // object; an eye inside a block sees nothing).
        const auto hit = world::raycast(state.world, eye, at - eye, distance);
        labels.push_back({std::move(text), at, *screen, distance, colour, hit.has_value()});
    };
    for (const auto& set : state.pendulumSets) {
        for (int i = 0; i < game::kPendulumSlots; ++i) {
            const physics::PendulumState s = set.drawnState(i, alpha);
            const physics::Method m = set.def().methods[static_cast<std::size_t>(i)];
            std::string text(physics::methodName(m));
            if (set.diverged(i)) text += " (diverged)";
            add(set.bobPosition(i, s.theta) + glm::vec3(0.0f, 0.25f, 0.0f), std::move(text), colourOf(m));
        }
    }
    // Each hair ball's solver, above its hair, in the ball's colour made lighter (readable on the dark
    // background whatever the colour). Not the carried ball: it floats in front of the eye.
    for (std::size_t i = 0; i < state.hairBalls.size(); ++i) {
        if (state.carriedBall == i) continue;
        const game::HairBall& ball = state.hairBalls[i];
        const game::HairBallDef& d = ball.def();
        const glm::vec3 centre = ball.previousCentre() + (ball.centre() - ball.previousCentre()) * alpha;
        const glm::vec3 c = glm::clamp(d.colour, 0.0f, 1.0f) * 0.6f + glm::vec3(0.4f);
        add(centre + glm::vec3(0.0f, d.radius + 0.5f * d.hair.strandLength + 0.15f, 0.0f),
            std::string(physics::hairMethodName(d.hair.method)),
            ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
    }
    return labels;
}

namespace {

float objectLabelFontSize(glm::vec2 frame) { return ImGui::GetFontSize() * std::clamp(frame.y / 360.0f, 0.6f, 1.0f); }

float objectLabelFloor(glm::vec2 frame) {
    // 2 px above the block name's top (its line stands 6 px above the hotbar, ui/hud.cpp): a label's rounded,
    // smoothed edge reaches a pixel past its box.
    return hotbarLayout(frame).corner[0].y - ImGui::GetFontSize() - 6.0f - 2.0f;
}

} // namespace

void drawObjectLabels(const game::GameState& state, const render::SceneRenderer& scene, float alpha) {
    // The text sits 3 px in from its background's sides and 1 px from its top and bottom. Below 360 px of height
    // the font shrinks with the frame (to 0.6 of its size), so that labels do not cover a small view.
    constexpr float kPadX = 3.0f, kPadY = 1.0f;
    const glm::vec2 frame(ImGui::GetIO().DisplaySize.x, ImGui::GetIO().DisplaySize.y);
    const float fontSize = objectLabelFontSize(frame);
    ImFont* font = ImGui::GetFont();
    std::vector<ObjectLabel> labels = objectLabels(state, scene, alpha);
    labels.erase(std::remove_if(labels.begin(), labels.end(), [](const ObjectLabel& l) { return l.hidden; }),
                 labels.end());
    std::vector<LabelBox> boxes;
    boxes.reserve(labels.size());
    for (const ObjectLabel& l : labels) {
        const ImVec2 ts = font->CalcTextSizeA(fontSize, FLT_MAX, 0.0f, l.text.c_str());
        boxes.push_back({l.screen, glm::vec2(ts.x + 2.0f * kPadX, ts.y + 2.0f * kPadY), l.distance});
    }
    // Labels stay above the HUD's block name and hotbar: they never print over them.
    LabelLayoutDef def;
    def.screen = glm::vec2(frame.x, std::max(0.0f, objectLabelFloor(frame)));
    const std::vector<LabelPlacement> placed = layoutLabels(boxes, def);
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    for (std::size_t k = 0; k < labels.size(); ++k) {
        if (!placed[k].shown) continue;
        const glm::vec2 a = placed[k].topLeft, b = a + boxes[k].size;
        dl->AddRectFilled(ImVec2(a.x, a.y), ImVec2(b.x, b.y), IM_COL32(0, 0, 0, 140), 3.0f);
        dl->AddText(font, fontSize, ImVec2(a.x + kPadX, a.y + kPadY), labels[k].colour, labels[k].text.c_str());
    }
}

} // namespace ui
