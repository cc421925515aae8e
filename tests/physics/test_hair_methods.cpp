// The hair methods (physics::HairMethod) against what theory fixes, each on an awake ball:
// - lengths: follow-the-leader, dynamic FTL and SHAKE keep every segment at its rest length to float rounding
//   after every step, through spin, carry, a frame spike and contact with the ball, another ball and blocks;
//   PBD and small steps within the bound their iteration counts give (measured and stated below);
// - damping: the solver's own step (not a helper fed its own factor) moves a free node like the closed form
//   of v' = -g - d v at 30, 60 and 144 Hz and under a jittered step;
// - the yardsticks of hair-bench (naive reference, limit kernel) compute what the solver computes;
// - frame-rate independence: a ball with hair on blocks comes to rest alike at 30, 60 and 144 Hz, and comes to
//   rest at every tick rate the game allows.
#include "lab/hair_reference.h"
#include "physics/hair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

using physics::HairMethod;
using physics::HairParams;
using physics::HairSolver;
using physics::HostPose;
using physics::SphereCollider;
using physics::VoxelOccupancy;

constexpr float kRadius = 0.25f;

std::string name(HairMethod m) { return std::string(physics::hairMethodName(m)); }

std::vector<HairMethod> allMethods() {
    std::vector<HairMethod> out;
    out.reserve(physics::kHairMethodCount);
    for (int i = 0; i < physics::kHairMethodCount; ++i) out.push_back(static_cast<HairMethod>(i));
    return out;
}

// hair-check's floor: blocks for y in [-2, 0), x and z in [-8, 8).
VoxelOccupancy blockFloor() { return physics::blockFloor(8); }

TEST(HairMethods, NamesRoundTripAndUnknownNamesAreRefused) {
    for (HairMethod m : allMethods()) {
        ASSERT_FALSE(name(m).empty());
        EXPECT_EQ(physics::hairMethodFromName(name(m)), m);
        EXPECT_NE(physics::hairMethodNames().find(name(m)), std::string::npos);
    }
    EXPECT_FALSE(physics::hairMethodFromName("Shake"));
    EXPECT_FALSE(physics::hairMethodFromName(""));
    EXPECT_TRUE(physics::hairMethodName(HairMethod::Count).empty());
    HairParams bad;
    bad.method = HairMethod::Count;
    EXPECT_THROW(physics::validateHairParams(bad), std::invalid_argument);
}

// Every method through the phases of hair-check, checked after every step of an awake ball. The bound for
// the exact-length methods is float rounding: a segment of 4 cm at coordinates near 2 m carries about 2.4e-7 m
// of rounding per end, 1.2e-5 of its length; the measured worst is 1e-5.
TEST(HairMethods, LengthsWithinEachMethodsBoundAfterEveryStepOfAnAwakeBall) {
    const VoxelOccupancy floor = blockFloor();
    for (HairMethod m : allMethods()) {
        HairParams params = physics::hairMethodDefaults(m);
        params.strands = 256;
        params.sleepSpeed = 0.0f; // awake throughout (asserted below as well)
        HostPose pose{{0.0f, 1.2f, 0.0f}, {}};
        HairSolver h(params, kRadius, pose);
        const std::vector<SphereCollider> other{{{0.55f, 0.6f, 0.0f}, 0.2f}};
        float worst = 0.0f;
        double angle = 0.0;
        const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, 1.0f, 0.1f));
        for (int i = 0; i < 360; ++i) {
            const float dt = i == 200 ? 0.25f : 1.0f / 60.0f; // a frame spike in the carry
            if (i < 120) {                                    // spin up to 4 rad/s
                angle += 4.0 * std::min(1.0, i / 60.0) * dt;
                pose.orientation = glm::angleAxis(static_cast<float>(angle), axis);
            } else if (i < 240) { // carry at up to 1 m/s, past the other ball
                pose.centre.x = 0.3f * std::sin(static_cast<float>(i - 120) / 20.0f);
            } else { // drop onto the blocks
                pose.centre.y = std::max(0.3f, pose.centre.y - 0.05f);
            }
            const auto stats = h.step(pose, dt, other, &floor);
            ASSERT_FALSE(h.sleeping()) << name(m) << " step " << i;
            ASSERT_FALSE(stats.nan) << name(m) << " step " << i;
            ASSERT_LT(stats.maxPenetration, 2e-3f) << name(m) << " step " << i;
            worst = std::max(worst, stats.maxSegmentError);
            if (m == HairMethod::Ftl || m == HairMethod::Dftl || m == HairMethod::Shake) {
                ASSERT_LT(stats.maxSegmentError, 2e-5f) << name(m) << " step " << i;
            }
        }
        // PBD's lengths are exact only in the limit of many iterations: what its 4 passes (or 4 small steps)
        // leave under this spin, carry, frame spike and contact is large (measured 0.662 for pbd and 0.907 for
        // xpbd-substeps; the lab's charts give it against the passes). Held to 15 % above what was measured, and
        // to at least half of it (a pass that stopped projecting would stretch far more; one that became exact
        // would be news for docs/HAIR.md).
        if (m == HairMethod::Pbd || m == HairMethod::XpbdSubsteps) {
            const float measured = m == HairMethod::Pbd ? 0.662f : 0.907f;
            EXPECT_LT(worst, 1.15f * measured) << name(m);
            EXPECT_GT(worst, 0.5f * measured) << name(m);
        }
        std::printf("[ measured ] %s: worst segment error %.3g over 360 steps\n", name(m).c_str(),
                    static_cast<double>(worst));
    }
}

// A node far out on a 1,000 m segment, moving across it, is a free particle to within (y / L)^2 ~ 1e-5: its
// height under gravity g and damping d follows y(t) = -(g / d) t + (g / d^2)(1 - e^{-d t}) from rest.
// The previous step (e^{-d h} on the displacement, a h (h + hPrev) / 2 for gravity) was off by 2.1 % in
// terminal velocity at 60 Hz; the exact exponential step leaves float rounding, ~1e-5 of the drop.
TEST(HairMethods, DampedFallOfTheSolversOwnStepMatchesTheClosedFormAtAnyStep) {
    const double g = 9.81, d = 2.5;
    const auto exact = [&](double t) { return -(g / d) * t + (g / (d * d)) * (1.0 - std::exp(-d * t)); };
    std::vector<std::pair<std::string, std::vector<double>>> schedules;
    for (int hz : {30, 60, 144}) schedules.emplace_back(std::to_string(hz) + " Hz", std::vector<double>(hz, 1.0 / hz));
    std::vector<double> jittered;
    for (double sum = 0.0; sum < 1.0 - 1e-9;) {
        const double h = std::min(0.004 + 0.03 * ((jittered.size() * 7919) % 101) / 100.0, 1.0 - sum);
        jittered.push_back(h);
        sum += h;
    }
    schedules.emplace_back("jittered", jittered);
    for (HairMethod m : allMethods()) {
        for (const auto& [label, steps] : schedules) {
            HairParams p = physics::hairMethodDefaults(m);
            p.strands = 1;
            p.nodesPerStrand = 2;
            p.strandLength = 1000.0f;
            p.dampingPerSecond = static_cast<float>(d);
            p.gravity = static_cast<float>(g);
            p.hostCollision = false;
            p.maxSubstepSeconds = 0.0f;
            p.substeps = 1;
            p.sleepSpeed = 0.0f;
            const HostPose pose{};
            HairSolver h(p, 1e-3f, pose);
            const glm::vec3 root = h.rootPosition(pose, 0);
            const glm::vec3 strand[2] = {root, root + glm::vec3(1000.0f, 0.0f, 0.0f)};
            h.setStrand(0, strand);
            double t = 0.0;
            for (double step : steps) {
                h.step(pose, static_cast<float>(step));
                t += step;
                const double y = static_cast<double>(h.y()[1] - root.y);
                ASSERT_NEAR(y, exact(t), 1e-4 * std::abs(exact(t)) + 1e-6) << name(m) << ", " << label << ", t " << t;
            }
            EXPECT_NEAR(t, 1.0, 1e-9);
        }
    }
}

// hair-bench's yardsticks must time the solver's own arithmetic: from the same state, the limit kernel gives
// the solver's positions bit for bit over 20 steps (it runs the same level loops); the naive reference gives
// them to rounding after one step (1e-6 m, a few float steps at 2 m: its SHAKE sums in another order and its
// pushes round (p - c) + c differently). Over more steps that rounding grows, as any rounding does in hair
// draping chaotically over its ball (measured: 2e-7 m after one step, 1e-3 m after eight).
TEST(HairMethods, NaiveReferenceLimitKernelAndSolverComputeTheSamePositions) {
    for (HairMethod m : allMethods()) {
        HairParams p = physics::hairMethodDefaults(m);
        p.strands = 200; // three blocks, the last partial
        p.sleepSpeed = 0.0f;
        p.maxSubstepSeconds = 0.0f; // one substep a step, as the naive reference and the limit kernel take
        const HostPose pose{{0.0f, 2.0f, 0.0f}, {}};
        HairSolver solver(p, kRadius, pose);
        for (int i = 0; i < 30; ++i) solver.step(pose, 1.0f / 60.0f); // draped, in contact with the ball
        lab::NaiveHairReference naive(solver);
        lab::HairLimitKernel limit(solver);
        const auto compare = [&](float& worstNaive, int& differentLimit) {
            worstNaive = 0.0f;
            differentLimit = 0;
            for (int s = 0; s < solver.strands(); ++s) {
                for (int n = 0; n < solver.nodesPerStrand(); ++n) {
                    const std::size_t i = static_cast<std::size_t>(n) * static_cast<std::size_t>(solver.strands()) +
                                          static_cast<std::size_t>(s);
                    const glm::vec3 x(solver.x()[i], solver.y()[i], solver.z()[i]);
                    worstNaive = std::max(worstNaive, glm::length(naive.position(s, n) - x));
                    differentLimit += limit.position(s, n) != x;
                }
            }
        };
        float worstNaive = 0.0f;
        int differentLimit = 0;
        for (int i = 0; i < 20; ++i) {
            solver.step(pose, 1.0f / 60.0f);
            naive.step(1.0f / 60.0f);
            limit.step(1.0f / 60.0f);
            ASSERT_FALSE(solver.sleeping());
            compare(worstNaive, differentLimit);
            if (i == 0) {
                EXPECT_LT(worstNaive, 1e-6f) << name(m);
            }
            ASSERT_EQ(differentLimit, 0) << name(m) << " step " << i;
        }
    }
}

struct RestResult {
    double settleSeconds = -1;
    std::vector<glm::vec3> nodes;
};

// The game's default ball (0.25 m here, as in hair-check) resting 0.3 m above the blocks, hair starting
// straight out: time until it sleeps, and its shape then (or, with `sleep` false, its shape after 10 s: where it
// comes to rest, not where sleep froze it).
RestResult restOnBlocks(double tickRate, HairMethod method, bool sleep = true) {
    HairParams p = physics::hairMethodDefaults(method);
    if (!sleep) p.sleepSpeed = 0.0f;
    const VoxelOccupancy floor = blockFloor();
    const HostPose pose{{0.0f, 0.3f, 0.0f}, {}};
    HairSolver h(p, kRadius, pose);
    RestResult r;
    const float dt = static_cast<float>(1.0 / tickRate);
    for (int i = 1; i <= static_cast<int>((sleep ? 30.0 : 10.0) * tickRate); ++i) {
        h.step(pose, dt, {}, &floor);
        if (h.sleeping()) {
            r.settleSeconds = i / tickRate;
            break;
        }
    }
    const std::size_t total = static_cast<std::size_t>(h.strands()) * static_cast<std::size_t>(h.nodesPerStrand());
    for (std::size_t i = 0; i < total; ++i) r.nodes.emplace_back(h.x()[i], h.y()[i], h.z()[i]);
    return r;
}

// The default method's substeps are at most 1/60 s whatever the tick, with damping exact per second and
// contacts that keep lengths: settle time and rest shape compared at 60, 144 and 240 Hz, three rates whose
// substeps differ (30 Hz takes two substeps of 1/60 s, the same as 60 Hz: comparing those shows nothing). The
// shape is compared after 10 s with sleep off (where the hair rests, not where sleep caught it).
TEST(HairMethods, DefaultMethodSettlesAlikeAtRatesWhoseSubstepsDiffer) {
    const HairMethod m = HairParams{}.method;
    const auto substep = [](double hz) {
        const double tick = 1.0 / hz, most = static_cast<double>(HairParams{}.maxSubstepSeconds);
        return tick / std::ceil(tick / most - 1e-9);
    };
    ASSERT_EQ(substep(30), substep(60)); // why 30 Hz is not among them
    ASSERT_LT(substep(144), substep(60));
    ASSERT_LT(substep(240), substep(144));
    const RestResult a = restOnBlocks(60, m), b = restOnBlocks(144, m), c = restOnBlocks(240, m);
    ASSERT_GT(a.settleSeconds, 0.0);
    ASSERT_GT(b.settleSeconds, 0.0);
    ASSERT_GT(c.settleSeconds, 0.0);
    const double lo = std::min({a.settleSeconds, b.settleSeconds, c.settleSeconds});
    const double hi = std::max({a.settleSeconds, b.settleSeconds, c.settleSeconds});
    std::printf("[ measured ] settle at 60 / 144 / 240 Hz: %.3f / %.3f / %.3f s\n", a.settleSeconds, b.settleSeconds,
                c.settleSeconds);
    // Measured 3.00 / 3.12 / 3.53 s: stepped by the tick, the solver settles 18 % later at 240 Hz than at 60 Hz
    // (the game steps it on its 1/60 s clock instead: docs/HAIR.md, "Frame-rate independence"). Held to the
    // measured spread with 5 points of margin, so a change that widens it fails here.
    EXPECT_LE(hi, 1.23 * lo);
    const RestResult sa = restOnBlocks(60, m, false), sb = restOnBlocks(144, m, false),
                     sc = restOnBlocks(240, m, false);
    const auto rms = [](const RestResult& x, const RestResult& y) {
        double sum = 0.0;
        for (std::size_t i = 0; i < x.nodes.size(); ++i) {
            const glm::vec3 d = x.nodes[i] - y.nodes[i];
            sum += static_cast<double>(glm::dot(d, d));
        }
        return std::sqrt(sum / static_cast<double>(x.nodes.size())) / static_cast<double>(HairParams{}.strandLength);
    };
    std::printf(
        "[ measured ] node-by-node RMS difference 60-144 / 144-240 / 60-240 Hz: %.3f / %.3f / %.3f of a strand\n",
        rms(sa, sb), rms(sb, sc), rms(sa, sc));
    // The shape a player sees: how high the hair lies (mean height of its nodes above the blocks) and how far
    // it spreads (mean horizontal distance from the ball's axis). Which way one strand happened to drape is
    // not shape: contact friction keeps whatever the path gave it, so node by node the rests of 60 and 144 Hz
    // differ by 16 % of a strand RMS (printed above).
    const auto shape = [](const RestResult& r) {
        double height = 0.0, spread = 0.0;
        for (const glm::vec3& n : r.nodes) {
            height += static_cast<double>(n.y);
            spread += std::sqrt(static_cast<double>(n.x * n.x + n.z * n.z));
        }
        const double count = static_cast<double>(r.nodes.size());
        return std::pair{height / count, spread / count};
    };
    const auto [h60, s60] = shape(sa);
    const auto [h144, s144] = shape(sb);
    const auto [h240, s240] = shape(sc);
    std::printf("[ measured ] mean height / spread at 60, 144, 240 Hz: %.4f / %.4f, %.4f / %.4f, %.4f / %.4f m\n", h60,
                s60, h144, s144, h240, s240);
    EXPECT_LE(std::max({h60, h144, h240}), 1.15 * std::min({h60, h144, h240}));
    EXPECT_LE(std::max({s60, s144, s240}), 1.15 * std::min({s60, s144, s240}));
}

TEST(HairMethods, DefaultMethodComesToRestAtEveryTickRateTheGameAllows) {
    for (double hz : {10.0, 20.0, 500.0, 1000.0}) {
        const RestResult r = restOnBlocks(hz, HairParams{}.method);
        EXPECT_GT(r.settleSeconds, 0.0) << hz << " Hz";
    }
}

} // namespace
