#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/fixed_step.h"
#include "core/frame_rate.h"

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

// The F3 overlay's bug: a rate average seeded by a near-zero first frame read "98571 fps" for 10-20 s.
TEST(FrameRate, NearZeroFirstFrameDoesNotDominate) {
    core::FrameRate rate;
    rate.addFrame(0.00001); // 0.01 ms: the window's first swap
    for (int i = 0; i < 60; ++i) rate.addFrame(0.0167);
    EXPECT_NEAR(rate.fps(), 60.0, 1.0);
    EXPECT_NEAR(rate.frameMs(), 16.7, 0.3);
    // Already after a few frames it reads the frames' own rate, not thousands.
    core::FrameRate early;
    early.addFrame(0.00001);
    for (int i = 0; i < 5; ++i) early.addFrame(0.0167);
    EXPECT_LT(early.fps(), 80.0);
    EXPECT_GT(early.fps(), 55.0);
}

TEST(FrameRate, AveragesTimesNotRates) {
    // Alternating 10 ms and 30 ms frames: 50 frames a second. A mean of rates would say 66.7.
    core::FrameRate rate;
    for (int i = 0; i < 200; ++i) rate.addFrame(i % 2 == 0 ? 0.010 : 0.030);
    EXPECT_NEAR(rate.fps(), 50.0, 1e-9);
    EXPECT_NEAR(rate.frameMs(), 20.0, 1e-9);
}

TEST(FrameRate, FollowsAChangeWithinAboutOneWindow) {
    core::FrameRate rate(1.0);
    for (int i = 0; i < 600; ++i) rate.addFrame(1.0 / 144.0);
    EXPECT_NEAR(rate.fps(), 144.0, 1e-6);
    // 1.1 s of 30 fps frames: the 144 fps frames are out of the window.
    for (int i = 0; i < 33; ++i) rate.addFrame(1.0 / 30.0);
    EXPECT_NEAR(rate.fps(), 30.0, 1e-6);
    EXPECT_LE(rate.frames(), 31u);
    EXPECT_GE(rate.frames(), 30u);
}

TEST(FrameRate, EmptyAndBadDurations) {
    core::FrameRate rate;
    EXPECT_EQ(rate.fps(), 0.0);
    EXPECT_EQ(rate.frameMs(), 0.0);
    rate.addFrame(std::numeric_limits<double>::quiet_NaN());
    rate.addFrame(-1.0);
    EXPECT_EQ(rate.fps(), 0.0); // no time has passed
    for (int i = 0; i < 10; ++i) rate.addFrame(0.02);
    EXPECT_TRUE(std::isfinite(rate.fps()));
    EXPECT_NEAR(rate.frameMs(), 200.0 / 12.0, 1e-9); // the two bad frames count as zero-length
    // A long stall (a window drag) stays in the average until newer frames cover the window alone.
    core::FrameRate stall;
    stall.addFrame(5.0);
    EXPECT_NEAR(stall.fps(), 0.2, 1e-12);
    stall.addFrame(0.5);
    EXPECT_NEAR(stall.fps(), 2.0 / 5.5, 1e-12);
    stall.addFrame(0.5);
    EXPECT_NEAR(stall.fps(), 2.0, 1e-12);
    EXPECT_EQ(stall.frames(), 2u);
}

} // namespace
