// The player's settings file: a commented TOML file in the user's config directory holding bindings,
// look and stick tuning, graphics and simulation rate. Loading never fails and never throws: each bad
// value is reported (file, line, key) and replaced by its default, so the game always starts. The file
// is never destroyed: one that is not TOML at all is left as it is, and saving goes through a temporary
// file and a rename. The command line overrides this file for one run (options.h); nothing here reads
// flags. This struct is plain data so that the settings panel (ui) can edit it through the header alone.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "game/day_clock.h"
#include "game/hair_budget.h"
#include "input/mapper.h"

namespace session {

// A frame's size in pixels.
struct PixelSize {
    int width = 1280, height = 720;
    bool operator==(const PixelSize&) const = default;
};

// A replay's keyframes: every 30 ticks (half a second at 60 Hz) within 256 MiB; a recording's keyframe file: every
// 1800 ticks (30 s at 60 Hz: a seek steps at most that far, about 5 % of replaying minute 9 from the start).
inline constexpr int kDefaultKeyframeInterval = 30;
inline constexpr int kDefaultKeyframeBudgetMiB = 256;
inline constexpr int kDefaultKeyframeFileInterval = 1800;

// The values; session/setting_table.h holds each one's key, flag, range, unit and help. A member initializer here is
// the setting's default.
struct Settings {
    input::InputConfig input; // key and pad bindings, mouse, sticks, triggers (see mapper.h)
    float fov = 70.0f;        // degrees, vertical
    int viewRadius = 8;       // chunks
    int tickRate = 60;        // ticks per second
    PixelSize size;           // the window's inside, or the headless frame
    bool vsync = true;
    bool levelOfDetail = true;    // distant chunks meshed from coarser cells (docs/ENGINE.md)
    bool occlusionCulling = true; // chunks hidden behind terrain are not drawn (docs/ENGINE.md)
    // Hair level of detail: 0 = low (a quarter of each ball's strands simulated and drawn), 1 = half,
    // 2 = full. The game scales each ball's active strand count by hairDetailFraction(); the ball's
    // own strand count (saved in the world) is unchanged.
    int hairDetail = 2;
    // Hair work all balls together may take per tick, in thousands of node passes (game/hair_budget.h):
    // beyond it the level of detail simulates fewer strands on far and unseen balls.
    int hairBudgetThousands = static_cast<int>(game::kDefaultHairBudget / 1000);
    float dayLengthMinutes = static_cast<float>(game::kDefaultDayMinutes); // a whole day and night (game/day_clock.h)
    bool dayCycle = true;                                                  // false: the sun stands still
    // A replay's keyframes (session/keyframes.h) and a recording's keyframe file (session/keyframe_file.h).
    int keyframeInterval = kDefaultKeyframeInterval;
    int keyframeBudgetMiB = kDefaultKeyframeBudgetMiB;
    int keyframeFileInterval = kDefaultKeyframeFileInterval;

    bool operator==(const Settings&) const = default;
};

// 0.25, 0.5 or 1.0 for hairDetail 0, 1, 2 (clamped).
std::int64_t hairBudgetPasses(const Settings& settings); // node passes a tick
float hairDetailFraction(int hairDetail);

struct SettingsLoad {
    Settings settings;
    std::vector<std::string> warnings; // "FILE:LINE: key 'section.name' = VALUE: what is wrong; using DEFAULT"
    // Notes that are not problems: "FILE:LINE: key 'graphics.window_width' is now 'graphics.size'; read as such".
    std::vector<std::string> notes;
    bool created = false; // the file was missing and a commented default file was written
    // Keys of an older build were read under their new names (notes says which); loadSettings then rewrote the
    // file with the new names, keeping the old text beside it as FILE.old, when nothing else in it was wrong.
    bool migrated = false;
};

// Reads the file; creates it with commented defaults when it does not exist. Missing keys take their
// defaults silently; bad values (wrong type, out of range, NaN, unknown key or button name) and unknown
// keys give a warning each. A file that cannot be read or is not TOML gives one warning (toml++'s
// message, with file and line), all defaults, and is left untouched. Never throws.
SettingsLoad loadSettings(const std::filesystem::path& file);
// The same for a file's text, named `name` in messages (loadSettings reads the file and calls this; the fuzzer
// calls it directly). Never throws; `created` stays false.
SettingsLoad parseSettings(std::string_view text, const std::string& name);

// Bindings where one press does two things: two actions on one key or gamepad button (the game has no
// modes, so any such pair fires together), or an action on a key 1-9 (which always selects a hotbar
// slot). "actions 'jump' and 'sprint' share key SPACE". The defaults have none. loadSettings warns
// about each, naming the file and the line of the later binding.
std::vector<std::string> bindingConflicts(const Settings& settings);

// Writes the commented file (creating its folder) through a temporary file and a rename.
// Throws std::runtime_error naming the file on failure; the previous file is then left as it was.
void saveSettings(const Settings& settings, const std::filesystem::path& file);

// The commented file for these settings; defaultSettingsText() == settingsText(Settings{}).
std::string settingsText(const Settings& settings);
std::string defaultSettingsText();

} // namespace session
