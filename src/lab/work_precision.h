// The work-precision study of minecrappy-lab (`minecrappy-lab work-precision`).
#pragma once
#include <cstdint>
#include <filesystem>
#include <limits>
#include <ostream>
#include <vector>

#include "lab/pendulum_common.h"
#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

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

} // namespace lab
