// The pendulum studies of minecrappy-lab, as library functions so that tests can run them on tiny
// inputs: one run written as CSV, work-precision (accuracy against cost), stability limits found by
// scan and bisection, and the seed write-up's figures redone against the exact solution.
// Every function takes its sizes and durations as parameters; the defaults are the full studies.
// It must never touch a terminal or exit: progress goes through a callback, results are returned,
// and files are written whole (temporary file + rename) or not at all.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

using Progress = std::function<void(const std::string& line)>;

// Every method that takes steps (all but Exact), in enum order.
std::vector<physics::Method> steppedMethods();
// A fixed colour per method, shared by all charts so a method looks the same everywhere.
int methodColour(physics::Method method);
// Angle difference wrapped to (-pi, pi]: a pendulum one turn ahead is in the same place.
double wrapAngle(double radians);

// ---------------------------------------------------------------------------------------------------
// One run, written as CSV.

inline constexpr std::int64_t kMaxSteps = 50'000'000; // ~5 GB of CSV; more is refused, not attempted

struct PendulumRun {
    physics::Method method = physics::Method::Rk4;
    physics::PendulumParams params{};
    physics::PendulumState initial{}; // theta (rad) from straight down, omega (rad/s)
    double dt = 0.01;                 // step (s), finite and > 0
    double seconds = 10.0;            // simulated time (s), finite and > 0
};

// Steps needed to reach `seconds`: the last one may end past it, but 10 / 0.001 is 10000, not 10001.
// Returns -1 when the count is not finite or does not fit.
std::int64_t stepCount(double seconds, double dt);

// An empty string when the run can be done; otherwise what is wrong with it, in words.
std::string validateRun(const PendulumRun& run);

// Header `t,theta,omega,energy,theta_exact,energy_error` (+ `,theta_from_position,rod_length` for
// euler-cartesian), then one row per step including t = 0, full precision. energy_error is
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
};

struct WorkPrecisionPoint {
    physics::Method method = physics::Method::Euler;
    double dt = 0.0;                // s (errorTime / whole number)
    double evalsPerSimSecond = 0.0; // force evaluations per simulated second
    double nsPerSimSecond = 0.0;    // measured wall nanoseconds per simulated second
    double angleError = 0.0;        // |theta - theta_exact| at errorTime, wrapped (rad)
    double maxEnergyError = 0.0;    // max |E - E0| / (m g L) over energyTime
};

// The step sizes the sweep uses: log-spaced, each rounded so errorTime / dt is a whole number.
std::vector<double> workPrecisionSteps(const WorkPrecisionOptions& options);
// Throws std::invalid_argument for options that make no sweep (no methods, minDt > maxDt, ...).
std::vector<WorkPrecisionPoint> runWorkPrecision(const WorkPrecisionOptions& options, const Progress& progress = {});
// Columns: method,dt,evals_per_sim_second,ns_per_sim_second,angle_error_10s,max_energy_error_60s
void writeWorkPrecisionCsv(const std::vector<WorkPrecisionPoint>& points, std::ostream& out);
// Log-log: angle error against measured cost, against evaluations, and energy error against evaluations.
Chart workPrecisionChart(const std::vector<WorkPrecisionPoint>& points, const WorkPrecisionOptions& options);
// Writes work_precision.csv and work_precision.svg into `dir` (which must exist); returns their paths.
std::vector<std::filesystem::path> writeWorkPrecision(const std::vector<WorkPrecisionPoint>& points,
                                                      const WorkPrecisionOptions& options,
                                                      const std::filesystem::path& dir);

// ---------------------------------------------------------------------------------------------------
// Stability: the largest omega0 * dt at which a pendulum released from rest stays bounded.

struct StabilityOptions {
    std::vector<physics::Method> methods = steppedMethods();
    std::vector<double> anglesDeg = {10.0, 60.0, 120.0, 170.0, 179.0};
    physics::PendulumParams params{};
    double seconds = 60.0;           // how long a run must stay bounded (s)
    double energyTolerance = 0.5;    // allowed |E - E0| in units of m g L
    double scanMin = 1e-3;           // coarse scan of omega0 * dt from here...
    double scanMax = 4.0;            // ...up to here (above RK4's linear limit 2 sqrt 2)
    double scanRatio = 1.25;         // each scan point is this much larger than the last
    double floor = 1e-5;             // when scanMin already fails, go down (x 1/4) no lower than this
    double relativeTolerance = 1e-3; // bisection stops when hi / lo <= 1 + this
};

enum class StabilityBound {
    Bisected,        // a passing and a failing omega0*dt bracketed the limit and bisection narrowed it
    FailsAtFloor,    // even omega0*dt = floor failed: the limit is below it (reported as 0)
    PassesAtScanMax, // nothing up to scanMax failed: the limit is at least scanMax (reported as scanMax)
};

struct StabilityPoint {
    physics::Method method = physics::Method::Euler;
    double theta0Deg = 0.0;
    double maxStableOmegaDt = 0.0;
    StabilityBound bound = StabilityBound::Bisected;
    int runs = 0; // simulations it took
};

// One run from rest at theta0 (rad): true when |theta| < pi and |E - E0| <= tolerance * m g L throughout.
bool staysBounded(physics::Method method, const physics::PendulumParams& params, double theta0, double dt,
                  double seconds, double energyTolerance);
// Scan from small to large omega0*dt for the first failure (stability need not be monotonic in dt, so
// bisection alone could land on a later island), then bisect between the last pass and that failure.
StabilityPoint findStabilityLimit(physics::Method method, double theta0Deg, const StabilityOptions& options);
std::vector<StabilityPoint> runStability(const StabilityOptions& options, const Progress& progress = {});
// Columns: method,theta0_deg,max_stable_omega_dt
void writeStabilityCsv(const std::vector<StabilityPoint>& points, std::ostream& out);
// Max stable omega0*dt against release angle, one series per method, linear limits as dashed lines.
Chart stabilityChart(const std::vector<StabilityPoint>& points, const StabilityOptions& options);
std::vector<std::filesystem::path> writeStability(const std::vector<StabilityPoint>& points,
                                                  const StabilityOptions& options, const std::filesystem::path& dir);

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
