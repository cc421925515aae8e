// minecrappy: the game. Parses the command line and runs the window or the headless twin.
#include <cstdio>
#include <exception>
#include <string>

#include "app/options.h"
#include "app/runners.h"
#include "input/script.h"
#include "render/context.h"
#include "render/context_glfw.h"
#include "save/world_store.h"

int main(int argc, char** argv) {
    const app::ParseOutcome parsed = app::parseOptions(argc, argv);
    if (!parsed.options) {
        std::fputs(parsed.output.c_str(), parsed.exitCode == 0 ? stdout : stderr);
        return parsed.exitCode;
    }
    app::Options o = *parsed.options;
    app::Settings settings;
    if (o.settingsFile) {
        // A bad value is reported and replaced by its default; the game still starts.
        app::SettingsLoad loaded = app::loadSettings(*o.settingsFile);
        for (const auto& w : loaded.warnings) std::fprintf(stderr, "minecrappy: warning: %s\n", w.c_str());
        if (loaded.created) std::fprintf(stderr, "minecrappy: wrote default settings to %s\n", o.settingsFile->c_str());
        settings = loaded.settings;
    }
    app::mergeSettings(o, settings);
    // The settings file's window size is the headless frame size too when --size is not given.
    if (o.headless && !o.given.size) {
        const std::string from = o.settingsFile ? o.settingsFile->string() : std::string("the built-in defaults");
        const std::string problem =
            app::frameMemoryProblem("window size from " + from, o.width, o.height, app::availableMemoryBytes());
        if (!problem.empty()) {
            std::fprintf(stderr, "minecrappy: %s\n", problem.c_str());
            return 2;
        }
    }
    // Before the first tick: an hour-long run must not end in "cannot write" with nothing to show.
    if (const std::string problem = app::checkOutputPaths(o); !problem.empty()) {
        std::fprintf(stderr, "minecrappy: %s\n", problem.c_str());
        return 2;
    }
    try {
        if (!o.headless && !render::GlfwWindow::displayAvailable()) {
            std::fprintf(
                stderr, "minecrappy: no display found (DISPLAY and WAYLAND_DISPLAY are unset), so no window can open.\n"
                        "Run it off-screen instead, e.g.: minecrappy --headless --ticks 60 --screenshot demo.png\n");
            return 1;
        }
        return o.headless ? app::runHeadless(o, settings) : app::runWindowed(o, settings);
    } catch (const save::WorldFileError& e) {
        std::fprintf(stderr, "minecrappy: %s\n", e.what());
        return 2;
    } catch (const input::ScriptError& e) {
        std::fprintf(stderr, "minecrappy: %s\n", e.what());
        return 2;
    } catch (const render::RenderError& e) {
        std::fprintf(stderr, "minecrappy: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "minecrappy: %s\n", e.what());
        return 1;
    }
}
