// Faults the game must ride out with a clear message and no lost data: a 0.25 s tick, a million-tick
// jump of the clock, a hair ball teleported in one tick, the world file deleted or made read-only while
// the game runs. (A display lost is the window's business: see tests/e2e/cli_test.sh for the start-up
// path; a connection dying mid-game ends in Xlib's I/O error handler.)
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <thread>

#include "../temp_dir.h"
#include "core/fixed_step.h"
#include "game/game_state.h"
#include "save/world_store.h"
#include "session/session.h"

namespace {

namespace fs = std::filesystem;

// Every node of every strand finite and within strand length + radius (+ slack) of the ball's centre.
void expectHairHeld(const game::HairBall& ball, float slack, const char* when) {
    const physics::HairSolver& h = ball.solver();
    const float reach = ball.def().radius + ball.def().hair.strandLength + slack;
    float worst = 0.0f;
    const int n = h.strands() * h.nodesPerStrand();
    for (int k = 0; k < n; ++k) {
        const glm::vec3 p(h.x()[k], h.y()[k], h.z()[k]);
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << when << ": node " << k;
        worst = std::max(worst, glm::length(p - ball.centre()));
    }
    EXPECT_LE(worst, reach) << when << ": a node left " << worst << " m from the centre";
}

void expectPendulumsSane(const game::GameState& s, const char* when) {
    for (const auto& set : s.pendulumSets) {
        for (int i = 0; i < game::kPendulumSlots; ++i) {
            const auto st = set.slot(i).state();
            EXPECT_TRUE(std::isfinite(st.theta) && std::isfinite(st.omega)) << when << ": slot " << i;
            if (set.slot(i).method() == physics::Method::Exact) {
                EXPECT_NEAR(set.energyError(i), 0.0, 1e-9) << when;
            }
        }
    }
}

fs::path freshDir(const std::string& name) {
    return test_util::freshTempDir("minecrappy-faults-" + name + "-" + std::to_string(::getpid()));
}

session::Options worldOptions(const fs::path& file) {
    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    o.world = file.string();
    o.autosaveTicks = 10;
    return o;
}

// Autosaves run on a worker thread: wait for its report, bounded only against a hang (60 s: a busy machine's disk
// can take seconds; a passing run waits milliseconds).
std::vector<std::string> waitForSaveErrors(session::Session& s) {
    for (int i = 0; i < 6000; ++i) {
        auto e = s.takeSaveErrors();
        if (!e.empty()) return e;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return {};
}

// The start of the save-fault tests: plays the session 20 ticks and asserts that saving the world succeeds.
void playAndSave(session::Session& s) {
    for (int i = 0; i < 20; ++i) s.step();
    ASSERT_TRUE(s.saveNow().empty());
}

// After a fault to the saved world: plays 25 ticks, past two autosaves, and returns the save errors reported.
std::vector<std::string> playPastTwoAutosaves(session::Session& s) {
    for (int i = 0; i < 25; ++i) s.step();
    return waitForSaveErrors(s);
}

} // namespace

TEST(Faults, QuarterSecondTickKeepsEverythingFiniteAndBounded) {
    game::GameState s{game::GameDef{}};
    ASSERT_FALSE(s.hairBalls.empty());
    for (int i = 0; i < 30; ++i) game::tick(s, {}, 0.25); // 7.5 s of frame spikes in a row
    expectPendulumsSane(s, "after 0.25 s ticks");
    for (const auto& ball : s.hairBalls) {
        EXPECT_FALSE(ball.lastStats().nan);
        expectHairHeld(ball, 1e-3f, "after 0.25 s ticks");
    }
}

TEST(Faults, MillionTickJumpIsCappedAndTheGameStaysFinite) {
    core::FixedStepClock clock;
    const core::FixedStepDef def;
    EXPECT_EQ(clock.advance(1e6 / 60.0), def.maxTicksPerFrame);
    EXPECT_GE(clock.alpha(), 0.0);
    EXPECT_LT(clock.alpha(), 1.0);
    EXPECT_GT(clock.droppedSeconds(), 1e6 / 60.0 - 1.0); // the rest of the jump is dropped, not owed
    EXPECT_EQ(clock.advance(def.tickSeconds), 1);        // and the next frame is an ordinary one

    // The game's tick counter itself jumped a million ticks ahead (a world saved after a long session).
    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    session::Session session(o);
    session.state().tick = 1'000'000;
    for (int i = 0; i < 600; ++i) session.step();
    EXPECT_EQ(session.state().tick, 1'000'600u);
    expectPendulumsSane(session.state(), "after a tick-counter jump");
    for (const auto& ball : session.state().hairBalls) expectHairHeld(ball, 1e-3f, "after a tick-counter jump");
}

TEST(Faults, TeleportedHairBallBringsEveryNodeAlong) {
    const world::World w(world::TerrainDef{1, world::TerrainKind::Flat});
    game::HairBallDef def;
    def.spinRate = 1.5f;
    game::HairBall ball({0.5f, 60.0f, 0.5f}, def);
    for (int i = 0; i < 120; ++i) ball.tick(1.0 / 60.0, 1, 0.0, w, {}, def.hair.strands);
    expectHairHeld(ball, 1e-3f, "settled");
    ball.moveTo({5000.5f, 90.0f, -7000.5f}); // kilometres in one tick
    ball.tick(1.0 / 60.0, 1, 0.0, w, {}, def.hair.strands);
    EXPECT_FALSE(ball.lastStats().nan);
    expectHairHeld(ball, 1e-2f, "one tick after the teleport");
    for (int i = 0; i < 60; ++i) ball.tick(1.0 / 60.0, 1, 0.0, w, {}, def.hair.strands);
    expectHairHeld(ball, 1e-3f, "a second after the teleport");
}

TEST(Faults, WorldFileDeletedWhilePlayingIsReportedAndTheGameGoesOn) {
    const fs::path dir = freshDir("deleted");
    const fs::path file = dir / "gone.mcworld";
    {
        session::Session s(worldOptions(file));
        ASSERT_NO_FATAL_FAILURE(playAndSave(s));
        fs::remove(file);
        const auto errors = playPastTwoAutosaves(s);
        ASSERT_FALSE(errors.empty()) << "a deleted world must not be saved silently into nothing";
        EXPECT_NE(errors[0].find(file.string()), std::string::npos) << errors[0];
        EXPECT_NE(errors[0].find("gone"), std::string::npos) << errors[0];
        for (int i = 0; i < 10; ++i) s.step();
        EXPECT_EQ(s.state().tick, 55u); // still playing
        (void)s.saveNow();
    }
    EXPECT_FALSE(fs::exists(file)) << "a deleted world is not silently recreated empty";
    fs::remove_all(dir);
}

TEST(Faults, WorldFileMadeReadOnlyWhilePlayingKeepsTheLastGoodSave) {
    const fs::path dir = freshDir("readonly");
    const fs::path file = dir / "locked.mcworld";
    {
        session::Session s(worldOptions(file));
        ASSERT_NO_FATAL_FAILURE(playAndSave(s));
        ASSERT_EQ(::chmod(file.c_str(), 0444), 0);
        // As root access(W_OK) still says writable: the permission bits alone must stop the save.
        const auto errors = playPastTwoAutosaves(s);
        ASSERT_FALSE(errors.empty()) << "a read-only world must be reported"
                                     << (::geteuid() == 0 ? " (running as root)" : "");
        EXPECT_NE(errors[0].find(file.string()), std::string::npos) << errors[0];
        for (int i = 0; i < 10; ++i) s.step();
        EXPECT_EQ(s.state().tick, 55u);
    }
    EXPECT_EQ(save::WorldStore::open(file, false)->load().tick, 20u) << "the last good save must stay on disk";
    ::chmod(file.c_str(), 0644);
    fs::remove_all(dir);
}

// Hair detail and the hair budget are settings of this machine, not of a world: the settings panel changes
// them live (Session::applySettings) and they stay when the player opens another world.
TEST(Faults, HairDetailAppliesLiveAndSurvivesOpeningAnotherWorld) {
    const fs::path dir = freshDir("detail");
    session::Options o = worldOptions(dir / "a.mcworld");
    session::Settings settings;
    settings.hairDetail = 0;
    settings.hairBudgetThousands = 250;
    session::mergeSettings(o, settings); // as the game does: the run's settings are the options'
    session::Session session(o);
    EXPECT_EQ(session.state().def.hairDetail, 0.25f);
    EXPECT_EQ(session.state().def.hairBudget, 250'000);
    settings.hairDetail = 1;
    settings.hairBudgetThousands = 3000;
    EXPECT_TRUE(session.applySettings(settings).empty()); // no recording: nothing kept back
    session.step();
    session.openWorld(dir / "b.mcworld", 3, world::TerrainKind::Flat); // new
    EXPECT_EQ(session.state().def.hairDetail, 0.5f);
    EXPECT_EQ(session.state().def.hairBudget, 3'000'000);
    session.openWorld(dir / "a.mcworld", 1, world::TerrainKind::Default); // loaded
    EXPECT_EQ(session.state().def.hairDetail, 0.5f);
    EXPECT_EQ(session.state().def.hairBudget, 3'000'000);
    fs::remove_all(dir);
}
