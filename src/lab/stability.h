// The stability-limits study of minecrappy-lab: the first unbounded step per method and release angle.
#pragma once
#include <filesystem>
#include <limits>
#include <ostream>
#include <vector>

#include "lab/pendulum_common.h"
#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

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
    // Near the separatrix the unbounded windows are densest: at these release angles the refined scan covers
    // the whole range from the grid's start to the first failure. No grid finds every window (some are a few
    // millionths wide, between any two points of the refined grid).
    std::vector<double> wholeRangeRefineAnglesDeg = {170.0, 179.0};
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

} // namespace lab
