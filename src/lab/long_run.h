// The long-run energy study of minecrappy-lab (`minecrappy-lab long-run`): every stepped method run from rest
// for a long horizon at a few fixed steps, its largest energy error |E - E0| / (m g L) recorded per window of
// time, the windows ending at log-spaced times. On a log-log chart the shape tells the method's kind at a
// glance. Measured with the defaults (60 degrees, 20000 s, dt = 0.05, 1/60 and 0.005 s):
// - flat: a bounded error, no secular drift (symplectic-euler, verlet; implicit-midpoint, yoshida4): the last
//   window's maximum is within 0.3 % of the first's;
// - slope 1, error linear in time: rk4 (and dopri5) lose energy, as |R(ix)|^2 = 1 - x^6 / 72 < 1 says;
// - curving upward, exponential: euler (|R|^2 = 1 + x^2) and trapezoid (Heun, 1 + x^4 / 4) gain energy until
//   they go over the top;
// - flat, then rising with slope 1: the leapfrog midpoint, whose parasitic mode (the root near -1 of its
//   two-step map) is not damped on the nonlinear pendulum: at dt = 0.05 s 1.1e-3 up to about 50 s, then
//   growing about 8.8e-6 m g L per second, 0.18 by 20000 s (it levels off near 0.5 by 200000 s).
//
// Blow-up: a run stops at the first step whose state is not finite or whose energy error exceeds
// LongRunOptions::blowUpError (default 10 m g L, five times the whole range from the bottom to the top: the
// pendulum is spinning over the top, and what follows says nothing more about conservation: left to run, euler
// at 0.05 s levels off at 202 m g L, where omega dt reaches pi and successive kicks cancel); the window holding
// that step and every later window of the run are recorded (and written to the CSV) as +infinity, so there is
// always one row per (method, dt, window), and the chart draws only the finite windows before it (its note
// names the runs that blew up and by when).
//
// Cost: 5.6 million steps per method and fewer for runs that blow up; measured with the defaults (-O2, the
// 2-core development machine, the ten stepped methods): 3.9 to 4.2 s.
// As in pendulum_common.h: no terminal, no exit; progress through a callback; files written whole or not at all.
#pragma once
#include <filesystem>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "lab/pendulum_common.h"
#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

struct LongRunOptions {
    std::vector<physics::Method> methods = steppedMethods();
    // 0.05 s (omega0 dt = 0.157 for L = 1 m): coarse, so every drift shows early, and the step at which the
    // leapfrog midpoint's parasitic growth was reported; 1/60 s: the game's default tick, what players see;
    // 0.005 s: fine, where drifts are slow and only a long horizon tells them from a bounded error.
    std::vector<double> dts = {0.05, 1.0 / 60.0, 0.005};
    physics::PendulumParams params{};
    double theta0Deg = 60.0;     // released from rest at this angle (degrees)
    double seconds = 20000.0;    // horizon (s); the last window ends here (its last step may end past it)
    double firstWindowEnd = 1.0; // the first window is (0, firstWindowEnd] (s)
    int windowsPerDecade = 4;    // window ends log-spaced from firstWindowEnd to seconds, at least this dense
    double blowUpError = 10.0;   // a run stops once |E - E0| exceeds this (m g L), or on a non-finite state
                                 // (see the top of this file)
};

struct LongRunPoint {
    physics::Method method = physics::Method::Euler;
    double dt = 0.0;        // s
    double windowEnd = 0.0; // s: the window is (previous window's end, windowEnd], or (0, windowEnd] for the first
    // max |E - E0| / (m g L) over the steps ending in the window; +infinity once the run has blown up.
    double maxEnergyError = 0.0;
    // (E - E0) / (m g L) at the step where that maximum was reached, sign kept (gained > 0, lost < 0); +infinity
    // once the run has blown up. Not in the CSV (its header is fixed); for the tests and the chart.
    double signedEnergyError = 0.0;
};

// The window ends: firstWindowEnd, then log-spaced with ratio (seconds / firstWindowEnd)^(1 / n), n the fewest
// windows after the first that are at least windowsPerDecade per decade; the last is `seconds` exactly.
// Default: 19 ends, 1 s to 20000 s (ratio 1.734). Assumes validateLongRun passed.
std::vector<double> longRunWindowEnds(const LongRunOptions& options);

// An empty string when the study can be run; otherwise what is wrong, naming the value: no methods, a method
// that takes no steps, no steps or a step that is not finite and > 0, seconds or firstWindowEnd not finite
// and > 0 or firstWindowEnd > seconds, windowsPerDecade outside [1, 100], blowUpError not > 0, an initial
// angle or parameters that physics::validatePendulum rejects, a run over kMaxSteps steps, or a window that
// holds no step at some dt.
std::string validateLongRun(const LongRunOptions& options);

// Methods in the given order, each at every dt in order, each run's windows in time order. Throws
// std::invalid_argument with validateLongRun's message when it objects.
std::vector<LongRunPoint> runLongRun(const LongRunOptions& options, const Progress& progress = {});

// Header `method,dt,window_end_s,max_energy_error`, then one row per point in order (inf after a blow-up).
void writeLongRunCsv(const std::vector<LongRunPoint>& points, std::ostream& out);

// Log-log, window end against the window's max energy error: one panel per dt, one series per method in
// methodColour; only finite points are drawn.
Chart longRunChart(const std::vector<LongRunPoint>& points, const LongRunOptions& options);

// Writes long_run.csv and long_run.svg into `dir` (which must exist); returns their paths.
std::vector<std::filesystem::path> writeLongRun(const std::vector<LongRunPoint>& points, const LongRunOptions& options,
                                                const std::filesystem::path& dir);

} // namespace lab
