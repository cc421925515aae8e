#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "input/mapper.h"
#include "input/script.h"

namespace {

using input::Actions;
using input::InputMapper;
namespace key = input::key;

constexpr float kDt = 1.0f / 60.0f;

void press(InputMapper& m, int k) { m.handle(input::KeyEvent{k, true}); }
void release(InputMapper& m, int k) { m.handle(input::KeyEvent{k, false}); }
void click(InputMapper& m, input::MouseButton b, bool down) { m.handle(input::MouseButtonEvent{b, down}); }

bool anyEdge(const Actions& a) {
    return a.place || a.breakBlock || a.pickBlock || a.toggleFly || a.togglePause || a.screenshot || a.toggleOverlay ||
           a.toggleHelp || a.selectDelta != 0 || a.selectSlot != -1;
}

TEST(Mapper, NothingHappensWithoutInput) {
    InputMapper m;
    for (int i = 0; i < 3; ++i) {
        const Actions a = m.takeTickActions(kDt);
        EXPECT_EQ(a.move, glm::vec2(0.0f));
        EXPECT_EQ(a.yawDelta, 0.0f);
        EXPECT_EQ(a.pitchDelta, 0.0f);
        EXPECT_FALSE(a.jump || a.descend || a.sprint || anyEdge(a));
        EXPECT_FALSE(a.teleport || a.lookAbsolute);
    }
}

TEST(Mapper, HeldKeysMoveEveryTick) {
    InputMapper m;
    press(m, key::W);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(m.takeTickActions(kDt).move, glm::vec2(0.0f, 1.0f)) << i;
    release(m, key::W);
    EXPECT_EQ(m.takeTickActions(kDt).move, glm::vec2(0.0f));

    press(m, key::S);
    EXPECT_EQ(m.takeTickActions(kDt).move, glm::vec2(0.0f, -1.0f));
    press(m, key::W); // opposite keys cancel
    EXPECT_EQ(m.takeTickActions(kDt).move, glm::vec2(0.0f));
    release(m, key::S);
    press(m, key::D);
    const glm::vec2 diagonal = m.takeTickActions(kDt).move;
    EXPECT_NEAR(glm::length(diagonal), 1.0f, 1e-6f); // no faster diagonals
    EXPECT_NEAR(diagonal.x, diagonal.y, 1e-6f);
    EXPECT_GT(diagonal.x, 0.0f);
    release(m, key::W);
    release(m, key::D);
    press(m, key::A);
    EXPECT_EQ(m.takeTickActions(kDt).move, glm::vec2(-1.0f, 0.0f));
}

TEST(Mapper, HeldActions) {
    InputMapper m;
    press(m, key::Space);
    press(m, key::LeftShift);
    press(m, key::LeftControl);
    for (int i = 0; i < 3; ++i) {
        const Actions a = m.takeTickActions(kDt);
        EXPECT_TRUE(a.jump && a.descend && a.sprint);
        EXPECT_FALSE(anyEdge(a));
    }
    release(m, key::Space);
    const Actions a = m.takeTickActions(kDt);
    EXPECT_FALSE(a.jump);
    EXPECT_TRUE(a.descend && a.sprint);
}

TEST(Mapper, EdgesFireOncePerPress) {
    struct Edge {
        int key;
        bool Actions::*flag;
    };
    const Edge edges[] = {{key::F, &Actions::toggleFly},
                          {key::Escape, &Actions::togglePause},
                          {key::F1, &Actions::toggleHelp},
                          {key::F2, &Actions::screenshot},
                          {key::F3, &Actions::toggleOverlay}};
    for (const Edge& edge : edges) {
        InputMapper m;
        press(m, edge.key);
        EXPECT_TRUE(m.takeTickActions(kDt).*(edge.flag)) << edge.key;
        for (int i = 0; i < 3; ++i) EXPECT_FALSE(m.takeTickActions(kDt).*(edge.flag)) << edge.key; // still held
        release(m, edge.key);
        EXPECT_FALSE(m.takeTickActions(kDt).*(edge.flag));
        press(m, edge.key);
        EXPECT_TRUE(m.takeTickActions(kDt).*(edge.flag)) << edge.key;
    }
}

TEST(Mapper, PressAndReleaseWithinOneTickFiresOnce) {
    InputMapper m;
    press(m, key::F);
    release(m, key::F);
    EXPECT_TRUE(m.takeTickActions(kDt).toggleFly);
    EXPECT_FALSE(m.takeTickActions(kDt).toggleFly);

    // A tap shorter than a tick also holds its action for that one tick: a quick jump is not lost.
    press(m, key::Space);
    release(m, key::Space);
    EXPECT_TRUE(m.takeTickActions(kDt).jump);
    EXPECT_FALSE(m.takeTickActions(kDt).jump);

    // Two full taps within one tick are still one edge per tick (a toggle must not cancel itself).
    press(m, key::F);
    release(m, key::F);
    press(m, key::F);
    release(m, key::F);
    EXPECT_TRUE(m.takeTickActions(kDt).toggleFly);
    EXPECT_FALSE(m.takeTickActions(kDt).toggleFly);
}

TEST(Mapper, KeyRepeatDoesNotFireAgain) {
    InputMapper m;
    press(m, key::F);
    press(m, key::F); // GLFW_REPEAT arrives as another "down"
    press(m, key::F);
    EXPECT_TRUE(m.takeTickActions(kDt).toggleFly);
    press(m, key::F);
    press(m, key::F);
    EXPECT_FALSE(m.takeTickActions(kDt).toggleFly);
    press(m, key::Digit3);
    EXPECT_EQ(m.takeTickActions(kDt).selectSlot, 2);
    press(m, key::Digit3);
    EXPECT_EQ(m.takeTickActions(kDt).selectSlot, -1);
}

TEST(Mapper, NumberKeysSelectSlots) {
    InputMapper m;
    for (int i = 0; i < 9; ++i) {
        press(m, key::Digit1 + i);
        release(m, key::Digit1 + i);
        EXPECT_EQ(m.takeTickActions(kDt).selectSlot, i);
        EXPECT_EQ(m.takeTickActions(kDt).selectSlot, -1);
    }
    press(m, key::Digit0); // nine slots: 0 selects nothing
    EXPECT_EQ(m.takeTickActions(kDt).selectSlot, -1);
    press(m, key::Digit2);
    press(m, key::Digit7); // the last pressed wins
    EXPECT_EQ(m.takeTickActions(kDt).selectSlot, 6);
}

TEST(Mapper, RebindingAndUnknownKeys) {
    InputMapper m;
    m.config().keys.forward = key::Up;
    m.config().keys.toggleFly = -1; // unbound
    press(m, key::W);
    press(m, key::F);
    Actions a = m.takeTickActions(kDt);
    EXPECT_EQ(a.move, glm::vec2(0.0f));
    EXPECT_FALSE(a.toggleFly);
    press(m, key::Up);
    EXPECT_EQ(m.takeTickActions(kDt).move, glm::vec2(0.0f, 1.0f));
    for (int bad : {-1, input::kKeyLast + 1, 100000, -100000}) {
        press(m, bad);
        release(m, bad);
    }
    a = m.takeTickActions(kDt);
    EXPECT_FALSE(anyEdge(a));
}

TEST(Mapper, MouseSensitivityAndInversion) {
    InputMapper m;
    const float s = m.config().mouseDegreesPerPixel;
    m.handle(input::MouseMoveEvent{10.0f, 0.0f});
    m.handle(input::MouseMoveEvent{5.0f, 0.0f});
    EXPECT_NEAR(m.pendingLook().x, 15.0f * s, 1e-5f);
    Actions a = m.takeTickActions(kDt);
    EXPECT_NEAR(a.yawDelta, 15.0f * s, 1e-5f); // moving right turns right
    EXPECT_EQ(a.pitchDelta, 0.0f);
    EXPECT_EQ(m.pendingLook(), glm::vec2(0.0f)); // consumed
    EXPECT_EQ(m.takeTickActions(kDt).yawDelta, 0.0f);

    m.handle(input::MouseMoveEvent{0.0f, 10.0f});                      // mouse moved down
    EXPECT_NEAR(m.takeTickActions(kDt).pitchDelta, -10.0f * s, 1e-5f); // looks down
    m.config().invertY = true;
    m.handle(input::MouseMoveEvent{0.0f, 10.0f});
    EXPECT_NEAR(m.pendingLook().y, 10.0f * s, 1e-5f);
    EXPECT_NEAR(m.takeTickActions(kDt).pitchDelta, 10.0f * s, 1e-5f);

    m.config().invertY = false;
    m.config().mouseDegreesPerPixel = 0.5f;
    m.handle(input::MouseMoveEvent{-4.0f, -2.0f});
    a = m.takeTickActions(kDt);
    EXPECT_NEAR(a.yawDelta, -2.0f, 1e-6f);
    EXPECT_NEAR(a.pitchDelta, 1.0f, 1e-6f);
}

TEST(Mapper, MouseButtons) {
    InputMapper m;
    click(m, input::MouseButton::Left, true);
    Actions a = m.takeTickActions(kDt);
    EXPECT_TRUE(a.breakBlock);
    EXPECT_FALSE(a.place || a.pickBlock);
    EXPECT_FALSE(m.takeTickActions(kDt).breakBlock); // held: no repeat
    click(m, input::MouseButton::Left, false);
    click(m, input::MouseButton::Right, true);
    click(m, input::MouseButton::Right, false); // click within one tick
    a = m.takeTickActions(kDt);
    EXPECT_TRUE(a.place);
    EXPECT_FALSE(a.breakBlock);
    EXPECT_FALSE(m.takeTickActions(kDt).place);
    click(m, input::MouseButton::Middle, true);
    EXPECT_TRUE(m.takeTickActions(kDt).pickBlock);
}

TEST(Mapper, ScrollDirectionAndAccumulation) {
    InputMapper m;
    m.handle(input::ScrollEvent{1.0f}); // wheel up: previous slot
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, -1);
    m.handle(input::ScrollEvent{-1.0f});
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, 1);
    for (int i = 0; i < 3; ++i) m.handle(input::ScrollEvent{1.0f});
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, -3);
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, 0);
    // Trackpad fractions add up across ticks.
    m.handle(input::ScrollEvent{-0.5f});
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, 0);
    m.handle(input::ScrollEvent{-0.5f});
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, 1);
    m.handle(input::ScrollEvent{1e30f}); // absurd values are bounded, not undefined behaviour
    EXPECT_LT(m.takeTickActions(kDt).selectDelta, 0);
}

TEST(Mapper, TeleportAndAbsoluteLookAreOneShot) {
    InputMapper m;
    m.handle(input::MouseMoveEvent{100.0f, 0.0f}); // superseded by the absolute look below
    m.handle(input::TeleportEvent{{1.0f, 2.0f, 3.0f}});
    m.handle(input::LookEvent{90.0f, -10.0f});
    m.handle(input::MouseMoveEvent{10.0f, 0.0f});
    Actions a = m.takeTickActions(kDt);
    ASSERT_TRUE(a.teleport && a.lookAbsolute);
    EXPECT_EQ(*a.teleport, glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(*a.lookAbsolute, glm::vec2(90.0f, -10.0f));
    EXPECT_NEAR(a.yawDelta, 10.0f * m.config().mouseDegreesPerPixel, 1e-5f);
    a = m.takeTickActions(kDt);
    EXPECT_FALSE(a.teleport || a.lookAbsolute);
}

TEST(Mapper, ReleaseAllOnFocusLoss) {
    InputMapper m;
    press(m, key::W);
    press(m, key::Space);
    m.takeTickActions(kDt);
    press(m, key::Escape);
    m.handle(input::MouseMoveEvent{50.0f, 50.0f});
    m.handle(input::ScrollEvent{2.0f});
    m.handle(input::GamepadButtonEvent{input::GamepadButton::A, true});
    m.releaseAll();
    EXPECT_EQ(m.pendingLook(), glm::vec2(0.0f));
    Actions a = m.takeTickActions(kDt);
    // The pause press happened before focus went; it still counts. Motion and scroll are dropped.
    EXPECT_TRUE(a.togglePause);
    EXPECT_EQ(a.yawDelta, 0.0f);
    EXPECT_EQ(a.selectDelta, 0);
    a = m.takeTickActions(kDt);
    EXPECT_EQ(a.move, glm::vec2(0.0f));
    EXPECT_FALSE(a.jump);
    EXPECT_FALSE(m.gamepad().button(input::GamepadButton::A));
    // Keys work normally afterwards: W is up, so pressing it is a fresh press.
    press(m, key::W);
    EXPECT_EQ(m.takeTickActions(kDt).move, glm::vec2(0.0f, 1.0f));
}

TEST(Mapper, KeyboardAndGamepadCombine) {
    InputMapper m;
    input::GamepadState pad;
    pad.connected = true;
    pad.axes[static_cast<std::size_t>(input::GamepadAxis::LeftY)] = -1.0f; // full forward
    pad.axes[static_cast<std::size_t>(input::GamepadAxis::RightX)] = 1.0f;
    pad.buttons[static_cast<std::size_t>(input::GamepadButton::DpadRight)] = true;
    m.setGamepadState(pad);
    press(m, key::W);
    press(m, key::D);
    m.handle(input::MouseMoveEvent{10.0f, 0.0f});
    m.handle(input::ScrollEvent{1.0f});
    Actions a = m.takeTickActions(kDt);
    EXPECT_NEAR(glm::length(a.move), 1.0f, 1e-6f); // clamped, not 2
    EXPECT_GT(a.move.y, a.move.x);
    EXPECT_NEAR(a.yawDelta, 10.0f * m.config().mouseDegreesPerPixel + m.config().lookStickDegreesPerSecond * kDt,
                1e-4f);
    EXPECT_EQ(a.selectDelta, 0); // wheel up (-1) + dpad right (+1)
    release(m, key::W);
    pad.axes[static_cast<std::size_t>(input::GamepadAxis::LeftY)] = 0.0f;
    pad.axes[static_cast<std::size_t>(input::GamepadAxis::LeftX)] = -1.0f; // stick left cancels key right
    m.setGamepadState(pad);
    a = m.takeTickActions(kDt);
    EXPECT_NEAR(glm::length(a.move), 0.0f, 1e-6f);
    EXPECT_EQ(a.selectDelta, 0); // dpad still held: no new step

    pad.buttons[static_cast<std::size_t>(input::GamepadButton::Y)] = true;
    m.setGamepadState(pad);
    press(m, key::F); // both at once: edges OR, still one toggle
    EXPECT_TRUE(m.takeTickActions(kDt).toggleFly);
}

TEST(Mapper, GamepadTapsBetweenTicksAreNotLost) {
    InputMapper m;
    // The window may poll several frames per tick; a press and release in between still fires once.
    input::GamepadState pad;
    pad.connected = true;
    m.setGamepadState(pad);
    // The window's poll of the pad with the right bumper (place) down or up.
    const auto bumper = [&](bool down) {
        pad.buttons[static_cast<std::size_t>(input::GamepadButton::RightBumper)] = down;
        m.setGamepadState(pad);
    };
    bumper(true);
    bumper(false);
    EXPECT_TRUE(m.takeTickActions(kDt).place);
    EXPECT_FALSE(m.takeTickActions(kDt).place);

    // Held since the last tick, released and pressed again before the next: a second press.
    bumper(true);
    EXPECT_TRUE(m.takeTickActions(kDt).place);
    bumper(false);
    bumper(true);
    EXPECT_TRUE(m.takeTickActions(kDt).place);
    EXPECT_FALSE(m.takeTickActions(kDt).place);

    // A trigger pulled and let go between ticks steps once.
    m.handle(input::GamepadAxisEvent{input::GamepadAxis::RightTrigger, 1.0f});
    m.handle(input::GamepadAxisEvent{input::GamepadAxis::RightTrigger, -1.0f});
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, 1);
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, 0);
    // Held across ticks it steps once.
    m.handle(input::GamepadAxisEvent{input::GamepadAxis::LeftTrigger, 1.0f});
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, -1);
    EXPECT_EQ(m.takeTickActions(kDt).selectDelta, 0);
}

TEST(Mapper, VirtualPadFromEventsAndRealPadDisconnect) {
    InputMapper m;
    EXPECT_FALSE(m.gamepad().connected);
    m.handle(input::GamepadButtonEvent{input::GamepadButton::A, true});
    EXPECT_TRUE(m.gamepad().connected);
    EXPECT_TRUE(m.takeTickActions(kDt).jump);
    EXPECT_TRUE(m.takeTickActions(kDt).jump);
    m.handle(input::GamepadAxisEvent{input::GamepadAxis::LeftY, -1.0f});
    EXPECT_NEAR(m.takeTickActions(kDt).move.y, 1.0f, 1e-6f);
    m.setGamepadState(input::GamepadState{}); // unplugged
    const Actions a = m.takeTickActions(kDt);
    EXPECT_FALSE(a.jump);
    EXPECT_EQ(a.move, glm::vec2(0.0f));
}

TEST(Mapper, ScriptDrivesTheSamePath) {
    const auto events = input::parseScript("0 key W down\n"
                                           "2 key W up\n"
                                           "3 key F down\n"
                                           "3 key F up\n"
                                           "4 mouse_move 10 0\n"
                                           "5 gamepad_button right_bumper down\n"
                                           "7 gamepad_button right_bumper up\n",
                                           "same_path.txt");
    InputMapper m;
    std::vector<Actions> ticks;
    std::size_t next = 0;
    for (std::uint64_t tick = 0; tick < 8; ++tick) {
        while (next < events.size() && events[next].tick == tick) m.handle(events[next++].event);
        ticks.push_back(m.takeTickActions(kDt));
    }
    EXPECT_EQ(ticks[0].move.y, 1.0f);
    EXPECT_EQ(ticks[1].move.y, 1.0f);
    EXPECT_EQ(ticks[2].move.y, 0.0f);
    EXPECT_TRUE(ticks[3].toggleFly);
    EXPECT_FALSE(ticks[4].toggleFly);
    EXPECT_NEAR(ticks[4].yawDelta, 10.0f * m.config().mouseDegreesPerPixel, 1e-5f);
    EXPECT_TRUE(ticks[5].place);
    EXPECT_FALSE(ticks[6].place);
    EXPECT_FALSE(ticks[7].place);
}

// Script triggers are travel 0..1 like the mapper's thresholds: "right_trigger 0" is a released trigger
// that re-arms, where the raw -1..1 value 0 read as half pulled and never re-armed.
TEST(Mapper, ScriptTriggerZeroIsReleased) {
    const auto events = input::parseScript("0 gamepad_axis right_trigger 1\n"
                                           "1 gamepad_axis right_trigger 0\n"
                                           "2 gamepad_axis right_trigger 1\n"
                                           "3 gamepad_axis right_trigger 0.45\n" // between release and press
                                           "4 gamepad_axis right_trigger 1\n",
                                           "t.txt");
    ASSERT_EQ(events.size(), 5u);
    InputMapper m;
    ASSERT_GT(m.config().triggerRelease, 0.0f); // so that 0 is below it and 0.45 is not
    ASSERT_LT(m.config().triggerRelease, 0.45f);
    ASSERT_GT(m.config().triggerPress, 0.45f);
    int steps = 0;
    for (const auto& e : events) {
        m.handle(e.event);
        steps += m.takeTickActions(kDt).selectDelta;
    }
    EXPECT_EQ(steps, 2); // the third pull never re-armed: it rested at 0.45 in between
}

} // namespace
