// The hair solver against what theory fixes: roots pinned exactly to the moving, spinning host; the
// time-corrected Verlet step exact for constant acceleration under a jittered step; no node left inside a collider
// (fast nodes included); Galilean invariance of the shape; area-uniform roots (chi-square); bit-for-bit determinism
// across thread counts; sleeping and waking; a voxel floor. Each method's lengths, damping and agreement with the
// yardsticks: test_hair_methods.cpp.
#include "physics/hair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using physics::HairParams;
using physics::HairSolver;
using physics::HairSolverState;
using physics::HostPose;
using physics::SphereCollider;
using physics::VoxelOccupancy;

constexpr float kRadius = 0.25f;

glm::vec3 node(const HairSolver& h, int strand, int n) {
    const std::size_t i =
        static_cast<std::size_t>(n) * static_cast<std::size_t>(h.strands()) + static_cast<std::size_t>(strand);
    return {h.x()[i], h.y()[i], h.z()[i]};
}

bool allFinite(const HairSolver& h) {
    const std::size_t total = static_cast<std::size_t>(h.strands()) * static_cast<std::size_t>(h.nodesPerStrand());
    for (std::size_t i = 0; i < total; ++i)
        if (!std::isfinite(h.x()[i]) || !std::isfinite(h.y()[i]) || !std::isfinite(h.z()[i])) return false;
    return true;
}

HostPose spinning(double t) {
    HostPose p;
    p.centre = glm::vec3(0.3f * static_cast<float>(t), 2.0f, 0.0f);
    p.orientation = glm::angleAxis(static_cast<float>(6.0 * t), glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f)));
    return p;
}

TEST(Hair, RootsPinnedExactlyToTheMovingSpinningHost) {
    HairParams params;
    params.strands = 200;
    HairSolver h(params, kRadius, spinning(0.0));
    for (int i = 1; i <= 120; ++i) {
        const HostPose pose = spinning(i / 60.0);
        h.step(pose, 1.0f / 60.0f);
        for (int s = 0; s < h.strands(); ++s) {
            const glm::vec3 r = node(h, s, 0);
            const glm::vec3 expected = h.rootPosition(pose, s);
            ASSERT_EQ(r.x, expected.x);
            ASSERT_EQ(r.y, expected.y);
            ASSERT_EQ(r.z, expected.z);
            // ...and rootPosition is the rotated, translated root direction on the sphere.
            const glm::vec3 formula = pose.centre + kRadius * (pose.orientation * h.rootDirection(s));
            ASSERT_NEAR(glm::length(r - formula), 0.0f, 1e-6f);
        }
    }
}

TEST(Hair, VerletStepExactForConstantAccelerationUnderJitteredStep) {
    // x(t) = x0 + v0 t - g t^2 / 2. The history is the exact position one (first) step back.
    const double x0 = 1.5, v0 = 2.0, g = 9.81;
    double hPrev = 0.013;
    double x = x0, prev = x0 - v0 * hPrev - g * hPrev * hPrev / 2.0, t = 0.0;
    float xf = static_cast<float>(x), pf = static_cast<float>(prev);
    for (int i = 0; i < 200; ++i) {
        const double h = 0.004 + 0.03 * ((i * 7919) % 101) / 100.0; // 4..34 ms, jittered
        const double next = physics::verletStep(x, prev, 0.0, h / hPrev, 1.0, -g * h * (h + hPrev) / 2.0);
        const float nextF = physics::verletStep(xf, pf, 0.0f, static_cast<float>(h / hPrev), 1.0f,
                                                static_cast<float>(-g * h * (h + hPrev) / 2.0));
        prev = x, x = next, pf = xf, xf = nextF, hPrev = h, t += h;
        const double exact = x0 + v0 * t - g * t * t / 2.0;
        ASSERT_NEAR(x, exact, 1e-9 * std::max(1.0, std::abs(exact))) << "step " << i;
        ASSERT_NEAR(xf, exact, 2e-4 * std::max(1.0, std::abs(exact))) << "step " << i; // float rounding, ~200 steps
    }
    // The seed's formula (no step ratio, a dt1 dt2) drifts from the closed form under the same jitter.
    double sx = x0, sp = x0 - v0 * 0.013, st = 0.0, sh = 0.013;
    for (int i = 0; i < 200; ++i) {
        const double h = 0.004 + 0.03 * ((i * 7919) % 101) / 100.0;
        const double next = sx + (sx - sp) - g * h * sh;
        sp = sx, sx = next, sh = h, st += h;
    }
    EXPECT_GT(std::abs(sx - (x0 + v0 * st - g * st * st / 2.0)), 1.0);
}

TEST(Hair, PushOutOfSphereKeepsTheEntrySideForFastNodes) {
    const glm::vec3 c(0.0f);
    const float r = 0.25f;
    // Moving 1 m in one step (4 radii) straight through: back on the entry side (top), not thrown out below.
    const glm::vec3 p = physics::pushOutOfSphere({0.01f, -0.1f, 0.0f}, {0.01f, 0.9f, 0.0f}, c, r);
    EXPECT_GE(glm::length(p - c), r - 1e-6f);
    EXPECT_GT(p.y, 0.0f);
    // Tunnelling clean through (both ends outside, the path crosses): put back on the entry side as well.
    const glm::vec3 q = physics::pushOutOfSphere({0.0f, -0.6f, 0.05f}, {0.0f, 0.6f, 0.05f}, c, r);
    EXPECT_GE(glm::length(q - c), r - 1e-6f);
    EXPECT_GT(q.y, 0.0f);
    // Arriving from the far side (below): out below.
    const glm::vec3 u = physics::pushOutOfSphere({0.02f, 0.1f, 0.0f}, {0.02f, -0.9f, 0.0f}, c, r);
    EXPECT_GE(glm::length(u - c), r - 1e-6f);
    EXPECT_LT(u.y, 0.0f);
    // A path that misses leaves the node alone.
    const glm::vec3 m = physics::pushOutOfSphere({1.0f, 0.5f, 0.0f}, {-1.0f, 0.5f, 0.0f}, c, r);
    EXPECT_EQ(m, glm::vec3(1.0f, 0.5f, 0.0f));
}

TEST(Hair, NoNodeInsideAColliderAfterAStepEvenWhenFast) {
    HairParams params;
    params.strands = 256;
    HostPose pose{{0.0f, 2.0f, 0.0f}, {}};
    HairSolver h(params, kRadius, pose);
    const float dt = 1.0f / 60.0f;
    std::vector<SphereCollider> others = {{{0.4f, 1.45f, 0.0f}, 0.2f}};
    for (int i = 0; i < 240; ++i) {
        // The host jerks by up to 0.6 m per step (relative node speeds far above radius / dt) and spins.
        const float t = static_cast<float>(i) * dt;
        pose.centre = glm::vec3((i / 20) % 2 == 0 ? 0.0f : 0.6f, 2.0f + ((i / 7) % 2) * 0.3f, 0.0f);
        pose.orientation = glm::angleAxis(8.0f * t, glm::vec3(0.0f, 0.0f, 1.0f));
        // Another ball swept through the hair fast, from alternating sides.
        others[0].centre = glm::vec3(((i % 2) ? -1.0f : 1.0f) * 0.4f, 1.45f,
                                     0.1f * static_cast<float>(i % 3)); // never overlapping the host
        const auto stats = h.step(pose, dt, others);
        ASSERT_FALSE(stats.nan);
        ASSERT_LT(stats.maxPenetration, 1e-5f) << "step " << i; // float rounding on the surface only
        // Independent check of the host ball.
        for (int s = 0; s < h.strands(); ++s)
            for (int n = 1; n < h.nodesPerStrand(); ++n)
                ASSERT_GE(glm::length(node(h, s, n) - pose.centre), kRadius - 1e-5f);
    }
}

TEST(Hair, BoundedAndFiniteAtThirtyHertzAndThroughAFrameSpike) {
    HairSolver h(HairParams{}, kRadius, spinning(0.0));
    double t = 0.0;
    const float reach = kRadius + h.params().strandLength + 1e-3f;
    for (int i = 0; i < 200; ++i) {
        const float dt = i == 100 ? 0.25f : 1.0f / 30.0f;
        t += dt;
        const HostPose pose = spinning(t);
        const auto stats = h.step(pose, dt);
        ASSERT_FALSE(stats.nan);
        ASSERT_TRUE(allFinite(h));
        for (int s = 0; s < h.strands(); ++s)
            ASSERT_LE(glm::length(node(h, s, h.nodesPerStrand() - 1) - pose.centre), reach);
    }
}

// Galilean invariance: the same hair on a host at rest and on one moving at constant velocity (new hair moves
// with its host) moves alike, up to the rounding of positions at different places. Hair falling over its ball
// is chaotic (contacts decide which side a strand drapes), so rounding grows: the motions agree to rounding
// over the first 10 steps (measured 1.4e-5 m), and both come to rest hanging alike (mean node height
// relative to the host within 1 cm); the exact drape, which contact friction makes depend on the path, may
// differ.
TEST(Hair, HostAtConstantVelocityKeepsTheShapeOfAHostAtRest) {
    HairParams params;
    params.strands = 128;
    params.sleepSpeed = 0.0f; // keep both running
    const glm::vec3 start(0.0f, 2.0f, 0.0f), v(1.5f, 0.0f, -0.8f);
    HairSolver rest(params, kRadius, HostPose{start, {}});
    HairSolver moving(params, kRadius, HostPose{start, {}});
    const float dt = 1.0f / 60.0f;
    const auto worstDifference = [&](int i) {
        const glm::vec3 offset = v * (static_cast<float>(i) * dt);
        float worst = 0.0f;
        for (int s = 0; s < rest.strands(); ++s)
            for (int n = 0; n < rest.nodesPerStrand(); ++n)
                worst = std::max(worst, glm::length((node(moving, s, n) - offset) - node(rest, s, n)));
        return worst;
    };
    const auto meanHeight = [&](const HairSolver& h, float centreY) {
        double sum = 0.0;
        for (int s = 0; s < h.strands(); ++s)
            for (int n = 1; n < h.nodesPerStrand(); ++n) sum += static_cast<double>(node(h, s, n).y - centreY);
        return sum / (h.strands() * (h.nodesPerStrand() - 1));
    };
    for (int i = 1; i <= 240; ++i) {
        rest.step(HostPose{start, {}}, dt);
        moving.step(HostPose{start + v * (static_cast<float>(i) * dt), {}}, dt);
        if (i == 1) {
            EXPECT_LT(worstDifference(i), 2e-6f);
        }
        if (i == 10) {
            EXPECT_LT(worstDifference(i), 1e-4f);
        }
    }
    EXPECT_NEAR(meanHeight(moving, start.y), meanHeight(rest, start.y), 0.01);
}

// Chi-square of root counts in equal-area bins (y = cos theta in equal steps, phi in equal steps).
double chiSquare(const std::vector<glm::vec3>& dirs, int count, float halfAngle, int yBins, int phiBins) {
    std::vector<int> bins(static_cast<std::size_t>(yBins * phiBins), 0);
    const double yMin = std::cos(static_cast<double>(halfAngle));
    for (int k = 0; k < count; ++k) {
        const glm::vec3 d = dirs[static_cast<std::size_t>(k)];
        const double u = (1.0 - d.y) / (1.0 - yMin);
        double phi = std::atan2(static_cast<double>(d.z), static_cast<double>(d.x));
        if (phi < 0.0) phi += 2.0 * std::numbers::pi;
        const int a = std::clamp(static_cast<int>(u * yBins), 0, yBins - 1);
        const int b = std::clamp(static_cast<int>(phi / (2.0 * std::numbers::pi) * phiBins), 0, phiBins - 1);
        ++bins[static_cast<std::size_t>(a) * static_cast<std::size_t>(phiBins) + static_cast<std::size_t>(b)];
    }
    const double expected = static_cast<double>(count) / (yBins * phiBins);
    double chi = 0.0;
    for (int c : bins) chi += (c - expected) * (c - expected) / expected;
    return chi;
}

TEST(Hair, RootsAreAreaUniformAndEveryPrefixIsSpread) {
    // Critical values of chi-square at p = 0.001: df 63 -> 103.4, df 15 -> 37.7.
    for (float half : {3.14159265f, 1.0f}) {
        const auto dirs = physics::hairRootDirections(4096, half, 7);
        for (const glm::vec3& d : dirs) {
            ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
            ASSERT_GE(d.y, std::cos(half) - 1e-5f);
        }
        EXPECT_LT(chiSquare(dirs, 4096, half, 8, 8), 103.4) << half;
        EXPECT_LT(chiSquare(dirs, 512, half, 8, 8), 103.4) << half;
        EXPECT_LT(chiSquare(dirs, 64, half, 4, 4), 37.7) << half; // a level-of-detail prefix
    }
    // The seed's sampling (uniform theta) fails the same test: it clusters at the poles.
    std::vector<glm::vec3> seed;
    for (int i = 0; i < 32; ++i)
        for (int j = 0; j < 16; ++j) {
            const double th = std::numbers::pi * (i + 0.5) / 32.0, ph = 2.0 * std::numbers::pi * (j + 0.5) / 16.0;
            seed.emplace_back(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
        }
    EXPECT_GT(chiSquare(seed, 512, 3.14159265f, 8, 8), 103.4);
}

TEST(Hair, SameInputsSameStateAndThreadsDoNotChangeIt) {
    HairParams params;
    params.strands = 1000; // not a multiple of the block or of the vector width
    const auto run = [&](int threads) {
        HairSolver h(params, kRadius, spinning(0.0));
        std::vector<SphereCollider> others = {{{0.4f, 1.8f, 0.0f}, 0.15f}};
        VoxelOccupancy floor;
        floor.origin = {-3, 0, -3};
        floor.size = {6, 2, 6};
        floor.solid.assign(72, 0);
        for (int i = 0; i < 36; ++i) floor.solid[static_cast<std::size_t>(i)] = 1; // y = 0 layer
        for (int i = 1; i <= 90; ++i) {
            HostPose pose = spinning(i / 60.0);
            pose.centre.y = 2.0f - 0.012f * static_cast<float>(i);
            h.step(pose, i == 45 ? 0.1f : 1.0f / 60.0f, others, &floor, threads);
        }
        return h.hashState();
    };
    const auto one = run(1);
    EXPECT_EQ(one, run(1));
    EXPECT_EQ(one, run(2));
    EXPECT_EQ(one, run(3));
}

TEST(Hair, RestingBallFallsAsleepAndAMovedHostWakesIt) {
    HairParams params;
    params.strands = 128;
    const HostPose pose{{0.0f, 2.0f, 0.0f}, {}};
    HairSolver h(params, kRadius, pose);
    int steps = 0;
    while (!h.sleeping() && steps < 60 * 30) h.step(pose, 1.0f / 60.0f), ++steps;
    ASSERT_TRUE(h.sleeping()) << "not asleep after 30 s";
    const auto hash = h.hashState();
    h.step(pose, 1.0f / 60.0f);
    EXPECT_TRUE(h.sleeping());
    EXPECT_EQ(hash, h.hashState());
    HostPose moved = pose;
    moved.centre.x += 0.05f;
    h.step(moved, 1.0f / 60.0f);
    EXPECT_FALSE(h.sleeping());
    EXPECT_NE(hash, h.hashState());
    while (!h.sleeping() && steps < 60 * 60) h.step(moved, 1.0f / 60.0f), ++steps;
    ASSERT_TRUE(h.sleeping());
    h.wake();
    EXPECT_FALSE(h.sleeping());
}

TEST(Hair, HairDoesNotSinkIntoAVoxelFloor) {
    HairParams params;
    params.strands = 256;
    const VoxelOccupancy floor = physics::blockFloor(4); // the floor's top is y = 0
    HostPose pose{{0.0f, 1.5f, 0.0f}, {}};
    HairSolver h(params, kRadius, pose);
    const float dt = 1.0f / 60.0f;
    float lowest = 1e9f;
    for (int i = 0; i < 180; ++i) {
        // Dropped fast onto the floor, then rolled along it resting 5 cm above.
        pose.centre.y = std::max(0.3f, 1.5f - 4.0f * static_cast<float>(i) * dt);
        if (pose.centre.y <= 0.3f) pose.centre.x += 0.01f;
        const auto stats = h.step(pose, dt, {}, &floor);
        ASSERT_FALSE(stats.nan);
        ASSERT_LT(stats.maxPenetration, 1e-5f) << "step " << i;
        for (int s = 0; s < h.strands(); ++s)
            for (int n = 1; n < h.nodesPerStrand(); ++n) lowest = std::min(lowest, node(h, s, n).y);
        ASSERT_GE(lowest, -1e-5f) << "step " << i;
    }
    EXPECT_LT(lowest, 0.01f); // the hair did reach the floor
}

TEST(Hair, LevelOfDetailSimulatesOnlyAPrefix) {
    HairParams params;
    params.strands = 300;
    HairSolver h(params, kRadius, HostPose{{0.0f, 2.0f, 0.0f}, {}});
    h.setActiveStrands(100);
    EXPECT_EQ(h.activeStrands(), 100);
    const glm::vec3 frozen = node(h, 250, 5);
    for (int i = 0; i < 30; ++i) h.step(HostPose{{0.0f, 2.0f, 0.0f}, {}}, 1.0f / 60.0f);
    EXPECT_EQ(node(h, 250, 5), frozen);
    EXPECT_NE(node(h, 50, 5), glm::vec3(0.0f));
    h.setActiveStrands(1000);
    EXPECT_EQ(h.activeStrands(), 300);
    const HostPose moved{{1.0f, 2.0f, 0.0f}, {}};
    h.step(moved, 1.0f / 60.0f);
    EXPECT_EQ(node(h, 250, 0), h.rootPosition(moved, 250)); // carried to its root when it came back
    EXPECT_LT(glm::length(node(h, 250, 5) - moved.centre), kRadius + params.strandLength);
}

TEST(Hair, BadParametersAndInputsAreRefused) {
    HairParams p;
    p.strands = 0;
    EXPECT_THROW(HairSolver(p, kRadius, {}), std::invalid_argument);
    p = {};
    p.nodesPerStrand = 1;
    EXPECT_THROW(HairSolver(p, kRadius, {}), std::invalid_argument);
    p = {};
    p.strands = 1'000'000'000;
    EXPECT_THROW(HairSolver(p, kRadius, {}), std::invalid_argument);
    p = {};
    p.dampingPerSecond = -1.0f;
    EXPECT_THROW(HairSolver(p, kRadius, {}), std::invalid_argument);
    EXPECT_THROW(HairSolver(HairParams{}, 0.0f, {}), std::invalid_argument);
    HairSolver h(HairParams{}, kRadius, {});
    const auto before = h.hashState();
    EXPECT_TRUE(h.step({}, 0.0f).nan);
    EXPECT_TRUE(h.step({}, std::nanf("")).nan);
    EXPECT_TRUE(h.step(HostPose{{std::nanf(""), 0.0f, 0.0f}, {}}, 0.01f).nan);
    EXPECT_EQ(before, h.hashState());
}

} // namespace

// Found by the game-state fuzzer: a ball of radius 1e-7 m at y = 40 made NaN hair on its first step. Its roots
// round onto the centre there, and the strands' initial direction was (root - centre) normalised: zero.
TEST(Hair, ATinyBallFarFromTheOriginStaysFinite) {
    physics::HairParams p;
    p.strands = 22;
    p.nodesPerStrand = 7;
    p.strandLength = 0.25f;
    p.patchHalfAngle = 0.25f;
    const physics::HostPose pose{{5.9f, 34.6f, -1.8f}, {}};
    physics::HairSolver hair(p, 1e-7f, pose);
    for (int t = 0; t < 30; ++t) {
        const physics::HairStepStats stats = hair.step(pose, 1.0f / 60.0f);
        ASSERT_FALSE(stats.nan) << "step " << t;
    }
    ASSERT_FALSE(hair.sleeping()) << "precondition: the hair was stepped";
    for (int i = 0; i < p.strands * p.nodesPerStrand; ++i) {
        ASSERT_TRUE(std::isfinite(hair.x()[i]) && std::isfinite(hair.y()[i]) && std::isfinite(hair.z()[i])) << i;
    }
}

// ---- the solver's state: taken, restored, hashed ------------------------------------------------------

// A solver restored from another's state takes the same steps, bit for bit: while the host spins and moves,
// when the level of detail brings strands back (reseat), through the rest window and into sleep, and after
// it wakes. Catches a state that leaves out anything the next step reads (drop m_lastH from it and the first
// step after the restore already differs).
TEST(HairSolverState, ARestoredSolverContinuesBitForBit) {
    HairParams p;
    p.strands = 96;
    const VoxelOccupancy floor = physics::blockFloor(4);
    HairSolver a(p, kRadius, spinning(0.0));
    const auto stepBoth = [&](HairSolver& x, HairSolver* y, const HostPose& pose) {
        x.step(pose, 1.0f / 60.0f, {}, &floor);
        if (y) y->step(pose, 1.0f / 60.0f, {}, &floor);
    };
    for (int i = 0; i < 40; ++i) stepBoth(a, nullptr, spinning(i / 60.0));
    a.setActiveStrands(50);
    stepBoth(a, nullptr, spinning(40 / 60.0));
    a.setActiveStrands(96); // strands 50..95 come back at the next step: restored mid-reseat
    const HairSolverState mid = a.state();
    ASSERT_GE(mid.reseatFrom, 0);
    HairSolver b(p, kRadius, spinning(0.0));
    b.restore(mid);
    ASSERT_EQ(b.hashState(), a.hashState());
    for (int i = 41; i < 100; ++i) {
        stepBoth(a, &b, spinning(i / 60.0));
        ASSERT_EQ(b.hashState(), a.hashState()) << "step " << i;
    }
    // Still host: the rest window opens; restore inside it, then run into sleep together.
    const HostPose still{{0.0f, 0.3f, 0.0f}, {}};
    int i = 0;
    for (; i < 600 && !a.state().window; ++i) stepBoth(a, &b, still);
    stepBoth(a, &b, still);
    ASSERT_TRUE(a.state().window) << "precondition: a rest window is open";
    HairSolver c(p, kRadius, spinning(0.0));
    c.restore(a.state());
    for (i = 0; i < 1800 && !a.sleeping(); ++i) {
        stepBoth(a, &c, still);
        ASSERT_EQ(c.hashState(), a.hashState()) << "still step " << i;
    }
    ASSERT_TRUE(a.sleeping()) << "precondition: the hair fell asleep";
    ASSERT_TRUE(c.sleeping());
    for (i = 0; i < 30; ++i) { // woken by the host moving again
        stepBoth(a, &c, spinning(i / 60.0));
        ASSERT_EQ(c.hashState(), a.hashState()) << "woken step " << i;
    }
}

// The hash reads every field of the state: each one moved by its smallest step (one ulp for a float, one for
// a counter, a flipped flag) gives another hash. Catches a field left out of hashState.
TEST(HairSolverState, TheHashSeesTheSmallestChangeOfEveryField) {
    HairParams p;
    p.strands = 16;
    p.nodesPerStrand = 4;
    HairSolver a(p, kRadius, spinning(0.0));
    for (int i = 0; i < 20; ++i) a.step(spinning(i / 60.0), 1.0f / 60.0f);
    HairSolverState base = a.state();
    base.active = 10;
    base.reseatFrom = 5;
    base.window = true;
    base.wx = base.x, base.wy = base.y, base.wz = base.z;
    base.restTime = 0.25f;
    base.envHash = 12345;
    HairSolver b(p, kRadius, spinning(0.0));
    b.restore(base);
    const std::uint64_t reference = b.hashState();
    const auto up = [](float& f) { f = std::nextafter(f, std::numeric_limits<float>::infinity()); };
    std::vector<std::pair<std::string, std::function<void(HairSolverState&)>>> changes = {
        {"active", [](HairSolverState& s) { s.active += 1; }},
        {"reseatFrom", [](HairSolverState& s) { s.reseatFrom += 1; }},
        {"pose.centre.x", [&](HairSolverState& s) { up(s.pose.centre.x); }},
        {"pose.centre.y", [&](HairSolverState& s) { up(s.pose.centre.y); }},
        {"pose.centre.z", [&](HairSolverState& s) { up(s.pose.centre.z); }},
        {"pose.orientation.w", [&](HairSolverState& s) { up(s.pose.orientation.w); }},
        {"pose.orientation.x", [&](HairSolverState& s) { up(s.pose.orientation.x); }},
        {"pose.orientation.y", [&](HairSolverState& s) { up(s.pose.orientation.y); }},
        {"pose.orientation.z", [&](HairSolverState& s) { up(s.pose.orientation.z); }},
        {"hostMove.x", [&](HairSolverState& s) { up(s.hostMove.x); }},
        {"hostMove.y", [&](HairSolverState& s) { up(s.hostMove.y); }},
        {"hostMove.z", [&](HairSolverState& s) { up(s.hostMove.z); }},
        {"lastH", [&](HairSolverState& s) { up(s.lastH); }},
        {"fresh", [](HairSolverState& s) { s.fresh = !s.fresh; }},
        {"sleeping", [](HairSolverState& s) { s.sleeping = !s.sleeping; }},
        {"restTime", [&](HairSolverState& s) { up(s.restTime); }},
        {"window", [](HairSolverState& s) { s.window = false, s.wx.clear(), s.wy.clear(), s.wz.clear(); }},
        {"envHash", [](HairSolverState& s) { s.envHash += 1; }},
    };
    const std::pair<const char*, std::vector<float> HairSolverState::*> arrays[] = {
        {"x", &HairSolverState::x},   {"y", &HairSolverState::y},   {"z", &HairSolverState::z},
        {"px", &HairSolverState::px}, {"py", &HairSolverState::py}, {"pz", &HairSolverState::pz},
        {"cx", &HairSolverState::cx}, {"cy", &HairSolverState::cy}, {"cz", &HairSolverState::cz},
        {"wx", &HairSolverState::wx}, {"wy", &HairSolverState::wy}, {"wz", &HairSolverState::wz}};
    for (const auto& array : arrays) {
        std::vector<float> HairSolverState::*member = array.second;        // (clang 14 cannot capture a binding)
        for (const std::size_t at : {std::size_t{0}, base.x.size() - 1}) { // a root and the last strand's tip
            changes.emplace_back(std::string(array.first) + "[" + std::to_string(at) + "]",
                                 [&up, member, at](HairSolverState& s) { up((s.*member)[at]); });
        }
    }
    for (const auto& [name, change] : changes) {
        HairSolverState s = base;
        change(s);
        HairSolver c(p, kRadius, spinning(0.0));
        c.restore(s);
        EXPECT_NE(c.hashState(), reference) << name;
    }
}

TEST(HairSolverState, RestoreRefusesAStateThatDoesNotFitAndChangesNothing) {
    HairParams p;
    p.strands = 16;
    p.nodesPerStrand = 4;
    HairSolver a(p, kRadius, spinning(0.0));
    a.step(spinning(0.1), 1.0f / 60.0f);
    const std::uint64_t before = a.hashState();
    const HairSolverState good = a.state();
    const auto refused = [&](const HairSolverState& s, const char* why) {
        try {
            a.restore(s);
            ADD_FAILURE() << "accepted: " << why;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("hair state"), std::string::npos) << e.what();
        }
        EXPECT_EQ(a.hashState(), before) << why;
    };
    HairSolverState s = good;
    s.x.pop_back();
    refused(s, "a node short");
    s = good;
    s.py[3] = std::numeric_limits<float>::quiet_NaN();
    refused(s, "a NaN node");
    s = good;
    s.active = 17;
    refused(s, "more active strands than the ball has");
    s = good;
    s.window = true; // without its arrays
    refused(s, "a window without its nodes");
    s = good;
    s.lastH = -1.0f;
    refused(s, "a negative step");
}
