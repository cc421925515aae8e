// Input mapping: raw events (window callbacks or script lines, through the same path) and gamepad
// state -> one Actions per fixed tick. Owns bindings, sensitivities, deadzones and edge detection.
// Must never read a device, a clock or a file itself: everything arrives as an event or a state, so
// a script reproduces exactly what a player did. No GLFW here (key codes are plain ints, keys.h).
#pragma once
#include <array>

#include <glm/vec2.hpp>

#include "input/actions.h"
#include "input/events.h"
#include "input/keys.h"

namespace input {

// GLFW key codes; -1 leaves an action unbound.
struct Bindings {
    int forward = key::W;
    int back = key::S;
    int left = key::A;
    int right = key::D;
    int jump = key::Space;
    int descend = key::LeftShift;
    int sprint = key::LeftControl;
    int toggleFly = key::F;
    int interact = key::E; // open the panel of the pendulum set or hair ball looked at
    int carry = key::Q;    // pick up the hair ball looked at, or put the carried one down
    int pause = key::Escape;
    int help = key::F1;
    int screenshot = key::F2;
    int overlay = key::F3;

    bool operator==(const Bindings&) const = default;
};

// Gamepad buttons by action; GamepadButton::Count leaves an action unbound. Triggers and sticks are
// not rebindable: LT/RT always step the hotbar, the sticks always move and look.
struct GamepadBindings {
    GamepadButton jump = GamepadButton::A;           // held
    GamepadButton descend = GamepadButton::B;        // held
    GamepadButton sprint = GamepadButton::LeftThumb; // held
    GamepadButton place = GamepadButton::RightBumper;
    GamepadButton breakBlock = GamepadButton::LeftBumper;
    GamepadButton pickBlock = GamepadButton::X;
    GamepadButton toggleFly = GamepadButton::Y;
    GamepadButton pause = GamepadButton::Start;
    GamepadButton overlay = GamepadButton::Back;
    GamepadButton interact = GamepadButton::DpadUp;
    GamepadButton carry = GamepadButton::RightThumb;
    GamepadButton selectPrev = GamepadButton::DpadLeft;
    GamepadButton selectNext = GamepadButton::DpadRight;

    bool operator==(const GamepadBindings&) const = default;
};

struct InputConfig {
    Bindings keys;
    GamepadBindings pad;
    float mouseDegreesPerPixel = 0.12f;       // degrees of yaw/pitch per pixel of mouse motion
    bool invertY = false;                     // mouse and right stick: pushing up / moving up looks down
    float stickDeadzone = 0.15f;              // radial, 0..1; output is rescaled to start at 0 at the edge
    float lookStickDegreesPerSecond = 200.0f; // right stick fully deflected
    float triggerPress = 0.6f;                // 0..1 trigger travel (GLFW -1..1 mapped to 0..1)
    float triggerRelease = 0.3f;              // must fall below this before the next pull counts

    bool operator==(const InputConfig&) const = default;
};

// What mapGamepad needs to remember between ticks to find edges.
struct GamepadMemory {
    bool leftTriggerHeld = false, rightTriggerHeld = false;
    std::array<bool, kGamepadButtonCount> prevButtons{};
};

struct GamepadMapping {
    Actions actions;
    GamepadMemory memory;
};

// Pure: the same inputs always give the same output. dt = tick length in seconds (stick look is per second).
// Left stick moves (pushing it forward, i.e. negative GLFW y, moves forward); right stick looks (+x turns
// right, pushing up looks up unless invertY). Both sticks use a radial deadzone.
// LT = selectDelta -1, RT = selectDelta +1, one step per pull: fires when crossing triggerPress from
// below and re-arms only after falling below triggerRelease.
// Buttons follow config.pad; with the defaults:
// Press edges (against memory.prevButtons): RB = place, LB = breakBlock, X = pickBlock, Y = toggleFly,
// Start = togglePause, Back = toggleOverlay, dpad up = interact, right stick click = carry,
// dpad left/right = selectDelta -1/+1.
// Held: A = jump, B = descend, left stick click = sprint.
// A disconnected pad yields no actions and a reset memory.
GamepadMapping mapGamepad(const GamepadState& now, const GamepadMemory& previous, const InputConfig& config, float dt);

// Turns raw events into one Actions per tick. Keyboard/mouse and gamepad combine: move = keys + left
// stick clamped to length 1, look deltas add, edges OR, selectDelta adds.
// A press between two ticks fires its edge once at the next tick even if released before it, and a
// held action is on for that tick too; key repeats (down while down) do not fire again.
class InputMapper {
public:
    explicit InputMapper(InputConfig config = {});

    // Keys, mouse, scroll, teleport, look; gamepad axis/button events edit a virtual pad (for scripts)
    // and mark it connected.
    void handle(const InputEvent& event);
    // The window polls the real pad each frame and sets it here. Presses and trigger pulls are noticed
    // per call, so a tap shorter than a tick still counts.
    void setGamepadState(const GamepadState& state);
    const GamepadState& gamepad() const;

    // Everything since the last call becomes one tick of intent; one-shot parts are then cleared.
    // dt = tick length in seconds.
    Actions takeTickActions(float dt);
    // Focus lost: keys, buttons and the virtual pad go up/centred, pending mouse motion and scroll are
    // dropped. Presses already seen still fire at the next tick.
    void releaseAll();
    // Yaw/pitch degrees of mouse motion not yet consumed, so the renderer can add it to the camera and
    // hide a tick of latency.
    glm::vec2 pendingLook() const;
    InputConfig& config();

private:
    static constexpr std::size_t kKeySlots = static_cast<std::size_t>(kKeyLast) + 1;
    static constexpr std::size_t kMouseButtons = 3;

    bool keyHeld(int key) const;
    bool keyPressed(int key) const;
    void applyGamepadState(const GamepadState& next);

    InputConfig m_config;
    std::array<bool, kKeySlots> m_keyDown{};
    std::array<bool, kKeySlots> m_keyPressed{}; // up->down since the last tick
    std::array<bool, kMouseButtons> m_mouseDown{};
    std::array<bool, kMouseButtons> m_mousePressed{};
    glm::vec2 m_mouseDelta{0.0f}; // pixels since the last tick (or last absolute look)
    float m_scroll = 0.0f;        // notches not yet turned into hotbar steps
    int m_selectSlot = -1;
    std::optional<glm::vec3> m_teleport;
    std::optional<glm::vec2> m_lookAbsolute;
    std::optional<Actions> m_recorded; // an ActionsEvent for the coming tick

    GamepadState m_pad;
    std::array<bool, kGamepadButtonCount> m_padPressed{}; // up->down since the last tick
    // Trigger hysteresis runs on every pad update, so the held flags always match m_pad.
    bool m_leftTriggerHeld = false, m_rightTriggerHeld = false;
    int m_triggerSteps = 0; // trigger pulls since the last tick, as hotbar steps
};

} // namespace input
