#include "session/options.h"

#include "core/atomic_file.h"
#include "core/log.h"

#include <fcntl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "game/day_clock.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace session {

namespace {

// Peak resident memory of `minecrappy --headless --settings none --ticks 1 --size WxH --screenshot a.png`,
// measured with /usr/bin/time -v (maximum resident set size) on this project's x86-64 machine with
// OSMesa (llvmpipe): 161 MiB at 256x256, 245 MiB at 2048x2048, 491 MiB at 4096x4096, 1463 MiB at
// 8192x8192. The growth is 20.4 bytes per pixel between each pair (colour and depth buffers of the GL
// context, the read-back image, PNG encoding); the issue saw 5.5 GB at 16384x16384, the same slope.
// Rounded up to leave some margin.
constexpr std::uint64_t kFrameBytesPerPixel = 21;
constexpr std::uint64_t kBaseRunBytes = std::uint64_t{170} << 20; // the run without its frame

std::string lower(std::string s) {
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
}

// A value as it may be quoted in a message: one line, not a screenful.
std::string shortQuote(const std::string& s) { return "'" + (s.size() > 40 ? s.substr(0, 37) + "..." : s) + "'"; }

std::string gigabytes(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GB", static_cast<double>(bytes) / 1e9);
    return text;
}

// errno of trying to create a new file in `folder`; 0 when that works. The file is removed again. A real
// attempt, not access(): it also sees read-only mounts, sysfs and /proc, and root's writes refused there.
int tryCreateIn(const std::filesystem::path& folder) {
    const std::filesystem::path probe =
        folder / (".minecrappy-write-test-" + std::to_string(static_cast<long>(::getpid())));
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) return errno;
    ::close(fd);
    ::unlink(probe.c_str());
    return 0;
}

enum class Output {
    File,            // a file by core::writeOutput's rule: its folder must exist
    FolderMakingDirs // a folder the writer creates when missing (--screenshot-dir, --capture-dir)
};

// Why `path` cannot be written as `kind`, "" when nothing stops it. Files follow core::writeOutput's rule
// (core/atomic_file.h); a FIFO is not opened here, since closing it would end its reader's input.
std::string outputProblem(const std::filesystem::path& path, Output kind) {
    const auto withReason = [&](int error) { return "cannot write '" + path.string() + "': " + std::strerror(error); };
    if (kind == Output::File) {
        core::OutputPath out;
        try {
            out = core::resolveOutput(path);
        } catch (const core::OutputError& e) {
            return e.what();
        }
        if (out.kind == core::OutputPath::Kind::InPlace)
            return ::access(out.resolved.c_str(), W_OK) == 0 ? std::string() : withReason(errno);
        const std::filesystem::path folder = out.resolved.has_parent_path() ? out.resolved.parent_path() : ".";
        const int error = tryCreateIn(folder);
        return error == 0 ? std::string() : withReason(error);
    }
    if (std::string link = core::brokenLinkOnPath(path); !link.empty()) return "cannot make the folder: " + link;
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (status.type() != std::filesystem::file_type::not_found && !ec) {
        if (status.type() != std::filesystem::file_type::directory) return withReason(ENOTDIR);
        const int error = tryCreateIn(path);
        return error == 0 ? std::string() : withReason(error);
    }
    // Walk up to the folder that exists: the writer creates the rest below it.
    std::filesystem::path folder = path.parent_path();
    while (!folder.empty() && std::filesystem::status(folder, ec).type() == std::filesystem::file_type::not_found)
        folder = folder.parent_path();
    if (folder.empty()) folder = ".";
    const auto folderStatus = std::filesystem::status(folder, ec);
    if (ec) return withReason(ec.value()); // e.g. a folder on the way that may not be searched: EACCES
    if (folderStatus.type() != std::filesystem::file_type::directory) return withReason(ENOTDIR);
    const int error = tryCreateIn(folder);
    return error == 0 ? std::string() : withReason(error);
}

// CLI11 would wrap "-3" into a huge unsigned number and saturate one above 2^64-1: refuse both before
// conversion.
CLI::Validator unsignedIntegerValidator() {
    return CLI::Validator(
        [](const std::string& s) {
            if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
                return "expected a non-negative whole number, got " + shortQuote(s);
            std::uint64_t value = 0;
            if (std::from_chars(s.data(), s.data() + s.size(), value).ec == std::errc::result_out_of_range)
                return shortQuote(s) + " is above 2^64-1 (18446744073709551615), the largest it takes";
            return std::string();
        },
        "UINT");
}

// The screenshot is always PNG; a .jpg name would hold PNG bytes that other programs misread.
CLI::Validator pngNameValidator() {
    return CLI::Validator(
        [](const std::string& s) {
            return s.size() >= 4 && lower(s.substr(s.size() - 4)) == ".png"
                       ? std::string()
                       : "writes PNG: the file name must end in .png, got " + shortQuote(s);
        },
        "FILE.png");
}

// A setting's flag is checked by its row (session/setting_table.h): the type, the range, NaN.
CLI::Validator settingValidator(const SettingRow& row) {
    return CLI::Validator(
        [&row](const std::string& s) {
            Settings scratch;
            const std::string problem = parseSetting(row, s, scratch);
            return problem.empty() ? problem : problem + ", got " + shortQuote(s);
        },
        "");
}

// The word --help shows for the row's value.
const char* settingTypeName(const SettingRow& row) {
    return row.type == SettingType::Size ? "WxH" : row.type == SettingType::Bool ? "BOOL" : "NUMBER";
}

// The flag's help: the row's help on one line, its range and unit.
std::string settingHelp(const SettingRow& row) {
    std::string help(row.help);
    std::replace(help.begin(), help.end(), '\n', ' ');
    if (row.type != SettingType::Bool) {
        help += " (" + settingRangeText(row);
        if (!row.unit.empty()) help += ", " + std::string(row.unit);
        help += ")";
    }
    return help;
}

// The checks across flags once every flag parsed (and what the parsed text becomes): the problem, empty when
// none.
std::string finishOptions(Options& o, const std::array<std::string, kSettingRows.size()>& settingTexts,
                          const std::string& terrain, const std::string& settingsFile) {
    for (std::size_t i = 0; i < kSettingRows.size(); ++i)
        if (o.given.settings[i]) parseSetting(kSettingRows[i], settingTexts[i], o.settings); // checked by the flag
    if (settingsFile == "none") {
        o.settingsFile.reset();
    } else {
        o.settingsFile = settingsFile;
    }
    o.terrain = *world::terrainFromName(terrain);
    // Headless plays no world file unless one is named, so "none" means the same as in the window:
    // nothing is saved (rather than a file called none).
    if (o.headless && o.world == "none") o.world.clear();
    if (o.headless && o.given.setting("size")) {
        std::string problem = frameMemoryProblem("--size " + settingText(*findSetting("size"), o.settings),
                                                 o.settings.size.width, o.settings.size.height, availableMemoryBytes());
        if (!problem.empty()) return problem;
    }
    if (!o.headless) {
        for (const auto& [flag, value] :
             {std::pair{"--screenshot", &o.screenshot}, std::pair{"--frame-stats", &o.frameStats},
              std::pair{"--soak-report", &o.soakReport}, std::pair{"--capture-dir", &o.captureDir}}) {
            if (!value->empty()) return std::string(flag) + " needs --headless";
        }
    }
    if (o.glBackend != "auto" && o.glBackend != "osmesa" && o.glBackend != "egl") // from the environment
        return "MINECRAPPY_GL_BACKEND=" + o.glBackend + ": expected auto, osmesa or egl";
    if ((o.captureEvery > 0) != !o.captureDir.empty())
        return o.captureEvery > 0 ? "--capture-every needs --capture-dir" : "--capture-dir needs --capture-every";
    if (o.seek) {
        const std::string seek = "--seek " + std::to_string(*o.seek);
        if (!o.headless) return seek + " needs --headless";
        if (o.script.empty()) return seek + " needs --replay or --script: the run to seek in";
        if (!o.record.empty()) return seek + " with --record: a run that records starts at its first tick";
    }
    return {};
}
} // namespace

ParseOutcome parseOptions(int argc, const char* const* argv) {
    Options o;
    CLI::App cli{"Minecrappy: a voxel sandbox that is also a physics lab.\n"
                 "Without --headless it opens a window; with --headless it runs a fixed number of ticks\n"
                 "off-screen (OSMesa) and can write a PNG and a JSON state dump.",
                 "minecrappy"};
    cli.set_version_flag("--version", std::string("minecrappy ") + MC_VERSION);
    std::string terrain = "default";
    std::string settingsFile = o.settingsFile->string();

    cli.add_flag("--headless", o.headless, "Run off-screen without a window");
    const CLI::Validator unsignedInteger = unsignedIntegerValidator(), pngName = pngNameValidator();
    cli.add_option("--settings", settingsFile,
                   "Settings file (created with commented defaults if missing); 'none': built-in defaults, "
                   "nothing read or written")
        ->capture_default_str();
    cli.add_option("--ticks", o.ticks, "Headless: number of ticks to simulate")
        ->capture_default_str()
        ->check(unsignedInteger);
    auto* seedFlag = cli.add_option("--seed", o.seed, "World seed")->capture_default_str()->check(unsignedInteger);
    std::string timeOfDay;
    auto* timeFlag = cli.add_option("--time-of-day", timeOfDay,
                                    "Start at this hour, 0 to 24 (12 noon, 18 sunset, 0 midnight); a loaded world too")
                         ->check(CLI::Validator(
                             [](const std::string& s) {
                                 try {
                                     (void)game::parseHours(s);
                                     return std::string();
                                 } catch (const std::invalid_argument& e) {
                                     return std::string(e.what());
                                 }
                             },
                             "HOURS"));
    auto* terrainFlag = cli.add_option("--terrain", terrain, "Terrain: default or flat")
                            ->capture_default_str()
                            ->check(CLI::IsMember({"default", "flat"}));
    auto* scriptFlag =
        cli.add_option("--script", o.script, "Input script: one 'TICK COMMAND ARGS' per line (see docs/SCRIPTS.md)")
            ->check(CLI::ExistingFile);
    std::string replay;
    cli.add_option("--replay", replay, "Replay this recording (written by --record); a file that is not one is refused")
        ->check(CLI::ExistingFile)
        ->excludes(scriptFlag);
    std::uint64_t seek = 0;
    auto* seekFlag = cli.add_option("--seek", seek,
                                    "Headless, with --replay or --script: bring the run to this tick first; --ticks "
                                    "then counts from it, and pictures and the state dump are of the ticks from it")
                         ->check(unsignedInteger);
    cli.add_option("--screenshot", o.screenshot, "Headless: write the final frame to this PNG")->check(pngName);
    cli.add_option("--dump-state", o.dumpState, "Write the final game state as JSON to this file");
    cli.add_option("--screenshot-scale", o.screenshotScale,
                   "F2 and --screenshot: render the picture this many times larger than the frame, 1..8 "
                   "(a 1280x720 window gives 5120x2880 at 4), HUD scaled alike")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    cli.add_option("--capture-every", o.captureEvery,
                   "Headless: write a frame every N ticks into --capture-dir (frame-TTTTTT.png), for a clip")
        ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
    cli.add_option("--capture-dir", o.captureDir, "Headless: the folder --capture-every writes into (made if missing)");
    if (const char* env = std::getenv("MINECRAPPY_GL_BACKEND"); env && *env) o.glBackend = env;
    cli.add_option("--gl-backend", o.glBackend,
                   "Headless: off-screen OpenGL through osmesa, egl, or auto (OSMesa when present, else EGL); "
                   "default $MINECRAPPY_GL_BACKEND or auto")
        ->capture_default_str()
        ->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cli.add_option("--gamepad-mappings", o.gamepadMappings,
                   "Window: extra gamepad mappings, SDL's gamecontrollerdb.txt format (default: the config "
                   "folder's gamecontrollerdb.txt, if any)")
        ->check(CLI::ExistingFile);
    cli.add_option("--record", o.record,
                   "Record this session (every tick's input and panel edits, with state hashes) to this file; "
                   "replay it headless with --script");
    cli.add_option("--frame-stats", o.frameStats,
                   "Headless benchmark: render every tick and write frame times, triangles, draw calls, meshing, GPU "
                   "wait, fragments per pixel (every 30th frame), the slowest frames and peak memory as JSON "
                   "(docs/ENGINE.md)");
    cli.add_option("--soak-report", o.soakReport,
                   "Headless soak: check energy bounds, NaN, memory and tick time every game minute, write them "
                   "as JSON here and exit 1 if a check failed");
    cli.add_option("--soak-tick-budget-ms", o.soakTickBudgetMs,
                   "Headless soak: CPU time one tick may take; 0 means one tick period (16.7 ms at 60 Hz)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1000.0));
    auto* screenshotDirFlag =
        cli.add_option("--screenshot-dir", o.screenshotDir, "Folder for F2 screenshots")->capture_default_str();
    cli.add_option("--world", o.world,
                   "World file (SQLite): loaded if it exists, else created; autosaved. The window uses "
                   "WORLDS/default.mcworld unless given; 'none' plays without saving (both modes)");
    cli.add_flag("--save", o.saveAtEnd, "Headless: save the world when the run ends (autosaves happen anyway)");
    cli.add_option("--autosave-ticks", o.autosaveTicks, "Autosave every this many ticks of game time")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    cli.add_option("--worlds-dir", o.worldsFolder,
                   "Window: folder of the world list (default: the user's data folder)");
    // The settings that have a flag, from their rows: each flag's text is read into o.settings once parsed.
    std::array<std::string, kSettingRows.size()> settingTexts;
    std::array<CLI::Option*, kSettingRows.size()> settingFlags{};
    for (std::size_t i = 0; i < kSettingRows.size(); ++i) {
        const SettingRow& row = kSettingRows[i];
        if (row.flag.empty()) continue;
        settingTexts[i] = settingDefaultText(row);
        settingFlags[i] = cli.add_option(std::string(row.flag), settingTexts[i], settingHelp(row))
                              ->capture_default_str()
                              ->type_name(settingTypeName(row))
                              ->check(settingValidator(row));
    }

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
        out.output = core::errorLine(e.what()) + "\nRun with --help for the flags.\n";
        return out;
    }
    for (std::size_t i = 0; i < kSettingRows.size(); ++i)
        o.given.settings[i] = settingFlags[i] != nullptr && settingFlags[i]->count() > 0;
    o.given.screenshotDir = screenshotDirFlag->count() > 0;
    o.given.seed = seedFlag->count() > 0;
    o.given.terrain = terrainFlag->count() > 0;
    if (timeFlag->count() > 0) o.timeOfDay = game::parseHours(timeOfDay);
    if (!replay.empty()) o.script = replay, o.replay = true;
    if (seekFlag->count() > 0) o.seek = seek;
    if (const std::string problem = finishOptions(o, settingTexts, terrain, settingsFile); !problem.empty()) {
        out.exitCode = 2;
        out.output = core::errorLine(problem) + "\n";
        return out;
    }
    out.options = o;
    return out;
}

std::string checkOutputPaths(const Options& o) {
    const struct {
        const char* flag;
        const std::string& path;
        Output kind;
    } outputs[] = {
        {"--screenshot", o.screenshot, Output::File},
        {"--dump-state", o.dumpState, Output::File},
        {"--frame-stats", o.frameStats, Output::File},
        {"--soak-report", o.soakReport, Output::File},
        {"--record", o.record, Output::File},
        {"--capture-dir", o.captureDir, Output::FolderMakingDirs},
        {"--screenshot-dir", o.given.screenshotDir ? o.screenshotDir : std::string(), Output::FolderMakingDirs},
    };
    for (const auto& out : outputs) {
        if (out.path.empty()) continue;
        if (const std::string problem = outputProblem(out.path, out.kind); !problem.empty())
            return std::string(out.flag) + ": " + problem;
    }
    return {};
}

std::uint64_t estimatedFrameBytes(int width, int height) {
    const auto pixels =
        static_cast<std::uint64_t>(std::max(width, 0)) * static_cast<std::uint64_t>(std::max(height, 0));
    return kBaseRunBytes + kFrameBytesPerPixel * pixels;
}

std::optional<std::uint64_t> availableMemoryBytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::uint64_t kib = 0;
    std::string unit;
    while (in >> key >> kib >> unit) {
        if (key == "MemAvailable:") return kib * 1024;
    }
    return std::nullopt;
}

std::string frameMemoryProblem(const std::string& what, int width, int height, std::optional<std::uint64_t> available) {
    if (!available) return {};
    const std::uint64_t need = estimatedFrameBytes(width, height);
    // Half: the rest of the machine (and this process's other allocations) keep their room.
    if (need <= *available / 2) return {};
    return what + ": a headless frame of " + std::to_string(width) + "x" + std::to_string(height) + " needs about " +
           gigabytes(need) + " of memory (" + std::to_string(kFrameBytesPerPixel) +
           " bytes per pixel), more than half of the " + gigabytes(*available) +
           " available (MemAvailable); choose a smaller size";
}

bool GivenFlags::setting(std::string_view key) const {
    for (std::size_t i = 0; i < kSettingRows.size(); ++i)
        if (kSettingRows[i].key == key) return settings[i];
    return false;
}

void mergeSettings(Options& options, Settings& settings) {
    for (std::size_t i = 0; i < kSettingRows.size(); ++i)
        if (options.given.settings[i]) copySetting(kSettingRows[i], options.settings, settings);
    options.settings = settings;
}

} // namespace session
