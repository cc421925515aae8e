#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>

#include "app/panels.h"
#include "app/runners.h"
#include "app/session.h"
#include "render/context_osmesa.h"
#include "render/data_dir.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"
#include "ui/ui.h"

namespace app {

namespace {

struct Frame {
    render::OsMesaContext& context;
    render::SceneRenderer& scene;
    ui::ImGuiLayer& imgui;
    ObjectPanels& panels;
};

// Draws the current state (alpha = 1: headless has no time between ticks) with the HUD. A lone frame
// (a screenshot) first lays the UI out once without drawing it: Dear ImGui sizes auto-fitting windows
// on their first frame and shows them from the second.
void drawFrame(Frame& f, Session& s, const render::SceneSettings& settings, const ui::HudMessage& message,
               bool& overlay, bool& help, bool lone) {
    const glm::ivec2 size = f.context.framebufferSize();
    f.scene.render(s.state(), render::interpolatedCamera(s.state(), 1.0f), size, settings);
    for (int pass = lone ? 0 : 1; pass < 2; ++pass) {
        f.imgui.beginFrame(size, static_cast<float>(s.tickSeconds()));
        ui::drawPendulumLabels(s.state(), f.scene, 1.0f);
        ui::drawHud(s.state(), f.scene.atlas(), message);
        f.panels.show(s);
        if (overlay) {
            ui::OverlayInfo info;
            info.chunks = f.scene.stats().chunks;
            info.renderCpuMs = f.scene.stats().cpuMs;
            ui::showOverlayPanel(s.state(), info, &overlay);
        }
        if (help) ui::showHelpPanel(&help);
        if (s.state().paused) ui::showPausePanel(&help);
        if (pass == 0) {
            f.imgui.discardFrame();
        } else {
            f.imgui.endFrame();
        }
    }
    f.context.present();
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const auto i = static_cast<std::size_t>(std::min<double>(static_cast<double>(v.size() - 1), p * static_cast<double>(v.size() - 1) + 0.5));
    return v[i];
}

} // namespace

int runHeadless(const Options& o, const Settings& userSettings) {
    Session session(o, userSettings);
    for (const auto& w : session.loadWarnings()) std::fprintf(stderr, "minecrappy: warning: %s\n", w.c_str());
    if (session.hasWorld()) std::printf("world: %s (tick %llu)\n", session.worldPath().c_str(), static_cast<unsigned long long>(session.state().tick));
    render::OsMesaContext context(o.width, o.height);
    const auto data = render::dataDir();
    render::SceneRenderer scene(data);
    ui::ImGuiLayer imgui(nullptr);
    ObjectPanels panels;
    Frame frame{context, scene, imgui, panels};

    render::SceneSettings settings;
    settings.fovDegrees = o.fov;
    settings.viewRadius = o.viewRadius;
    // Screenshots must not depend on how fast this machine meshes: stream everything in range first.
    settings.meshBudgetSeconds = 0.0;

    const bool benchmark = !o.frameStats.empty();
    render::SceneSettings benchSettings = settings;
    benchSettings.meshBudgetSeconds = 0.004; // as the window does
    std::vector<double> frameMs;
    double trianglesSum = 0.0, drawnSum = 0.0;
    bool overlay = false, help = false;
    ui::HudMessage message;

    int exitCode = 0;
    for (std::uint64_t t = 0; t < o.ticks; ++t) {
        const AppRequests r = session.step();
        for (const auto& e : session.takeSaveErrors()) { // keep playing: the last good save stays on disk
            std::fprintf(stderr, "minecrappy: autosave failed: %s\n", e.c_str());
            message = {"Autosave failed: " + e, 5.0};
        }
        overlay ^= r.toggleOverlay;
        help ^= r.toggleHelp;
        if (r.interact) panels.interact(session.state());
        message.secondsLeft -= session.tickSeconds();
        if (benchmark) {
            const auto start = std::chrono::steady_clock::now();
            drawFrame(frame, session, benchSettings, message, overlay, help, false);
            frameMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            trianglesSum += static_cast<double>(scene.stats().chunks.triangles);
            drawnSum += scene.stats().chunks.drawn;
        }
        if (r.screenshot) {
            drawFrame(frame, session, settings, message, overlay, help, true);
            char name[64];
            std::snprintf(name, sizeof name, "minecrappy-tick-%06llu", static_cast<unsigned long long>(session.state().tick));
            std::filesystem::path path = std::filesystem::path(o.screenshotDir) / (std::string(name) + ".png");
            for (int n = 2; std::filesystem::exists(path); ++n) {
                path = std::filesystem::path(o.screenshotDir) / (std::string(name) + "-" + std::to_string(n) + ".png");
            }
            render::writePng(render::readFramebuffer(o.width, o.height), path);
            std::printf("screenshot: %s\n", path.c_str());
            message = {"Saved " + path.string(), 3.0};
        }
    }

    if (!o.screenshot.empty()) {
        drawFrame(frame, session, settings, message, overlay, help, true);
        render::writePng(render::readFramebuffer(o.width, o.height), o.screenshot);
        std::printf("wrote %s\n", o.screenshot.c_str());
    }
    if (o.saveAtEnd && session.hasWorld()) {
        const auto errors = session.saveNow();
        for (const auto& e : errors) std::fprintf(stderr, "minecrappy: save failed: %s\n", e.c_str());
        if (errors.empty()) {
            std::printf("saved %s\n", session.worldPath().c_str());
        } else {
            exitCode = 1;
        }
    }
    if (!o.dumpState.empty()) {
        session.writeDump(o.dumpState);
        std::printf("wrote %s\n", o.dumpState.c_str());
    }
    if (benchmark) {
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        const double sum = std::accumulate(frameMs.begin(), frameMs.end(), 0.0);
        nlohmann::json stats = {
            {"frames", frameMs.size()},
            {"size", {o.width, o.height}},
            {"view_radius", o.viewRadius},
            {"mean_ms", frameMs.empty() ? 0.0 : sum / static_cast<double>(frameMs.size())},
            {"median_ms", percentile(frameMs, 0.5)},
            {"p99_ms", percentile(frameMs, 0.99)},
            {"worst_ms", frameMs.empty() ? 0.0 : *std::max_element(frameMs.begin(), frameMs.end())},
            {"frames_over_50ms", std::count_if(frameMs.begin(), frameMs.end(), [](double v) { return v > 50.0; })},
            {"mean_triangles", frameMs.empty() ? 0.0 : trianglesSum / static_cast<double>(frameMs.size())},
            {"mean_chunks_drawn", frameMs.empty() ? 0.0 : drawnSum / static_cast<double>(frameMs.size())},
            {"peak_rss_mib", static_cast<double>(usage.ru_maxrss) / 1024.0},
        };
        std::ofstream out(o.frameStats);
        if (!out || !(out << stats.dump(2) << '\n')) throw std::runtime_error("cannot write " + o.frameStats);
        std::printf("frames %zu: median %.2f ms, p99 %.2f ms, worst %.2f ms, %.0f triangles, peak RSS %.0f MiB -> %s\n",
                    frameMs.size(), stats["median_ms"].get<double>(), stats["p99_ms"].get<double>(),
                    stats["worst_ms"].get<double>(), stats["mean_triangles"].get<double>(),
                    stats["peak_rss_mib"].get<double>(), o.frameStats.c_str());
    }
    return exitCode;
}

} // namespace app
