// The run instruments (session/diagnostics.h): the soak monitor's verdicts and the frame statistics'
// summary, on runs short enough for a unit test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "session/diagnostics.h"
#include "session/session.h"

namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    return fs::temp_directory_path() / ("mc_diag_" + std::to_string(::getpid()) + "_" + name);
}

// The demo scene (pendulum sets and hair balls), no settings file.
session::Options demoOptions() {
    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    return o;
}

nlohmann::json readJson(const fs::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

TEST(Percentile, NearestRankOfTheSortedValues) {
    EXPECT_EQ(session::percentile({}, 0.5), 0.0);
    EXPECT_EQ(session::percentile({3.0, 1.0, 2.0}, 0.5), 2.0);
    EXPECT_EQ(session::percentile({3.0, 1.0, 2.0}, 0.0), 1.0);
    EXPECT_EQ(session::percentile({3.0, 1.0, 2.0}, 1.0), 3.0);
}

TEST(FrameStats, SummarisesTheFramesItWasGiven) {
    session::FrameStats stats;
    const auto sample = [](double ms, double triangles, double calls, double meshMs, double waitMs) {
        session::FrameSample f;
        f.frameMs = ms;
        f.triangles = triangles;
        f.drawCalls = calls;
        f.chunksDrawn = 10.0;
        f.meshMs = meshMs;
        f.gpuWaitMs = waitMs;
        if (static_cast<int>(ms) % 2 == 0) f.fragmentsPerPixel = 1.0 + waitMs / 100.0; // counted on even frames
        return f;
    };
    // Frame i takes i ms, draws 1000 + i triangles in 50 + i % 7 calls, meshes for i / 100 ms and
    // waits i / 2 ms for the frame to finish; even frames count their fragments, 1 + i / 200 per pixel.
    for (int i = 1; i <= 100; ++i) {
        const double d = i;
        stats.add(sample(d, 1000.0 + d, 50.0 + i % 7, d / 100.0, d / 2.0));
    }
    stats.add(sample(80.0, 5000.0, 300.0, 4.0, 70.0)); // one slow frame that also drew and meshed the most
    ASSERT_EQ(stats.frames(), 101u);
    const fs::path out = scratch("frames.json");
    stats.write(out.string(), 640, 360, 8);
    const nlohmann::json j = readJson(out);
    EXPECT_EQ(j["frames"].get<int>(), 101);
    EXPECT_EQ(j["median_ms"].get<double>(), 51.0);
    EXPECT_EQ(j["worst_ms"].get<double>(), 100.0);
    EXPECT_EQ(j["frames_over_50ms"].get<int>(), 51); // 51..100 and the 80
    EXPECT_DOUBLE_EQ(j["mean_triangles"].get<double>(), (100.0 * 1000.0 + 5050.0 + 5000.0) / 101.0);
    // Each quantity is summed up on its own: median by nearest rank, p99 the 100th of 101, worst.
    struct Summary {
        const char* quantity;
        const char* statistic;
        double expected; // exactly
    };
    for (const Summary& s : {Summary{"triangles", "median", 1051.0}, Summary{"triangles", "p99", 1100.0},
                             Summary{"triangles", "worst", 5000.0}, Summary{"draw_calls", "worst", 300.0},
                             Summary{"draw_calls", "p99", 56.0}, Summary{"mesh_ms", "worst", 4.0},
                             Summary{"gpu_wait_ms", "median", 25.5}, Summary{"gpu_wait_ms", "worst", 70.0}}) {
        EXPECT_EQ(j[s.quantity][s.statistic].get<double>(), s.expected) << s.quantity << " " << s.statistic;
    }
    EXPECT_DOUBLE_EQ(j["mesh_ms"]["median"].get<double>(), 0.51);
    // Over the 51 frames that counted fragments only (2, 4, .. 100 and the 80 ms one).
    EXPECT_EQ(j["fragments_per_pixel"]["frames"].get<int>(), 51);
    EXPECT_DOUBLE_EQ(j["fragments_per_pixel"]["median"].get<double>(), 1.26);
    EXPECT_DOUBLE_EQ(j["fragments_per_pixel"]["worst"].get<double>(), 1.7);
    EXPECT_DOUBLE_EQ(j["slowest"][0]["fragments_per_pixel"].get<double>(), 1.5); // frame 100 (100 ms)
    EXPECT_TRUE(j["slowest"][1]["fragments_per_pixel"].is_null());               // frame 99 did not count
    // Every frame in the order it was added, as columns.
    const nlohmann::json& each = j["per_frame"];
    for (const char* column : {"tick", "frame_ms", "triangles", "gpu_wait_ms"}) {
        ASSERT_EQ(each[column].size(), 101u) << column;
    }
    EXPECT_EQ(each["frame_ms"][0].get<double>(), 1.0);
    EXPECT_EQ(each["triangles"][41].get<double>(), 1042.0);
    EXPECT_EQ(each["gpu_wait_ms"][99].get<double>(), 50.0);
    EXPECT_EQ(each["frame_ms"][100].get<double>(), 80.0); // the slow frame, last
    EXPECT_EQ(each["triangles"][100].get<double>(), 5000.0);
    fs::remove(out);
}

// views_completed: each stretch from a frame that left chunks pending to the first that left none.
TEST(FrameStats, ViewsCompletedSpanFromPendingChunksToNone) {
    session::FrameStats stats;
    const int pending[] = {3, 2, 0, 0, 5, 1, 0, 0, 4};
    for (int i = 0; i < 9; ++i) {
        session::FrameSample f;
        f.frameMs = 10.0 + i;
        f.tick = 100 + static_cast<std::uint64_t>(i);
        f.pendingChunks = pending[i];
        stats.add(f);
    }
    const fs::path out = scratch("views.json");
    stats.write(out.string(), 640, 360, 8);
    const nlohmann::json v = readJson(out)["views_completed"];
    ASSERT_EQ(v.size(), 3u);
    EXPECT_EQ(v[0]["from_tick"].get<int>(), 100);
    EXPECT_EQ(v[0]["frames"].get<int>(), 3);
    EXPECT_EQ(v[0]["ms"].get<double>(), 10.0 + 11.0 + 12.0);
    EXPECT_TRUE(v[0]["complete"].get<bool>());
    EXPECT_EQ(v[1]["from_tick"].get<int>(), 104);
    EXPECT_EQ(v[1]["frames"].get<int>(), 3);
    EXPECT_EQ(v[1]["ms"].get<double>(), 14.0 + 15.0 + 16.0);
    EXPECT_EQ(v[2]["from_tick"].get<int>(), 108);
    EXPECT_FALSE(v[2]["complete"].get<bool>()); // still pending when the run ended
    fs::remove(out);
}

// The loading at the start (frames until the first with nothing pending) is left out of after_load, a
// later stretch with chunks pending (a teleport) is not; slowest lists the spikes with what they did.
TEST(FrameStats, AfterLoadLeavesOutTheLoadingAndSlowestNamesTheSpikes) {
    session::FrameStats stats;
    // Ticks 1..3 load (90, 60, 40 ms), then 20 ms frames, one 70 ms teleport frame at tick 50.
    for (int i = 1; i <= 100; ++i) {
        session::FrameSample f;
        f.tick = static_cast<std::uint64_t>(i);
        f.pendingChunks = i < 3 ? 500 - 100 * i : (i == 50 ? 40 : 0);
        f.frameMs = i == 1 ? 90.0 : i == 2 ? 60.0 : i == 3 ? 40.0 : i == 50 ? 70.0 : 20.0;
        f.chunksMeshed = i <= 3 || i == 50 ? 100 : 0;
        f.meshMs = i == 50 ? 4.5 : 0.25;
        stats.add(f);
    }
    const fs::path out = scratch("after_load.json");
    stats.write(out.string(), 640, 360, 8);
    const nlohmann::json j = readJson(out);
    ASSERT_EQ(j["worst_ms"].get<double>(), 90.0); // precondition: the loading is in the whole-run figures
    const nlohmann::json& a = j["after_load"];
    EXPECT_EQ(a["from_tick"].get<int>(), 4); // tick 3 was the first with nothing pending
    EXPECT_EQ(a["frames"].get<int>(), 97);
    EXPECT_EQ(a["median_ms"].get<double>(), 20.0);
    EXPECT_EQ(a["p99_ms"].get<double>(), 20.0);   // 96th of 97 by nearest rank
    EXPECT_EQ(a["worst_ms"].get<double>(), 70.0); // the teleport is play, not loading
    const nlohmann::json& slow = j["slowest"];
    ASSERT_EQ(slow.size(), session::FrameStats::kSlowestListed);
    const int ticks[] = {1, 50, 2, 3};
    for (int k = 0; k < 4; ++k) EXPECT_EQ(slow[static_cast<std::size_t>(k)]["tick"].get<int>(), ticks[k]);
    EXPECT_EQ(slow[1]["mesh_ms"].get<double>(), 4.5);
    EXPECT_EQ(slow[1]["chunks_meshed"].get<int>(), 100);
    EXPECT_EQ(slow[1]["pending_chunks"].get<int>(), 40);
    EXPECT_EQ(slow[9]["frame_ms"].get<double>(), 20.0);
    ASSERT_EQ(j["per_frame"]["tick"].size(), 100u);
    EXPECT_EQ(j["per_frame"]["tick"][49].get<int>(), 50); // frames keep their ticks
    EXPECT_EQ(j["per_frame"]["frame_ms"][49].get<double>(), 70.0);
    fs::remove(out);
}

// A view that never completes has no frames after loading, and fewer frames than the list is long are
// all listed.
TEST(FrameStats, AfterLoadIsEmptyWhenTheViewNeverCompleted) {
    session::FrameStats stats;
    for (int i = 0; i < 3; ++i) {
        session::FrameSample f;
        f.frameMs = 10.0 * (i + 1);
        f.pendingChunks = 7;
        stats.add(f);
    }
    const fs::path out = scratch("never_loaded.json");
    stats.write(out.string(), 640, 360, 8);
    const nlohmann::json j = readJson(out);
    EXPECT_EQ(j["after_load"]["frames"].get<int>(), 0);
    EXPECT_EQ(j["after_load"]["worst_ms"].get<double>(), 0.0);
    ASSERT_EQ(j["slowest"].size(), 3u);
    EXPECT_EQ(j["slowest"][0]["frame_ms"].get<double>(), 30.0);
    fs::remove(out);
}

// A soak of one game minute at 60 Hz: the setup puts exact, symplectic-euler, verlet and euler in every
// set; the exact slot stays within its bound and the report passes. A run shorter than a minute checked
// nothing and must fail rather than pass.
TEST(SoakMonitor, OneCleanMinutePassesAndARunShorterThanAMinuteFails) {
    session::Session s(demoOptions());
    ASSERT_FALSE(s.state().pendulumSets.empty()); // precondition: the demo scene has sets to watch
    session::SoakMonitor::setUp(s);
    session::SoakMonitor soak(3600, 1e9); // ticks per game minute at 60 Hz
    for (int t = 0; t < 60 * 60; ++t) {
        s.step();
        soak.afterTick(s.state(), 0.1);
    }
    ASSERT_EQ(s.state().pendulumSets[0].slot(0).method(), physics::Method::Exact); // setUp took effect
    const fs::path report = scratch("soak.json");
    EXPECT_TRUE(soak.finish(report.string()));
    const nlohmann::json j = readJson(report);
    EXPECT_TRUE(j["passed"].get<bool>());
    EXPECT_EQ(j["minutes"].size(), 1u);
    EXPECT_LE(j["max_energy_error"]["exact"].get<double>(), session::SoakMonitor::kExactBound);

    session::SoakMonitor tooShort(3600, 1e9);
    s.step();
    ASSERT_NE(s.state().tick % 3600, 0u); // precondition: this tick does not end a game minute
    tooShort.afterTick(s.state(), 0.1);
    EXPECT_FALSE(tooShort.finish(report.string()));
    EXPECT_FALSE(readJson(report)["passed"].get<bool>());
    fs::remove(report);
}

TEST(SoakMonitor, TwoTicksOverBudgetFailOneIsAWarning) {
    session::Session s(demoOptions());
    const fs::path report = scratch("soak_budget.json");
    for (int over : {1, 2}) {
        session::SoakMonitor soak(60, 1.0);
        for (int t = 0; t < 60; ++t) {
            s.step();
            soak.afterTick(s.state(), t < over ? 5.0 : 0.5);
        }
        EXPECT_EQ(soak.finish(report.string()), over == 1) << over << " tick(s) over budget";
        EXPECT_EQ(readJson(report)["ticks_over_budget"].size(), static_cast<std::size_t>(over));
    }
    fs::remove(report);
}

} // namespace
