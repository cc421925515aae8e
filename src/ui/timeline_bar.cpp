#include "ui/timeline_bar.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "game/day_clock.h"
#include "game/state_io.h"
#include "input/keys.h"

namespace ui {

namespace {

ImU32 markColour(session::Timeline::MarkKind kind) {
    switch (kind) {
    case session::Timeline::MarkKind::Build:
        return IM_COL32(230, 120, 60, 255);
    case session::Timeline::MarkKind::Carry:
        return IM_COL32(120, 220, 120, 255);
    case session::Timeline::MarkKind::Edit:
        return IM_COL32(110, 170, 255, 255);
    case session::Timeline::MarkKind::Time:
        return IM_COL32(250, 220, 90, 255);
    case session::Timeline::MarkKind::Pause:
        return IM_COL32(200, 200, 200, 255);
    }
    return IM_COL32_WHITE;
}

std::string speedText(double speed) {
    char b[32];
    const double a = speed < 0 ? -speed : speed;
    if (a >= 1.0) {
        std::snprintf(b, sizeof b, "%s%gx", speed < 0 ? "-" : "", a);
    } else {
        std::snprintf(b, sizeof b, "%s1/%gx", speed < 0 ? "-" : "", 1.0 / a);
    }
    return b;
}

} // namespace

void drawTimeline(session::Timeline& t, const game::GameState& state) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(display.x, 0.0f));
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoFocusOnAppearing;
    if (!ImGui::Begin("Replay timeline", nullptr, flags)) {
        ImGui::End();
        return;
    }
    if (ImGui::Button("|<")) t.jumpTo(t.firstTick());
    ImGui::SameLine();
    if (ImGui::Button("<<")) t.previousMark();
    ImGui::SameLine();
    if (ImGui::Button("<")) t.step(-1);
    ImGui::SameLine();
    if (ImGui::Button(t.playing() ? "Pause" : "Play")) t.togglePlay();
    ImGui::SameLine();
    if (ImGui::Button(">")) t.step(1);
    ImGui::SameLine();
    if (ImGui::Button(">>")) t.nextMark();
    ImGui::SameLine();
    if (ImGui::Button(">|")) t.jumpTo(t.lastTick());
    ImGui::SameLine();
    if (ImGui::Button("-")) t.slower();
    ImGui::SameLine();
    ImGui::TextUnformatted(speedText(t.speed()).c_str());
    ImGui::SameLine();
    if (ImGui::Button("+")) t.faster();
    ImGui::SameLine();
    if (ImGui::Button("Reverse")) t.reverse();
    ImGui::SameLine();
    if (ImGui::Button("Take over (T)")) t.takeOver();

    // The bar: the recording from its first tick to its last, its marks, the tick on screen; click or drag.
    const float width = std::max(ImGui::GetContentRegionAvail().x, 50.0f), height = 18.0f;
    const ImVec2 a = ImGui::GetCursorScreenPos(), b(a.x + width, a.y + height);
    ImGui::InvisibleButton("##timeline", ImVec2(width, height));
    const double span = std::max<double>(1.0, static_cast<double>(t.lastTick() - t.firstTick()));
    const auto xOf = [&](std::uint64_t tick) {
        return a.x + static_cast<float>(static_cast<double>(tick - t.firstTick()) / span) * width;
    };
    if (ImGui::IsItemActive()) {
        const float f = std::clamp((ImGui::GetIO().MousePos.x - a.x) / width, 0.0f, 1.0f);
        const auto tick = t.firstTick() + static_cast<std::uint64_t>(std::llround(static_cast<double>(f) * span));
        if (tick != t.target()) t.jumpTo(tick);
    }
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(a, b, IM_COL32(40, 40, 40, 230), 3.0f);
    for (const session::Timeline::Mark& m : t.marks()) {
        const float x = xOf(m.tick);
        dl->AddLine(ImVec2(x, a.y + 2.0f), ImVec2(x, b.y - 2.0f), markColour(m.kind), 1.0f);
    }
    if (t.catchingUp()) { // where the seek is going
        const float x = xOf(t.target());
        dl->AddLine(ImVec2(x, a.y), ImVec2(x, b.y), IM_COL32(255, 255, 255, 110), 3.0f);
    }
    if (t.divergedAt()) { // the rest of the bar is not the recording's any more
        const float from = xOf(*t.divergedAt());
        dl->AddRectFilled(ImVec2(from, a.y), b, IM_COL32(160, 30, 30, 200), 3.0f);
    }
    const float x = xOf(std::clamp(t.tick(), t.firstTick(), t.lastTick()));
    dl->AddRectFilled(ImVec2(x - 2.0f, a.y - 2.0f), ImVec2(x + 2.0f, b.y + 2.0f), IM_COL32(255, 255, 255, 255));

    char line[200];
    const double seconds = static_cast<double>(t.tick()) * state.tickSeconds;
    std::snprintf(line, sizeof line, "tick %llu / %llu   %d:%04.1f   day %s   hash %s%s",
                  static_cast<unsigned long long>(t.tick()), static_cast<unsigned long long>(t.lastTick()),
                  static_cast<int>(seconds / 60.0), seconds - 60.0 * static_cast<int>(seconds / 60.0),
                  game::clockText(state.day.hours).c_str(), game::hashToHex(t.hash()).c_str(),
                  t.catchingUp() ? "   (going to the tick marked)" : "");
    ImGui::TextUnformatted(line);
    if (t.divergedAt()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", t.divergence().c_str());
    ImGui::End();
}

bool timelineKey(session::Timeline& t, int key, bool shift, int tickRate) {
    const std::int64_t step = shift ? tickRate : 1;
    switch (key) {
    case input::key::Space:
        t.togglePlay();
        return true;
    case input::key::Left:
        t.step(-step);
        return true;
    case input::key::Right:
        t.step(step);
        return true;
    case input::key::Up:
        t.faster();
        return true;
    case input::key::Down:
        t.slower();
        return true;
    case input::key::R:
        t.reverse();
        return true;
    case input::key::PageUp:
        t.previousMark();
        return true;
    case input::key::PageDown:
        t.nextMark();
        return true;
    case input::key::Home:
        t.jumpTo(t.firstTick());
        return true;
    case input::key::End:
        t.jumpTo(t.lastTick());
        return true;
    case input::key::T:
        t.takeOver();
        return true;
    default:
        return false;
    }
}

} // namespace ui
