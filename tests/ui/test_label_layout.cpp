// ui::layoutLabels (src/ui/label_layout.h): the pendulum bobs' names never overlap and stay on screen.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "ui/label_layout.h"

namespace {

bool overlap(const ui::LabelPlacement& a, glm::vec2 sa, const ui::LabelPlacement& b, glm::vec2 sb) {
    return a.topLeft.x < b.topLeft.x + sb.x && b.topLeft.x < a.topLeft.x + sa.x && a.topLeft.y < b.topLeft.y + sb.y &&
           b.topLeft.y < a.topLeft.y + sa.y;
}

bool onScreen(const ui::LabelPlacement& p, glm::vec2 size, glm::vec2 screen) {
    return p.topLeft.x >= 0.0f && p.topLeft.y >= 0.0f && p.topLeft.x + size.x <= screen.x &&
           p.topLeft.y + size.y <= screen.y;
}

TEST(LabelLayout, CrowdedLabelsNeverOverlapAndStayOnScreen) {
    // The spawn view: four bobs of one set within a few pixels of each other, twice (two sets), with
    // names of different lengths; the same input the old code drew as "trapezatd".
    ui::LabelLayoutDef def;
    def.screen = {640.0f, 360.0f};
    std::vector<ui::LabelBox> boxes;
    const float widths[] = {62.0f, 41.0f, 62.0f, 69.0f};
    for (int set = 0; set < 2; ++set) {
        for (int i = 0; i < 4; ++i) {
            const float x = 420.0f + 30.0f * static_cast<float>(set) + 6.0f * static_cast<float>(i);
            boxes.push_back({{x, 140.0f + 2.0f * static_cast<float>(i)},
                             {widths[i], 15.0f},
                             10.0f + static_cast<float>(set) + 0.1f * static_cast<float>(i)});
        }
    }
    const auto placed = ui::layoutLabels(boxes, def);
    ASSERT_EQ(placed.size(), boxes.size());
    std::size_t shown = 0;
    for (std::size_t i = 0; i < placed.size(); ++i) {
        if (!placed[i].shown) continue;
        ++shown;
        EXPECT_TRUE(onScreen(placed[i], boxes[i].size, def.screen)) << i;
        // Within its allowed shift of where it wants to be.
        EXPECT_LE(std::abs(placed[i].topLeft.y - (boxes[i].anchor.y - boxes[i].size.y)), def.maxShift + 1e-3f) << i;
        for (std::size_t j = i + 1; j < placed.size(); ++j) {
            if (placed[j].shown) {
                EXPECT_FALSE(overlap(placed[i], boxes[i].size, placed[j], boxes[j].size)) << i << " " << j;
            }
        }
    }
    // Precondition of the check above: the input really was crowded and most labels still show.
    EXPECT_TRUE(overlap({{boxes[0].anchor.x - 31.0f, 125.0f}, true}, boxes[0].size,
                        {{boxes[1].anchor.x - 20.5f, 127.0f}, true}, boxes[1].size));
    EXPECT_GE(shown, 6u);
    // The nearest label keeps its own spot: centred over its anchor.
    EXPECT_EQ(placed[0].topLeft, glm::vec2(420.0f - 31.0f, 125.0f));
}

TEST(LabelLayout, NearerLabelsArePlacedFirst) {
    ui::LabelLayoutDef def;
    def.screen = {640.0f, 360.0f};
    def.maxShift = 0.0f; // no room to move: the farther of two labels on one spot is hidden
    const std::vector<ui::LabelBox> boxes = {{{100.0f, 100.0f}, {50.0f, 15.0f}, 9.0f},
                                             {{100.0f, 100.0f}, {50.0f, 15.0f}, 3.0f}};
    const auto placed = ui::layoutLabels(boxes, def);
    EXPECT_FALSE(placed[0].shown);
    EXPECT_TRUE(placed[1].shown);
    // With room, the farther one moves (up first) instead of vanishing.
    def.maxShift = 40.0f;
    const auto moved = ui::layoutLabels(boxes, def);
    ASSERT_TRUE(moved[0].shown && moved[1].shown);
    EXPECT_EQ(moved[1].topLeft, glm::vec2(75.0f, 85.0f));
    EXPECT_LT(moved[0].topLeft.y, moved[1].topLeft.y);
    EXPECT_FALSE(overlap(moved[0], boxes[0].size, moved[1], boxes[1].size));
}

TEST(LabelLayout, ClampsToTheScreenEdges) {
    ui::LabelLayoutDef def;
    def.screen = {320.0f, 200.0f};
    const glm::vec2 size(60.0f, 15.0f);
    const std::vector<ui::LabelBox> boxes = {
        {{2.0f, 100.0f}, size, 1.0f},   // left edge
        {{319.0f, 150.0f}, size, 2.0f}, // right edge
        {{160.0f, 4.0f}, size, 3.0f},   // top: the label would start above the screen
        {{200.0f, 199.0f}, size, 4.0f}, // bottom corner
    };
    const auto placed = ui::layoutLabels(boxes, def);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        ASSERT_TRUE(placed[i].shown) << i;
        EXPECT_TRUE(onScreen(placed[i], size, def.screen)) << i;
    }
    EXPECT_EQ(placed[0].topLeft.x, 0.0f);
    EXPECT_EQ(placed[1].topLeft.x, 320.0f - 60.0f);
    EXPECT_EQ(placed[2].topLeft.y, 0.0f);
}

TEST(LabelLayout, HidesWhatCannotBeShown) {
    ui::LabelLayoutDef def;
    def.screen = {320.0f, 200.0f};
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<ui::LabelBox> boxes = {
        {{-50.0f, 100.0f}, {40.0f, 15.0f}, 1.0f}, // its bob is off screen
        {{nan, 100.0f}, {40.0f, 15.0f}, 1.0f},    // a broken state (issue 9: a non-finite player)
        {{100.0f, inf}, {40.0f, 15.0f}, 1.0f},    {{100.0f, 100.0f}, {400.0f, 15.0f}, 1.0f}, // wider than the screen
        {{100.0f, 100.0f}, {40.0f, 15.0f}, nan}, // an unknown depth still gets a place
    };
    const auto placed = ui::layoutLabels(boxes, def);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_FALSE(placed[i].shown) << i;
    EXPECT_TRUE(placed[4].shown);
}

} // namespace

// The pendulum panel's work-precision chart: methods of like cost and error put their dots on one spot, and
// their labels ("midpoint 1.2e-03") used to print over each other. Three dots on one point, one beside
// them, and a dot at the chart's top right corner: every label shows, inside the chart, none overlapping.
TEST(LabelLayout, ChartPointLabelsAllShowWithoutOverlap) {
    const glm::vec2 area(360.0f, 110.0f);
    const std::vector<glm::vec2> points = {
        {200.0f, 60.0f}, {200.0f, 60.0f}, {200.0f, 60.0f}, {203.0f, 62.0f}, {358.0f, 2.0f}};
    const std::vector<glm::vec2> sizes = {
        {105.0f, 13.0f}, {98.0f, 13.0f}, {126.0f, 13.0f}, {84.0f, 13.0f}, {91.0f, 13.0f}};
    const auto placed = ui::layoutPointLabels(points, sizes, area);
    ASSERT_EQ(placed.size(), points.size());
    for (std::size_t i = 0; i < placed.size(); ++i) {
        EXPECT_TRUE(placed[i].shown) << i;
        EXPECT_TRUE(onScreen(placed[i], sizes[i], area)) << i;
        for (std::size_t j = i + 1; j < placed.size(); ++j)
            EXPECT_FALSE(overlap(placed[i], sizes[i], placed[j], sizes[j])) << i << " " << j;
    }
    // The first label sits where it wants: right of its dot, centred on it.
    EXPECT_EQ(placed[0].topLeft, glm::vec2(206.0f, 53.5f));
}
