// Places text labels that are anchored to points on screen (each bob's method name, each hair ball's
// solver) so that no two overlap and each stays wholly on screen. Pure geometry, no ImGui: the caller
// measures the text and draws the result, and tests check the layout with plain numbers.
// Nearer labels are placed first and keep their spot; a later label that would collide moves up or
// down in small steps, never further than a limit, and is hidden when no free place is found. A
// label is never drawn over another to be unreadable ("trapezatd").
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <vector>

#include <glm/vec2.hpp>

namespace ui {

struct LabelBox {
    glm::vec2 anchor{0.0f}; // screen pixels: the label's bottom centre wants to sit here
    glm::vec2 size{0.0f};   // pixels, the label's box (text and its background)
    float depth = 0.0f;     // distance from the camera; smaller is placed first
};

struct LabelLayoutDef {
    glm::vec2 screen{0.0f}; // pixels; labels stay within [0, screen]
    float gap = 2.0f;       // pixels kept free between two labels
    float step = 3.0f;      // pixels per move when looking for a free place
    float maxShift = 60.0f; // pixels a label may move away from its anchor, up or down
};

struct LabelPlacement {
    glm::vec2 topLeft{0.0f}; // pixels
    bool shown = false;
};

// One placement per box, in the same order.
inline std::vector<LabelPlacement> layoutLabels(const std::vector<LabelBox>& boxes, const LabelLayoutDef& def) {
    std::vector<LabelPlacement> out(boxes.size());
    std::vector<std::size_t> order(boxes.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    // Stable: equal depths keep the caller's order, so the same scene lays out the same way every frame.
    // An unknown (NaN) depth sorts last: a NaN in the comparison would break the sort's ordering.
    const auto depth = [&](std::size_t i) {
        return std::isnan(boxes[i].depth) ? std::numeric_limits<float>::infinity() : boxes[i].depth;
    };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth(a) < depth(b); });
    const float gap = std::isfinite(def.gap) ? std::max(def.gap, 0.0f) : 0.0f;
    const float step = std::isfinite(def.step) && def.step > 0.0f ? def.step : 1.0f;
    const float maxShift = std::isfinite(def.maxShift) ? std::max(def.maxShift, 0.0f) : 0.0f;
    std::vector<std::size_t> placed;
    const auto collides = [&](glm::vec2 topLeft, glm::vec2 size) {
        for (const std::size_t k : placed) {
            const glm::vec2 a = out[k].topLeft, b = a + boxes[k].size;
            if (topLeft.x < b.x + gap && a.x < topLeft.x + size.x + gap && topLeft.y < b.y + gap &&
                a.y < topLeft.y + size.y + gap)
                return true;
        }
        return false;
    };
    for (const std::size_t i : order) {
        const LabelBox& box = boxes[i];
        // A label whose anchor is off screen (or not a number: a broken state) belongs to nothing visible;
        // one larger than the screen cannot stay on it.
        const bool finite = std::isfinite(box.anchor.x) && std::isfinite(box.anchor.y) && std::isfinite(box.size.x) &&
                            std::isfinite(box.size.y);
        if (!finite || box.anchor.x < 0.0f || box.anchor.y < 0.0f || box.anchor.x > def.screen.x ||
            box.anchor.y > def.screen.y || box.size.x < 0.0f || box.size.y < 0.0f || box.size.x > def.screen.x ||
            box.size.y > def.screen.y)
            continue;
        const glm::vec2 maxTopLeft = def.screen - box.size;
        const glm::vec2 preferred(std::clamp(box.anchor.x - box.size.x * 0.5f, 0.0f, maxTopLeft.x),
                                  box.anchor.y - box.size.y);
        // 0, up one step, down one step, up two... up first: the label belongs above its bob.
        const int steps = static_cast<int>(maxShift / step);
        for (int k = 0; k <= 2 * steps; ++k) {
            const int ring = (k + 1) / 2; // 0, 1, 1, 2, 2...: whole steps away from the preferred place
            const float shift = static_cast<float>(ring) * step * (k % 2 == 1 ? -1.0f : 1.0f);
            const glm::vec2 at(preferred.x, std::clamp(preferred.y + shift, 0.0f, maxTopLeft.y));
            if (!collides(at, box.size)) {
                out[i] = {at, true};
                placed.push_back(i);
                break;
            }
        }
    }
    return out;
}

// The labels of a chart's points (the pendulum panel's work-precision dots), each wanting to sit just right
// of its point, centred on it, inside a chart of `area` pixels: laid out as above, earlier points first, each
// free to move up or down the whole chart, so that a few points always get every label, none overlapping,
// however close the points are. Placements are relative to the chart's top left.
inline std::vector<LabelPlacement> layoutPointLabels(const std::vector<glm::vec2>& points,
                                                     const std::vector<glm::vec2>& sizes, glm::vec2 area,
                                                     float offset = 6.0f) {
    std::vector<LabelBox> boxes;
    for (std::size_t i = 0; i < points.size() && i < sizes.size(); ++i) {
        const glm::vec2 anchor(std::clamp(points[i].x + offset + sizes[i].x * 0.5f, 0.0f, area.x),
                               std::clamp(points[i].y + sizes[i].y * 0.5f, 0.0f, area.y));
        boxes.push_back({anchor, sizes[i], static_cast<float>(i)});
    }
    LabelLayoutDef def;
    def.screen = area;
    def.gap = 1.0f;
    def.step = 1.0f;
    def.maxShift = area.y;
    return layoutLabels(boxes, def);
}

} // namespace ui
