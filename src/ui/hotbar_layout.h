// Where the hotbar's slots go in a frame of any size: nine equal squares in a row, centred at the bottom,
// at most 64 px and at least 36 px high (7.5 % of the frame's height between), and narrower when the frame
// is too narrow for that, so that every slot is wholly inside the frame down to the 160x90 of the tests.
// Pure geometry, no ImGui: ui/hud.cpp draws it, tests check it with plain numbers.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <glm/vec2.hpp>

#include "game/player.h"

namespace ui {

struct HotbarLayout {
    float slot = 0.0f;                                 // side of a slot (px)
    float pad = 0.0f;                                  // between two slots (px)
    float inset = 0.0f;                                // from a slot's edge to its icon (px)
    float digitSize = 13.0f;                           // font size of the slot's number in its corner (px)
    std::array<glm::vec2, game::kHotbarSize> corner{}; // each slot's top-left corner (px)
};

inline HotbarLayout hotbarLayout(glm::vec2 frame) {
    constexpr float kMargin = 4.0f, kBottom = 12.0f;
    constexpr int n = game::kHotbarSize;
    HotbarLayout h;
    h.pad = 4.0f;
    h.slot = std::clamp(frame.y * 0.075f, 36.0f, 64.0f);
    const float room = frame.x - 2.0f * kMargin;
    if (n * h.slot + (n - 1) * h.pad > room) { // too narrow: shrink slots and gaps together
        h.pad = std::max(1.0f, room / (n * 10.0f + n - 1));
        h.slot = std::max(1.0f, (room - (n - 1) * h.pad) / n);
    }
    h.inset = std::min(5.0f, std::round(h.slot * 0.14f));
    // The number keeps to the slot's top-left quarter and to at least 8 px (a 15 px slot at 160x90 gets 8 px).
    h.digitSize = std::clamp(h.slot * 0.5f, 8.0f, 13.0f);
    const float total = n * h.slot + (n - 1) * h.pad;
    const float x0 = frame.x * 0.5f - total * 0.5f;
    const float y0 = std::max(0.0f, frame.y - h.slot - std::min(kBottom, frame.y * 0.05f));
    for (int i = 0; i < n; ++i)
        h.corner[static_cast<std::size_t>(i)] = {x0 + static_cast<float>(i) * (h.slot + h.pad), y0};
    return h;
}

} // namespace ui
