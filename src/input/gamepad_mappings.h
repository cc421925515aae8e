// Gamepad mappings in SDL's gamecontrollerdb.txt format, checked line by line before GLFW sees them, so that a
// malformed line is reported by its number and the others still load (GLFW's glfwUpdateGamepadMappings only
// says that something in the string was wrong). GL-free; the window hands the good lines to GLFW.
// A line: GUID,NAME,ELEMENT:SOURCE,... with GUID 32 hex digits, NAME not empty, ELEMENT one of SDL's names
// (a b x y back guide start leftstick rightstick leftshoulder rightshoulder dpup dpdown dpleft dpright leftx
// lefty rightx righty lefttrigger righttrigger, and others GLFW ignores) and SOURCE bN, aN (with an optional +
// or - before it and ~ after it), or hN.M; "platform:NAME" is allowed. Blank lines and # comments are skipped.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace input {

struct GamepadMappings {
    std::vector<std::string> lines;    // well-formed mappings, in file order
    std::vector<std::string> problems; // "FILE:LINE: what is wrong" for each malformed line
};

GamepadMappings parseGamepadMappings(std::string_view text, std::string_view fileName);

// What the F3 overlay says of the first joystick GLFW sees: "NAME (mapped)" when GLFW has a gamepad mapping
// for it (it can be used), "NAME (no mapping)" when it has none (add its line to gamecontrollerdb.txt), and
// nothing when none is connected. An empty name reads "gamepad" or "joystick".
std::string padLabel(bool connected, bool mapped, std::string_view name);

} // namespace input
