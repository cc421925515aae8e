#include "app/options.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace app {

namespace {
bool parseSize(const std::string& s, int& w, int& h) {
    const auto x = s.find('x');
    if (x == std::string::npos) return false;
    const char* b = s.data();
    const auto r1 = std::from_chars(b, b + x, w);
    const auto r2 = std::from_chars(b + x + 1, b + s.size(), h);
    return r1.ec == std::errc() && r1.ptr == b + x && r2.ec == std::errc() && r2.ptr == b + s.size() && w >= 16 &&
           h >= 16 && w <= 16384 && h <= 16384;
}
} // namespace

ParseOutcome parseOptions(int argc, const char* const* argv) {
    Options o;
    CLI::App cli{"Minecrappy: a voxel sandbox that is also a physics lab.\n"
                 "Without --headless it opens a window; with --headless it runs a fixed number of ticks\n"
                 "off-screen (OSMesa) and can write a PNG and a JSON state dump.",
                 "minecrappy"};
    cli.set_version_flag("--version", std::string("minecrappy ") + MC_VERSION);
    std::string size = std::to_string(o.width) + "x" + std::to_string(o.height);
    std::string terrain = "default";
    std::string settingsFile = o.settingsFile->string();

    cli.add_flag("--headless", o.headless, "Run off-screen without a window");
    // CLI11 would wrap "-3" into a huge unsigned number: reject the sign before conversion.
    const auto unsignedInteger = CLI::Validator(
        [](const std::string& s) {
            return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos
                       ? std::string()
                       : "expected a non-negative whole number, got '" + s + "'";
        },
        "UINT");
    cli.add_option("--settings", settingsFile,
                   "Settings file (created with commented defaults if missing); 'none': built-in defaults, "
                   "nothing read or written")
        ->capture_default_str();
    cli.add_option("--ticks", o.ticks, "Headless: number of ticks to simulate")
        ->capture_default_str()
        ->check(unsignedInteger);
    auto* sizeFlag =
        cli.add_option("--size", size, "Frame size WxH in pixels (window or off-screen)")
            ->capture_default_str()
            ->check([](const std::string& s) {
                int w, h;
                return parseSize(s, w, h) ? std::string() : "expected WxH with each side 16..16384, e.g. 1280x720";
            });
    cli.add_option("--seed", o.seed, "World seed")->capture_default_str()->check(unsignedInteger);
    cli.add_option("--terrain", terrain, "Terrain: default or flat")
        ->capture_default_str()
        ->check(CLI::IsMember({"default", "flat"}));
    cli.add_option("--script", o.script, "Input script: one 'TICK COMMAND ARGS' per line (see README)")
        ->check(CLI::ExistingFile);
    cli.add_option("--screenshot", o.screenshot, "Headless: write the final frame to this PNG");
    cli.add_option("--dump-state", o.dumpState, "Write the final game state as JSON to this file");
    cli.add_option("--frame-stats", o.frameStats,
                   "Headless benchmark: render every tick and write frame times and peak memory as JSON");
    cli.add_option("--soak-report", o.soakReport,
                   "Headless soak: check energy bounds, NaN, memory and tick time every game minute, write them "
                   "as JSON here and exit 1 if a check failed");
    cli.add_option("--soak-tick-budget-ms", o.soakTickBudgetMs,
                   "Headless soak: CPU time one tick may take; 0 means one tick period (16.7 ms at 60 Hz)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1000.0));
    cli.add_option("--screenshot-dir", o.screenshotDir, "Folder for F2 screenshots")->capture_default_str();
    cli.add_option("--world", o.world,
                   "World file (SQLite): loaded if it exists, else created; autosaved. The window uses "
                   "WORLDS/default.mcworld unless given; 'none' plays without saving");
    cli.add_flag("--save", o.saveAtEnd, "Headless: save the world when the run ends (autosaves happen anyway)");
    cli.add_option("--autosave-ticks", o.autosaveTicks, "Autosave every this many ticks of game time")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    cli.add_option("--worlds-dir", o.worldsFolder,
                   "Window: folder of the world list (default: the user's data folder)");
    auto* tickRateFlag = cli.add_option("--tick-rate", o.tickRate, "Simulation ticks per second")
                             ->capture_default_str()
                             ->check(CLI::Range(10, 1000));
    auto* viewRadiusFlag = cli.add_option("--view-radius", o.viewRadius, "View distance in chunks")
                               ->capture_default_str()
                               ->check(CLI::Range(2, 32));
    // CLI::Range lets NaN through (every comparison with it is false), so "--fov nan" is refused here.
    const auto notNan = CLI::Validator(
        [](const std::string& s) {
            return std::isnan(std::strtod(s.c_str(), nullptr)) ? "expected a number, got '" + s + "'" : std::string();
        },
        "NUMBER");
    auto* fovFlag = cli.add_option("--fov", o.fov, "Vertical field of view in degrees")
                        ->capture_default_str()
                        ->check(notNan)
                        ->check(CLI::Range(30.0, 120.0));
    auto* vsyncFlag =
        cli.add_option("--vsync", o.vsync, "Window: wait for vertical sync (true/false)")->capture_default_str();

    ParseOutcome out;
    try {
        cli.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        out.output = cli.help();
        return out;
    } catch (const CLI::CallForVersion&) {
        out.output = std::string("minecrappy ") + MC_VERSION + "\n";
        return out;
    } catch (const CLI::ParseError& e) {
        out.exitCode = 2;
        out.output = std::string("minecrappy: ") + e.what() + "\nRun with --help for the flags.\n";
        return out;
    }
    parseSize(size, o.width, o.height);
    o.given = {sizeFlag->count() > 0, tickRateFlag->count() > 0, viewRadiusFlag->count() > 0, fovFlag->count() > 0,
               vsyncFlag->count() > 0};
    if (settingsFile == "none") {
        o.settingsFile.reset();
    } else {
        o.settingsFile = settingsFile;
    }
    o.terrain = *world::terrainFromName(terrain);
    if (!o.headless) {
        for (const auto& [flag, value] :
             {std::pair{"--screenshot", &o.screenshot}, std::pair{"--frame-stats", &o.frameStats},
              std::pair{"--soak-report", &o.soakReport}}) {
            if (!value->empty()) {
                out.exitCode = 2;
                out.output = std::string("minecrappy: ") + flag + " needs --headless\n";
                return out;
            }
        }
    }
    out.options = o;
    return out;
}

void mergeSettings(Options& options, Settings& settings) {
    const GivenFlags& g = options.given;
    auto merge = [](bool given, auto& flag, auto& setting) {
        if (given) {
            setting = flag;
        } else {
            flag = setting;
        }
    };
    merge(g.size, options.width, settings.windowWidth);
    merge(g.size, options.height, settings.windowHeight);
    merge(g.tickRate, options.tickRate, settings.tickRate);
    merge(g.viewRadius, options.viewRadius, settings.viewRadius);
    merge(g.fov, options.fov, settings.fov);
    merge(g.vsync, options.vsync, settings.vsync);
}

} // namespace app
