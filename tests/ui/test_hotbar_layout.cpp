// ui::hotbarLayout (src/ui/hotbar_layout.h): the nine slots fit every frame the game can draw.
#include "ui/hotbar_layout.h"

#include <gtest/gtest.h>

namespace {

// Every render size --size allows from the tests' 160x90 up, and the settings' window sizes: each slot
// wholly inside the frame, the slots equal, in order and apart, the row centred. Checked slot by slot at
// every width from 16 to 4096 in steps of 4 and at the heights 90, 180, 720 and 2160. Catches the layout
// before the fix, whose row of 36 px slots was wider than a 320 px frame (slots 1 and 9 were cut off).
TEST(HotbarLayout, EverySlotIsInsideEveryFrameFromTheTestsSmallestUp) {
    int frames = 0;
    for (const float height : {90.0f, 180.0f, 720.0f, 2160.0f}) {
        for (float width = 160.0f; width <= 4096.0f; width += 4.0f) {
            const ui::HotbarLayout h = ui::hotbarLayout({width, height});
            ++frames;
            ASSERT_GT(h.slot, 0.0f);
            for (std::size_t i = 0; i < h.corner.size(); ++i) {
                const glm::vec2 a = h.corner[i];
                ASSERT_GE(a.x, 0.0f) << width << "x" << height << " slot " << i + 1;
                ASSERT_LE(a.x + h.slot, width) << width << "x" << height << " slot " << i + 1;
                ASSERT_GE(a.y, 0.0f) << width << "x" << height << " slot " << i + 1;
                ASSERT_LE(a.y + h.slot, height) << width << "x" << height << " slot " << i + 1;
                if (i > 0) {
                    ASSERT_GE(a.x, h.corner[i - 1].x + h.slot) << "slots overlap at " << width;
                }
            }
            const float left = h.corner.front().x, right = width - (h.corner.back().x + h.slot);
            ASSERT_NEAR(left, right, 1e-3f) << "not centred at " << width;
        }
    }
    EXPECT_GT(frames, 3000);
}

// Where there is room the slots keep their size: 7.5 % of the height, between 36 and 64 px.
TEST(HotbarLayout, AWideFrameKeepsTheUsualSlots) {
    EXPECT_FLOAT_EQ(ui::hotbarLayout({1280.0f, 720.0f}).slot, 54.0f);
    EXPECT_FLOAT_EQ(ui::hotbarLayout({3840.0f, 2160.0f}).slot, 64.0f);
    EXPECT_FLOAT_EQ(ui::hotbarLayout({640.0f, 360.0f}).slot, 36.0f);
    // The slot's number: the font's own 13 px where there is room, 8 px (legible) in a 15 px slot at 160x90.
    EXPECT_FLOAT_EQ(ui::hotbarLayout({1280.0f, 720.0f}).digitSize, 13.0f);
    EXPECT_FLOAT_EQ(ui::hotbarLayout({160.0f, 90.0f}).digitSize, 8.0f);
}

} // namespace
