#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "flat_world.h"
#include "game/game_state.h"
#include "game/pendulum_set.h"
#include "game/state_io.h"

namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr double kPi = 3.14159265358979323846;

TEST(PendulumSet, EachSlotStepsWithItsOwnMethodExactlyAsTheLabWould) {
    game::PendulumSet set({0, 33, 0});
    set.release();
    const physics::PendulumParams params = set.params();
    const physics::PendulumState start{60.0 * kPi / 180.0, 0.0};
    std::array<physics::Pendulum, 4> reference{physics::Pendulum(physics::Method::Exact, params, start),
                                               physics::Pendulum(physics::Method::Euler, params, start),
                                               physics::Pendulum(physics::Method::Midpoint, params, start),
                                               physics::Pendulum(physics::Method::Trapezoid, params, start)};
    for (int t = 0; t < 300; ++t) {
        set.tick(kDt);
        for (auto& r : reference) r.step(kDt);
    }
    for (int i = 0; i < game::kPendulumSlots; ++i) {
        EXPECT_EQ(set.slot(i).method(), reference[static_cast<std::size_t>(i)].method());
        EXPECT_EQ(set.slot(i).state().theta, reference[static_cast<std::size_t>(i)].state().theta) << i;
        EXPECT_EQ(set.slot(i).state().omega, reference[static_cast<std::size_t>(i)].state().omega) << i;
    }
    EXPECT_NEAR(set.time(), 300 * kDt, 1e-12);
    // The methods really differ: euler has drifted from exact, visibly.
    EXPECT_GT(std::abs(set.slot(1).state().theta - set.slot(0).state().theta), 0.01);
}

TEST(PendulumSet, HeldUntilReleasedAndResetReturnsToTheReleaseAngle) {
    game::PendulumSet set({0, 33, 0});
    set.reset();
    for (int t = 0; t < 10; ++t) set.tick(kDt);
    EXPECT_DOUBLE_EQ(set.time(), 0.0);
    EXPECT_DOUBLE_EQ(set.slot(0).state().theta, 60.0 * kPi / 180.0);
    set.release();
    set.tick(kDt);
    EXPECT_GT(set.time(), 0.0);
    set.reset();
    EXPECT_FALSE(set.released());
    EXPECT_DOUBLE_EQ(set.slot(2).state().theta, 60.0 * kPi / 180.0);
}

TEST(PendulumSet, StepMultiplierScalesTheStep) {
    game::PendulumSetDef def;
    def.stepMultiplier = 4.0;
    game::PendulumSet set({0, 33, 0}, def);
    set.release();
    physics::Pendulum ref(physics::Method::Euler, set.params(), {60.0 * kPi / 180.0, 0.0});
    for (int t = 0; t < 30; ++t) {
        set.tick(kDt);
        ref.step(4.0 * kDt);
    }
    EXPECT_EQ(set.slot(1).state().theta, ref.state().theta);
    EXPECT_NEAR(set.time(), 30 * 4.0 * kDt, 1e-12);
}

// Past its limit a method does not overflow (the pendulum's force is bounded, so omega can only grow
// linearly): it gains energy until it swings over the top. The exact one never does.
TEST(PendulumSet, AMethodPushedPastItsLimitGoesOverTheTop) {
    game::PendulumSetDef def;
    def.stepMultiplier = 12.0; // h = 0.2 s: omega0 * h = 0.63
    game::PendulumSet set({0, 33, 0}, def);
    set.release();
    double maxEuler = 0.0, maxExact = 0.0;
    for (int t = 0; t < 600; ++t) {
        set.tick(kDt);
        maxExact = std::max(maxExact, std::abs(set.slot(0).state().theta));
        maxEuler = std::max(maxEuler, std::abs(set.slot(1).state().theta));
    }
    EXPECT_GT(maxEuler, kPi);
    EXPECT_LE(maxExact, 60.0 * kPi / 180.0 + 1e-9);
    for (int i = 0; i < game::kPendulumSlots; ++i) EXPECT_FALSE(set.diverged(i));
}

// The guard for what cannot be drawn: a state that overflows is frozen at its last finite value.
TEST(PendulumSet, OverflowIsCaughtAndFrozen) {
    game::PendulumSetDef def;
    def.gravity = game::kMaxPendulumGravity; // the strongest a set may have, stepped 16,667 s at a time
    def.stepMultiplier = 1e6;
    def.methods = {physics::Method::Euler, physics::Method::Rk4, physics::Method::Verlet, physics::Method::Trapezoid};
    game::PendulumSet set({0, 33, 0}, def);
    set.release();
    for (int t = 0; t < 5; ++t) set.tick(kDt);
    for (int i = 0; i < game::kPendulumSlots; ++i) {
        EXPECT_TRUE(set.diverged(i)) << i;
        EXPECT_TRUE(std::isfinite(set.slot(i).state().theta));
        EXPECT_TRUE(std::isfinite(set.drawnState(i, 0.5).theta));
    }
}

TEST(PendulumSet, ExactIsDrawnAtTheInterpolatedTime) {
    game::PendulumSet set({0, 33, 0});
    set.release();
    for (int t = 0; t < 7; ++t) set.tick(kDt);
    const double mid = set.previousTime() + 0.3 * (set.time() - set.previousTime());
    const physics::ExactPendulum exact(set.params(), {60.0 * kPi / 180.0, 0.0});
    EXPECT_DOUBLE_EQ(set.drawnState(0, 0.3).theta, exact.at(mid).theta);
    // A stepped slot interpolates between its last two states.
    const double a = set.previousState(1).theta, b = set.slot(1).state().theta;
    EXPECT_DOUBLE_EQ(set.drawnState(1, 0.5).theta, a + 0.5 * (b - a));
}

TEST(PendulumSet, PlacedFromTheHotbarBrokenByClickingAndDumped) {
    game::GameState s(flatNoDemo());
    // Far enough ahead (3.5 m) that the swings, which reach 2.3 m from the post, clear the player.
    ASSERT_EQ(placeFromHotbar(s, -25.0f, 8, kDt), "pendulum_set");
    ASSERT_EQ(s.pendulumSets.size(), 1u);
    EXPECT_EQ(s.pendulumSets[0].base().y, 33);                            // standing on the grass
    EXPECT_EQ(s.world.editCount(), 0u);                                   // an object, not a block
    EXPECT_EQ(game::placeTargeted(s), game::EditResult::NothingTargeted); // the post is in the way now

    const auto dump = game::dumpState(s);
    ASSERT_EQ(dump["pendulums"].size(), 1u);
    ASSERT_EQ(dump["pendulums"][0]["slots"].size(), 4u);
    EXPECT_EQ(dump["pendulums"][0]["slots"][0]["method"], "exact");
    EXPECT_EQ(dump["pendulums"][0]["slots"][1]["method"], "euler");
    EXPECT_EQ(dump["pendulums"][0]["slots"][2]["method"], "midpoint");
    EXPECT_EQ(dump["pendulums"][0]["slots"][3]["method"], "trapezoid");
    for (const auto& slot : dump["pendulums"][0]["slots"]) {
        EXPECT_TRUE(slot.contains("theta") && slot.contains("omega") && slot.contains("energy"));
    }

    // Looking at the post and clicking breaks the set, not the ground behind it.
    game::Target target = game::targetOf(s);
    ASSERT_EQ(target.kind, game::Target::Kind::PendulumSet);
    input::Actions brk;
    brk.breakBlock = true;
    game::tick(s, brk, kDt);
    EXPECT_TRUE(s.pendulumSets.empty());
    EXPECT_EQ(s.world.editCount(), 0u);
}

TEST(PendulumSet, PanelCommandsApplyAtTheNextTickAndChangeTheHash) {
    game::GameState s(game::GameDef{});
    ASSERT_EQ(s.pendulumSets.size(), 1u); // the demo set near spawn
    const auto before = game::stateHash(s);
    game::PendulumSetDef def = s.pendulumSets[0].def();
    def.methods[1] = physics::Method::Rk4;
    def.releaseDegrees = 120.0;
    game::tick(s, {}, kDt, {{{0, game::PendulumCommand::Op::SetDef, def}}, {}, {}, {}});
    EXPECT_EQ(s.pendulumSets[0].def().methods[1], physics::Method::Rk4);
    EXPECT_FALSE(s.pendulumSets[0].released()); // new parameters: held at the new angle
    EXPECT_DOUBLE_EQ(s.pendulumSets[0].slot(1).state().theta, 120.0 * kPi / 180.0);
    EXPECT_NE(game::stateHash(s), before);
    game::tick(s, {}, kDt, {{{0, game::PendulumCommand::Op::Release, {}}}, {}, {}, {}});
    EXPECT_TRUE(s.pendulumSets[0].released());
    game::tick(s, {}, kDt, {{{7, game::PendulumCommand::Op::Release, {}}}, {}, {}, {}}); // no such set: ignored
}

// A def the physics refuses (a typed 1e30 degree release, a zero step multiplier, a NaN length) leaves the
// set exactly as it was, and as a panel command it is dropped without ending the game.
TEST(PendulumSet, RefusedDefChangesNothing) {
    game::GameState s(game::GameDef{}), t(game::GameDef{}); // t: the same game without the refused commands
    ASSERT_EQ(s.pendulumSets.size(), 1u);
    for (int i = 0; i < 30; ++i) {
        game::tick(s, {}, kDt);
        game::tick(t, {}, kDt);
    }
    const auto before = game::stateHash(s);
    const game::PendulumSetDef good = s.pendulumSets[0].def();
    game::PendulumSetDef angle = good, step = good, length = good, tooLong = good;
    angle.releaseDegrees = 1e30;
    step.stepMultiplier = 0.0;
    length.length = std::nan("");
    tooLong.length = 5000.0;
    for (const auto& bad : {angle, step, length, tooLong}) {
        game::PendulumSet copy = s.pendulumSets[0];
        EXPECT_THROW(copy.setDef(bad), std::invalid_argument);
        EXPECT_EQ(copy.def().releaseDegrees, good.releaseDegrees);
        EXPECT_EQ(copy.def().stepMultiplier, good.stepMultiplier);
        EXPECT_EQ(copy.slot(0).state().theta, s.pendulumSets[0].slot(0).state().theta);
        EXPECT_THROW(game::PendulumSet(glm::ivec3(0), bad), std::invalid_argument);
    }
    game::tick(
        s, {}, kDt,
        {{{0, game::PendulumCommand::Op::SetDef, angle}, {0, game::PendulumCommand::Op::SetDef, step}}, {}, {}, {}});
    game::tick(t, {}, kDt);
    EXPECT_EQ(game::stateHash(s), game::stateHash(t));
    EXPECT_NE(game::stateHash(s), before); // and the game went on
}

TEST(PendulumSet, DemoSetStandsInFrontOfTheSpawnView) {
    game::GameState s(game::GameDef{});
    ASSERT_EQ(s.pendulumSets.size(), 1u);
    const glm::vec3 toSet = glm::vec3(s.pendulumSets[0].base()) + glm::vec3(0.5f, 0.0f, 0.5f) - s.player.position;
    const glm::vec3 forward = game::lookDirection(s.player.yaw, 0.0f);
    EXPECT_GT(glm::dot(glm::normalize(glm::vec3(toSet.x, 0.0f, toSet.z)), forward), 0.9f); // within ~25 degrees
    EXPECT_LT(glm::length(glm::vec2(toSet.x, toSet.z)), 16.0f);
}

} // namespace
