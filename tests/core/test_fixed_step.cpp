#include <gtest/gtest.h>

#include "core/fixed_step.h"

namespace {

TEST(FixedStep, WholeTicksFromExactFrames) {
    core::FixedStepClock clock({1.0 / 60.0, 0.25, 8});
    int total = 0;
    for (int i = 0; i < 600; ++i) total += clock.advance(1.0 / 60.0);
    EXPECT_EQ(total, 600); // floating-point accumulation must not lose or gain a tick
    EXPECT_NEAR(clock.alpha(), 0.0, 1e-6);
}

TEST(FixedStep, AccumulatesPartialFramesAndReportsAlpha) {
    core::FixedStepClock clock({0.01, 0.25, 8});
    EXPECT_EQ(clock.advance(0.004), 0);
    EXPECT_NEAR(clock.alpha(), 0.4, 1e-9);
    EXPECT_EQ(clock.advance(0.004), 0);
    EXPECT_EQ(clock.advance(0.004), 1);
    EXPECT_NEAR(clock.alpha(), 0.2, 1e-9);
}

TEST(FixedStep, FastFramesAtHighRefreshGiveTheRightTickRate) {
    core::FixedStepClock clock({1.0 / 60.0, 0.25, 8});
    int total = 0;
    for (int i = 0; i < 144 * 10; ++i) total += clock.advance(1.0 / 144.0);
    EXPECT_NEAR(total, 600, 1); // ten seconds of play is ten seconds of simulation
}

TEST(FixedStep, LongFrameIsClampedAndCapped) {
    core::FixedStepClock clock({1.0 / 60.0, 0.25, 8});
    const int ticks = clock.advance(5.0); // a debugger pause
    EXPECT_EQ(ticks, 8);                  // capped: the game slows rather than spirals
    EXPECT_GT(clock.droppedSeconds(), 4.0);
    EXPECT_GE(clock.alpha(), 0.0);
    EXPECT_LT(clock.alpha(), 1.0);
    EXPECT_LE(clock.advance(1.0 / 60.0), 2); // nothing queued from the long frame
}

TEST(FixedStep, ClampWithoutCapKeepsFrameTime) {
    core::FixedStepClock clock({0.1, 0.25, 8});
    EXPECT_EQ(clock.advance(10.0), 2); // 0.25 s of the 10 s frame: 2 ticks, 0.05 s left
    EXPECT_NEAR(clock.alpha(), 0.5, 1e-9);
}

TEST(FixedStep, RejectsNegativeAndNonFiniteFrames) {
    core::FixedStepClock clock({0.01, 0.25, 8});
    EXPECT_EQ(clock.advance(-1.0), 0);
    EXPECT_EQ(clock.advance(std::numeric_limits<double>::quiet_NaN()), 0);
    EXPECT_EQ(clock.advance(std::numeric_limits<double>::infinity()), 0);
    EXPECT_EQ(clock.alpha(), 0.0);
}

} // namespace
