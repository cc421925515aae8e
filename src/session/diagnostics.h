// Instruments for long and timed runs of the game, kept out of the runners: the soak monitor
// (--soak-report) and the frame statistics (--frame-stats). GL-free; the headless runner feeds them.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "game/game_state.h"
#include "session/session.h"

namespace session {

// --soak-report: checks a long run once per game minute. Per tick it only reads the state (energy
// errors of 4 slots, a finite check of every hair node: microseconds); /proc is read once a minute.
// Bounds: the exact slot to 1e-9 of m g L; symplectic-euler and verlet conserve a nearby energy, so
// their error stays within kSymplecticFactor x what they reached in the first minute (measured in
// the same run, not guessed); RSS may grow by kRssGrowthMiB after minute kWarmupMinutes; a tick
// (Session::step: script events and game::tick) must fit in its own period. Ticks are timed in this
// thread's CPU time, not wall time: on a shared machine preemption alone made wall-time ticks of
// 20-48 ms out of a 0.4 ms mean, which says nothing about the game. Even CPU time has one-off
// outliers there (one tick of 18 ms in CI beside a 1.6-3.9 ms worst when run alone; a parallel test or
// the hypervisor stalls the thread mid-tick). The script repeats the same minute 60 times, so a
// slow path of the game shows up in many minutes; the soak therefore allows one isolated tick
// over budget in the hour, reports it as a warning, and fails on a second one.
class SoakMonitor {
public:
    static constexpr double kExactBound = 1e-9, kSymplecticFactor = 2.0, kRssGrowthMiB = 4.0;
    static constexpr int kWarmupMinutes = 5;
    static constexpr std::size_t kIsolatedOverBudget = 1;
    static constexpr const char* kMethods[3] = {"exact", "symplectic-euler", "verlet"};

    // This thread's CPU time in ms (what a tick is timed in).
    static double threadCpuMs();

    SoakMonitor(std::uint64_t ticksPerMinute, double budgetMs)
        : m_ticksPerMinute(ticksPerMinute), m_budgetMs(budgetMs) {}

    // Puts the methods the soak bounds into every set (exact, symplectic-euler, verlet) next to euler,
    // which blows up and must stay finite (marked diverged), and releases them.
    static void setUp(Session& session);
    void afterTick(const game::GameState& s, double tickMs);
    // Writes the report to path (throws std::runtime_error naming it), prints each failure; true when
    // every check passed.
    bool finish(const std::string& path);

private:
    struct Minute {
        std::uint64_t tick;
        std::array<double, 3> energy;
        std::set<std::string> nan;
        double rssMiB, longestMs;
    };
    void closeMinute(std::uint64_t tick);

    std::uint64_t m_ticksPerMinute;
    double m_budgetMs;
    std::array<double, 3> m_energy{};
    std::set<std::string> m_nan;
    double m_longestMs = 0.0;
    std::vector<Minute> m_minutes;
    std::vector<std::pair<std::uint64_t, double>> m_overBudget; // (tick, CPU ms) of every tick over budget
};

// --frame-stats: per drawn frame, its wall time and where that time and work went, summed up as JSON
// (docs/ENGINE.md): median, p99 and worst of frame time, triangles, draw calls, meshing time and GPU
// wait, and of fragments shaded per pixel over the frames that counted them; the mean frame, frames
// over 50 ms, chunks drawn and peak RSS; `views_completed`: every stretch of frames from one that
// left chunks pending (the start, a teleport, a fast walk) to the first with none, with its wall
// time; `after_load`: frame time without the loading at the start (the frames before the view first
// completed); `slowest`: the slowest frames, each with what it did.
struct FrameSample {
    double frameMs = 0.0;     // issuing the frame and waiting for the frame before it to finish
    double triangles = 0.0;   // chunk triangles drawn
    double drawCalls = 0.0;   // every draw call: chunks, sky, lines, hair, objects and UI
    double chunksDrawn = 0.0; // after frustum culling
    double meshMs = 0.0;      // generating and meshing chunks within the frame
    double gpuWaitMs = 0.0;   // after issuing it, waiting for the frame before it to finish (one in flight)
    // Fragments that passed the depth test, per pixel (1: no overdraw); counted on some frames only.
    std::optional<double> fragmentsPerPixel;
    std::uint64_t tick = 0; // the game tick the frame shows
    int pendingChunks = 0;  // chunks in range still without an up-to-date mesh after the frame
    int chunksMeshed = 0;   // meshes made ready this frame (by this thread or the worker)
    // Chunks showing a mesh older than their blocks and light after the frame (waiting for the worker after
    // an edit), and those the render thread meshed in it because they had waited too long (render::ChunkStreaming).
    int staleChunks = 0, completedLate = 0;
};

class FrameStats {
public:
    FrameStats(); // starts counting light's cost (world::countLightCost), which write() reports
    static constexpr std::size_t kSlowestListed = 10; // frames listed whole in "slowest"
    void add(const FrameSample& s) { m_samples.push_back(s); }
    // Fills in the fragments per pixel of frame i (counted from 0), read once that frame was drawn.
    void setFragmentsPerPixel(std::size_t i, double v) { m_samples.at(i).fragmentsPerPixel = v; }
    std::size_t frames() const { return m_samples.size(); }
    // Writes the summary to path (throws std::runtime_error naming it) and prints its one-line digest.
    void write(const std::string& path, int width, int height, int viewRadius) const;

private:
    std::vector<FrameSample> m_samples;
};

// The p-quantile of v (0..1) by nearest rank; 0 for an empty v.
double percentile(std::vector<double> v, double p);

} // namespace session
