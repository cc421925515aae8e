// minecrappy: the game. Parses the command line and runs the window or the headless twin.
#include <malloc.h>

#include <cstdio>
#include <exception>
#include <string>

#include "app/runners.h"
#include "core/atomic_file.h"
#include "core/log.h"
#include "input/script.h"
#include "platform/glfw_window.h"
#include "save/world_store.h"
#include "session/options.h"
#include "session/recording.h"
#include "session/session.h"

int main(int argc, char** argv) {
    // Under llvmpipe the driver allocates the binned frame while the game thread issues the draws (tens of
    // MiB at radius 12 without the level of detail) and frees it once the frame is drawn. glibc gave the
    // freed top of the heap back to the kernel each time and took it again with the next frame's page
    // faults (13,678 brk calls in 300 frames; frames of 120-140 ms once a frame stays in flight). Keeping
    // up to 128 MiB freed leaves 526 brk calls and no such frames (docs/ENGINE.md, "One frame in flight").
    mallopt(M_TRIM_THRESHOLD, 128 * 1024 * 1024);
    // Setting the trim threshold fixes glibc's mmap threshold at 128 KiB, so every block of that size or more
    // (a chunk's mesh, a terrain footprint, a light region's field) was mapped fresh, faulted in page by page
    // and unmapped again on free, with a TLB flush on both cores: about a sixth of the CPU time spent meshing
    // a view (perf, radius 16). Blocks under 32 MiB come from the heap instead, and are reused.
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
    const session::ParseOutcome parsed = session::parseOptions(argc, argv);
    if (!parsed.options) {
        std::fputs(parsed.output.c_str(), parsed.exitCode == 0 ? stdout : stderr);
        return parsed.exitCode;
    }
    session::Options o = *parsed.options;
    session::Settings settings;
    if (o.settingsFile) {
        // A bad value is reported and replaced by its default; the game still starts.
        session::SettingsLoad loaded = session::loadSettings(*o.settingsFile);
        for (const auto& w : loaded.warnings) core::logWarn("%s", w.c_str());
        for (const auto& n : loaded.notes) core::logNote("%s", n.c_str());
        if (loaded.created) core::logNote("wrote default settings to %s", o.settingsFile->c_str());
        settings = loaded.settings;
    }
    session::mergeSettings(o, settings);
    // The settings file's window size is the headless frame size too when --size is not given.
    if (o.headless && !o.given.setting("size")) {
        const std::string from = o.settingsFile ? o.settingsFile->string() : std::string("the built-in defaults");
        const std::string problem = session::frameMemoryProblem(
            "window size from " + from, o.settings.size.width, o.settings.size.height, session::availableMemoryBytes());
        if (!problem.empty()) {
            core::logError("%s", problem.c_str());
            return 2;
        }
    }
    // Before the first tick: an hour-long run must not end in "cannot write" with nothing to show.
    if (const std::string problem = session::checkOutputPaths(o); !problem.empty()) {
        core::logError("%s", problem.c_str());
        return 2;
    }
    try {
        if (!o.headless && !platform::GlfwWindow::displayAvailable()) {
            core::logError("no display found (DISPLAY and WAYLAND_DISPLAY are unset), so no window can open.\n"
                           "Run it off-screen instead, e.g.: minecrappy --headless --ticks 60 --screenshot demo.png");
            return 1;
        }
        return o.headless ? app::runHeadless(o) : app::runWindowed(o);
    } catch (const session::ReplayDiverged& e) {
        core::logError("%s", e.what());
        return 3; // the replay is not the recorded session: told apart from bad input and failures
    } catch (const std::exception& e) {
        core::logError("%s", e.what());
        // A world file or a script the user gave is bad input (2), and so is an output that cannot be written
        // (a path the output rule refuses, a full disk: core::OutputError); anything else is a runtime failure.
        const bool badInput = dynamic_cast<const save::WorldFileError*>(&e) ||
                              dynamic_cast<const input::ScriptError*>(&e) ||
                              dynamic_cast<const core::OutputError*>(&e) || dynamic_cast<const session::SeekError*>(&e);
        return badInput ? 2 : 1;
    }
}
