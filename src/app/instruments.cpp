#include "app/instruments.h"

#include <chrono>
#include <cstdint>

#include "render/fragment_counter.h"
#include "render/gl_loader.h"
#include "session/diagnostics.h"

namespace app {

namespace {

// --frame-stats: after every tick a frame drawn as the window would (its meshing budget), timed from the first
// call to the end of the wait for the frame before it, with its triangles, draw calls and chunk work; the
// overdraw counted on some frames.
class FrameSampler final : public Instrument {
public:
    FrameSampler(const session::Options& o, const session::Session& session, glm::ivec2 size)
        : m_path(o.frameStats), m_width(o.settings.size.width), m_height(o.settings.size.height),
          m_viewRadius(o.settings.viewRadius), m_size(size) {
        m_frame.size = size;
        m_frame.seconds = session.tickSeconds();
    }

    void afterTick(Frontend& frontend, render::RenderContext& context, const session::Session& session) override {
        using Clock = std::chrono::steady_clock;
        const auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
        const std::uint64_t callsBefore = render::drawCallsIssued();
        const auto start = Clock::now();
        frontend.sceneSettings().meshBudgetSeconds = kWindowMeshBudget;
        // Counting fragments costs llvmpipe about 2 ms a frame, so only every kCountFragmentsEvery-th frame
        // counts them (docs/ENGINE.md), and only once the count before was read (one query).
        const bool countFragments = m_stats.frames() % kCountFragmentsEvery == 0 && m_counted == kNoFrame;
        if (countFragments) m_fragments.begin();
        frontend.draw(m_frame);
        if (countFragments) m_fragments.end();
        const auto issued = Clock::now();
        context.submit(); // the wait for the frame before this one to finish
        const auto finished = Clock::now();
        const auto& chunks = frontend.scene().stats().chunks;
        session::FrameSample sample;
        sample.frameMs = ms(finished - start);
        sample.triangles = static_cast<double>(chunks.triangles);
        sample.drawCalls = static_cast<double>(render::drawCallsIssued() - callsBefore);
        sample.chunksDrawn = chunks.drawn;
        sample.meshMs = chunks.meshMs;
        sample.gpuWaitMs = ms(finished - issued);
        // The frame that counted is finished once this one is submitted: read its count now, so the reading
        // never waits for a frame in flight.
        readCount();
        if (countFragments) m_counted = m_stats.frames();
        sample.tick = session.state().tick;
        sample.pendingChunks = chunks.pending;
        sample.chunksMeshed = chunks.meshedThisFrame;
        sample.staleChunks = chunks.stale;
        sample.completedLate = chunks.completedLate;
        m_stats.add(sample);
    }

    bool finish() override {
        readCount();
        m_stats.write(m_path, m_width, m_height, m_viewRadius);
        return true;
    }

private:
    static constexpr double kWindowMeshBudget = 0.004; // s, as the window meshes
    static constexpr std::size_t kCountFragmentsEvery = 30;
    // No frame's fragments are being counted. Not an optional: GCC 12 takes its value for uninitialised at
    // -O3 (-Wmaybe-uninitialized).
    static constexpr std::size_t kNoFrame = SIZE_MAX;

    void readCount() {
        if (m_counted == kNoFrame) return;
        const double pixels = static_cast<double>(m_size.x) * static_cast<double>(m_size.y);
        m_stats.setFragmentsPerPixel(m_counted, static_cast<double>(m_fragments.result()) / pixels);
        m_counted = kNoFrame;
    }

    std::string m_path;
    int m_width, m_height, m_viewRadius;
    glm::ivec2 m_size;
    FrameRequest m_frame; // a frame after a tick: alpha 1, no mouse motion unconsumed
    session::FrameStats m_stats;
    render::FragmentCounter m_fragments;
    std::size_t m_counted = kNoFrame; // the frame whose fragments are counted, until its count is read
};

// --soak-report: each tick's CPU time against the budget and the pendulums' energy (session::SoakMonitor).
class Soak final : public Instrument {
public:
    Soak(const session::Options& o, session::Session& session)
        : m_path(o.soakReport),
          m_monitor(static_cast<std::uint64_t>(o.settings.tickRate) * 60,
                    o.soakTickBudgetMs > 0.0 ? o.soakTickBudgetMs : 1000.0 * session.tickSeconds()) {
        session::SoakMonitor::setUp(session);
    }
    void beforeStep() override { m_tickStart = session::SoakMonitor::threadCpuMs(); }
    void afterStep(const session::Session& session) override {
        m_monitor.afterTick(session.state(), session::SoakMonitor::threadCpuMs() - m_tickStart);
    }
    bool finish() override { return m_monitor.finish(m_path); }

private:
    std::string m_path;
    session::SoakMonitor m_monitor;
    double m_tickStart = 0.0;
};

} // namespace

std::vector<std::unique_ptr<Instrument>> makeInstruments(const session::Options& o, session::Session& session,
                                                         glm::ivec2 frameSize) {
    std::vector<std::unique_ptr<Instrument>> out;
    // The soak's report first, then the frame statistics (the order their files are written in).
    if (!o.soakReport.empty()) out.push_back(std::make_unique<Soak>(o, session));
    if (!o.frameStats.empty()) out.push_back(std::make_unique<FrameSampler>(o, session, frameSize));
    return out;
}

} // namespace app
