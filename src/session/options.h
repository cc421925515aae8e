// The game's command line. Parsing never exits the process itself: it returns what to do, and main()
// turns usage errors into exit code 2 with a message that names the flag and the bad value. Besides
// the syntax it checks what can be known before a run starts: numbers in range (never saturated), a
// headless frame that fits in memory, and (checkOutputPaths) output files that can be written.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "session/paths.h"
#include "session/setting_table.h"
#include "session/settings.h"
#include "world/terrain.h"

namespace session {

// Which flags were given on the command line (not left at their defaults).
struct GivenFlags {
    // Per row of kSettingRows (session/setting_table.h): only the settings given override the file
    // (mergeSettings), and a replay refuses a simulation setting given with another value than its recording's.
    std::array<bool, kSettingRows.size()> settings{};
    bool screenshotDir = false;               // only a folder named on the command line is checked before the run
    bool seed = false, terrain = false;       // a replay refuses them when they differ from its recording
    bool setting(std::string_view key) const; // the setting of this key was given
};

struct Options {
    bool headless = false;
    std::uint64_t ticks = 0; // headless: exactly this many ticks, then exit
    // The settings of session/setting_table.h that have a flag: after parsing, the flags given (the others at
    // their defaults); after mergeSettings, the settings in effect for this run.
    Settings settings;
    std::uint64_t seed = 1;
    world::TerrainKind terrain = world::TerrainKind::Default;
    // --time-of-day: the hour the run starts at (game::parseHours), a new world's or a loaded one's; none: a new
    // world's game::kDefaultHours, a loaded world's own.
    std::optional<double> timeOfDay;
    std::string script;                // input script, applied in both modes
    bool replay = false;               // --replay: `script` must be a recording (session/recording.h)
    std::optional<std::uint64_t> seek; // headless: bring the state to this tick first (Session::seek)
    std::string screenshot;            // headless: PNG of the final frame
    std::string dumpState;             // JSON state at the end (headless, and the window on exit)
    std::string frameStats;            // headless benchmark: render every tick, write frame times here
    std::string soakReport;            // headless soak: per-minute energy, NaN, RSS and tick-time checks here
    std::uint64_t captureEvery = 0;    // headless: a PNG every this many ticks into captureDir (0: none)
    std::string captureDir;            // headless: frame-TTTTTT.png, TTTTTT the tick
    int screenshotScale = 1;           // F2 and --screenshot: the PNG is this many times the frame's size (1..8)
    std::string record;                // write every tick's input and panel edits here (session/recording.h)
    // Headless: the off-screen OpenGL, "auto" (OSMesa when it loads, else EGL), "osmesa" or "egl"; the default
    // is $MINECRAPPY_GL_BACKEND when set (the tests run each backend that way).
    std::string glBackend = "auto";
    // Window: SDL-format gamepad mappings to add to GLFW's; empty: the config folder's gamecontrollerdb.txt
    // when it exists (session/paths.h).
    std::string gamepadMappings;
    double soakTickBudgetMs = 0.0; // soak: CPU ms a tick may take; 0: one tick period
    std::string screenshotDir = "screenshots";
    std::string world;        // world file: loaded if it exists, else created; empty in headless: none;
                              // the window: empty plays the default world, "none" plays unsaved
    bool saveAtEnd = false;   // headless: also save the world when the run ends
    int autosaveTicks = 300;  // autosave every this many ticks of game time (5 s at 60 Hz)
    std::string worldsFolder; // window: where the world list lives (empty: the user's data folder)
    GivenFlags given;
    // The settings file; nullopt after `--settings none` (built-in defaults, nothing read or written).
    std::optional<std::filesystem::path> settingsFile = defaultSettingsPath();
};

struct ParseOutcome {
    std::optional<Options> options; // set when the program should run
    int exitCode = 0;               // otherwise: 0 after --help/--version, 2 after a usage error
    std::string output;             // what to print (stdout for help, stderr for errors)
};

ParseOutcome parseOptions(int argc, const char* const* argv);

// Checks, before the first tick, that every output the run will write can be written: for each of
// --screenshot, --dump-state, --frame-stats, --soak-report and a given --screenshot-dir, the path is
// not a directory (the folder for --screenshot-dir is one) and its folder exists (or, where the writer
// creates folders, its nearest existing ancestor is a folder) and accepts a new file, tried for real.
// Returns "" when all can be written, else "FLAG PATH: cannot write there: REASON" (strerror).
std::string checkOutputPaths(const Options& options);

// Peak resident memory of a headless run drawing and saving one frame of width x height (bytes).
std::uint64_t estimatedFrameBytes(int width, int height);
// MemAvailable from /proc/meminfo in bytes; nullopt when it cannot be read.
std::optional<std::uint64_t> availableMemoryBytes();
// "" when estimatedFrameBytes fits in half of `available` (or `available` is unknown), else a message
// that names the size, the estimate and the available memory. `what` names where the size came from.
std::string frameMemoryProblem(const std::string& what, int width, int height, std::optional<std::uint64_t> available);

// Makes the run's values agree: a flag given on the command line wins for this run, otherwise the
// file's value is used. Both sides are updated (options.settings becomes the settings in effect), so the
// runners read Options and the settings panel shows (and would save) what is in effect.
void mergeSettings(Options& options, Settings& settings);

} // namespace session
