// The game's command line. Parsing never exits the process itself: it returns what to do, and main()
// turns usage errors into exit code 2 with a message that names the flag and the bad value.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "world/terrain.h"

namespace app {

struct Options {
    bool headless = false;
    std::uint64_t ticks = 0;           // headless: exactly this many ticks, then exit
    int width = 1280, height = 720;    // pixels
    std::uint64_t seed = 1;
    world::TerrainKind terrain = world::TerrainKind::Default;
    std::string script;                // input script, applied in both modes
    std::string screenshot;            // headless: PNG of the final frame
    std::string dumpState;             // JSON state at the end (headless, and the window on exit)
    std::string frameStats;            // headless benchmark: render every tick, write frame times here
    std::string screenshotDir = "screenshots";
    int tickRate = 60;                 // ticks per second
    int viewRadius = 8;                // chunks
    float fov = 70.0f;                 // degrees, vertical
    bool vsync = true;
};

struct ParseOutcome {
    std::optional<Options> options; // set when the program should run
    int exitCode = 0;               // otherwise: 0 after --help/--version, 2 after a usage error
    std::string output;             // what to print (stdout for help, stderr for errors)
};

ParseOutcome parseOptions(int argc, const char* const* argv);

} // namespace app
