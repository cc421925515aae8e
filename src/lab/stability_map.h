// The stability-map study of minecrappy-lab: bounded cells over release angle and omega0 * dt, per method.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <vector>

#include "lab/pendulum_common.h"
#include "lab/stability.h"
#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

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

} // namespace lab
