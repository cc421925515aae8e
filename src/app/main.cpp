// minecrappy: the game. Parses the command line and runs the window or the headless twin.
#include <cstdio>
#include <exception>

#include "app/options.h"
#include "app/runners.h"
#include "input/script.h"
#include "render/context.h"
#include "render/context_glfw.h"

int main(int argc, char** argv) {
    const app::ParseOutcome parsed = app::parseOptions(argc, argv);
    if (!parsed.options) {
        std::fputs(parsed.output.c_str(), parsed.exitCode == 0 ? stdout : stderr);
        return parsed.exitCode;
    }
    const app::Options& o = *parsed.options;
    try {
        if (!o.headless && !render::GlfwWindow::displayAvailable()) {
            std::fprintf(stderr,
                         "minecrappy: no display found (DISPLAY and WAYLAND_DISPLAY are unset), so no window can open.\n"
                         "Run it off-screen instead, e.g.: minecrappy --headless --ticks 60 --screenshot demo.png\n");
            return 1;
        }
        return o.headless ? app::runHeadless(o) : app::runWindowed(o);
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
