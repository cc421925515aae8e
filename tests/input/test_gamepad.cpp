#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "input/mapper.h"

namespace {

using input::GamepadAxis;
using input::GamepadButton;
using input::GamepadMemory;
using input::GamepadState;
using input::InputConfig;
using input::mapGamepad;

constexpr float kDt = 1.0f / 60.0f;

GamepadState connectedPad() {
    GamepadState pad;
    pad.connected = true;
    return pad;
}

void setAxis(GamepadState& pad, GamepadAxis axis, float value) { pad.axes[static_cast<std::size_t>(axis)] = value; }
void setButton(GamepadState& pad, GamepadButton button, bool down) {
    pad.buttons[static_cast<std::size_t>(button)] = down;
}

GamepadState leftStick(float x, float y) {
    GamepadState pad = connectedPad();
    setAxis(pad, GamepadAxis::LeftX, x);
    setAxis(pad, GamepadAxis::LeftY, y);
    return pad;
}

glm::vec2 moveFor(float x, float y, const InputConfig& config = {}) {
    return mapGamepad(leftStick(x, y), {}, config, kDt).actions.move;
}

void expectSameActions(const input::Actions& a, const input::Actions& b) {
    EXPECT_EQ(a.move, b.move);
    EXPECT_EQ(a.yawDelta, b.yawDelta);
    EXPECT_EQ(a.pitchDelta, b.pitchDelta);
    EXPECT_EQ(a.jump, b.jump);
    EXPECT_EQ(a.descend, b.descend);
    EXPECT_EQ(a.sprint, b.sprint);
    EXPECT_EQ(a.place, b.place);
    EXPECT_EQ(a.breakBlock, b.breakBlock);
    EXPECT_EQ(a.pickBlock, b.pickBlock);
    EXPECT_EQ(a.toggleFly, b.toggleFly);
    EXPECT_EQ(a.togglePause, b.togglePause);
    EXPECT_EQ(a.screenshot, b.screenshot);
    EXPECT_EQ(a.toggleOverlay, b.toggleOverlay);
    EXPECT_EQ(a.toggleHelp, b.toggleHelp);
    EXPECT_EQ(a.selectDelta, b.selectDelta);
    EXPECT_EQ(a.selectSlot, b.selectSlot);
    EXPECT_EQ(a.teleport, b.teleport);
    EXPECT_EQ(a.lookAbsolute, b.lookAbsolute);
}

void expectSameMemory(const GamepadMemory& a, const GamepadMemory& b) {
    EXPECT_EQ(a.leftTriggerHeld, b.leftTriggerHeld);
    EXPECT_EQ(a.rightTriggerHeld, b.rightTriggerHeld);
    EXPECT_EQ(a.prevButtons, b.prevButtons);
}

TEST(Gamepad, DefaultStateIsAtRest) {
    const GamepadState pad;
    EXPECT_FALSE(pad.connected);
    EXPECT_EQ(pad.axis(GamepadAxis::LeftX), 0.0f);
    EXPECT_EQ(pad.axis(GamepadAxis::RightY), 0.0f);
    EXPECT_EQ(pad.axis(GamepadAxis::LeftTrigger), -1.0f);
    EXPECT_EQ(pad.axis(GamepadAxis::RightTrigger), -1.0f);
    // A connected pad at rest does nothing at all.
    expectSameActions(mapGamepad(connectedPad(), {}, {}, kDt).actions, input::Actions{});
}

TEST(Gamepad, DeadzoneGivesExactlyZeroInside) {
    for (const auto& [x, y] : std::vector<std::pair<float, float>>{{0.0f, 0.0f},
                                                                   {0.1f, 0.0f},
                                                                   {-0.149f, 0.0f},
                                                                   {0.0f, 0.15f},
                                                                   {0.1f, 0.1f},
                                                                   {-0.1f, -0.11f},
                                                                   {0.15f, 0.0f}}) {
        const glm::vec2 m = moveFor(x, y);
        EXPECT_EQ(m.x, 0.0f) << x << "," << y;
        EXPECT_EQ(m.y, 0.0f) << x << "," << y;
    }
    // Radial, not per axis: (0.11, 0.11) has length 0.156 and is outside although each axis is inside.
    EXPECT_GT(glm::length(moveFor(0.11f, 0.11f)), 0.0f);
    // The right stick shares the deadzone.
    GamepadState pad = connectedPad();
    setAxis(pad, GamepadAxis::RightX, 0.14f);
    setAxis(pad, GamepadAxis::RightY, -0.02f);
    const auto actions = mapGamepad(pad, {}, {}, kDt).actions;
    EXPECT_EQ(actions.yawDelta, 0.0f);
    EXPECT_EQ(actions.pitchDelta, 0.0f);
}

TEST(Gamepad, DeadzoneRescalesContinuouslyFromTheEdge) {
    const float dz = InputConfig{}.stickDeadzone;
    // Just outside the edge the output is tiny, not a jump to the deadzone's size.
    EXPECT_NEAR(moveFor(dz + 1e-4f, 0.0f).x, 1e-4f / (1.0f - dz), 1e-5f);
    // Linear in between: halfway between the edge and full deflection gives one half.
    EXPECT_NEAR(moveFor(dz + (1.0f - dz) * 0.5f, 0.0f).x, 0.5f, 1e-5f);
    EXPECT_NEAR(moveFor(1.0f, 0.0f).x, 1.0f, 1e-6f);
    // Monotonic and without gaps across the whole travel.
    float previous = 0.0f;
    for (int i = 0; i <= 1000; ++i) {
        const float r = static_cast<float>(i) / 1000.0f;
        const float out = moveFor(r, 0.0f).x;
        EXPECT_GE(out, previous) << r;
        EXPECT_LE(out - previous, 1.0f / (1000.0f * (1.0f - dz)) + 1e-5f) << r;
        previous = out;
    }
    // Direction is kept; square-gate corners are capped at length 1.
    const glm::vec2 diagonal = moveFor(0.6f, -0.8f);
    EXPECT_NEAR(diagonal.x, 0.6f, 1e-5f);
    EXPECT_NEAR(diagonal.y, 0.8f, 1e-5f);
    EXPECT_NEAR(glm::length(moveFor(1.0f, 1.0f)), 1.0f, 1e-5f);
    // A zero deadzone passes the stick straight through.
    InputConfig noDeadzone;
    noDeadzone.stickDeadzone = 0.0f;
    EXPECT_NEAR(moveFor(0.05f, 0.0f, noDeadzone).x, 0.05f, 1e-6f);
}

TEST(Gamepad, StickDirections) {
    // GLFW reports pushing the stick forward as negative y.
    EXPECT_NEAR(moveFor(0.0f, -1.0f).y, 1.0f, 1e-6f);
    EXPECT_NEAR(moveFor(0.0f, 1.0f).y, -1.0f, 1e-6f);
    EXPECT_NEAR(moveFor(1.0f, 0.0f).x, 1.0f, 1e-6f);
    EXPECT_NEAR(moveFor(-1.0f, 0.0f).x, -1.0f, 1e-6f);

    InputConfig config;
    GamepadState pad = connectedPad();
    setAxis(pad, GamepadAxis::RightX, 1.0f);
    auto a = mapGamepad(pad, {}, config, kDt).actions;
    EXPECT_NEAR(a.yawDelta, config.lookStickDegreesPerSecond * kDt, 1e-4f); // turns right
    EXPECT_EQ(a.pitchDelta, 0.0f);
    EXPECT_EQ(a.move, glm::vec2(0.0f));

    pad = connectedPad();
    setAxis(pad, GamepadAxis::RightY, -1.0f); // pushed up
    a = mapGamepad(pad, {}, config, kDt).actions;
    EXPECT_NEAR(a.pitchDelta, config.lookStickDegreesPerSecond * kDt, 1e-4f); // looks up
    config.invertY = true;
    EXPECT_NEAR(mapGamepad(pad, {}, config, kDt).actions.pitchDelta, -config.lookStickDegreesPerSecond * kDt, 1e-4f);
    // Look speed is per second: twice the tick, twice the turn.
    EXPECT_NEAR(mapGamepad(pad, {}, config, 2 * kDt).actions.pitchDelta, -2 * config.lookStickDegreesPerSecond * kDt,
                1e-4f);
}

TEST(Gamepad, BadAxisValuesAreHarmless) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(moveFor(nan, nan), glm::vec2(0.0f));
    EXPECT_NEAR(moveFor(0.0f, -5.0f).y, 1.0f, 1e-6f);
    GamepadState pad = connectedPad();
    setAxis(pad, GamepadAxis::RightTrigger, nan);
    EXPECT_EQ(mapGamepad(pad, {}, {}, kDt).actions.selectDelta, 0);
}

// Feeds trigger travel values (0 = released, 1 = fully pulled) tick by tick, as the mapper would.
struct TriggerRun {
    int fires = 0;
    int totalSelect = 0;
    GamepadMemory memory;
};

TriggerRun pullTrigger(GamepadAxis trigger, const std::vector<float>& travel, TriggerRun run = {}) {
    for (float t : travel) {
        GamepadState pad = connectedPad();
        setAxis(pad, trigger, t * 2.0f - 1.0f);
        const auto result = mapGamepad(pad, run.memory, {}, kDt);
        run.memory = result.memory;
        run.totalSelect += result.actions.selectDelta;
        run.fires += result.actions.selectDelta != 0 ? 1 : 0;
    }
    return run;
}

TEST(Gamepad, TriggerHoveringBetweenThresholdsFiresOnce) {
    // Pulled past the press threshold (0.6), then hovering above the release threshold (0.3).
    std::vector<float> travel{0.0f, 0.65f};
    for (int i = 0; i < 200; ++i) travel.push_back(i % 2 ? 0.31f : 0.59f);
    const TriggerRun run = pullTrigger(GamepadAxis::RightTrigger, travel);
    EXPECT_EQ(run.fires, 1);
    EXPECT_EQ(run.totalSelect, 1);
    // A noisy trigger dithering across the press threshold, never falling below the release one.
    std::vector<float> noisy{0.0f};
    for (int i = 0; i < 200; ++i) noisy.push_back(i % 3 == 0 ? 0.62f : (i % 3 == 1 ? 0.58f : 0.35f));
    EXPECT_EQ(pullTrigger(GamepadAxis::RightTrigger, noisy).fires, 1);
    // Hovering there from rest, never reaching the press threshold, never fires.
    std::vector<float> hover;
    hover.reserve(200);
    for (int i = 0; i < 200; ++i) hover.push_back(0.31f + 0.28f * static_cast<float>(i % 7) / 6.0f);
    EXPECT_EQ(pullTrigger(GamepadAxis::RightTrigger, hover).fires, 0);
}

TEST(Gamepad, FullPullFiresExactlyOnceAndAReleaseRearms) {
    std::vector<float> held(100, 1.0f);
    TriggerRun run = pullTrigger(GamepadAxis::RightTrigger, held);
    EXPECT_EQ(run.fires, 1);
    EXPECT_EQ(run.totalSelect, 1);
    // Easing off only to 0.35 does not re-arm.
    run = pullTrigger(GamepadAxis::RightTrigger, {0.35f, 1.0f, 1.0f}, run);
    EXPECT_EQ(run.fires, 1);
    // A real release and a second pull fires again.
    run = pullTrigger(GamepadAxis::RightTrigger, {0.0f, 0.0f, 0.8f, 1.0f, 1.0f}, run);
    EXPECT_EQ(run.fires, 2);
    EXPECT_EQ(run.totalSelect, 2);
}

TEST(Gamepad, TriggersStepTheHotbarBothWays) {
    EXPECT_EQ(pullTrigger(GamepadAxis::LeftTrigger, {0.0f, 1.0f, 1.0f, 0.0f, 1.0f}).totalSelect, -2);
    EXPECT_EQ(pullTrigger(GamepadAxis::RightTrigger, {0.0f, 1.0f, 1.0f, 0.0f, 1.0f}).totalSelect, 2);
    // The two triggers are independent: both pulled at once cancel but each remembers its own pull.
    TriggerRun run;
    for (int i = 0; i < 3; ++i) {
        GamepadState pad = connectedPad();
        setAxis(pad, GamepadAxis::LeftTrigger, 1.0f);
        setAxis(pad, GamepadAxis::RightTrigger, 1.0f);
        const auto result = mapGamepad(pad, run.memory, {}, kDt);
        EXPECT_EQ(result.actions.selectDelta, 0);
        EXPECT_TRUE(result.memory.leftTriggerHeld);
        EXPECT_TRUE(result.memory.rightTriggerHeld);
        run.memory = result.memory;
    }
}

TEST(Gamepad, ButtonEdgesFireOncePerPress) {
    struct Edge {
        GamepadButton button;
        bool input::Actions::*flag;
    };
    const Edge edges[] = {
        {GamepadButton::RightBumper, &input::Actions::place}, {GamepadButton::LeftBumper, &input::Actions::breakBlock},
        {GamepadButton::X, &input::Actions::pickBlock},       {GamepadButton::Y, &input::Actions::toggleFly},
        {GamepadButton::Start, &input::Actions::togglePause}, {GamepadButton::Back, &input::Actions::toggleOverlay},
    };
    for (const Edge& edge : edges) {
        GamepadState pad = connectedPad();
        setButton(pad, edge.button, true);
        GamepadMemory memory;
        std::vector<bool> fired;
        for (bool down : {true, true, true, false, true, true}) {
            setButton(pad, edge.button, down);
            const auto result = mapGamepad(pad, memory, {}, kDt);
            fired.push_back(result.actions.*(edge.flag));
            memory = result.memory;
        }
        EXPECT_EQ(fired, (std::vector<bool>{true, false, false, false, true, false})) << static_cast<int>(edge.button);
    }
}

TEST(Gamepad, DpadStepsAndHeldButtons) {
    GamepadState pad = connectedPad();
    setButton(pad, GamepadButton::DpadRight, true);
    auto result = mapGamepad(pad, {}, {}, kDt);
    EXPECT_EQ(result.actions.selectDelta, 1);
    EXPECT_EQ(mapGamepad(pad, result.memory, {}, kDt).actions.selectDelta, 0);
    pad = connectedPad();
    setButton(pad, GamepadButton::DpadLeft, true);
    EXPECT_EQ(mapGamepad(pad, {}, {}, kDt).actions.selectDelta, -1);

    // Held actions stay on for as long as the button is down.
    pad = connectedPad();
    setButton(pad, GamepadButton::A, true);
    setButton(pad, GamepadButton::B, true);
    setButton(pad, GamepadButton::LeftThumb, true);
    GamepadMemory memory;
    for (int i = 0; i < 3; ++i) {
        result = mapGamepad(pad, memory, {}, kDt);
        EXPECT_TRUE(result.actions.jump);
        EXPECT_TRUE(result.actions.descend);
        EXPECT_TRUE(result.actions.sprint);
        memory = result.memory;
    }
    // Unmapped buttons do nothing.
    pad = connectedPad();
    for (GamepadButton b :
         {GamepadButton::Guide, GamepadButton::RightThumb, GamepadButton::DpadUp, GamepadButton::DpadDown})
        setButton(pad, b, true);
    expectSameActions(mapGamepad(pad, {}, {}, kDt).actions, input::Actions{});
}

TEST(Gamepad, DisconnectedPadYieldsNothingAndResetsMemory) {
    GamepadState pad = connectedPad();
    pad.buttons.fill(true);
    pad.axes.fill(1.0f);
    pad.connected = false;
    GamepadMemory previous;
    previous.leftTriggerHeld = previous.rightTriggerHeld = true;
    previous.prevButtons.fill(false);
    const auto result = mapGamepad(pad, previous, {}, kDt);
    expectSameActions(result.actions, input::Actions{});
    expectSameMemory(result.memory, GamepadMemory{});
}

TEST(Gamepad, PureSameInputsSameOutputs) {
    GamepadState pad = connectedPad();
    setAxis(pad, GamepadAxis::LeftX, 0.3f);
    setAxis(pad, GamepadAxis::LeftY, -0.7f);
    setAxis(pad, GamepadAxis::RightX, -0.5f);
    setAxis(pad, GamepadAxis::RightY, 0.4f);
    setAxis(pad, GamepadAxis::RightTrigger, 0.9f);
    setButton(pad, GamepadButton::A, true);
    setButton(pad, GamepadButton::RightBumper, true);
    setButton(pad, GamepadButton::DpadLeft, true);
    GamepadMemory previous;
    previous.prevButtons[static_cast<std::size_t>(GamepadButton::DpadLeft)] = true;
    const GamepadMemory previousCopy = previous;
    const auto first = mapGamepad(pad, previous, {}, kDt);
    for (int i = 0; i < 5; ++i) {
        const auto again = mapGamepad(pad, previous, {}, kDt);
        expectSameActions(first.actions, again.actions);
        expectSameMemory(first.memory, again.memory);
    }
    expectSameMemory(previous, previousCopy);
    EXPECT_TRUE(first.actions.place);
    EXPECT_EQ(first.actions.selectDelta, 1); // RT pulled; dpad left was already down
    EXPECT_LE(glm::length(first.actions.move), 1.0f);
}

} // namespace
