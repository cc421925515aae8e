// The hair solver's charts for minecrappy-lab, as library functions so tests can run them on tiny inputs:
// - hair-work-precision: every constraint method (physics::HairMethod) at several steps and iteration or
//   substep counts, on the lab's free chain (lab/hair_chain.h: a straight horizontal strand released at rest,
//   against a converged reference), with the work each one costs, counted (projections per node) and measured
//   (ns per node-step on a realistic ball). Written as hair_work_precision.csv and .svg.
// - hair-stability: per method at its game defaults (physics::hairMethodDefaults), which steps, spin rates
//   and carry speeds keep a hair ball bounded, scanned over a whole grid (stability need not be monotonic,
//   so values that pass again beyond the first failure are reported as islands). Written as
//   hair_stability.csv, hair_stability_limits.csv and hair_stability.svg.
// Every size and duration is an option; the defaults are the full studies (measured: about 6 s each in a
// Release build here), quick() the tests' versions. Timing is reported, never asserted.
// It must never touch a terminal or exit: progress goes through a callback, results are returned, and files
// are written whole (temporary file + rename) or not at all.
#pragma once
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "lab/hair_chain.h"      // lab::ChainLook
#include "lab/pendulum_common.h" // lab::Progress
#include "lab/svg_chart.h"
#include "physics/hair.h"

namespace lab {

// Every method, in enum order (physics::HairMethod 0 .. Count - 1).
std::vector<physics::HairMethod> hairMethods();
// A fixed colour per method, shared by all hair charts.
int hairMethodColour(physics::HairMethod method);

// ---------------------------------------------------------------------------------------------------
// Work-precision.

struct HairWorkPrecisionOptions {
    std::vector<physics::HairMethod> methods = hairMethods();
    std::vector<double> dts = {1.0 / 30.0, 1.0 / 60.0, 1.0 / 120.0, 1.0 / 240.0}; // steps (s)
    std::vector<int> iterations = {1, 2, 4, 8};   // ftl, dftl, pbd: passes per step (1 substep)
    std::vector<int> shakeIterations = {1, 2, 3}; // shake: Newton iterations per step (1 substep)
    std::vector<int> substeps = {1, 2, 4, 8};     // xpbd-substeps: substeps per step (1 iteration each)
    // shake as the game runs it too: its default Newton iterations with automatic substeps (chosen from its
    // segments' turn, physics::hairSubstepsFor), its cost the substeps it took on average.
    bool shakeAutomatic = true;
    // The chain (lab/hair_chain.h).
    int links = 11;
    double length = 0.45;   // m
    double seconds = 10.0;  // s simulated; >= lateTime and lookTo
    double gravity = 9.81;  // m/s^2
    double earlyTime = 0.5; // s: tip error read here (column tip_error_0_5s)...
    double lateTime = 2.0;  // s: ...and here (column tip_error_2s)
    // Past the predictability horizon (2.5 s for this chain: chainHorizon, the hair report's table) a tip error
    // compares nothing; what the eye sees (lab::chainLook) is read over [lookFrom, lookTo] instead.
    double lookFrom = 2.5; // s
    double lookTo = 10.0;  // s
    // Timing: a ball like the game's, host collision on, no other colliders, never asleep, one thread,
    // spinning slowly; the best of a few batches counts. Timed once per (method, iterations, substeps) at
    // timingDt: a step's work does not depend on its length (no automatic substeps: maxSubstepSeconds = 0).
    int timingStrands = 4096;
    int timingNodes = 12;         // per strand, root included
    double timingRadius = 0.25;   // m
    double timingDt = 1.0 / 60.0; // s
    int timingWarmupSteps = 10;
    int timingSteps = 100; // timed steps, in batches of about 20

    // The tests' version: two steps, a 2 s chain, a small ball timed for a few steps.
    static HairWorkPrecisionOptions quick();
};

struct HairWorkPrecisionRow {
    physics::HairMethod method = physics::HairMethod::Ftl;
    double dt = 0.0;               // s
    int iterations = 1;            // HairParams::iterations
    int substeps = 1;              // HairParams::substeps
    bool automatic = false;        // shake with automatic substeps (HairWorkPrecisionOptions::shakeAutomatic)
    double meanSubsteps = 1.0;     // substeps a step took on average (= substeps unless automatic)
    double projectionsPerNode = 0; // physics::hairProjectionsPerNode per free node per step (x meanSubsteps)
    double nsPerNodeStep = 0.0;    // measured, per node (roots included) per step()
    double tipErrorEarly = 0.0;    // m, |tip - reference tip| at earlyTime
    double tipErrorLate = 0.0;     // m, at lateTime
    double maxSegmentError = 0.0;  // relative, largest over the run
    double maxEnergyError = 0.0;   // largest |energy error| over the run (HairChainRow::energyError)
    ChainLook look;                // over [lookFrom, lookTo]: the method's and the reference's (lab::chainLook)
};

// The cells the sweep runs, in order (method, then iterations or substeps, then dt), with their accuracy
// and cost fields unset: what runHairWorkPrecision() returns one row for.
std::vector<HairWorkPrecisionRow> hairWorkPrecisionCells(const HairWorkPrecisionOptions& options);
// Throws std::invalid_argument for options that make no sweep (no methods or steps, a count < 1, a read-out
// time outside the run, a chain lab/hair_chain.h refuses, a ball HairSolver refuses).
std::vector<HairWorkPrecisionRow> runHairWorkPrecision(const HairWorkPrecisionOptions& options,
                                                       const Progress& progress = {});
// Columns: method,dt,iterations,substeps,automatic,mean_substeps,projections_per_node,ns_per_node_step,
// tip_error_0_5s,tip_error_2s,max_segment_error,max_energy_error,look_energy,look_mean_tip_height,
// look_swing_period,ref_mean_tip_height,ref_swing_period (full precision; nan where a run blew up or, for a
// period, where the tip did not swing).
void writeHairWorkPrecisionCsv(const std::vector<HairWorkPrecisionRow>& rows, std::ostream& out);
// Log-log, one colour per method, one line per iteration (or substep) count through its steps: tip error at
// earlyTime against measured cost and against projections (both per simulated second, so steps compare), and
// the largest segment error against measured cost; then, past the horizon, the mean energy, the tip's mean
// height and its swing period against measured cost, the reference's as a dashed line.
Chart hairWorkPrecisionChart(const std::vector<HairWorkPrecisionRow>& rows, const HairWorkPrecisionOptions& options);
// Writes hair_work_precision.csv and hair_work_precision.svg into `dir` (which must exist); returns their paths.
std::vector<std::filesystem::path> writeHairWorkPrecision(const std::vector<HairWorkPrecisionRow>& rows,
                                                          const HairWorkPrecisionOptions& options,
                                                          const std::filesystem::path& dir);

// ---------------------------------------------------------------------------------------------------
// Stability.

// What "bounded" allows (see runHairStabilityCase):
inline constexpr double kHairStableSegmentError = 0.05; // max | |segment| / rest - 1 |, strictly below
inline constexpr double kHairPenetrationSlack = 1e-3;   // m inside a collider after a step (1/40 of a segment)
inline constexpr double kHairReachSlack = 1e-4;         // m beyond the furthest a node may be from its root

enum class HairScan { Step, Spin, Carry };
inline constexpr int kHairScanCount = 3;
// "dt", "spin", "carry": the CSVs' scan column.
std::string_view hairScanName(HairScan scan);
// "s", "rad/s", "m/s".
std::string_view hairScanUnit(HairScan scan);

// lo, lo r, lo r^2, ... while below hi, then hi itself (so both ends are on the grid). Throws
// std::invalid_argument unless 0 < lo <= hi (finite) and r > 1.
std::vector<double> geometricGrid(double lo, double hi, double ratio);

struct HairStabilityOptions {
    std::vector<physics::HairMethod> methods = hairMethods();
    // The ball: roots over the whole sphere, its centre `height` above a floor of blocks (solid for y in
    // [-2, 0), x and z in [-16, 16)), so hair hanging straight down ends 0.05 m above it and spinning,
    // swinging and carrying bring it onto the blocks.
    int strands = 256;
    int nodes = 12;             // per strand, root included
    double strandLength = 0.45; // m
    double radius = 0.25;       // m
    double height = 0.75;       // m, ball centre above the floor's top
    double seconds = 2.5;       // s each run lasts (or until it first fails)
    // Step scan: the host spins at stepScanSpin about a tilted axis, no automatic substeps
    // (maxSubstepSeconds = 0), so the method's own limit is measured.
    std::vector<double> dts = geometricGrid(1.0 / 480.0, 0.25, 1.4142135623730951);
    double stepScanSpin = 4.0; // rad/s
    // Spin scan: the host's spin ramps up linearly over spinRampSeconds to the value, then holds.
    std::vector<double> spins = {0, 1, 2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100, 150, 200}; // rad/s
    double spinRampSeconds = 0.5;
    // Carry scan: the host moves along x as -A cos(2 pi t / carryPeriod), starting at rest, peak speed the
    // value (A = value carryPeriod / 2 pi), not spinning.
    std::vector<double> carrySpeeds = {0, 0.5, 1, 2, 3, 5, 7, 10, 15, 20, 30, 40, 50}; // m/s
    double carryPeriod = 1.0;                                                          // s
    double scanDt = 1.0 / 60.0; // s, the spin and carry scans' step (the game's tick)

    // The tests' version: a small ball, a 1 s run, a few values per scan.
    static HairStabilityOptions quick();
};

// The grid a scan runs over (options.dts, spins or carrySpeeds), in increasing order.
const std::vector<double>& hairStabilityGrid(HairScan scan, const HairStabilityOptions& options);

struct HairStabilityRow {
    physics::HairMethod method = physics::HairMethod::Ftl;
    HairScan scan = HairScan::Step;
    double value = 0.0; // dt (s), spin (rad/s) or peak carry speed (m/s)
    bool bounded = false;
    // Worst over the run, up to and including the step where it first failed (a failed run stops there).
    double maxSegmentError = 0.0;
    double maxPenetration = 0.0; // m
    bool nan = false;
    double maxReach = 0.0;  // largest node-to-root distance / strandLength
    double failedAt = -1.0; // s into the run where it first failed; -1 when bounded
};

// One run of a hair ball at the method's defaults. Bounded: through every step, no NaN (stats or
// positions), max segment error below kHairStableSegmentError, penetration at most kHairPenetrationSlack,
// and no node farther from its root than strandLength (1 + kHairStableSegmentError) + kHairReachSlack.
// (A strand whose segments each stretch by less than the allowed 5 % reaches at most 1.05 strandLength;
// holding it to strandLength itself would fail every pbd run at rest under gravity, which measures its
// stretch, reported by max_segment_error, not its stability. The reach test is the positions' own
// check that nothing escaped the strand's sphere, independent of the solver's stats. The slack covers float
// rounding of 11 segments at up to ~10 m from the origin: a few ulps of 1e-6 m each.)
HairStabilityRow runHairStabilityCase(physics::HairMethod method, HairScan scan, double value,
                                      const HairStabilityOptions& options);
// Every method x scan x grid value, in that order.
std::vector<HairStabilityRow> runHairStability(const HairStabilityOptions& options, const Progress& progress = {});

struct HairScanSummary {
    std::optional<double> firstFailure; // the first grid value that fails; unset when every value is bounded
    std::optional<double> lastBounded;  // the last bounded value before it (the limit); unset if the first fails
    std::vector<double> islands;        // bounded values beyond the first failure, in grid order
};
// `values` in grid order, bounded[i] for values[i]; throws std::invalid_argument for different lengths.
HairScanSummary summariseHairScan(const std::vector<double>& values, const std::vector<bool>& bounded);

struct HairStabilityLimit {
    physics::HairMethod method = physics::HairMethod::Ftl;
    HairScan scan = HairScan::Step;
    HairScanSummary summary;
};
// One per (method, scan) present in `rows`, in the order they first appear.
std::vector<HairStabilityLimit> hairStabilityLimits(const std::vector<HairStabilityRow>& rows);

// Columns: method,scan,value,bounded,max_segment_error,max_penetration,nan (bounded and nan as 1 / 0).
void writeHairStabilityCsv(const std::vector<HairStabilityRow>& rows, std::ostream& out);
// Columns: method,scan,first_failure,islands. first_failure is "none" when every value is bounded; islands
// are the bounded values beyond it separated by ';' (empty when there are none).
void writeHairStabilityLimitsCsv(const std::vector<HairStabilityLimit>& limits, std::ostream& out);
// A strip chart, one panel per scan: one row per method, bounded cells as solid lines with markers in the
// method's colour, unbounded cells dashed black.
Chart hairStabilityChart(const std::vector<HairStabilityRow>& rows, const HairStabilityOptions& options);
// Writes hair_stability.csv, hair_stability_limits.csv and hair_stability.svg into `dir` (which must exist).
std::vector<std::filesystem::path> writeHairStability(const std::vector<HairStabilityRow>& rows,
                                                      const HairStabilityOptions& options,
                                                      const std::filesystem::path& dir);

// ---------------------------------------------------------------------------------------------------
// The commands (minecrappy-lab hair-work-precision / hair-stability --out DIR [--quick]): create `outDir`
// (and its parents), run the full study (or quick()), progress to `err`, "<command>: wrote PATH" per file to
// `out` (hair-stability also prints each method's limits there). Returns 0 when done, 2 when the folder
// cannot be made (the message names it), 1 when a file cannot be written (the message names it).
int runHairWorkPrecisionCommand(const std::string& outDir, bool quick, std::ostream& out, std::ostream& err);
int runHairStabilityCommand(const std::string& outDir, bool quick, std::ostream& out, std::ostream& err);

} // namespace lab
