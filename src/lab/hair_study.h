// The hair studies of minecrappy-lab, as library functions so tests can run them on tiny inputs:
// hair-bench times the project's solver beside a naive reference written the way the seed's code is and a
// minimal vectorised kernel (the practical limit of the machine), all in one run; hair-check drives a ball
// through spin, carry, a frame spike and a drop onto blocks and reports the worst segment error, the deepest
// penetration, NaNs and how long the hair takes to come to rest, then how long a new ball on the blocks takes.
// It must never touch a terminal or exit: results are returned, and JSON is written whole or not at all.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "physics/hair.h"

namespace lab {

inline constexpr int kMaxHairStrands = 1 << 20; // --strands above this is refused
inline constexpr int kMaxHairNodesPerStrand = 256;
inline constexpr int kMaxHairSteps = 1'000'000;
inline constexpr int kMaxHairThreads = 64;

struct HairBenchOptions {
    std::string solver = "dftl"; // a physics::hairMethodName
    int strands = 512;           // strands on the ball
    int nodes = 12;              // nodes per strand, root included
    int iterations = 0;          // constraint passes (shake: Newton iterations) per substep; 0 = the game's default
    int substeps = 0;            // substeps per step; 0 = the game's default for the solver
    int steps = 300;             // timed steps of the solver and the limit kernel (the naive reference gets fewer)
    int threads = 1;             // threads for the project's solver
};

// The hair parameters a study runs with: the game's defaults for `solver` (physics::hairMethodDefaults), with
// iterations and substeps replaced where given (> 0). The solver name must be valid (validate first).
physics::HairParams hairStudyParams(const std::string& solver, int iterations, int substeps);
// An empty string when `solver` names a method; otherwise the message for `flag`, listing the choices.
std::string validateHairSolverName(const std::string& solver, const std::string& flag = "--solver");
// An empty string when --iterations and --substeps are in 0..1000 (0: the solver's default); otherwise what
// is wrong, naming the flag and the value.
std::string validatePassCounts(int iterations, int substeps);

struct HairBenchResult {
    HairBenchOptions options;
    int iterations = 0, substeps = 0; // what was run (the options' 0 resolved to the solver's defaults)
    double nodeStepsPerS = 0;         // project's solver: strands * nodes * steps / second
    double naiveNodeStepsPerS = 0;    // the seed-style reference (AoS, one object per strand, scalar)
    double limitNodeStepsPerS = 0;    // the minimal SoA kernel, one thread
    double msPerStep = 0;             // project's solver
    double limitMsPerStep = 0, naiveMsPerStep = 0;
    double speedupVsNaive() const { return naiveNodeStepsPerS > 0 ? nodeStepsPerS / naiveNodeStepsPerS : 0; }
    double fractionOfLimit() const { return limitNodeStepsPerS > 0 ? nodeStepsPerS / limitNodeStepsPerS : 0; }
};

// An empty string when the options are usable; otherwise what is wrong, naming the flag (--strands ...).
std::string validateHairBench(const HairBenchOptions& options);
HairBenchResult runHairBench(const HairBenchOptions& options);
void writeHairBenchJson(const HairBenchResult& result, std::ostream& out);
void writeHairBenchSummary(const HairBenchResult& result, std::ostream& out);

struct HairCheckOptions {
    std::string solver = "dftl"; // a physics::hairMethodName
    int iterations = 0;          // 0 = the game's default for the solver
    int substeps = 0;            // 0 = the game's default for the solver
    double dt = 1.0 / 60.0;      // s, the game's tick; (0, 1]
    double seconds = 2.0;        // s, length of each phase (spin, carry, drop); (0, 600]
    double perturbation = 0.0;   // added to the spin axis' x (before normalising; hairDropSettles' perturbations)
};

struct HairCheckResult {
    HairCheckOptions options;
    int iterations = 0, substeps = 0; // what was run
    double maxSegmentError = 0;       // relative, worst over every step
    double maxPenetration = 0;        // m inside any collider after a step, worst
    bool nan = false;
    double settleSeconds = -1; // s from the host stopping to the hair at rest (asleep); -1: not within 30 s
    // s for a new ball resting 0.3 m above the blocks, hair straight out, to come to rest: the same start at
    // every --dt, so it compares tick rates (settleSeconds starts from wherever the chaotic phases left the
    // hair); -1: not within 30 s
    double restSettleSeconds = -1;
    int steps = 0;
};

std::string validateHairCheck(const HairCheckOptions& options);

// The settle time after the drop is one sample of a chaotic motion (the spin, carry and drop leave the hair in
// a state that depends on every rounding): `drops` runs of hair-check whose spin axes differ by 1e-4 (k x 1e-4
// added to its x, k = 0..drops-1, about 0.1 mrad apart), their settle times sorted, median and range.
struct HairDropSettles {
    std::vector<double> seconds; // sorted
    double median = 0.0, min = 0.0, max = 0.0;
    int unsettled = 0; // runs that did not settle within 30 s (not in seconds)
};
HairDropSettles hairDropSettles(const HairCheckOptions& options, int drops);
HairCheckResult runHairCheck(const HairCheckOptions& options);
void writeHairCheckJson(const HairCheckResult& result, std::ostream& out);

} // namespace lab
