// Every player setting, listed once, as input/action_table.h lists the actions. Each row names the setting's
// file key, command-line flag, panel label, unit, help, type and range, whether it applies while playing and
// whether it changes what the simulation computes. The command line (options.cpp), the settings file
// (settings.cpp), the settings panel (ui/settings_panel.cpp), the clamps, the recording header and the options a
// replay refuses (recording.cpp, session.cpp) all read this table, so adding a setting is a field in Settings
// and one row here. A setting's default is its member initializer in Settings (settings.h), the one place it is
// written; settingDefaultText() reads it through the row. Key and gamepad bindings are rows of
// input/action_table.h instead.
#pragma once
#include <array>
#include <string>
#include <string_view>

#include "session/settings.h"

namespace session {

enum class SettingType { Int, Float, Bool, Size };
enum class SettingScale { Linear, Logarithmic }; // how the panel's slider spreads the range

struct SettingRow {
    std::string_view key = {}; // the settings file's key under [section]; the recording header's for simulation rows
    std::string_view section = {}; // the settings file's section; the panel shows graphics and simulation rows on its
                                   // Graphics tab, replay rows on Replay, the others on Controls
    std::string_view flag = {};    // the command line's flag, "" when the setting has none
    std::string_view label = {};   // the settings panel's row
    std::string_view unit = {};    // shown after the value in the panel and the help ("" when it has none)
    std::string_view help = {}; // the settings file's comment, the flag's help and the panel's tooltip ('\n': new line)
    SettingType type = SettingType::Int;
    double lo = 0.0, hi = 0.0; // the inclusive range (Int, Float; Size: each side)
    bool live = true;          // applied while playing; otherwise from the next start
    // Changes what the simulation computes from the same input: written into a recording's header, taken from it
    // by a replay (which refuses a flag asking for another value), and seen by the state hash through what it
    // changes (tests/session/test_setting_table.cpp proves each row's column).
    bool simulation = false;
    int& (*intRef)(Settings&) = nullptr;
    float& (*floatRef)(Settings&) = nullptr;
    bool& (*boolRef)(Settings&) = nullptr;
    PixelSize& (*sizeRef)(Settings&) = nullptr;
    SettingScale scale = SettingScale::Linear;
    std::string_view choices = {}; // Int rows shown as a choice in the panel: the names of lo..hi, '|' between
    // Keys in the same section that older builds wrote for this setting, read once and rewritten under the new key
    // (Size: the width's and the height's).
    std::array<std::string_view, 2> renamedFrom = {};
};

// NOLINTBEGIN(bugprone-macro-parentheses): a type and a member name cannot be parenthesised
#define MC_SETTING(type, member) [](Settings& s) -> type& { return s.member; }

inline constexpr std::array kSettingRows{
    SettingRow{.key = "fov",
               .section = "graphics",
               .flag = "--fov",
               .label = "Field of view",
               .unit = "degrees",
               .help = "Vertical field of view.",
               .type = SettingType::Float,
               .lo = 30.0,
               .hi = 120.0,
               .floatRef = MC_SETTING(float, fov)},
    SettingRow{.key = "view_radius",
               .section = "graphics",
               .flag = "--view-radius",
               .label = "View radius",
               .unit = "chunks",
               .help = "View distance. Larger costs memory and meshing time.",
               .type = SettingType::Int,
               .lo = 2,
               .hi = 32,
               .intRef = MC_SETTING(int, viewRadius)},
    SettingRow{.key = "size",
               .section = "graphics",
               .flag = "--size",
               .label = "Frame size",
               .unit = "pixels",
               .help =
                   "The size of the frame the game draws, WIDTHxHEIGHT: the window's inside (at least 320 a side),\n"
                   "or with --headless the off-screen picture's. One setting on purpose: a headless run draws what\n"
                   "the window would.",
               .type = SettingType::Size,
               .lo = 16,
               .hi = 16384,
               .sizeRef = MC_SETTING(PixelSize, size),
               .renamedFrom = {"window_width", "window_height"}},
    SettingRow{.key = "vsync",
               .section = "graphics",
               .flag = "--vsync",
               .label = "Vsync",
               .help = "Wait for the display's vertical sync (true/false).",
               .type = SettingType::Bool,
               .boolRef = MC_SETTING(bool, vsync)},
    SettingRow{.key = "level_of_detail",
               .section = "graphics",
               .flag = "--lod",
               .label = "Level of detail",
               .help = "Mesh chunks beyond 4 chunks from cells of 2 blocks and beyond 8 of 4 blocks (true/false).",
               .type = SettingType::Bool,
               .boolRef = MC_SETTING(bool, levelOfDetail)},
    SettingRow{.key = "occlusion_culling",
               .section = "graphics",
               .flag = "--occlusion-culling",
               .label = "Occlusion culling",
               .help = "Leave out chunks the camera cannot see into through the air between (true/false).",
               .type = SettingType::Bool,
               .boolRef = MC_SETTING(bool, occlusionCulling)},
    SettingRow{.key = "hair_detail",
               .section = "graphics",
               .flag = "--hair-detail",
               .label = "Hair detail",
               .help = "Hair level of detail: 0 = low (a quarter of each ball's strands), 1 = half, 2 = full.\n"
                       "Fewer strands are simulated and drawn; the balls saved in the world keep their strand count.",
               .type = SettingType::Int,
               .lo = 0,
               .hi = 2,
               .simulation = true,
               .intRef = MC_SETTING(int, hairDetail),
               .choices = "Low (1/4 of the strands)|Half of the strands|Full"},
    SettingRow{.key = "hair_budget",
               .section = "graphics",
               .flag = "--hair-budget",
               .label = "Hair budget",
               .unit = "thousand node passes a tick",
               .help = "Hair work per tick for all balls together. Past it, far and unseen balls simulate fewer\n"
                       "strands. 1000: 100 balls packed together take about 6 ms a tick on a 2-core machine\n"
                       "(docs/HAIR.md).",
               .type = SettingType::Int,
               .lo = 100,
               .hi = 100000,
               .simulation = true,
               .intRef = MC_SETTING(int, hairBudgetThousands),
               .scale = SettingScale::Logarithmic},
    SettingRow{.key = "tick_rate",
               .section = "simulation",
               .flag = "--tick-rate",
               .label = "Tick rate",
               .unit = "ticks a second",
               .help = "Simulation ticks per second. Physics accuracy and cost both grow with it.",
               .type = SettingType::Int,
               .lo = 10,
               .hi = 1000,
               .live = false,
               .simulation = true,
               .intRef = MC_SETTING(int, tickRate),
               .scale = SettingScale::Logarithmic},
    SettingRow{.key = "day_length",
               .section = "simulation",
               .flag = "--day-length",
               .label = "Day length",
               .unit = "minutes",
               .help = "Real minutes a whole day and night take (game/day_clock.h); a world's time of day is saved\n"
                       "with it.",
               .type = SettingType::Float,
               .lo = 1.0,
               .hi = 1440.0,
               .simulation = true,
               .floatRef = MC_SETTING(float, dayLengthMinutes),
               .scale = SettingScale::Logarithmic},
    SettingRow{.key = "day_cycle",
               .section = "simulation",
               .flag = "--day-cycle",
               .label = "Time passes",
               .help = "Whether the sun moves. Off: the time of day stands where it is (set it with --time-of-day,\n"
                       "the pause menu or a script's time command).",
               .type = SettingType::Bool,
               .simulation = true,
               .boolRef = MC_SETTING(bool, dayCycle)},
    SettingRow{.key = "keyframe_interval",
               .section = "replay",
               .flag = "--keyframe-interval",
               .label = "Keyframe interval",
               .unit = "ticks",
               .help = "A replay in the window keeps the whole state every this many ticks, to seek and step back\n"
                       "(docs/CAPTURE.md); over the budget the spacing doubles.",
               .type = SettingType::Int,
               .lo = 1,
               .hi = 100000,
               .live = false,
               .intRef = MC_SETTING(int, keyframeInterval),
               .scale = SettingScale::Logarithmic},
    SettingRow{.key = "keyframe_budget",
               .section = "replay",
               .flag = "--keyframe-budget",
               .label = "Keyframe memory",
               .unit = "MiB",
               .help = "Memory a replay's keyframes may take; a budget that does not hold one keyframe of the\n"
                       "replay is refused.",
               .type = SettingType::Int,
               .lo = 1,
               .hi = 65536,
               .live = false,
               .intRef = MC_SETTING(int, keyframeBudgetMiB),
               .scale = SettingScale::Logarithmic},
    SettingRow{.key = "keyframe_file_interval",
               .section = "replay",
               .flag = "--keyframe-file-interval",
               .label = "Recording keyframes",
               .unit = "ticks",
               .help = "--record also writes the state every this many ticks (rounded up to a multiple of 10) into\n"
                       "FILE.keys beside the recording, so a headless --seek steps only from the nearest one.",
               .type = SettingType::Int,
               .lo = 10,
               .hi = 1000000,
               .live = false,
               .intRef = MC_SETTING(int, keyframeFileInterval),
               .scale = SettingScale::Logarithmic},
    SettingRow{.key = "sensitivity",
               .section = "mouse",
               .label = "Mouse sensitivity",
               .unit = "degrees a pixel",
               .help = "Degrees of turn per pixel of mouse motion.",
               .type = SettingType::Float,
               .lo = 0.001,
               .hi = 10.0,
               .floatRef = MC_SETTING(float, input.mouseDegreesPerPixel),
               .scale = SettingScale::Logarithmic},
    SettingRow{.key = "invert_y",
               .section = "mouse",
               .label = "Invert Y (mouse and right stick)",
               .help = "Moving the mouse (or right stick) up looks down.",
               .type = SettingType::Bool,
               .boolRef = MC_SETTING(bool, input.invertY)},
    SettingRow{.key = "stick_deadzone",
               .section = "gamepad_tuning",
               .label = "Stick deadzone",
               .unit = "of full deflection",
               .help = "Radial stick deadzone; movement starts from 0 at its edge.",
               .type = SettingType::Float,
               .lo = 0.0,
               .hi = 0.9,
               .floatRef = MC_SETTING(float, input.stickDeadzone)},
    SettingRow{.key = "look_speed",
               .section = "gamepad_tuning",
               .label = "Stick look speed",
               .unit = "degrees a second",
               .help = "Right stick turn speed at full deflection.",
               .type = SettingType::Float,
               .lo = 1.0,
               .hi = 2000.0,
               .floatRef = MC_SETTING(float, input.lookStickDegreesPerSecond),
               .scale = SettingScale::Logarithmic},
    // Not 0: no release could be below it, so the trigger would never re-arm (the settings fuzzer found a file with
    // trigger_press = 0 that warned again after every save).
    SettingRow{.key = "trigger_press",
               .section = "gamepad_tuning",
               .label = "Trigger press",
               .unit = "of full travel",
               .help = "Trigger travel at which a pull steps the hotbar; it must then fall below\n"
                       "trigger_release (which must be smaller) before the next pull counts.",
               .type = SettingType::Float,
               .lo = 0.05,
               .hi = 1.0,
               .floatRef = MC_SETTING(float, input.triggerPress)},
    SettingRow{.key = "trigger_release",
               .section = "gamepad_tuning",
               .label = "Trigger release",
               .unit = "of full travel",
               .help = "Must stay below trigger_press: a pull counts again only after falling below it.",
               .type = SettingType::Float,
               .lo = 0.0,
               .hi = 1.0,
               .floatRef = MC_SETTING(float, input.triggerRelease)},
};

#undef MC_SETTING
// NOLINTEND(bugprone-macro-parentheses)

// The sections of the settings file in order (the bindings' [keys] and [gamepad] come last).
inline constexpr std::array<std::string_view, 5> kSettingSections{"graphics", "simulation", "replay", "mouse",
                                                                  "gamepad_tuning"};

// The row of a key; nullptr when there is none.
const SettingRow* findSetting(std::string_view key);

// Shortest text that reads back as the same float, always with a '.' or an exponent (so TOML reads a float).
std::string settingFloatText(float v);

// The setting's value in `s` as the settings file writes it (Size: "WIDTHxHEIGHT").
std::string settingText(const SettingRow& row, const Settings& s);
// The same for Settings{}.
std::string settingDefaultText(const SettingRow& row);
// "30.0..120.0", "2..32", "16..16384 each side".
std::string settingRangeText(const SettingRow& row);

// Reads `text` as the row's value (the command line's and the recording header's syntax, which is the file's
// without quotes; a Bool also takes 1/0, yes/no and on/off, as the command line always did): "" and the value
// set in `out` when it is a value of the row's type within its range,
// otherwise what is wrong ("expected a whole number", "out of range 2..32", "not a number"). `out` is unchanged
// on failure.
std::string parseSetting(const SettingRow& row, std::string_view text, Settings& out);

// Holds the row's value in `s` to its range (the panel's typed values; a NaN becomes the default).
void clampSetting(const SettingRow& row, Settings& s);
// Every row clamped, then the rule across rows: the trigger's release below its press (holdTriggerRelease).
void clampSettings(Settings& s);
// A trigger release at or above the press would let a trigger resting between them step the hotbar every tick:
// such a release becomes the default release when that is below the press, else half the press. Returns whether
// it changed anything. The settings file and the panel hold the pair by this one rule.
bool holdTriggerRelease(input::InputConfig& in);

// Whether the row's value is the same in both.
bool sameSetting(const SettingRow& row, const Settings& a, const Settings& b);
// Copies the row's value, which must be in its range, from `from` into `to`.
void copySetting(const SettingRow& row, const Settings& from, Settings& to);

} // namespace session
