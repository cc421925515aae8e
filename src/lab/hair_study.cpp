#include "lab/hair_study.h"

#include "lab/lab_util.h"

#include "lab/hair_reference.h"
#include "physics/hair.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace lab {

namespace {

// JSON has no NaN or infinity: null.
std::string number(double v) { return std::isfinite(v) ? formatNumber("%.6g", v) : "null"; }

} // namespace

physics::HairParams hairStudyParams(const std::string& solver, int iterations, int substeps) {
    physics::HairParams p = physics::hairMethodDefaults(physics::hairMethodFromName(solver).value());
    if (iterations > 0) p.iterations = iterations;
    if (substeps > 0) p.substeps = substeps;
    return p;
}

std::string validateHairSolverName(const std::string& solver, const std::string& flag) {
    if (physics::hairMethodFromName(solver)) return {};
    return flag + " '" + solver + "' is not a hair solver; choose one of " + physics::hairMethodNames();
}

std::string validatePassCounts(int iterations, int substeps) {
    if (iterations < 0 || iterations > 1000)
        return "--iterations must be in 0..1000 (0: the solver's default), got " + std::to_string(iterations);
    if (substeps < 0 || substeps > 1000)
        return "--substeps must be in 0..1000 (0: the solver's default), got " + std::to_string(substeps);
    return {};
}

std::string validateHairBench(const HairBenchOptions& o) {
    if (std::string why = validateHairSolverName(o.solver); !why.empty()) return why;
    if (o.strands < 1 || o.strands > kMaxHairStrands)
        return "--strands must be in 1.." + std::to_string(kMaxHairStrands);
    if (o.nodes < 2 || o.nodes > kMaxHairNodesPerStrand)
        return "--nodes must be in 2.." + std::to_string(kMaxHairNodesPerStrand);
    if (static_cast<std::int64_t>(o.strands) * o.nodes > physics::kMaxHairNodes)
        return "--strands * --nodes must be at most " + std::to_string(physics::kMaxHairNodes);
    if (std::string why = validatePassCounts(o.iterations, o.substeps); !why.empty()) return why;
    if (o.steps < 1 || o.steps > kMaxHairSteps) return "--steps must be in 1.." + std::to_string(kMaxHairSteps);
    if (o.threads < 1 || o.threads > kMaxHairThreads)
        return "--threads must be in 1.." + std::to_string(kMaxHairThreads);
    return {};
}

HairBenchResult runHairBench(const HairBenchOptions& o) {
    HairBenchResult r;
    r.options = o;
    physics::HairParams params = hairStudyParams(o.solver, o.iterations, o.substeps);
    r.iterations = params.iterations;
    r.substeps = params.substeps;
    params.strands = o.strands;
    params.nodesPerStrand = o.nodes;
    params.sleepSpeed = 0.0f; // never sleep: time the work, not the shortcut
    const physics::HostPose pose{{0.0f, 2.0f, 0.0f}, {}};
    const float dt = 1.0f / 60.0f, radius = 0.25f;
    physics::HairSolver solver(params, radius, pose);
    for (int i = 0; i < 10; ++i) solver.step(pose, dt, {}, nullptr, o.threads); // drape the hair a little first
    lab::HairLimitKernel limit(solver);
    lab::NaiveHairReference naive(solver);
    const double nodes = static_cast<double>(o.strands) * o.nodes;

    // The solver and the limit kernel in alternating batches (bestSecondsPerStep's batching), so that both see the
    // same machine (clock, the other work on a shared host), not one the first half and the other the second.
    // Their states are separate: each computes the same positions as before.
    const int batches = std::clamp(o.steps / 20, 1, 10), perBatch = std::max(1, o.steps / batches);
    double solverS = 1e30, limitS = 1e30;
    for (int b = 0; b < batches; ++b) {
        auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < perBatch; ++i) solver.step(pose, dt, {}, nullptr, o.threads);
        solverS = std::min(solverS, secondsSince(t0) / perBatch);
        t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < perBatch; ++i) limit.step(dt);
        limitS = std::min(limitS, secondsSince(t0) / perBatch);
    }
    const double naiveS = bestSecondsPerStep(std::max(1, std::min(o.steps, 40)), [&] { naive.step(dt); });
    r.msPerStep = solverS * 1e3;
    r.limitMsPerStep = limitS * 1e3;
    r.naiveMsPerStep = naiveS * 1e3;
    r.nodeStepsPerS = nodes / solverS;
    r.limitNodeStepsPerS = nodes / limitS;
    r.naiveNodeStepsPerS = nodes / naiveS;
    return r;
}

void writeHairBenchJson(const HairBenchResult& r, std::ostream& out) {
    out << "{\n"
        << "  \"solver\": \"" << r.options.solver << "\",\n"
        << "  \"strands\": " << r.options.strands << ",\n"
        << "  \"nodes\": " << r.options.nodes << ",\n"
        << "  \"iterations\": " << r.iterations << ",\n"
        << "  \"substeps\": " << r.substeps << ",\n"
        << "  \"steps\": " << r.options.steps << ",\n"
        << "  \"threads\": " << r.options.threads << ",\n"
        << "  \"node_steps_per_s\": " << number(r.nodeStepsPerS) << ",\n"
        << "  \"naive_node_steps_per_s\": " << number(r.naiveNodeStepsPerS) << ",\n"
        << "  \"limit_node_steps_per_s\": " << number(r.limitNodeStepsPerS) << ",\n"
        << "  \"ms_per_step\": " << number(r.msPerStep) << ",\n"
        << "  \"naive_ms_per_step\": " << number(r.naiveMsPerStep) << ",\n"
        << "  \"limit_ms_per_step\": " << number(r.limitMsPerStep) << ",\n"
        << "  \"speedup_vs_naive\": " << number(r.speedupVsNaive()) << ",\n"
        << "  \"fraction_of_limit\": " << number(r.fractionOfLimit()) << "\n"
        << "}\n";
}

void writeHairBenchSummary(const HairBenchResult& r, std::ostream& out) {
    out << "hair-bench: " << r.options.solver << ", " << r.options.strands << " strands x " << r.options.nodes
        << " nodes, " << r.iterations << " iteration" << (r.iterations == 1 ? "" : "s") << " x " << r.substeps
        << " substep" << (r.substeps == 1 ? "" : "s") << ", ball collision on\n"
        << "  solver (" << r.options.threads << " thread" << (r.options.threads == 1 ? "" : "s")
        << "): " << number(r.msPerStep) << " ms/step, " << number(r.nodeStepsPerS / 1e6) << " M node-steps/s\n"
        << "  naive reference (AoS, seed-style): " << number(r.naiveMsPerStep) << " ms/step, "
        << number(r.naiveNodeStepsPerS / 1e6) << " M node-steps/s\n"
        << "  limit kernel (SoA, no features, 1 thread): " << number(r.limitMsPerStep) << " ms/step, "
        << number(r.limitNodeStepsPerS / 1e6) << " M node-steps/s\n"
        << "  solver / naive = " << number(r.speedupVsNaive())
        << "x, solver / limit = " << number(100.0 * r.fractionOfLimit()) << " %\n";
}

std::string validateHairCheck(const HairCheckOptions& o) {
    if (std::string why = validateHairSolverName(o.solver); !why.empty()) return why;
    if (std::string why = validatePassCounts(o.iterations, o.substeps); !why.empty()) return why;
    if (!(std::isfinite(o.dt) && o.dt > 0.0 && o.dt <= 1.0)) return "--dt must be a finite number in (0, 1] seconds";
    if (!(std::isfinite(o.seconds) && o.seconds > 0.0 && o.seconds <= 600.0))
        return "--seconds must be a finite number in (0, 600]";
    if (o.seconds / o.dt > kMaxHairSteps)
        return "--seconds / --dt asks for more than " + std::to_string(kMaxHairSteps) + " steps";
    return {};
}

HairCheckResult runHairCheck(const HairCheckOptions& o) {
    HairCheckResult r;
    r.options = o;
    const physics::HairParams params = hairStudyParams(o.solver, o.iterations, o.substeps);
    r.iterations = params.iterations;
    r.substeps = params.substeps;
    const float radius = 0.25f;
    const physics::VoxelOccupancy floor = physics::blockFloor(8); // blocks for y in [-2, 0), x and z in [-8, 8)

    physics::HostPose pose{{0.0f, 1.5f, 0.0f}, {}};
    physics::HairSolver hair(params, radius, pose);
    const double T = o.seconds;
    double t = 0.0;
    const auto account = [&](const physics::HairStepStats& s) {
        r.maxSegmentError = std::max(r.maxSegmentError, static_cast<double>(s.maxSegmentError));
        r.maxPenetration = std::max(r.maxPenetration, static_cast<double>(s.maxPenetration));
        r.nan = r.nan || s.nan;
        ++r.steps;
    };
    // As the game steps a ball: on the hair clock (substeps of exactly 1/60 s, physics::hairClockSteps), so that
    // every tick rate runs the same hair steps.
    // poseAt(time since the phase began at phaseStart) sets the host's pose at each substep's own time, so that
    // every tick rate gives the hair the same motion; without it (the frame spike, where the game would know the
    // pose only at the tick's end) the substeps move the host evenly towards the tick's pose.
    double phaseStart = 0.0;
    const auto advance = [&](double dt, const std::function<void(double)>& poseAt) {
        const int steps = physics::hairClockSteps(t, t + dt);
        if (steps > 0 && poseAt) {
            const double first = std::floor(t / physics::kHairClockSeconds + 1e-6) + 1.0;
            for (int j = 0; j < steps; ++j) {
                poseAt((first + j) * physics::kHairClockSeconds - phaseStart);
                account(hair.step(pose, static_cast<float>(physics::kHairClockSeconds), {}, &floor));
            }
        } else if (steps > 0) {
            account(hair.step(pose, static_cast<float>(steps * physics::kHairClockSeconds), {}, &floor));
        }
        t += dt;
    };
    // 1. Spin: angular velocity ramps up to 8 rad/s about a tilted axis, then holds.
    const glm::vec3 axis = glm::normalize(glm::vec3(0.3f + static_cast<float>(o.perturbation), 1.0f, 0.1f));
    // The host's motions are exact functions of time, sampled at the ticks, so that every tick rate sees the same
    // motion (only sampled more or less often). The spin's angle: the integral of the ramp 8 rad/s x t / (T/2).
    const auto spinAngle = [&](double s) {
        const double ramp = 0.5 * T;
        return s < ramp ? 8.0 * s * s / (2.0 * ramp) : 8.0 * ramp / 2.0 + 8.0 * (s - ramp);
    };
    const auto spinPose = [&](double s) { pose.orientation = glm::angleAxis(static_cast<float>(spinAngle(s)), axis); };
    phaseStart = t;
    for (std::int64_t k = 1; static_cast<double>(k - 1) * o.dt < T; ++k) {
        spinPose(static_cast<double>(k) * o.dt);
        advance(o.dt, spinPose);
    }
    // 2. Carry along a figure of eight at up to ~2 m/s, with a 0.25 s frame spike half way.
    const glm::vec3 start = pose.centre;
    // Tick times counted, not summed, so that the spike starts at 0.5 T and the phase ends at T exactly at every
    // rate (summed, a rate whose sum of ticks fell a rounding short ran one tick more, and the drop then started
    // a tick's carry away: 1.6 cm higher at 60 Hz than at 240 Hz); the last tick is cut short to end there.
    const auto carryPose = [&](double s) {
        const double u = 2.0 * 3.14159265358979 * s / T;
        pose.centre =
            start + glm::vec3(static_cast<float>(0.6 * std::sin(u)), static_cast<float>(0.2 * std::sin(2.0 * u)),
                              static_cast<float>(0.4 * std::sin(2.0 * u)));
    };
    phaseStart = t;
    {
        constexpr double kSlack = 1e-9;
        double s = 0.0, spikeEnd = 0.0;
        bool spiked = false;
        std::int64_t before = 0, after = 0; // ticks before and after the spike
        while (s < T - kSlack) {
            double next = 0.0;
            if (!spiked && s >= 0.5 * T - kSlack) {
                spiked = true;
                spikeEnd = s + 0.25;
                next = spikeEnd;
            } else {
                next = spiked ? spikeEnd + static_cast<double>(++after) * o.dt : static_cast<double>(++before) * o.dt;
            }
            next = std::min(next, T);
            const double dt = next - s;
            const bool spike = dt > 0.2;
            s = next;
            carryPose(s);
            advance(dt, spike ? std::function<void(double)>() : carryPose);
        }
    }
    // 3. Drop onto the blocks: free fall from where it is to resting 0.3 m above the floor (hair on the ground).
    const double dropFrom = static_cast<double>(pose.centre.y);
    const auto dropPose = [&](double s) {
        pose.centre.y = static_cast<float>(std::max(0.3, dropFrom - 0.5 * 9.81 * s * s));
    };
    phaseStart = t;
    for (std::int64_t k = 1; static_cast<double>(k - 1) * o.dt < T; ++k) {
        dropPose(static_cast<double>(k) * o.dt);
        advance(o.dt, dropPose);
    }
    // 4. Still host: how long until the hair is at rest.
    for (double s = 0.0; s < 30.0; s += o.dt) {
        advance(o.dt, {});
        if (hair.sleeping()) {
            r.settleSeconds = s + o.dt;
            break;
        }
    }
    // 5. The same rest from the same start at every step: a new ball 0.3 m above the blocks, hair straight out.
    // (Phases 1-3 scramble the hair chaotically, so settle_seconds also reflects where they left it.)
    const physics::HostPose still{{0.0f, 0.3f, 0.0f}, {}};
    physics::HairSolver fresh(params, radius, still);
    for (std::int64_t k = 0; static_cast<double>(k) * o.dt < 30.0; ++k) {
        const double from = static_cast<double>(k) * o.dt, to = from + o.dt;
        if (const int steps = physics::hairClockSteps(from, to); steps > 0)
            account(fresh.step(still, static_cast<float>(steps * physics::kHairClockSeconds), {}, &floor));
        if (fresh.sleeping()) {
            r.restSettleSeconds = to;
            break;
        }
    }
    return r;
}

void writeHairCheckJson(const HairCheckResult& r, std::ostream& out) {
    out << "{\n"
        << "  \"solver\": \"" << r.options.solver << "\",\n"
        << "  \"iterations\": " << r.iterations << ",\n"
        << "  \"substeps\": " << r.substeps << ",\n"
        << "  \"dt\": " << number(r.options.dt) << ",\n"
        << "  \"max_segment_error\": " << number(r.maxSegmentError) << ",\n"
        << "  \"max_penetration\": " << number(r.maxPenetration) << ",\n"
        << "  \"nan\": " << (r.nan ? "true" : "false") << ",\n"
        << "  \"settle_seconds\": " << number(r.settleSeconds) << ",\n"
        << "  \"rest_settle_seconds\": " << number(r.restSettleSeconds) << ",\n"
        << "  \"steps\": " << r.steps << "\n"
        << "}\n";
}

HairDropSettles hairDropSettles(const HairCheckOptions& options, int drops) {
    HairDropSettles r;
    for (int k = 0; k < drops; ++k) {
        HairCheckOptions o = options;
        o.perturbation = options.perturbation + 1e-4 * k;
        const double settle = runHairCheck(o).settleSeconds;
        if (settle > 0.0)
            r.seconds.push_back(settle);
        else
            ++r.unsettled;
    }
    std::sort(r.seconds.begin(), r.seconds.end());
    if (!r.seconds.empty()) {
        const std::size_t n = r.seconds.size();
        r.median = n % 2 == 1 ? r.seconds[n / 2] : 0.5 * (r.seconds[n / 2 - 1] + r.seconds[n / 2]);
        r.min = r.seconds.front();
        r.max = r.seconds.back();
    }
    return r;
}

} // namespace lab
