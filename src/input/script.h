// The headless input script: a text file of timed raw events that drives the game with no window.
// One event per line, `TICK COMMAND ARGS...`; `#` starts a comment anywhere on a line; blank lines
// are ignored; tokens are separated by spaces or tabs; CRLF line endings are accepted.
//   key NAME down|up                 NAME as GLFW spells it without GLFW_KEY_ (W, SPACE, LEFT_SHIFT)
//   mouse_move DX DY                 pixels, +DY = down
//   mouse_button left|right|middle down|up
//   scroll DY                        notches, +1 = wheel up
//   gamepad_axis NAME VALUE          left_x ... right_trigger, VALUE in -1..1 (GLFW convention)
//   gamepad_button NAME down|up      a b x y left_bumper ... dpad_left
//   teleport X Y Z                   world units
//   look YAW PITCH                   degrees, absolute, PITCH in -90..90
// TICK is a non-negative integer up to 2^53; lines may come in any order and are sorted stably by
// tick, so events of one tick keep their file order.
// Parsing never half-succeeds: the first bad line throws ScriptError naming the file and line.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "input/events.h"

namespace input {

inline constexpr std::uint64_t kMaxScriptTick = std::uint64_t{1} << 53;

struct ScriptEvent {
    std::uint64_t tick;
    int line; // 1-based line in the file, for messages from later stages
    InputEvent event;
};

class ScriptError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws ScriptError("FILE:LINE: what is wrong, quoting the bad token").
std::vector<ScriptEvent> parseScript(std::string_view text, std::string_view fileName);
// Throws ScriptError("PATH: cannot open: reason") and anything parseScript throws.
std::vector<ScriptEvent> loadScript(const std::string& path);

} // namespace input
