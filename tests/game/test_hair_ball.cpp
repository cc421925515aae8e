#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "flat_world.h"
#include "game/game_state.h"
#include "game/space.h"
#include "game/state_io.h"

namespace {

constexpr double kDt = 1.0 / 60.0;

TEST(HairBallInWorld, DemoWorldHasSeveralColouredBallsOneSpinning) {
    game::GameState s(game::GameDef{});
    ASSERT_GE(s.hairBalls.size(), 3u);
    int spinning = 0;
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        spinning += s.hairBalls[i].def().spinRate != 0.0f;
        for (std::size_t j = i + 1; j < s.hairBalls.size(); ++j) {
            EXPECT_NE(s.hairBalls[i].def().colour, s.hairBalls[j].def().colour);
        }
        // In front of the spawn view, so the first frame shows them.
        const glm::vec3 to = s.hairBalls[i].centre() - game::eyePosition(s.player);
        EXPECT_GT(glm::dot(glm::normalize(glm::vec3(to.x, 0.0f, to.z)), game::lookDirection(s.player.yaw, 0.0f)), 0.5f);
    }
    EXPECT_EQ(spinning, 1);
}

// The demo shows the solvers side by side: at least two different ones, each ball with its solver's own
// iterations and substeps, in the same places every time.
TEST(HairBallInWorld, DemoBallsShowAtLeastTwoSolvers) {
    const game::GameState s(game::GameDef{});
    std::set<physics::HairMethod> solvers;
    for (const auto& ball : s.hairBalls) {
        const physics::HairParams& h = ball.def().hair;
        solvers.insert(h.method);
        const physics::HairParams expected = physics::hairMethodDefaults(h.method, game::GameDef{}.ballDef.hair);
        EXPECT_EQ(h.iterations, expected.iterations) << physics::hairMethodName(h.method);
        EXPECT_EQ(h.substeps, expected.substeps) << physics::hairMethodName(h.method);
    }
    EXPECT_GE(solvers.size(), 2u);
    EXPECT_TRUE(solvers.count(physics::HairMethod::Dftl)) << "the game's default solver is among them";
    const game::GameState again(game::GameDef{});
    ASSERT_EQ(again.hairBalls.size(), s.hairBalls.size());
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        EXPECT_EQ(again.hairBalls[i].centre(), s.hairBalls[i].centre());
        EXPECT_EQ(again.hairBalls[i].def().hair.method, s.hairBalls[i].def().hair.method);
    }
}

TEST(HairBallInWorld, PlacedFromTheHotbarCarriedAndPutDown) {
    game::GameState s(flatNoDemo());
    ASSERT_EQ(placeFromHotbar(s, -45.0f, 7, kDt), "hair_ball");
    ASSERT_EQ(s.hairBalls.size(), 1u);
    EXPECT_GT(s.hairBalls[0].centre().y, 33.0f); // above the grass it was placed on
    EXPECT_EQ(s.world.editCount(), 0u);

    // Look at it and carry it: it follows the view.
    input::Actions look;
    const glm::vec3 to = s.hairBalls[0].centre() - game::eyePosition(s.player);
    look.lookAbsolute = glm::vec2(glm::degrees(std::atan2(to.x, -to.z)),
                                  glm::degrees(std::atan2(to.y, glm::length(glm::vec2(to.x, to.z)))));
    game::tick(s, look, kDt);
    ASSERT_EQ(game::targetOf(s).kind, game::Target::Kind::HairBall);
    input::Actions carry;
    carry.carry = true;
    game::tick(s, carry, kDt);
    ASSERT_TRUE(s.carriedBall.has_value());
    input::Actions turn;
    turn.yawDelta = 90.0f;
    game::tick(s, turn, kDt);
    const glm::vec3 rel = s.hairBalls[0].centre() - game::eyePosition(s.player);
    EXPECT_GT(glm::dot(glm::normalize(rel), game::lookDirection(s.player.yaw, s.player.pitch)), 0.99f);
    EXPECT_FALSE(s.hairBalls[0].solver().sleeping()); // moved: its hair swings

    game::tick(s, carry, kDt); // put it down where it is
    EXPECT_FALSE(s.carriedBall.has_value());
    const glm::vec3 putDown = s.hairBalls[0].centre();
    for (int i = 0; i < 10; ++i) game::tick(s, {}, kDt);
    EXPECT_EQ(s.hairBalls[0].centre(), putDown);

    const auto dump = game::dumpState(s);
    ASSERT_EQ(dump["hair_balls"].size(), 1u);
    const auto& b = dump["hair_balls"][0];
    for (const char* key : {"position", "colour", "damping", "strands", "nodes_per_strand", "hair_state",
                            "max_segment_error", "solver"}) {
        EXPECT_TRUE(b.contains(key)) << key;
    }
    EXPECT_TRUE(b["hair_state"].contains("sleeping"));
}

TEST(HairBallInWorld, DistantBallsSimulateFewerStrands) {
    game::HairBall ball(glm::vec3(0.0f, 40.0f, 0.0f));
    const int all = ball.def().hair.strands;
    EXPECT_EQ(game::activeStrandsFor(ball, glm::vec3(0.0f, 40.0f, 5.0f)), all);
    EXPECT_EQ(game::activeStrandsFor(ball, glm::vec3(0.0f, 40.0f, 20.0f)), all / 2);
    EXPECT_EQ(game::activeStrandsFor(ball, glm::vec3(0.0f, 40.0f, 50.0f)), all / 4);
}

TEST(HairBallInWorld, HairDoesNotSinkIntoTheGround) {
    game::GameState s(flatNoDemo());
    game::HairBallDef def;
    def.hair.strandLength = 1.2f; // long enough to reach the grass at y = 33
    s.hairBalls.emplace_back(glm::vec3(0.5f, 33.0f + def.radius + 0.4f, 0.5f), def);
    for (int i = 0; i < 180; ++i) game::tick(s, {}, kDt);
    const physics::HairSolver& h = s.hairBalls[0].solver();
    const std::size_t n = static_cast<std::size_t>(h.strands()) * static_cast<std::size_t>(h.nodesPerStrand());
    float lowest = 1e9f;
    for (std::size_t i = 0; i < n; ++i) lowest = std::min(lowest, h.y()[i]);
    EXPECT_GE(lowest, 33.0f - 1e-3f);
    EXPECT_LT(lowest, 33.2f); // it did reach the ground and lies on it
}

TEST(HairBallInWorld, BallEditsApplyThroughCommandsAndChangeTheHash) {
    game::GameState s(game::GameDef{});
    ASSERT_FALSE(s.hairBalls.empty());
    const auto before = game::stateHash(s);
    game::HairBallDef def = s.hairBalls[0].def();
    def.colour = {0.1f, 0.9f, 0.1f};
    def.hair.strands = 64;
    game::tick(s, {}, kDt, {{}, {{0, def}}, {}, {}});
    EXPECT_EQ(s.hairBalls[0].solver().strands(), 64);
    EXPECT_EQ(s.hairBalls[0].def().colour, glm::vec3(0.1f, 0.9f, 0.1f));
    EXPECT_NE(game::stateHash(s), before);
}

TEST(HairBallInWorld, DefsBeyondTheGamesLimitsAreRefusedAndEditsDropped) {
    const game::HairBallDef good;
    EXPECT_NO_THROW(game::validateHairBallDef(good));
    const struct {
        void (*change)(game::HairBallDef&);
        const char* why;
    } cases[] = {{[](game::HairBallDef& d) { d.radius = 0.0f; }, "radius"},
                 {[](game::HairBallDef& d) { d.radius = std::nanf(""); }, "radius"},
                 {[](game::HairBallDef& d) { d.radius = game::kMaxHairBallRadius * 1.01f; }, "radius"},
                 {[](game::HairBallDef& d) { d.hair.strandLength = 1e30f; }, "strand length"},
                 {[](game::HairBallDef& d) { d.spinRate = -1e30f; }, "spin rate"},
                 {[](game::HairBallDef& d) { d.hair.gravity = 2000.0f; }, "gravity"},
                 {[](game::HairBallDef& d) { d.colour.g = 1.5f; }, "colour"},
                 {[](game::HairBallDef& d) { d.hair.iterations = 101; }, "iterations"},
                 {[](game::HairBallDef& d) { d.hair.substeps = 17; }, "substeps"},
                 {[](game::HairBallDef& d) { d.hair.dampingPerSecond = -1.0f; }, "dampingPerSecond"}};
    for (const auto& c : cases) {
        game::HairBallDef d = good;
        c.change(d);
        try {
            game::validateHairBallDef(d);
            ADD_FAILURE() << "accepted: " << c.why;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(c.why), std::string::npos) << e.what();
        }
        EXPECT_THROW(game::HairBall(glm::vec3(0.0f), d), std::invalid_argument) << c.why;
    }
    // The limits themselves are accepted.
    game::HairBallDef edge = good;
    edge.radius = game::kMaxHairBallRadius;
    edge.hair.strandLength = game::kMaxHairStrandLength;
    edge.spinRate = -game::kMaxHairSpinRate;
    EXPECT_NO_THROW(game::validateHairBallDef(edge));

    // As a panel edit, a refused def is dropped: the ball keeps its parameters, the game goes on.
    game::GameState s(game::GameDef{});
    ASSERT_FALSE(s.hairBalls.empty());
    game::HairBallDef bad = s.hairBalls[0].def();
    bad.hair.strandLength = 1e30f;
    const float length = s.hairBalls[0].def().hair.strandLength;
    game::tick(s, {}, kDt, {{}, {{0, bad}}, {}, {}});
    EXPECT_EQ(s.hairBalls[0].def().hair.strandLength, length);
}

TEST(HairBallInWorld, SameInputsSameHairBitForBit) {
    auto run = [] {
        game::GameState s(game::GameDef{});
        for (int i = 0; i < 120; ++i) {
            input::Actions a;
            a.move = {0.0f, 1.0f};
            game::tick(s, a, kDt);
        }
        std::vector<std::uint64_t> hashes{game::stateHash(s)};
        for (const auto& ball : s.hairBalls) hashes.push_back(ball.solver().hashState());
        return hashes;
    };
    EXPECT_EQ(run(), run());
}

} // namespace

// Hair keeps its promises at every setting the game allows: strand lengths up to the 4 m limit, few and many
// nodes, the smallest and largest radii, many strands, each exact-length solver; on the demo's terraces, where
// long hair drapes over block edges and down their sides. Checked independently of the solver's own stats,
// every tenth tick until the ball has slept for a second (the sleeping hair is what the player looks at):
// - every segment within 1 % of its length (measured: at most 4e-5; 1.14 with 4 m strands when a node is pushed
//   back out of a wall through a face out of its parent's reach);
// - no node inside a block (its distance to the nearest free point, diagonal neighbours included, under
//   1 mm; before: nodes boxed in deep inside the terrace);
// - no segment deeper in a block than half its length: a straight segment between two nodes outside blocks
//   can cut a block's edge by no more (this is the geometry of nodes joined by straight lines, stated in
//   HAIR.md: raise `nodes` for long hair).
namespace {
struct HairInBlocks {
    float maxSegmentError = 0.0f, maxNodeDepth = 0.0f, maxSegmentDepth = 0.0f;
};
// How deep p lies in solid blocks: its distance to the nearest point of a free cell among the 26 around
// its own (0 in a free cell; 1 when none is free, deeper than this check needs to tell).
float depthInBlocks(const world::World& w, const glm::vec3& p) {
    const glm::ivec3 c(glm::floor(p));
    if (!world::isSolid(w.get(c))) return 0.0f;
    float best = 1.0f;
    for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const glm::ivec3 n = c + glm::ivec3(dx, dy, dz);
                if (world::isSolid(w.get(n))) continue;
                const glm::vec3 nearest = glm::clamp(p, glm::vec3(n), glm::vec3(n) + glm::vec3(1.0f));
                best = std::min(best, glm::length(p - nearest));
            }
        }
    }
    return best;
}
HairInBlocks inspectHair(const game::HairBall& ball, const world::World& w) {
    HairInBlocks r;
    const physics::HairSolver& h = ball.solver();
    const int S = h.strands(), N = h.nodesPerStrand();
    const float L = h.segmentLength();
    for (int s = 0; s < h.activeStrands(); ++s) {
        for (int n = 1; n < N; ++n) {
            const int i = n * S + s, j = (n - 1) * S + s;
            const glm::vec3 a(h.x()[j], h.y()[j], h.z()[j]), b(h.x()[i], h.y()[i], h.z()[i]);
            r.maxSegmentError = std::max(r.maxSegmentError, std::abs(glm::length(b - a) / L - 1.0f));
            r.maxNodeDepth = std::max(r.maxNodeDepth, depthInBlocks(w, b));
            for (int k = 1; k < 16; ++k)
                r.maxSegmentDepth =
                    std::max(r.maxSegmentDepth, depthInBlocks(w, a + (b - a) * (static_cast<float>(k) / 16.0f)));
        }
    }
    return r;
}
} // namespace

TEST(HairBallInWorld, EverySettingKeepsItsLengthsAndStaysOutOfBlocks) {
    struct Case {
        physics::HairMethod solver;
        float length, radius;
        int nodes, strands;
        float lift; // m above the demo ball's place (room for a large radius)
    };
    const Case cases[] = {
        {physics::HairMethod::Dftl, 4.0f, 0.3f, 12, 512, 0.0f},   // the case: the longest strands
        {physics::HairMethod::Dftl, 4.0f, 0.3f, 41, 128, 0.0f},   // long strands of short segments
        {physics::HairMethod::Shake, 4.0f, 0.3f, 12, 512, 0.0f},  // the other exact-length solvers
        {physics::HairMethod::Ftl, 2.0f, 0.3f, 12, 128, 0.0f},    //
        {physics::HairMethod::Dftl, 1.5f, 2.0f, 12, 256, 1.0f},   // the largest ball
        {physics::HairMethod::Dftl, 0.45f, 0.1f, 12, 2048, 0.0f}, // the smallest, dense
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::string(physics::hairMethodName(c.solver)) + " length " + std::to_string(c.length) +
                     " radius " + std::to_string(c.radius) + " nodes " + std::to_string(c.nodes));
        game::GameState s(game::GameDef{});
        s.hairBalls.erase(s.hairBalls.begin() + 1,
                          s.hairBalls.end()); // the first demo ball alone: room for the largest radius
        s.pendulumSets.clear();
        game::HairBallDef d = s.hairBalls[0].def();
        d.hair = physics::hairMethodDefaults(c.solver, d.hair);
        d.hair.strandLength = c.length;
        d.hair.nodesPerStrand = c.nodes;
        d.hair.strands = c.strands;
        d.radius = c.radius;
        s.hairBalls[0].moveTo(s.hairBalls[0].centre() + glm::vec3(0.0f, c.lift, 0.0f));
        game::TickCommands edit;
        edit.hair.push_back({0, d});
        HairInBlocks worst;
        int asleepTicks = 0, ticks = 0;
        // Until asleep for a second where the ball sleeps within 30 s; ten seconds, awake, for shake (it does not
        // sleep at 60 Hz, HAIR.md) and for 41-node strands (still creeping on the terrace after 30 s).
        const bool sleeps = c.solver != physics::HairMethod::Shake && c.nodes == 12;
        for (; ticks < (sleeps ? 1800 : 600) && asleepTicks < 60; ++ticks) {
            game::tick(s, input::Actions{}, kDt, ticks == 0 ? edit : game::TickCommands{});
            asleepTicks = s.hairBalls[0].solver().sleeping() ? asleepTicks + 1 : 0;
            if (ticks % 10 != 0 && asleepTicks != 60) continue;
            const HairInBlocks now = inspectHair(s.hairBalls[0], s.world);
            worst.maxSegmentError = std::max(worst.maxSegmentError, now.maxSegmentError);
            worst.maxNodeDepth = std::max(worst.maxNodeDepth, now.maxNodeDepth);
            worst.maxSegmentDepth = std::max(worst.maxSegmentDepth, now.maxSegmentDepth);
        }
        ASSERT_EQ(s.hairBalls[0].def().hair.strandLength, c.length) << "precondition: the edit was applied";
        if (sleeps) {
            EXPECT_EQ(asleepTicks, 60) << "precondition: the ball fell asleep within 30 s";
        }
        const float segment = c.length / static_cast<float>(c.nodes - 1);
        EXPECT_LE(worst.maxSegmentError, 0.01f);
        EXPECT_LE(worst.maxNodeDepth, 0.001f);
        EXPECT_LE(worst.maxSegmentDepth, 0.5f * segment + 0.001f);
        std::printf("%s length %.2f radius %.1f nodes %d: segment error %.2g, node depth %.2g m, segment depth %.3f m "
                    "(half a segment %.3f m), %s\n",
                    std::string(physics::hairMethodName(c.solver)).c_str(), c.length, c.radius, c.nodes,
                    worst.maxSegmentError, worst.maxNodeDepth, worst.maxSegmentDepth, 0.5f * segment,
                    asleepTicks == 60 ? ("asleep after " + std::to_string(ticks - 60) + " ticks").c_str() : "awake");
    }
}

// The demo's balls stand where the game would let a player put one (game::ballSpaceFree: no block, no other
// ball, not the set, not the player), on every terrain: a world file is then loaded with the same check
// (WorldFile.ABallInsideBlocksIsSkipped). They used to be placed by the column under their centre alone
// and could reach into a higher neighbour.
TEST(HairBallInWorld, DemoBallsStandWhereAPlayerCouldPutThem) {
    int checked = 0;
    for (const world::TerrainKind kind : {world::TerrainKind::Default, world::TerrainKind::Flat}) {
        for (std::uint64_t seed = 1; seed <= 40; ++seed) {
            game::GameDef def;
            def.terrain.kind = kind;
            def.terrain.seed = seed;
            const game::GameState s(def);
            ASSERT_EQ(s.hairBalls.size(), 3u) << "precondition: the demo's balls";
            for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
                const game::HairBall& b = s.hairBalls[i];
                EXPECT_TRUE(game::ballSpaceFree(s, b.centre(), b.def().radius, {i, std::nullopt}))
                    << "seed " << seed << " ball " << i << " at " << b.centre().x << " " << b.centre().y << " "
                    << b.centre().z;
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 240);
}

// Hair behaves the same at every tick rate: the game steps it on its own clock of 1/60 s substeps
// (physics::hairClockSteps), so a new ball resting on the flat ground settles alike at 30, 60, 144 and 240 Hz
// (measured 2.40, 2.30, 2.31 and 2.30 s; at 30 Hz the sleep test runs every other substep), held to the
// issue's 15 %. Stepped by the tick instead: 2.40, 2.30, 3.00 and 3.41 s, 48 % apart (caught).
TEST(HairBallInWorld, ANewBallSettlesAlikeAtEveryTickRate) {
    std::vector<double> settle;
    for (const int hz : {30, 60, 144, 240}) {
        game::GameDef def;
        def.terrain.kind = world::TerrainKind::Flat;
        def.demoObjects = false;
        game::GameState s(def);
        s.hairBalls.emplace_back(glm::vec3(3.5f, 33.31f, 0.5f), def.ballDef); // 1 cm over the ground
        const double dt = 1.0 / hz;
        double asleepAt = -1.0;
        for (int t = 1; t <= 30 * hz && asleepAt < 0.0; ++t) {
            game::tick(s, input::Actions{}, dt);
            if (s.hairBalls[0].solver().sleeping()) asleepAt = t * dt;
        }
        ASSERT_GT(asleepAt, 0.0) << hz << " Hz: precondition: the ball falls asleep within 30 s";
        std::printf("[ measured ] a new ball on the ground settles at %d Hz after %.3f s\n", hz, asleepAt);
        settle.push_back(asleepAt);
    }
    const auto [lo, hi] = std::minmax_element(settle.begin(), settle.end());
    EXPECT_LE(*hi, 1.15 * *lo);
}

// The hair's energy above its rest, as the game holds it: kinetic from the last hair substep (1/60 s on the
// hair clock) plus potential, unit node mass, summed over every node.
double hairEnergy(const physics::HairSolver& h) {
    const auto n = static_cast<std::size_t>(h.strands()) * static_cast<std::size_t>(h.nodesPerStrand());
    const double step = physics::kHairClockSeconds, g = 9.81;
    double e = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double vx = (h.x()[i] - h.prevX()[i]) / step, vy = (h.y()[i] - h.prevY()[i]) / step,
                     vz = (h.z()[i] - h.prevZ()[i]) / step;
        e += 0.5 * (vx * vx + vy * vy + vz * vz) + g * 0.5 * (h.y()[i] + h.prevY()[i]);
    }
    return e;
}

// A ball carried one swing (0.3 m out and back over 1 s, as a player carries it) and then held still, its hair
// swinging down, in open air. The game steps hair on its own clock, so the energy the hair keeps at 1.5 s is
// the same at every tick rate from 1/30 to 1/480 s (the 10 %), for the default damping and a light
// one: the damping a player sets means one decay rate at every tick. Measured (J, unit node mass): 1303, 1299,
// 1286, 1299, 1299 at 30, 60, 144, 240, 480 Hz with the default 2.5/s; 1982, 1977, 2015, 1977, 1977 with 0.5/s
// (144 Hz is the one whose clock substeps end between ticks: the host's pose is the tick's, up to 1/144 s
// later). Stepped by the tick instead, the solver's own step-dependent dissipation shows: 1303 at 30 Hz, 3319
// at 480 Hz (caught).
TEST(HairBallInWorld, CarriedHairKeepsTheSameEnergyAtEveryTickRate) {
    for (const float damping : {2.5f, 0.5f}) {
        std::vector<double> energy;
        for (const int hz : {30, 60, 144, 240, 480}) {
            game::GameDef def;
            def.terrain.kind = world::TerrainKind::Flat;
            def.demoObjects = false;
            game::HairBallDef ball = def.ballDef;
            ball.hair.dampingPerSecond = damping;
            game::GameState s(def);
            const glm::vec3 home(3.5f, 37.0f, 0.5f); // 4 m over the ground: the hair meets no block
            s.hairBalls.emplace_back(home, ball);
            const double dt = 1.0 / hz;
            // Let the new hair fall and settle first (its rest energy is the zero), then carry.
            const int rest = 8 * hz, carry = hz, hold = hz / 2;
            for (int t = 1; t <= rest; ++t) game::tick(s, input::Actions{}, dt);
            ASSERT_TRUE(s.hairBalls[0].solver().sleeping()) << hz << " Hz: precondition: asleep before the carry";
            const double e0 = hairEnergy(s.hairBalls[0].solver());
            for (int t = 1; t <= carry + hold; ++t) {
                const double u = std::min(static_cast<double>(t) / carry, 1.0);
                s.hairBalls[0].moveTo(
                    home + glm::vec3(static_cast<float>(0.15 * (1.0 - std::cos(2.0 * std::numbers::pi * u))), 0, 0));
                game::tick(s, input::Actions{}, dt);
            }
            ASSERT_FALSE(s.hairBalls[0].solver().sleeping()) << hz << " Hz: precondition: still swinging";
            energy.push_back(hairEnergy(s.hairBalls[0].solver()) - e0);
            std::printf("[ measured ] damping %.1f/s, %d Hz: hair energy above rest 0.5 s after the carry %.4g\n",
                        damping, hz, energy.back());
        }
        const auto [lo, hi] = std::minmax_element(energy.begin(), energy.end());
        ASSERT_GT(*lo, 0.0) << "precondition: the hair still moves";
        EXPECT_LE(*hi, 1.1 * *lo) << "damping " << damping;
    }
}

// The hair sees its host at the hair's own time: at 144 Hz a clock substep ends up to 1/144 s before the tick
// that runs it, and the spinning ball's roots must sit where the ball was then (physics::hairClockLag), not at
// the tick's end. Checked at every tick that stepped the hair over 1 s: the first root against
// HairSolver::rootPosition at the substep's spin angle (measured: equal to the bit; held to 1e-5 m), and at least
// one tick where that differs from the tick's end by over 1 mm (precondition). Catches the tick's pose.
TEST(HairBallInWorld, TheHairSeesItsSpinningHostAtTheHairClocksTime) {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    game::HairBallDef ball = def.ballDef;
    ball.spinRate = 3.0f;
    game::GameState s(def);
    s.hairBalls.emplace_back(glm::vec3(3.5f, 37.0f, 0.5f), ball);
    const double dt = 1.0 / 144.0;
    int lagged = 0, stepped = 0;
    float worst = 0.0f;
    for (int t = 1; t <= 144; ++t) {
        game::tick(s, input::Actions{}, dt);
        const double now = t * dt;
        if (physics::hairClockSteps(now - dt, now) == 0) continue;
        ++stepped;
        const game::HairBall& b = s.hairBalls[0];
        const double lag = physics::hairClockLag(now);
        physics::HostPose then = b.pose();
        then.orientation = glm::angleAxis(b.spinAngle() - ball.spinRate * static_cast<float>(lag), glm::vec3(0, 1, 0));
        const glm::vec3 root(b.solver().x()[0], b.solver().y()[0], b.solver().z()[0]);
        worst = std::max(worst, glm::length(root - b.solver().rootPosition(then, 0)));
        EXPECT_LT(glm::length(root - b.solver().rootPosition(then, 0)), 1e-5f) << "tick " << t;
        if (glm::length(root - b.solver().rootPosition(b.pose(), 0)) > 1e-3f) ++lagged;
    }
    std::printf("[ measured ] root from the substep's pose: at most %.3g m; %d of %d substeps end before their tick\n",
                static_cast<double>(worst), lagged, stepped);
    ASSERT_EQ(stepped, 60) << "precondition: 60 hair substeps in 1 s";
    EXPECT_GT(lagged, 0) << "precondition: some substeps end before their tick, far enough to tell apart";
}
