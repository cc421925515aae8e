// The pendulum studies of minecrappy-lab, as library functions so that tests can run them on tiny
// inputs: one run written as CSV, work-precision (accuracy against cost), stability limits as first
// failures on a fine grid, and the seed write-up's figures redone against the exact solution.
// Every function takes its sizes and durations as parameters; the defaults are the full studies.
// It must never touch a terminal or exit: progress goes through a callback, results are returned,
// and files are written whole (temporary file + rename) or not at all.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

using Progress = std::function<void(const std::string& line)>;

// Every method that takes steps (all but Exact), in enum order.
std::vector<physics::Method> steppedMethods();
// Every stepped method but the adaptive one (dopri5 picks its own steps, so every output step is bounded: its
// stability scan and map would be one verdict and cost as much as three others).
std::vector<physics::Method> fixedStepMethods();
// A fixed colour per method, shared by all charts so a method looks the same everywhere.
int methodColour(physics::Method method);
// Angle difference wrapped to (-pi, pi]: a pendulum one turn ahead is in the same place.
double wrapAngle(double radians);

// ---------------------------------------------------------------------------------------------------
// One run, written as CSV.

inline constexpr std::int64_t kMaxSteps = 50'000'000; // ~5 GB of CSV; more is refused, not attempted
inline constexpr double kMaxLabMass = 1.0e6;          // kg: the mass scales the energy column only

struct PendulumRun {
    physics::Method method = physics::Method::Rk4;
    physics::PendulumParams params{};
    physics::PendulumState initial{};                    // theta (rad) from straight down, omega (rad/s)
    double dt = 0.01;                                    // step (s), finite and > 0; dopri5: the output step (rows)
    double seconds = 10.0;                               // simulated time (s), finite and > 0
    double tolerance = physics::kDefaultDopri5Tolerance; // dopri5 only: in [kDopri5MinTolerance, kDopri5MaxTolerance]
};

// Steps needed to reach `seconds`: the last one may end past it, but 10 / 0.001 is 10000, not 10001.
// Returns -1 when the count is not finite or does not fit.
std::int64_t stepCount(double seconds, double dt);

// An empty string when the run can be done; otherwise what is wrong with it, in words.
std::string validateRun(const PendulumRun& run);

// Header `t,theta,omega,energy,theta_exact,energy_error` (+ `,theta_from_position,rod_length` for
// euler-cartesian, + `,steps` for dopri5: its accepted steps so far, the rows then at the output step from its
// dense output while it steps freely), then one row per step including t = 0, full precision. energy_error is
// (E - E0) / (m g L). theta_exact is empty-valued (nan) when the closed form does not apply (damping).
// Throws std::invalid_argument when validateRun() objects.
void writePendulumCsv(const PendulumRun& run, std::ostream& out);
void writePendulumCsv(const PendulumRun& run, const std::filesystem::path& path); // throws runtime_error

// ---------------------------------------------------------------------------------------------------
// Work-precision: how much accuracy each method buys per unit of cost.

struct WorkPrecisionOptions {
    std::vector<physics::Method> methods = steppedMethods();
    physics::PendulumParams params{};
    double theta0Deg = 60.0;          // released from rest at this angle (degrees)
    double minDt = 1e-4;              // smallest step (s)
    double maxDt = 0.1;               // largest step (s)
    int stepsInSweep = 16;            // log-spaced steps between minDt and maxDt, both included
    double errorTime = 10.0;          // angle error measured here (s); each dt is adjusted to divide it
    double energyTime = 60.0;         // energy error and timing over this long (s); a multiple of errorTime
    double timingBatchSeconds = 0.01; // wall time of one timing batch; the best of timingBatches counts, so
    int timingBatches = 5;            // one batch undisturbed by the rest of the machine is enough
    // dopri5 picks its own steps: its work axis is its tolerance instead, each run free over energyTime (no
    // output grid to land on), the angle at errorTime from its dense output.
    std::vector<double> tolerances = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
};

struct WorkPrecisionPoint {
    physics::Method method = physics::Method::Euler;
    double dt = 0.0;                // s (errorTime / whole number)
    double evalsPerSimSecond = 0.0; // force evaluations per simulated second
    double nsPerSimSecond = 0.0;    // measured wall nanoseconds per simulated second
    double angleError = 0.0;        // |theta - theta_exact| at errorTime, wrapped (rad)
    double maxEnergyError = 0.0;    // max |E - E0| / (m g L) over energyTime (dopri5: at its steps' ends)
    // dopri5 only (NaN and 0 for the others): its tolerance, and its accepted and rejected steps over energyTime;
    // its dt is then energyTime / accepted, the mean step.
    double tolerance = std::numeric_limits<double>::quiet_NaN();
    std::int64_t accepted = 0, rejected = 0;
};

// The step sizes the sweep uses: log-spaced, each rounded so errorTime / dt is a whole number.
std::vector<double> workPrecisionSteps(const WorkPrecisionOptions& options);
// Throws std::invalid_argument for options that make no sweep (no methods, minDt > maxDt, ...).
std::vector<WorkPrecisionPoint> runWorkPrecision(const WorkPrecisionOptions& options, const Progress& progress = {});
// Columns: method,dt,evals_per_sim_second,ns_per_sim_second,angle_error_10s,max_energy_error_60s,tolerance,
// accepted_steps,rejected_steps (the last three empty for fixed-step methods). Evaluations are counted by the
// run (physics::Pendulum::evaluations(), Dopri5Stats), not looked up: implicit-midpoint's Newton iterations vary.
void writeWorkPrecisionCsv(const std::vector<WorkPrecisionPoint>& points, std::ostream& out);
// Log-log: angle error against measured cost, against evaluations, and energy error against evaluations.
Chart workPrecisionChart(const std::vector<WorkPrecisionPoint>& points, const WorkPrecisionOptions& options);
// Writes work_precision.csv and work_precision.svg into `dir` (which must exist); returns their paths.
std::vector<std::filesystem::path> writeWorkPrecision(const std::vector<WorkPrecisionPoint>& points,
                                                      const WorkPrecisionOptions& options,
                                                      const std::filesystem::path& dir);

// ---------------------------------------------------------------------------------------------------
// Stability: the first step at which a pendulum released from rest stops being bounded, on a stated grid.
// "Bounded" (staysBounded) = never over the top and |E - E0| <= energyTolerance m g L for the whole run. The
// set of bounded omega0 * dt need not be an interval (verlet from 120 degrees is bounded up to 1.167, unbounded
// to 1.27, bounded again to 1.42), so a limit is only as good as the grid it was scanned on: a scan in 25 %
// strides steps over unbounded gaps (verlet from 60 degrees first fails at 1.52, a 25 % scan first at 2.46).
// Every cell is therefore scanned point by point on a geometric grid of relative spacing gridRatio - 1
// (0.1 %), from a step that was run and found bounded up to the first point that is not; what lies above
// (islands) is scanned on the same grid to scanMax.

struct StabilityOptions {
    std::vector<physics::Method> methods = fixedStepMethods();
    std::vector<double> anglesDeg = {10.0, 60.0, 120.0, 170.0, 179.0};
    physics::PendulumParams params{};
    double seconds = 60.0;        // how long a run must stay bounded (s)
    double energyTolerance = 0.5; // allowed |E - E0| in units of m g L
    // Where the grid starts: a coarse scan from scanMin up in coarseRatio strides finds a first coarse
    // failure c; the grid starts at c * gridStartFraction (lowered by the same factor until a run there passes).
    // When scanMin already fails, the coarse scan goes down (x 1/4) no lower than floor.
    double scanMin = 1e-3;
    double scanMax = 4.0; // the grid's top, above rk4's linear limit 2 sqrt 2: the largest step tried
    double coarseRatio = 1.25;
    double gridStartFraction = 0.25;
    double floor = 1e-5;
    double gridRatio = 1.001; // the grid: gridStart * gridRatio^k
    // The grid-sensitivity check: the grid refined `refine` times (gridRatio^(1/refine) apart; it holds every
    // point of the grid) over the refineWindow (10 %) below the first failure. A cell whose first failure
    // moves down by more than `sensitivity` (1 %) on it is grid-sensitive: near the separatrix the bounded set
    // has unbounded windows narrower than any grid.
    int refine = 10;            // 0: no check
    double refineWindow = 0.10; // the refined scan covers [first failure / (1 + this), first failure]
    double sensitivity = 0.01;
    bool scanIslands = true; // scan the grid above the first failure for bounded points
    // Two grid points at most this many grid steps apart, both bounded, belong to one island.
    int islandGapPoints = 10;
    int threads = 0; // cells in parallel; 0: one per hardware thread
};

// The grid's own name for a cell's verdict.
enum class StabilityBound {
    FirstFailure, // a grid point failed above a bounded start: firstFailureOmegaDt is that point
    FailsAtFloor, // even omega0*dt = floor failed: no bounded start exists above it (reported as 0)
    NeverFails,   // every grid point up to scanMax was bounded: maxStableOmegaDt is the largest step tried
};

// Bounded grid points above a cell's first failure, grouped: from and to are bounded grid points, and gaps of
// failing points between them are at most islandGapPoints long.
struct StabilityIsland {
    double fromOmegaDt = 0.0;
    double toOmegaDt = 0.0;
    int gridPoints = 0; // from to to, both included
    int failing = 0;    // of those, unbounded
    double failingFraction() const { return gridPoints > 0 ? static_cast<double>(failing) / gridPoints : 0.0; }
};

struct StabilityPoint {
    physics::Method method = physics::Method::Euler;
    double theta0Deg = 0.0;
    StabilityBound bound = StabilityBound::FirstFailure;
    double gridStart = 0.0; // a bounded run; the grid is gridStart * gridRatio^k
    double gridRatio = 0.0;
    // The largest grid point below which (from gridStart) every grid point was bounded: the point just below
    // the first failure; with NeverFails the largest step tried; 0 with FailsAtFloor.
    double maxStableOmegaDt = 0.0;
    double firstFailureOmegaDt = std::numeric_limits<double>::quiet_NaN(); // NaN unless FirstFailure
    // The largest bounded grid point at or above maxStableOmegaDt (an island's top, or maxStableOmegaDt).
    double largestBoundedOmegaDt = 0.0;
    std::vector<StabilityIsland> islands;
    // The refined grid's first failure over [refinedFromOmegaDt, firstFailureOmegaDt]; NaN when not checked.
    double refinedFromOmegaDt = std::numeric_limits<double>::quiet_NaN();
    double refinedFirstFailureOmegaDt = std::numeric_limits<double>::quiet_NaN();
    bool gridSensitive = false;
    int runs = 0;             // simulations it took
    double wallSeconds = 0.0; // and how long
};

// One run from rest at theta0 (rad): true when |theta| < pi and |E - E0| <= tolerance * m g L throughout.
// Stops at the first step that fails, so an unbounded run costs only the steps up to its failure.
bool staysBounded(physics::Method method, const physics::PendulumParams& params, double theta0, double dt,
                  double seconds, double energyTolerance);
// The omega0 * dt of grid point k (fractional k: the refined grid) of a grid from `start` by `ratio`.
double stabilityGridPoint(double start, double ratio, double k);
// One cell: the grid's start, its first failure, the grid-sensitivity check and the islands (see above).
// Throws std::invalid_argument for options that cannot make a grid.
StabilityPoint findStabilityLimit(physics::Method method, double theta0Deg, const StabilityOptions& options);
// Every method at every angle, cells in parallel (each cell's result does not depend on the threads).
// euler-cartesian steps theta and omega bit for bit as euler does, so when both are asked for its cells are
// euler's, not run again.
std::vector<StabilityPoint> runStability(const StabilityOptions& options, const Progress& progress = {});
// Columns: method,theta0_deg,grid_start,grid_ratio,max_stable_omega_dt,first_failure_omega_dt,
// largest_bounded_omega_dt,refined_from_omega_dt,refined_first_failure_omega_dt,grid_sensitive,islands,runs
// (nan where a value does not apply; grid_sensitive 0 or 1).
void writeStabilityCsv(const std::vector<StabilityPoint>& points, std::ostream& out);
// Columns: method,theta0_deg,from_omega_dt,to_omega_dt,grid_points,failing_fraction; one row per island.
void writeStabilityIslandsCsv(const std::vector<StabilityPoint>& points, std::ostream& out);
// First failure against release angle, one series per method, linear limits as dashed lines.
Chart stabilityChart(const std::vector<StabilityPoint>& points, const StabilityOptions& options);
// Writes stability.csv, stability_islands.csv and stability.svg into `dir` (which must exist).
std::vector<std::filesystem::path> writeStability(const std::vector<StabilityPoint>& points,
                                                  const StabilityOptions& options, const std::filesystem::path& dir);

// The stability map: every cell of a grid of release angle (linear) against omega0 * dt (log) run once with
// staysBounded, per method, so islands above the first failure show at every angle, not only at five; and
// per angle the first failure on the limits' own grid (findStabilityLimit's start and 0.1 % spacing, without
// the refinement and the islands), so the map's limit line has the limits' resolution, not the raster's.
// Default grid: 90 angles (1, 3, ..., 179 degrees: cells 2 degrees wide covering 0 to 180) by 80 values of
// omega0 * dt from 0.01 to 4 (8 % apart), 60 s each. Released at 0 degrees the pendulum never moves, so the
// map starts at 1. A bounded cell costs its full 188 / (omega0 dt) steps (g = 9.81, L = 1: omega0 T = 188 for
// 60 s), an unbounded one stops at its first failing step. The fine line is looked for within the map's
// range; it costs most where the first failure is smallest (explicit Euler's, near 0.02 at small angles).
// Each map's wall time is in StabilityMap::wallSeconds.

struct StabilityMapOptions {
    std::vector<physics::Method> methods = fixedStepMethods();
    double angleMinDeg = 1.0;   // release angles (degrees, in (0, 180)), evenly spaced from here...
    double angleMaxDeg = 179.0; // ...to here, both included
    int angleCount = 90;        // > 1 (with min < max), or 1 (with min == max)
    double omegaDtMin = 1e-2;   // omega0 * dt, log-spaced from here...
    double omegaDtMax = 4.0;    // ...to here, both included (above rk4's linear limit 2 sqrt 2)
    int omegaDtCount = 80;      // > 1 (with min < max), or 1 (with min == max)
    physics::PendulumParams params{};
    double seconds = 60.0;        // how long a cell's run must stay bounded (s), as in StabilityOptions
    double energyTolerance = 0.5; // allowed |E - E0| in units of m g L, as in StabilityOptions
    bool gridLine = true;         // the per-angle first failure on the limits' grid (gridFirstFailure)
    int threads = 0;              // angles in parallel; 0: one per hardware thread
};

struct StabilityMap {
    physics::Method method = physics::Method::Euler;
    std::vector<double> anglesDeg; // grid, increasing (degrees)
    std::vector<double> omegaDts;  // grid, increasing (omega0 * dt)
    // Angle-major: bounded[a * omegaDts.size() + w] is 1 when the run from anglesDeg[a] at omegaDts[w] stayed
    // bounded, else 0.
    std::vector<std::uint8_t> bounded;
    // Per angle: the first omega0 * dt on this grid, scanning up, whose run was unbounded (the limit line: the
    // limit lies between it and the grid value below, unless an unbounded gap narrower than one grid step hides
    // lower down); NaN when every value on the grid was bounded.
    std::vector<double> firstFailure;
    // Per angle: the first failure on the limits' grid (StabilityOptions' rule, over the map's own range); NaN
    // when the grid never fails (or gridLine is off), 0 when the map's bottom, omegaDtMin, already fails.
    std::vector<double> gridFirstFailure;
    int islandCells = 0;      // bounded cells above their angle's first failure
    double wallSeconds = 0.0; // wall time the map took (s)

    bool at(std::size_t angle, std::size_t omegaDt) const { return bounded[angle * omegaDts.size() + omegaDt] != 0; }
};

// Throws std::invalid_argument for a grid that cannot be made (angles outside (0, 180), omegaDtMin <= 0, a
// count < 1, several values with min >= max, one with min != max, seconds <= 0), a run longer than kMaxSteps
// at omegaDtMin, or a method that takes no steps.
std::vector<StabilityMap> runStabilityMaps(const StabilityMapOptions& options, const Progress& progress = {});
// Columns: method,theta0_deg,omega_dt,bounded (1 or 0); per method, angle-major.
void writeStabilityMapCsv(const std::vector<StabilityMap>& maps, std::ostream& out);
// Columns: method,theta0_deg,grid_first_failure_omega_dt,raster_first_failure_omega_dt; per method and angle.
void writeStabilityMapLimitsCsv(const std::vector<StabilityMap>& maps, std::ostream& out);
// One panel per map: bounded and unbounded cells as a raster (release angle against omega0 * dt, log), the
// first failure on the limits' grid as a line, the linear limit dashed, and, for methods in `limits` (from
// runStability, may be empty), those first failures as crosses.
Chart stabilityMapChart(const std::vector<StabilityMap>& maps, const StabilityMapOptions& options,
                        const std::vector<StabilityPoint>& limits = {});
// Writes stability_map.csv, stability_map_limits.csv and stability_map.svg into `dir` (which must exist).
std::vector<std::filesystem::path> writeStabilityMaps(const std::vector<StabilityMap>& maps,
                                                      const StabilityMapOptions& options,
                                                      const std::filesystem::path& dir,
                                                      const std::vector<StabilityPoint>& limits = {});

// ---------------------------------------------------------------------------------------------------
// The seed write-up's figures, redone: theta, omega and energy over time for its methods beside the
// exact solution, one figure per step size. The seed released a 1 m pendulum from 20 degrees at rest
// with g = 9.80665 and plotted theta in degrees; its Euler moved the bob in x, y (euler-cartesian) and
// also plotted the angle recovered from that position, so both Euler variants are drawn.

struct SeedFiguresOptions {
    std::vector<double> dts = {0.001, 0.016, 0.033}; // s
    std::vector<physics::Method> methods = {physics::Method::Euler, physics::Method::EulerCartesian,
                                            physics::Method::Midpoint, physics::Method::Trapezoid};
    physics::PendulumParams params{1.0, 9.80665, 1.0, 0.0};
    double theta0Deg = 20.0;
    double seconds = 20.0;
};

struct SeedTrace {
    physics::Method method = physics::Method::Exact; // Exact: the closed form on the same time grid
    std::vector<double> theta, omega, energy;        // rad, rad/s, J
    std::vector<double> thetaFromPosition;           // euler-cartesian only; empty otherwise
};

struct SeedFigure {
    double dt = 0.0;
    std::vector<double> t;
    std::vector<SeedTrace> traces; // options.methods in order, then the exact solution
};

std::vector<SeedFigure> runSeedFigures(const SeedFiguresOptions& options, const Progress& progress = {});
// "seed_dt1ms", "seed_dt16ms", "seed_dt0.5ms": the file stem for one step size.
std::string seedFigureStem(double dt);
// Wide CSV: t, then theta_M,omega_M,energy_M per method M (+ theta_from_position_euler-cartesian), exact last.
void writeSeedFigureCsv(const SeedFigure& figure, std::ostream& out);
Chart seedFigureChart(const SeedFigure& figure, const SeedFiguresOptions& options);
// Writes <stem>.svg and <stem>.csv per figure into `dir`; returns the paths written.
std::vector<std::filesystem::path> writeSeedFigures(const std::vector<SeedFigure>& figures,
                                                    const SeedFiguresOptions& options,
                                                    const std::filesystem::path& dir);

} // namespace lab
