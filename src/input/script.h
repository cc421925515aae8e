// The headless input script: a text file of timed raw events that drives the game with no window.
// One event per line, `TICK COMMAND ARGS...`; `#` starts a comment anywhere on a line; blank lines
// are ignored; tokens are separated by spaces or tabs; CRLF line endings are accepted.
//   key NAME down|up                 NAME as GLFW spells it without GLFW_KEY_ (W, SPACE, LEFT_SHIFT)
//   mouse_move DX DY                 pixels, +DY = down
//   mouse_button left|right|middle down|up
//   scroll DY                        notches, +1 = wheel up
//   gamepad_axis NAME VALUE          sticks left_x left_y right_x right_y: VALUE in -1..1 (GLFW, +y = down);
//                                    triggers left_trigger right_trigger: VALUE is travel 0..1 (0 released,
//                                    1 fully pulled), turned into GLFW's -1..1 (2 VALUE - 1) for the event
//   gamepad_button NAME down|up      a b x y left_bumper ... dpad_left
//   teleport X Y Z                   world units
//   look YAW PITCH                   degrees, absolute, PITCH in -90..90
// What a recording writes (session/recording.h), also usable by hand:
//   act [FIELD=VALUE...] [FLAG...]   the whole tick's intent, replacing what the devices said for that tick:
//                                    move=X,Y yaw=D pitch=D select=N slot=N teleport=X,Y,Z look=YAW,PITCH and
//                                    the flags jump descend sprint place break pick interact carry fly pause
//                                    screenshot overlay help; numbers read back bit for bit
//   pendulum INDEX set|release|reset [FIELD=VALUE...]   a pendulum panel's edit (game/command_text.h)
//   hair INDEX FIELD=VALUE...        a hair panel's edit
//   time HOURS                       sets the time of day (0 to 24, 12 noon) before the tick moves it on
//   hotbar SLOT ITEM                 puts ITEM (a block's name, pendulum_set or hair_ball) into hotbar slot SLOT
//                                    (1 to 9), as the pause menu's block picker does
// TICK is a non-negative integer up to 2^53; lines may come in any order and are sorted stably by
// tick, so events of one tick keep their file order.
// Parsing never half-succeeds: the first bad line throws ScriptError naming the file and line.
// Size is bounded so that any file (/dev/zero, a log pasted by mistake) is refused before it can take
// much memory: kMaxScriptBytes per file, kMaxScriptLineBytes per line, kMaxScriptEvents event lines.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "input/events.h"

namespace input {

inline constexpr std::uint64_t kMaxScriptTick = std::uint64_t{1} << 53;
// An hour of play at 60 Hz with an event on every tick is 216,000 lines; these leave ample room.
inline constexpr std::size_t kMaxScriptBytes = std::size_t{16} << 20; // 16 MiB
inline constexpr std::size_t kMaxScriptLineBytes = 4096;              // without the line break
inline constexpr std::size_t kMaxScriptEvents = 1'000'000;

// A panel edit (script commands `pendulum`, `hair`, `time` and `hotbar`): which object, and the command's words after
// the index as written ("set", "release=60", ...; `time`: index 0 and the hour; `hotbar`: the slot and the item). The
// input layer only splits the line; the session turns it into a game command (game/command_text.h) and the mapper
// ignores it.
struct EditEvent {
    std::string object; // "pendulum", "hair", "time" or "hotbar"
    std::uint64_t index = 0;
    std::vector<std::string> words;
};

struct ScriptEvent {
    std::uint64_t tick;
    int line; // 1-based line in the file, for messages from later stages
    InputEvent event;
    std::optional<EditEvent> edit; // a panel edit line; `event` is then unused
};

class ScriptError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws ScriptError("FILE:LINE: what is wrong, quoting the bad token").
std::vector<ScriptEvent> parseScript(std::string_view text, std::string_view fileName);
// Throws ScriptError("PATH: cannot open: reason"), ScriptError for a file over kMaxScriptBytes (read
// no further than one byte past the limit), and anything parseScript throws.
std::vector<ScriptEvent> loadScript(const std::string& path);
// The file's text, with the same checks and errors as loadScript (size, unreadable), unparsed.
std::string readScriptText(const std::string& path);

// The events of a sorted script that come at or after `tick` (and so never run in a run that stops
// there): how many, and the first of them in the file.
struct LateEvents {
    std::size_t count = 0;
    int firstLine = 0; // smallest line number among them; 0 when count == 0
};
LateEvents eventsFrom(const std::vector<ScriptEvent>& events, std::uint64_t tick);

// The words after "act" that make an `act` line read back as exactly `actions`: only what differs from a
// default Actions, floats in their shortest exact form; empty for a default Actions.
std::string actWords(const Actions& actions);

} // namespace input
