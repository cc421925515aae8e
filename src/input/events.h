// Raw input events: what a window callback or a script line says happened, before any meaning is
// attached. Both sources produce the same InputEvent so the mapper has one path for play and for
// headless runs. Must never include GLFW: keys are GLFW key codes as plain ints (see keys.h), and
// the gamepad enums follow GLFW's GLFW_GAMEPAD_* order so the window can cast indices across.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <variant>

#include <glm/vec3.hpp>

#include "input/actions.h"

namespace input {

enum class MouseButton { Left, Right, Middle };

// Same order as GLFW_GAMEPAD_AXIS_*.
enum class GamepadAxis { LeftX, LeftY, RightX, RightY, LeftTrigger, RightTrigger, Count };

// Same order as GLFW_GAMEPAD_BUTTON_*.
enum class GamepadButton {
    A,
    B,
    X,
    Y,
    LeftBumper,
    RightBumper,
    Back,
    Start,
    Guide,
    LeftThumb,
    RightThumb,
    DpadUp,
    DpadRight,
    DpadDown,
    DpadLeft,
    Count
};

inline constexpr std::size_t kGamepadAxisCount = static_cast<std::size_t>(GamepadAxis::Count);
inline constexpr std::size_t kGamepadButtonCount = static_cast<std::size_t>(GamepadButton::Count);
static_assert(kGamepadAxisCount == 6 && kGamepadButtonCount == 15, "must match GLFWgamepadstate");

// Values as GLFW reports them: sticks -1..1 with +y DOWN (pushing a stick forward gives negative y),
// triggers -1 (released) .. +1 (fully pulled). The default is a disconnected pad at rest: sticks 0,
// triggers -1 (0 would read as a half-pulled trigger).
struct GamepadState {
    bool connected = false;
    std::array<float, kGamepadAxisCount> axes{0.0f, 0.0f, 0.0f, 0.0f, -1.0f, -1.0f};
    std::array<bool, kGamepadButtonCount> buttons{};

    float axis(GamepadAxis a) const { return axes[static_cast<std::size_t>(a)]; }
    bool button(GamepadButton b) const { return buttons[static_cast<std::size_t>(b)]; }
};

struct KeyEvent {
    int key;
    bool down;
}; // GLFW key code; a repeat arrives as down again
struct MouseMoveEvent {
    float dx, dy;
}; // pixels; +dy = mouse moved down
struct MouseButtonEvent {
    MouseButton button;
    bool down;
};
struct ScrollEvent {
    float dy;
}; // notches; +1 = wheel up one notch
struct GamepadAxisEvent {
    GamepadAxis axis;
    float value;
};
struct GamepadButtonEvent {
    GamepadButton button;
    bool down;
};
struct TeleportEvent {
    glm::vec3 position;
}; // world units
struct LookEvent {
    float yawDeg, pitchDeg;
}; // absolute, degrees

// A whole tick of intent, as a recording writes it (script command `act`): the tick it arrives for takes
// exactly these actions, whatever else the mapper holds. Doom's demos record the same thing (a ticcmd).
struct ActionsEvent {
    Actions actions;
};
using InputEvent = std::variant<KeyEvent, MouseMoveEvent, MouseButtonEvent, ScrollEvent, GamepadAxisEvent,
                                GamepadButtonEvent, TeleportEvent, LookEvent, ActionsEvent>;

// Lower-case script names: left_x left_y right_x right_y left_trigger right_trigger.
std::optional<GamepadAxis> gamepadAxisFromName(std::string_view name);
// a b x y left_bumper right_bumper back start guide left_thumb right_thumb
// dpad_up dpad_right dpad_down dpad_left.
std::optional<GamepadButton> gamepadButtonFromName(std::string_view name);
// Inverses of the above; empty for Count or out-of-range values.
std::string_view gamepadAxisName(GamepadAxis axis);
std::string_view gamepadButtonName(GamepadButton button);

} // namespace input
