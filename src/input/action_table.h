// Every rebindable action, listed once. The mapper (which Actions field a binding drives, and whether it acts
// while held or once per press), the settings file (the key's name and its comment) and the settings panel
// (the row's label) all read these tables, so adding an action is one line here and a field in Bindings or
// GamepadBindings. The order is the order of the settings file and of the panel.
#pragma once
#include <array>
#include <string_view>

#include "input/actions.h"
#include "input/mapper.h"

namespace input {

enum class Trigger {
    Held,    // the action is true on every tick the control is down
    Pressed, // the action is true for one tick per press
    Steers,  // not a plain flag: the mapper reads it itself (movement keys, hotbar steps)
};

struct KeyAction {
    std::string_view id;    // the settings file's key under [keys]
    std::string_view label; // the settings panel's row
    std::string_view help;  // the settings file's comment above the key (may be empty)
    int Bindings::*key;
    Trigger trigger;
    bool Actions::*action; // nullptr for Trigger::Steers
};

struct PadAction {
    std::string_view id;    // the settings file's key under [gamepad]
    std::string_view label; // the settings panel's row
    std::string_view help;
    GamepadButton GamepadBindings::*button;
    Trigger trigger;
    bool Actions::*action; // nullptr for Trigger::Steers
};

inline constexpr std::array kKeyActions{
    KeyAction{"forward", "Forward", "", &Bindings::forward, Trigger::Steers, nullptr},
    KeyAction{"back", "Back", "", &Bindings::back, Trigger::Steers, nullptr},
    KeyAction{"left", "Left", "", &Bindings::left, Trigger::Steers, nullptr},
    KeyAction{"right", "Right", "", &Bindings::right, Trigger::Steers, nullptr},
    KeyAction{"jump", "Jump / fly up", "Jump, or fly up.", &Bindings::jump, Trigger::Held, &Actions::jump},
    KeyAction{"descend", "Fly down", "Fly down.", &Bindings::descend, Trigger::Held, &Actions::descend},
    KeyAction{"sprint", "Sprint", "", &Bindings::sprint, Trigger::Held, &Actions::sprint},
    KeyAction{"toggle_fly", "Toggle fly", "", &Bindings::toggleFly, Trigger::Pressed, &Actions::toggleFly},
    KeyAction{"interact", "Object panel", "Open the panel of the pendulum set or hair ball looked at.",
              &Bindings::interact, Trigger::Pressed, &Actions::interact},
    KeyAction{"carry", "Carry hair ball", "Pick up the hair ball looked at, or put the carried one down.",
              &Bindings::carry, Trigger::Pressed, &Actions::carry},
    KeyAction{"pause", "Pause menu", "", &Bindings::pause, Trigger::Pressed, &Actions::togglePause},
    KeyAction{"help", "Controls list", "", &Bindings::help, Trigger::Pressed, &Actions::toggleHelp},
    KeyAction{"screenshot", "Screenshot", "", &Bindings::screenshot, Trigger::Pressed, &Actions::screenshot},
    KeyAction{"overlay", "Performance overlay", "Performance overlay, and what a click acts on.", &Bindings::overlay,
              Trigger::Pressed, &Actions::toggleOverlay},
};

inline constexpr std::array kPadActions{
    PadAction{"jump", "Jump / fly up", "", &GamepadBindings::jump, Trigger::Held, &Actions::jump},
    PadAction{"descend", "Fly down", "", &GamepadBindings::descend, Trigger::Held, &Actions::descend},
    PadAction{"sprint", "Sprint", "", &GamepadBindings::sprint, Trigger::Held, &Actions::sprint},
    PadAction{"place", "Place block", "", &GamepadBindings::place, Trigger::Pressed, &Actions::place},
    PadAction{"break", "Break block", "", &GamepadBindings::breakBlock, Trigger::Pressed, &Actions::breakBlock},
    PadAction{"pick", "Pick block", "", &GamepadBindings::pickBlock, Trigger::Pressed, &Actions::pickBlock},
    PadAction{"toggle_fly", "Toggle fly", "", &GamepadBindings::toggleFly, Trigger::Pressed, &Actions::toggleFly},
    PadAction{"pause", "Pause menu", "", &GamepadBindings::pause, Trigger::Pressed, &Actions::togglePause},
    PadAction{"overlay", "Performance overlay", "", &GamepadBindings::overlay, Trigger::Pressed,
              &Actions::toggleOverlay},
    PadAction{"interact", "Object panel", "", &GamepadBindings::interact, Trigger::Pressed, &Actions::interact},
    PadAction{"carry", "Carry hair ball", "", &GamepadBindings::carry, Trigger::Pressed, &Actions::carry},
    PadAction{"select_previous", "Previous block", "", &GamepadBindings::selectPrev, Trigger::Steers, nullptr},
    PadAction{"select_next", "Next block", "", &GamepadBindings::selectNext, Trigger::Steers, nullptr},
};

} // namespace input
