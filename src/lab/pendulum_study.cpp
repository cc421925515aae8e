#include "lab/pendulum_study.h"

#include "lab/lab_util.h"

#include "core/atomic_file.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <thread>

namespace lab {

using physics::Method;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double degToRad(double deg) { return deg * kPi / 180.0; }

std::string name(Method m) { return std::string(physics::methodName(m)); }

double mgl(const physics::PendulumParams& p) { return p.mass * p.gravity * p.length; }

// The methods of `points`, each once, in the order they first appear (the charts' legend order).
template <typename Point>
std::vector<Method> methodsInOrder(const std::vector<Point>& points) {
    std::vector<Method> seen;
    for (const auto& p : points) {
        if (std::find(seen.begin(), seen.end(), p.method) == seen.end()) seen.push_back(p.method);
    }
    return seen;
}
} // namespace

std::vector<Method> steppedMethods() {
    std::vector<Method> out;
    for (int i = 0; i < physics::kMethodCount; ++i) {
        if (static_cast<Method>(i) != Method::Exact) out.push_back(static_cast<Method>(i));
    }
    return out;
}

std::vector<Method> fixedStepMethods() {
    std::vector<Method> out;
    for (const Method m : steppedMethods())
        if (m != Method::Dopri5) out.push_back(m);
    return out;
}

int methodColour(Method method) {
    switch (method) {
    case Method::Euler:
        return 0;
    case Method::EulerCartesian:
        return 5;
    case Method::Midpoint:
        return 2;
    case Method::Trapezoid:
        return 3;
    case Method::SymplecticEuler:
        return 1;
    case Method::Verlet:
        return 4;
    case Method::Rk4:
        return 6;
    case Method::ImplicitMidpoint:
        return 7;
    case Method::Yoshida4:
        return 8;
    case Method::Dopri5:
        return 9;
    case Method::Exact:
        return 6; // black too, but always dashed: the reference, never beside rk4's curve
    case Method::Count:
        break;
    }
    return 6;
}

namespace {
// Method `m`'s series in its colour: the point (x(p), y(p)) of each of `points` that `m` made, in order.
template <typename Point, typename X, typename Y>
Series methodSeries(const std::vector<Point>& points, Method m, X x, Y y) {
    Series s{name(m), {}, {}, methodColour(m), true, false, true};
    for (const auto& p : points) {
        if (p.method != m) continue;
        s.x.push_back(x(p));
        s.y.push_back(y(p));
    }
    return s;
}
} // namespace

double wrapAngle(double radians) {
    double d = std::remainder(radians, 2.0 * kPi); // [-pi, pi]
    if (d <= -kPi) d += 2.0 * kPi;
    return d;
}

// ---------------------------------------------------------------------------------------------------
// One run.

std::int64_t stepCount(double seconds, double dt) {
    if (!std::isfinite(seconds) || !std::isfinite(dt) || dt <= 0.0 || seconds < 0.0) return -1;
    const double ratio = seconds / dt;
    if (!std::isfinite(ratio) || ratio > 9.0e18) return -1;
    // 10 / 0.001 is 10000.000000000002 in doubles: a relative slack of a few ulps keeps it 10000.
    const double steps = std::ceil(ratio * (1.0 - 4.0 * std::numeric_limits<double>::epsilon()));
    return std::max<std::int64_t>(0, static_cast<std::int64_t>(steps));
}

std::string validateRun(const PendulumRun& run) {
    const auto& p = run.params;
    if (run.method == Method::Count || physics::methodName(run.method).empty()) return "unknown method";
    if (!std::isfinite(run.dt) || run.dt <= 0.0) return "the step must be a finite number > 0 (seconds)";
    if (!std::isfinite(run.seconds) || run.seconds <= 0.0) return "the duration must be a finite number > 0 (seconds)";
    if (!(p.length >= physics::kMinPendulumLength && p.length <= physics::kMaxPendulumLength))
        return "--length must be in [0.001, 16] m (the game's rods), got " + formatShort(p.length);
    if (!(p.gravity > 0.0 && p.gravity <= physics::kMaxPendulumGravity))
        return "--g must be in (0, 1e4] m/s^2 (the game's gravities), got " + formatShort(p.gravity);
    if (!(p.mass > 0.0 && p.mass <= kMaxLabMass)) return "--mass must be in (0, 1e6] kg, got " + formatShort(p.mass);
    if (!std::isfinite(p.damping) || p.damping < 0.0) return "the damping must be a finite number >= 0 (1/s)";
    if (!std::isfinite(run.initial.theta) || !std::isfinite(run.initial.omega))
        return "the initial state must be finite";
    const std::int64_t steps = stepCount(run.seconds, run.dt);
    if (steps < 0 || steps > kMaxSteps) {
        return "the run would take " + (steps < 0 ? std::string("too many") : std::to_string(steps)) +
               " steps (seconds / dt); at most " + std::to_string(kMaxSteps) + " are allowed";
    }
    if (run.method == Method::Exact && p.damping != 0.0) return "the exact solution is for the undamped pendulum";
    if (run.method == Method::Dopri5 &&
        !(run.tolerance >= physics::kDopri5MinTolerance && run.tolerance <= physics::kDopri5MaxTolerance)) {
        return "the tolerance must be in [" + formatShort(physics::kDopri5MinTolerance) + ", " +
               formatShort(physics::kDopri5MaxTolerance) + "], got " + formatShort(run.tolerance);
    }
    return {};
}

void writePendulumCsv(const PendulumRun& run, std::ostream& out) {
    if (const std::string why = validateRun(run); !why.empty()) throw std::invalid_argument(why);
    const std::int64_t steps = stepCount(run.seconds, run.dt);
    const bool cartesian = run.method == Method::EulerCartesian;
    const bool adaptive = run.method == Method::Dopri5;
    physics::Pendulum pendulum(run.method, run.params, run.initial, physics::MidpointStart::Rk4, run.tolerance);
    std::optional<physics::Dopri5> free;
    if (adaptive) free.emplace(run.params, run.initial, run.tolerance);
    std::optional<physics::ExactPendulum> exact;
    if (run.params.damping == 0.0) exact.emplace(run.params, run.initial);
    const double e0 = physics::energy(run.params, run.initial);
    const double scale = mgl(run.params);

    out << "t,theta,omega,energy,theta_exact,energy_error" << (cartesian ? ",theta_from_position,rod_length" : "")
        << (adaptive ? ",steps" : "") << '\n';
    std::string line;
    for (std::int64_t k = 0; k <= steps; ++k) {
        // Time as k * dt rather than a running sum, so row k is exactly where the exact solution is taken.
        const double t = static_cast<double>(k) * run.dt;
        physics::PendulumState s;
        if (adaptive) {
            while (free->time() < t) free->step();
            s = k == 0 ? run.initial : free->interpolate(t);
        } else {
            if (k > 0) pendulum.step(run.dt);
            s = pendulum.state();
        }
        const double e = physics::energy(run.params, s);
        line.clear();
        appendNumber(line, t);
        line += ',';
        appendNumber(line, s.theta);
        line += ',';
        appendNumber(line, s.omega);
        line += ',';
        appendNumber(line, e);
        line += ',';
        appendNumber(line, exact ? exact->at(t).theta : kNaN);
        line += ',';
        appendNumber(line, (e - e0) / scale);
        if (cartesian) {
            line += ',';
            appendNumber(line, pendulum.thetaFromPosition());
            line += ',';
            appendNumber(line, pendulum.rodLength());
        }
        if (adaptive) line += ',' + std::to_string(free->stats().accepted);
        line += '\n';
        out.write(line.data(), static_cast<std::streamsize>(line.size()));
    }
}

void writePendulumCsv(const PendulumRun& run, const std::filesystem::path& path) {
    if (const std::string why = validateRun(run); !why.empty()) throw std::invalid_argument(why);
    writeCsvFile(path, [&](std::ostream& out) { writePendulumCsv(run, out); });
}

// ---------------------------------------------------------------------------------------------------
// Work-precision.

std::vector<double> workPrecisionSteps(const WorkPrecisionOptions& o) {
    if (!(o.minDt > 0.0) || !(o.maxDt >= o.minDt) || !std::isfinite(o.maxDt) || o.stepsInSweep < 1 ||
        !(o.errorTime > 0.0) || !std::isfinite(o.errorTime)) {
        throw std::invalid_argument("work-precision: need 0 < minDt <= maxDt, at least one step and errorTime > 0");
    }
    std::vector<double> out;
    for (int i = 0; i < o.stepsInSweep; ++i) {
        const double f = o.stepsInSweep == 1 ? 0.0 : static_cast<double>(i) / (o.stepsInSweep - 1);
        const double target = o.minDt * std::pow(o.maxDt / o.minDt, f);
        // errorTime / dt whole, so the error is read at errorTime exactly and not a fraction of a step off.
        const double n = std::max(1.0, std::round(o.errorTime / target));
        const double dt = o.errorTime / n;
        if (out.empty() || dt != out.back()) out.push_back(dt);
    }
    return out;
}

namespace {

struct Accuracy {
    double angleError = kNaN;
    double maxEnergyError = 0.0;
    std::int64_t evaluations = 0; // force evaluations the run took
};

// Folds one energy error into a running maximum: a run that has blown up to NaN reports NaN from then on, not
// the stale maximum from before.
void foldEnergyError(Accuracy& a, double err) {
    a.maxEnergyError = std::isnan(err) || std::isnan(a.maxEnergyError) ? kNaN : std::max(a.maxEnergyError, err);
}

Accuracy measureAccuracy(Method method, const physics::PendulumParams& params, const physics::PendulumState& initial,
                         const physics::ExactPendulum& exact, double dt, std::int64_t errorSteps,
                         std::int64_t energySteps) {
    Accuracy a;
    physics::Pendulum p(method, params, initial);
    const double e0 = physics::energy(params, initial);
    const double scale = mgl(params);
    for (std::int64_t k = 1; k <= energySteps; ++k) {
        p.step(dt);
        const physics::PendulumState s = p.state();
        foldEnergyError(a, std::fabs(physics::energy(params, s) - e0) / scale);
        if (k == errorSteps) {
            a.angleError = std::fabs(wrapAngle(s.theta - exact.at(static_cast<double>(k) * dt).theta));
        }
    }
    a.evaluations = p.evaluations();
    return a;
}

// dopri5 run free to energyTime at one tolerance: the energy error at every accepted step's end, the angle at
// errorTime from the dense output of the step that passes it.
Accuracy measureAdaptive(const physics::PendulumParams& params, const physics::PendulumState& initial,
                         const physics::ExactPendulum& exact, double tolerance, double errorTime, double energyTime,
                         physics::Dopri5Stats& stats) {
    Accuracy a;
    physics::Dopri5 d(params, initial, tolerance);
    const double e0 = physics::energy(params, initial);
    const double scale = mgl(params);
    while (d.time() < energyTime) {
        const double before = d.time();
        d.step(energyTime);
        foldEnergyError(a, std::fabs(physics::energy(params, d.state()) - e0) / scale);
        if (before < errorTime && d.time() >= errorTime)
            a.angleError = std::fabs(wrapAngle(d.interpolate(errorTime).theta - exact.at(errorTime).theta));
    }
    stats = d.stats();
    a.evaluations = stats.evaluations;
    return a;
}

// Wall seconds for one call of `once` (a whole run, returning a value to keep alive), best of `batches` batches,
// each batch repeating it often enough to last `batchSeconds`, so clock resolution and one-off stalls do not
// dominate.
template <typename Run>
double bestRunSeconds(Run&& once, double batchSeconds, int batches) {
    volatile double sink = 0.0; // keeps the result alive; the steps live in another file, so no inlining away
    auto start = std::chrono::steady_clock::now();
    sink = sink + once(); // warms caches and calibrates
    const double single = std::max(secondsSince(start), 1e-9);
    const auto reps = static_cast<std::int64_t>(std::clamp(std::ceil(batchSeconds / single), 1.0, 1e7));
    double best = single;
    for (int b = 0; b < std::max(1, batches); ++b) {
        start = std::chrono::steady_clock::now();
        for (std::int64_t r = 0; r < reps; ++r) sink = sink + once();
        best = std::min(best, secondsSince(start) / static_cast<double>(reps));
    }
    return best;
}

// One run of `steps` fixed steps.
double timeRun(Method method, const physics::PendulumParams& params, const physics::PendulumState& initial, double dt,
               std::int64_t steps, double batchSeconds, int batches) {
    return bestRunSeconds(
        [&] {
            physics::Pendulum p(method, params, initial);
            for (std::int64_t k = 0; k < steps; ++k) p.step(dt);
            return p.state().theta;
        },
        batchSeconds, batches);
}

// One free dopri5 run to `seconds`.
double timeAdaptive(const physics::PendulumParams& params, const physics::PendulumState& initial, double tolerance,
                    double seconds, double batchSeconds, int batches) {
    return bestRunSeconds(
        [&] {
            physics::Dopri5 d(params, initial, tolerance);
            while (d.time() < seconds) d.step(seconds);
            return d.state().theta;
        },
        batchSeconds, batches);
}

} // namespace

std::vector<WorkPrecisionPoint> runWorkPrecision(const WorkPrecisionOptions& o, const Progress& progress) {
    const std::vector<double> dts = workPrecisionSteps(o);
    if (o.methods.empty()) throw std::invalid_argument("work-precision: no methods");
    if (!(o.energyTime >= o.errorTime) || !std::isfinite(o.energyTime)) {
        throw std::invalid_argument("work-precision: energyTime must be >= errorTime");
    }
    const physics::PendulumState initial{degToRad(o.theta0Deg), 0.0};
    const physics::ExactPendulum exact(o.params, initial);

    std::vector<WorkPrecisionPoint> points;
    for (const Method m : o.methods) {
        if (m == Method::Exact || m == Method::Count)
            throw std::invalid_argument("work-precision: exact takes no steps");
        if (m == Method::Dopri5) {
            for (const double tol : o.tolerances) {
                if (progress) progress("work-precision: dopri5 at tolerance " + formatShort(tol));
                physics::Dopri5Stats stats;
                const Accuracy a = measureAdaptive(o.params, initial, exact, tol, o.errorTime, o.energyTime, stats);
                const double wall =
                    timeAdaptive(o.params, initial, tol, o.energyTime, o.timingBatchSeconds, o.timingBatches);
                WorkPrecisionPoint pt;
                pt.method = m;
                pt.dt = o.energyTime / static_cast<double>(std::max<std::int64_t>(stats.accepted, 1));
                pt.evalsPerSimSecond = static_cast<double>(a.evaluations) / o.energyTime;
                pt.nsPerSimSecond = wall * 1e9 / o.energyTime;
                pt.angleError = a.angleError;
                pt.maxEnergyError = a.maxEnergyError;
                pt.tolerance = tol;
                pt.accepted = stats.accepted;
                pt.rejected = stats.rejected;
                points.push_back(pt);
            }
            continue;
        }
        for (std::size_t i = 0; i < dts.size(); ++i) {
            const double dt = dts[i];
            if (progress) {
                progress("work-precision: " + name(m) + " " + std::to_string(i + 1) + "/" + std::to_string(dts.size()) +
                         " (dt = " + formatShort(dt) + " s)");
            }
            const std::int64_t errorSteps = stepCount(o.errorTime, dt);
            const std::int64_t energySteps = stepCount(o.energyTime, dt);
            const double simSeconds = static_cast<double>(energySteps) * dt;
            const Accuracy a = measureAccuracy(m, o.params, initial, exact, dt, errorSteps, energySteps);
            const double wall = timeRun(m, o.params, initial, dt, energySteps, o.timingBatchSeconds, o.timingBatches);
            WorkPrecisionPoint pt;
            pt.method = m;
            pt.dt = dt;
            pt.evalsPerSimSecond = static_cast<double>(a.evaluations) / simSeconds;
            pt.nsPerSimSecond = wall * 1e9 / simSeconds;
            pt.angleError = a.angleError;
            pt.maxEnergyError = a.maxEnergyError;
            points.push_back(pt);
        }
    }
    return points;
}

void writeWorkPrecisionCsv(const std::vector<WorkPrecisionPoint>& points, std::ostream& out) {
    out << "method,dt,evals_per_sim_second,ns_per_sim_second,angle_error_10s,max_energy_error_60s,tolerance,"
           "accepted_steps,rejected_steps\n";
    std::string line;
    for (const auto& p : points) {
        line = name(p.method);
        for (double v : {p.dt, p.evalsPerSimSecond, p.nsPerSimSecond, p.angleError, p.maxEnergyError}) {
            line += ',';
            appendNumber(line, v);
        }
        if (std::isnan(p.tolerance)) {
            line += ",,,";
        } else {
            line += ',';
            appendNumber(line, p.tolerance);
            line += ',' + std::to_string(p.accepted) + ',' + std::to_string(p.rejected);
        }
        line += '\n';
        out << line;
    }
}

Chart workPrecisionChart(const std::vector<WorkPrecisionPoint>& points, const WorkPrecisionOptions& o) {
    const std::string errorLabel = "|theta - theta_exact| at t = " + formatShort(o.errorTime) + " s (rad)";
    Chart chart;
    chart.title = "Pendulum work-precision: released from " + formatShort(o.theta0Deg) +
                  "° at rest, L = " + formatShort(o.params.length) + " m, g = " + formatShort(o.params.gravity) +
                  " m/s²";
    Panel byTime{"Angle error against measured cost",
                 {"wall time per simulated second (ns), measured over " + formatShort(o.energyTime) + " s runs",
                  AxisScale::Log10,
                  {},
                  {}},
                 {errorLabel, AxisScale::Log10, {}, {}},
                 {},
                 "lower left is better; errors saturate near pi once a method has lost the phase"};
    Panel byEvals{"Angle error against force evaluations",
                  {"force evaluations per simulated second (implicit-midpoint: sin and cos)", AxisScale::Log10, {}, {}},
                  {errorLabel, AxisScale::Log10, {}, {}},
                  {},
                  "slope -p for a method of order p; euler-cartesian steps (theta, omega) exactly as euler does, "
                  "so their curves coincide"};
    Panel energy{"Energy error against force evaluations",
                 {"force evaluations per simulated second (implicit-midpoint: sin and cos)", AxisScale::Log10, {}, {}},
                 {"max |E - E0| / (m g L) over " + formatShort(o.energyTime) + " s", AxisScale::Log10, {}, {}},
                 {},
                 "symplectic-euler, verlet, yoshida4 and implicit-midpoint keep a bounded energy error; euler and "
                 "trapezoid gain energy, rk4 and dopri5 slowly lose it, the leapfrog midpoint's slowly grows "
                 "(long-run)"};
    const std::vector<Method> seen = methodsInOrder(points);
    using P = WorkPrecisionPoint;
    for (const Method m : seen) {
        byTime.series.push_back(methodSeries(
            points, m, [](const P& p) { return p.nsPerSimSecond; }, [](const P& p) { return p.angleError; }));
        byEvals.series.push_back(methodSeries(
            points, m, [](const P& p) { return p.evalsPerSimSecond; }, [](const P& p) { return p.angleError; }));
        energy.series.push_back(methodSeries(
            points, m, [](const P& p) { return p.evalsPerSimSecond; }, [](const P& p) { return p.maxEnergyError; }));
    }
    chart.panels = {std::move(byTime), std::move(byEvals), std::move(energy)};
    return chart;
}

std::vector<std::filesystem::path> writeWorkPrecision(const std::vector<WorkPrecisionPoint>& points,
                                                      const WorkPrecisionOptions& options,
                                                      const std::filesystem::path& dir) {
    return {writeCsvFile(dir / "work_precision.csv", [&](std::ostream& out) { writeWorkPrecisionCsv(points, out); }),
            writeSvg(workPrecisionChart(points, options), dir / "work_precision.svg")};
}

// ---------------------------------------------------------------------------------------------------
// Stability.

bool staysBounded(Method method, const physics::PendulumParams& params, double theta0, double dt, double seconds,
                  double energyTolerance) {
    const physics::PendulumState initial{theta0, 0.0};
    physics::Pendulum p(method, params, initial);
    const double e0 = physics::energy(params, initial);
    const double allowed = energyTolerance * mgl(params);
    const std::int64_t steps = stepCount(seconds, dt);
    if (steps < 0) throw std::invalid_argument("stability: too many steps");
    for (std::int64_t k = 0; k < steps; ++k) {
        p.step(dt);
        const physics::PendulumState s = p.state();
        // Written so that NaN fails both tests.
        if (!(std::fabs(s.theta) < kPi)) return false;
        if (!(std::fabs(physics::energy(params, s) - e0) <= allowed)) return false;
    }
    return true;
}

double stabilityGridPoint(double start, double ratio, double k) { return start * std::pow(ratio, k); }

namespace {

void checkStabilityOptions(const StabilityOptions& o) {
    const bool ok = o.scanMin > 0.0 && o.scanMax > o.scanMin && std::isfinite(o.scanMax) && o.coarseRatio > 1.0 &&
                    o.gridStartFraction > 0.0 && o.gridStartFraction < 1.0 && o.floor > 0.0 && o.floor <= o.scanMin &&
                    o.gridRatio > 1.0 && o.refine >= 0 && o.refineWindow > 0.0 && o.sensitivity > 0.0 &&
                    o.islandGapPoints >= 1 && o.seconds > 0.0 && std::isfinite(o.seconds) && o.energyTolerance > 0.0;
    if (!ok) {
        throw std::invalid_argument("stability: need 0 < floor <= scanMin < scanMax, coarse and grid ratios > 1, a "
                                    "grid start fraction in (0, 1), refine >= 0, a positive refine window, "
                                    "sensitivity, tolerance and duration, and an island gap of at least 1");
    }
}

// Runs and counts; each cell has its own.
struct CellRunner {
    physics::Method method;
    const StabilityOptions& o;
    double theta0;
    double omega0;
    int runs = 0;
    bool operator()(double omegaDt) {
        ++runs;
        return staysBounded(method, o.params, theta0, omegaDt / omega0, o.seconds, o.energyTolerance);
    }
};

// A step known to be bounded, for the grid to start from: a quarter (gridStartFraction) of the first failure
// of a coarse scan, lowered until it passes (it may lie below the floor, which bounds only the search down).
// 0 when even the floor fails.
double boundedStart(CellRunner& passes, const StabilityOptions& o) {
    double x = o.scanMin, coarseFailure = 0.0;
    if (passes(x)) {
        coarseFailure = o.scanMax;
        while (x < o.scanMax) {
            x = std::min(x * o.coarseRatio, o.scanMax);
            if (!passes(x)) {
                coarseFailure = x;
                break;
            }
        }
    } else {
        coarseFailure = x;
        while (true) {
            if (x <= o.floor) return 0.0;
            x = std::max(x / 4.0, o.floor);
            if (passes(x)) break;
            coarseFailure = x;
        }
    }
    double start = coarseFailure * o.gridStartFraction;
    while (!passes(start)) {
        if (start <= o.floor) return 0.0;
        start = std::max(start * o.gridStartFraction, o.floor);
    }
    return start;
}

} // namespace

StabilityPoint findStabilityLimit(Method method, double theta0Deg, const StabilityOptions& o) {
    checkStabilityOptions(o);
    const auto started = std::chrono::steady_clock::now();
    StabilityPoint out;
    out.method = method;
    out.theta0Deg = theta0Deg;
    out.gridRatio = o.gridRatio;
    CellRunner passes{method, o, degToRad(theta0Deg), physics::smallAngleFrequency(o.params)};
    auto finish = [&] {
        out.runs = passes.runs;
        out.wallSeconds = secondsSince(started);
        return out;
    };
    out.gridStart = boundedStart(passes, o);
    if (out.gridStart == 0.0) {
        out.bound = StabilityBound::FailsAtFloor;
        return finish();
    }
    const auto point = [&](double k) { return stabilityGridPoint(out.gridStart, o.gridRatio, k); };
    // The first failure: every grid point from the start up, each one run.
    int k = 1;
    while (point(k) <= o.scanMax && passes(point(k))) ++k;
    out.maxStableOmegaDt = point(k - 1);
    out.largestBoundedOmegaDt = out.maxStableOmegaDt;
    if (point(k) > o.scanMax) {
        out.bound = StabilityBound::NeverFails;
        return finish();
    }
    out.bound = StabilityBound::FirstFailure;
    out.firstFailureOmegaDt = point(k);

    if (o.refine > 0) {
        // The refined grid's points between two grid points; the grid's own points there are known bounded.
        const double f = out.firstFailureOmegaDt;
        const int last = k * o.refine;
        int j = std::max(0, static_cast<int>(std::ceil(o.refine * std::log(f / (1.0 + o.refineWindow) / out.gridStart) /
                                                       std::log(o.gridRatio))));
        j = std::min(j, last);
        out.refinedFromOmegaDt = point(static_cast<double>(j) / o.refine);
        out.refinedFirstFailureOmegaDt = f;
        for (; j < last; ++j) {
            if (j % o.refine == 0) continue;
            const double x = point(static_cast<double>(j) / o.refine);
            if (!passes(x)) {
                out.refinedFirstFailureOmegaDt = x;
                break;
            }
        }
        out.gridSensitive = out.refinedFirstFailureOmegaDt < f / (1.0 + o.sensitivity);
    }

    if (o.scanIslands) {
        StabilityIsland island;
        int islandTop = -1, failingSinceTop = 0;
        auto close = [&] {
            if (islandTop < 0) return;
            island.toOmegaDt = point(islandTop);
            out.islands.push_back(island);
            out.largestBoundedOmegaDt = std::max(out.largestBoundedOmegaDt, island.toOmegaDt);
            islandTop = -1;
        };
        for (int i = k + 1; point(i) <= o.scanMax; ++i) {
            if (passes(point(i))) {
                if (islandTop >= 0 && i - islandTop - 1 <= o.islandGapPoints) {
                    island.gridPoints += i - islandTop;
                    island.failing += failingSinceTop;
                } else {
                    close();
                    island = StabilityIsland{point(i), point(i), 1, 0};
                }
                islandTop = i;
                failingSinceTop = 0;
            } else {
                ++failingSinceTop;
            }
        }
        close();
    }
    return finish();
}

namespace {

// Runs job(i) for i in [0, count) on `threads` threads (0: one per hardware thread); each i exactly once.
template <typename Job>
void parallelFor(std::size_t count, int threads, Job&& job) {
    std::size_t n = threads > 0 ? static_cast<std::size_t>(threads) : std::thread::hardware_concurrency();
    n = std::clamp<std::size_t>(n, 1, std::max<std::size_t>(count, 1));
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto worker = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < count;) {
            try {
                job(i);
            } catch (...) {
                const std::lock_guard lock(failureMutex);
                if (!failure) failure = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

std::string describe(const StabilityPoint& p, const StabilityOptions& o) {
    switch (p.bound) {
    case StabilityBound::FirstFailure: {
        std::string line = "first failure at omega0*dt = " + formatShort(p.firstFailureOmegaDt);
        if (p.gridSensitive)
            line += " (grid-sensitive: " + formatShort(p.refinedFirstFailureOmegaDt) + " on the finer grid)";
        if (!p.islands.empty())
            line += "; " + std::to_string(p.islands.size()) + " islands, bounded up to " +
                    formatShort(p.largestBoundedOmegaDt);
        return line;
    }
    case StabilityBound::FailsAtFloor:
        return "unbounded even at omega0*dt = " + formatShort(o.floor) + ", reported as 0";
    case StabilityBound::NeverFails:
        return "bounded at every grid point up to omega0*dt = " + formatShort(p.maxStableOmegaDt) +
               " (the largest tried)";
    }
    return {};
}

} // namespace

std::vector<StabilityPoint> runStability(const StabilityOptions& o, const Progress& progress) {
    if (o.methods.empty() || o.anglesDeg.empty()) throw std::invalid_argument("stability: no methods or no angles");
    checkStabilityOptions(o);
    for (const Method m : o.methods) {
        if (m == Method::Exact || m == Method::Count) throw std::invalid_argument("stability: exact takes no steps");
    }
    for (const double a : o.anglesDeg) {
        if (!(a > 0.0 && a < 180.0))
            throw std::invalid_argument("stability: release angles must be in (0, 180) degrees");
    }
    const bool eulerToo = std::find(o.methods.begin(), o.methods.end(), Method::Euler) != o.methods.end();
    std::vector<StabilityPoint> out(o.methods.size() * o.anglesDeg.size());
    std::vector<std::size_t> cells; // the ones run; euler-cartesian's are copied from euler's after
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (!(eulerToo && o.methods[i / o.anglesDeg.size()] == Method::EulerCartesian)) cells.push_back(i);
    }
    std::mutex progressMutex;
    std::size_t done = 0;
    parallelFor(cells.size(), o.threads, [&](std::size_t c) {
        const std::size_t i = cells[c];
        const Method m = o.methods[i / o.anglesDeg.size()];
        const double a = o.anglesDeg[i % o.anglesDeg.size()];
        out[i] = findStabilityLimit(m, a, o);
        if (progress) {
            const std::lock_guard lock(progressMutex);
            ++done;
            progress("stability: " + name(m) + " from " + formatShort(a) + " deg (" + std::to_string(done) + "/" +
                     std::to_string(cells.size()) + "): " + describe(out[i], o) + " (" + std::to_string(out[i].runs) +
                     " runs, " + formatShort(out[i].wallSeconds) + " s)");
        }
    });
    if (eulerToo) {
        const std::size_t euler =
            static_cast<std::size_t>(std::find(o.methods.begin(), o.methods.end(), Method::Euler) - o.methods.begin());
        for (std::size_t i = 0; i < out.size(); ++i) {
            if (o.methods[i / o.anglesDeg.size()] != Method::EulerCartesian) continue;
            out[i] = out[euler * o.anglesDeg.size() + i % o.anglesDeg.size()];
            out[i].method = Method::EulerCartesian;
            out[i].runs = 0;
            out[i].wallSeconds = 0.0;
        }
    }
    return out;
}

void writeStabilityCsv(const std::vector<StabilityPoint>& points, std::ostream& out) {
    out << "method,theta0_deg,grid_start,grid_ratio,max_stable_omega_dt,first_failure_omega_dt,"
           "largest_bounded_omega_dt,refined_from_omega_dt,refined_first_failure_omega_dt,grid_sensitive,islands,"
           "runs\n";
    std::string line;
    for (const auto& p : points) {
        line = name(p.method) + ',';
        for (const double v : {p.theta0Deg, p.gridStart, p.gridRatio, p.maxStableOmegaDt, p.firstFailureOmegaDt,
                               p.largestBoundedOmegaDt, p.refinedFromOmegaDt, p.refinedFirstFailureOmegaDt}) {
            appendNumber(line, v);
            line += ',';
        }
        line += p.gridSensitive ? "1," : "0,";
        line += std::to_string(p.islands.size()) + ',' + std::to_string(p.runs) + '\n';
        out << line;
    }
}

void writeStabilityIslandsCsv(const std::vector<StabilityPoint>& points, std::ostream& out) {
    out << "method,theta0_deg,from_omega_dt,to_omega_dt,grid_points,failing_fraction\n";
    std::string line;
    for (const auto& p : points) {
        for (const auto& island : p.islands) {
            line = name(p.method) + ',';
            for (const double v : {p.theta0Deg, island.fromOmegaDt, island.toOmegaDt}) {
                appendNumber(line, v);
                line += ',';
            }
            line += std::to_string(island.gridPoints) + ',';
            appendNumber(line, island.failingFraction());
            line += '\n';
            out << line;
        }
    }
}

Chart stabilityChart(const std::vector<StabilityPoint>& points, const StabilityOptions& o) {
    Chart chart;
    chart.title = "Pendulum stability: the largest omega0·dt below the first failure, bounded for " +
                  formatShort(o.seconds) + " s";
    Panel panel{"Released from rest; bounded = never over the top and |E - E0| <= " + formatShort(o.energyTolerance) +
                    " m g L",
                {"release angle (degrees)", AxisScale::Linear, 0.0, 180.0},
                {"max stable omega0 · dt", AxisScale::Log10, {}, {}},
                {},
                "Each point: the grid point below the first unbounded one, on a grid " +
                    formatShort((o.gridRatio - 1.0) * 100.0) +
                    " % apart from a bounded step (a method that never failed: the largest step tried, " +
                    formatShort(o.scanMax) +
                    "). Dashed: the linear stability limit in the method's colour (euler, euler-cartesian and "
                    "trapezoid have none: 0). Not drawn: 0, unbounded even at omega0·dt = " +
                    formatShort(o.floor) +
                    ". euler-cartesian steps (theta, omega) exactly as euler does, so their curves coincide. "
                    "Grid-sensitive cells, and the bounded steps above the first failure (islands): stability.csv, "
                    "stability_islands.csv and stability_map.svg."};
    const std::vector<Method> seen = methodsInOrder(points);
    for (const Method m : seen) {
        panel.series.push_back(methodSeries(
            points, m, [](const StabilityPoint& p) { return p.theta0Deg; },
            [](const StabilityPoint& p) { return p.maxStableOmegaDt; }));
    }
    panel.series.push_back(Series{"linear limits, dashed", {}, {}, methodColour(Method::Exact), false, true, true});
    for (const Method m : seen) {
        const double limit = physics::linearStabilityLimit(m);
        if (!(limit > 0.0) || !std::isfinite(limit)) continue;
        panel.series.push_back(
            Series{name(m) + " linear limit", {0.0, 180.0}, {limit, limit}, methodColour(m), false, true, false});
    }
    chart.panels.push_back(std::move(panel));
    chart.panelHeight = 560;
    return chart;
}

std::vector<std::filesystem::path> writeStability(const std::vector<StabilityPoint>& points,
                                                  const StabilityOptions& options, const std::filesystem::path& dir) {
    return {
        writeCsvFile(dir / "stability.csv", [&](std::ostream& out) { writeStabilityCsv(points, out); }),
        writeCsvFile(dir / "stability_islands.csv", [&](std::ostream& out) { writeStabilityIslandsCsv(points, out); }),
        writeSvg(stabilityChart(points, options), dir / "stability.svg")};
}

// ---------------------------------------------------------------------------------------------------
// Stability map.

namespace {

// count values from lo to hi, both included; evenly spaced, or log-spaced (lo > 0). count 1: lo.
std::vector<double> grid(double lo, double hi, int count, bool logSpaced) {
    std::vector<double> out;
    for (int i = 0; i < count; ++i) {
        const double f = count == 1 ? 0.0 : static_cast<double>(i) / (count - 1);
        out.push_back(logSpaced ? lo * std::pow(hi / lo, f) : lo + (hi - lo) * f);
    }
    if (count > 1) out.back() = hi; // exactly the end asked for, not its rounding
    return out;
}

// Cell edges around increasing centres: midway between neighbours (geometric midway on a log axis), the
// outer ones half a spacing beyond the end centres; one centre gets a cell `single` wide (ratio on log).
std::vector<double> edges(const std::vector<double>& centres, bool logSpaced, double single) {
    std::vector<double> out;
    const std::size_t n = centres.size();
    auto mid = [&](double a, double b) { return logSpaced ? std::sqrt(a * b) : (a + b) / 2.0; };
    auto beyond = [&](double inner, double outer) { // reflect the midpoint: half a spacing past `outer`
        return logSpaced ? outer * std::sqrt(outer / inner) : outer + (outer - inner) / 2.0;
    };
    if (n == 1) {
        return logSpaced ? std::vector<double>{centres[0] / std::sqrt(single), centres[0] * std::sqrt(single)}
                         : std::vector<double>{centres[0] - single / 2.0, centres[0] + single / 2.0};
    }
    out.push_back(beyond(centres[1], centres[0]));
    for (std::size_t i = 0; i + 1 < n; ++i) out.push_back(mid(centres[i], centres[i + 1]));
    out.push_back(beyond(centres[n - 2], centres[n - 1]));
    return out;
}

void checkMapOptions(const StabilityMapOptions& o) {
    // One value: min == max; several: min < max, so no two grid values (or cells) coincide.
    auto spans = [](double lo, double hi, int count) { return count >= 1 && (count == 1 ? lo == hi : lo < hi); };
    const bool anglesOk =
        o.angleMinDeg > 0.0 && o.angleMaxDeg < 180.0 && spans(o.angleMinDeg, o.angleMaxDeg, o.angleCount);
    const bool stepsOk =
        o.omegaDtMin > 0.0 && std::isfinite(o.omegaDtMax) && spans(o.omegaDtMin, o.omegaDtMax, o.omegaDtCount);
    if (!anglesOk || !stepsOk || !(o.seconds > 0.0) || !std::isfinite(o.seconds) || !(o.energyTolerance >= 0.0)) {
        throw std::invalid_argument("stability map: need release angles in (0, 180) degrees and omegaDtMin > 0, "
                                    "each with min < max and a count > 1, or min == max and a count of 1, and "
                                    "seconds > 0");
    }
    if (o.methods.empty()) throw std::invalid_argument("stability map: no methods");
    for (const Method m : o.methods) {
        if (m == Method::Exact || m == Method::Count)
            throw std::invalid_argument("stability map: exact takes no steps");
    }
}

} // namespace

std::vector<StabilityMap> runStabilityMaps(const StabilityMapOptions& o, const Progress& progress) {
    checkMapOptions(o);
    const std::vector<double> angles = grid(o.angleMinDeg, o.angleMaxDeg, o.angleCount, false);
    const std::vector<double> omegaDts = grid(o.omegaDtMin, o.omegaDtMax, o.omegaDtCount, true);
    const double omega0 = physics::smallAngleFrequency(o.params);
    // The smallest omega0 * dt sets the run length: refuse a grid that would take more than kMaxSteps per cell.
    const std::int64_t longest = stepCount(o.seconds, omegaDts.front() / omega0);
    if (longest < 0 || longest > kMaxSteps) {
        throw std::invalid_argument("stability map: omegaDtMin too small for the duration (" +
                                    (longest < 0 ? std::string("too many") : std::to_string(longest)) +
                                    " steps per run; at most " + std::to_string(kMaxSteps) + ")");
    }
    std::vector<StabilityMap> maps;
    for (std::size_t mi = 0; mi < o.methods.size(); ++mi) {
        const auto start = std::chrono::steady_clock::now();
        StabilityMap map;
        map.method = o.methods[mi];
        map.anglesDeg = angles;
        map.omegaDts = omegaDts;
        map.bounded.assign(angles.size() * omegaDts.size(), 0);
        map.firstFailure.assign(angles.size(), kNaN);
        map.gridFirstFailure.assign(angles.size(), kNaN);
        // The limits' rule for the line, without the refinement and the islands: the raster shows those.
        StabilityOptions line;
        line.params = o.params;
        line.seconds = o.seconds;
        line.energyTolerance = o.energyTolerance;
        line.refine = 0;
        line.scanIslands = false;
        line.scanMin = o.omegaDtMin; // a first failure below the map's bottom is not looked for: 0 there
        line.floor = o.omegaDtMin;
        line.scanMax = o.omegaDtMax;
        parallelFor(angles.size(), o.threads, [&](std::size_t a) {
            const double theta0 = degToRad(angles[a]);
            for (std::size_t w = 0; w < omegaDts.size(); ++w) {
                const bool ok =
                    staysBounded(map.method, o.params, theta0, omegaDts[w] / omega0, o.seconds, o.energyTolerance);
                map.bounded[a * omegaDts.size() + w] = ok ? 1 : 0;
                if (!ok && std::isnan(map.firstFailure[a])) map.firstFailure[a] = omegaDts[w];
            }
            if (o.gridLine) {
                const StabilityPoint p = findStabilityLimit(map.method, angles[a], line);
                map.gridFirstFailure[a] = p.bound == StabilityBound::FailsAtFloor ? 0.0 : p.firstFailureOmegaDt;
            }
        });
        for (std::size_t a = 0; a < angles.size(); ++a) {
            for (std::size_t w = 0; w < omegaDts.size(); ++w) {
                if (map.at(a, w) && !std::isnan(map.firstFailure[a]) && omegaDts[w] > map.firstFailure[a])
                    ++map.islandCells;
            }
        }
        map.wallSeconds = secondsSince(start);
        if (progress) {
            std::size_t unbounded = 0;
            for (const std::uint8_t b : map.bounded) unbounded += b == 0 ? 1 : 0;
            progress("stability map: " + name(map.method) + " (" + std::to_string(mi + 1) + "/" +
                     std::to_string(o.methods.size()) + "): " + std::to_string(map.bounded.size()) + " cells, " +
                     std::to_string(unbounded) + " unbounded, " + std::to_string(map.islandCells) +
                     " bounded above the first failure, " + formatShort(map.wallSeconds) + " s");
        }
        maps.push_back(std::move(map));
    }
    return maps;
}

void writeStabilityMapCsv(const std::vector<StabilityMap>& maps, std::ostream& out) {
    out << "method,theta0_deg,omega_dt,bounded\n";
    std::string line;
    for (const auto& map : maps) {
        const std::string method = name(map.method) + ',';
        for (std::size_t a = 0; a < map.anglesDeg.size(); ++a) {
            for (std::size_t w = 0; w < map.omegaDts.size(); ++w) {
                line = method;
                appendNumber(line, map.anglesDeg[a]);
                line += ',';
                appendNumber(line, map.omegaDts[w]);
                line += map.at(a, w) ? ",1\n" : ",0\n";
                out.write(line.data(), static_cast<std::streamsize>(line.size()));
            }
        }
    }
}

void writeStabilityMapLimitsCsv(const std::vector<StabilityMap>& maps, std::ostream& out) {
    out << "method,theta0_deg,grid_first_failure_omega_dt,raster_first_failure_omega_dt\n";
    std::string line;
    for (const auto& map : maps) {
        for (std::size_t a = 0; a < map.anglesDeg.size(); ++a) {
            line = name(map.method) + ',';
            appendNumber(line, map.anglesDeg[a]);
            line += ',';
            appendNumber(line, map.gridFirstFailure[a]);
            line += ',';
            appendNumber(line, map.firstFailure[a]);
            line += '\n';
            out << line;
        }
    }
}

Chart stabilityMapChart(const std::vector<StabilityMap>& maps, const StabilityMapOptions& o,
                        const std::vector<StabilityPoint>& limits) {
    // Okabe-Ito sky blue and orange, lightened so the black lines over them stay legible: blue against
    // orange survives every common colour-vision deficiency, and the two also differ in lightness.
    constexpr const char* kBoundedColour = "#A6D8F5";
    constexpr const char* kUnboundedColour = "#F2C06B";
    constexpr int kLineColour = 6; // palette black, for every line over the map
    Chart chart;
    chart.title =
        "Pendulum stability map: which release angles and omega0·dt stay bounded for " + formatShort(o.seconds) + " s";
    for (const auto& map : maps) {
        const std::size_t nw = map.omegaDts.size();
        Raster raster;
        raster.xEdges = edges(map.anglesDeg, false, 2.0); // a lone angle: a cell 2 degrees wide
        raster.yEdges = edges(map.omegaDts, true, 1.1);   // a lone omega0 * dt: a cell 10 % tall
        raster.colours = {kBoundedColour, kUnboundedColour};
        raster.names = {"bounded", "unbounded"};
        raster.cells.resize(map.bounded.size());
        for (std::size_t a = 0; a < map.anglesDeg.size(); ++a) {
            for (std::size_t w = 0; w < nw; ++w) raster.cells[w * map.anglesDeg.size() + a] = map.at(a, w) ? 0 : 1;
        }
        const double linear = physics::linearStabilityLimit(map.method);
        const bool hasLinear = linear > 0.0 && std::isfinite(linear);
        std::string note =
            "bounded = never over the top and |E - E0| <= " + formatShort(o.energyTolerance) +
            " m g L. Solid line: the first failure on a grid 0.1 % apart scanning up from a bounded step (the "
            "raster is coarser: a cell can hide a narrow unbounded gap); bounded cells above the "
            "raster's first failure are islands (" +
            std::to_string(map.islandCells) + " here). Dashed: the linear stability limit" +
            (hasLinear      ? " " + formatShort(linear) + "."
             : linear > 0.0 ? " (none: A-stable, bounded at every step of the linear problem)."
                            : " (none: 0).");
        const Axis angleAxis{"release angle (degrees)", AxisScale::Linear, raster.xEdges.front(), raster.xEdges.back()};
        const Axis stepAxis{"omega0 · dt", AxisScale::Log10, raster.yEdges.front(), raster.yEdges.back()};
        Panel panel{name(map.method), angleAxis, stepAxis, {}, std::move(note), std::move(raster)};
        // The first failure on the limits' grid, angle by angle (0: unbounded at the floor, not drawable on a
        // log axis; NaN: never failed), broken where an angle has none.
        Series gridLine{"first failure (0.1 % grid)", {}, {}, kLineColour, false, false, true};
        for (std::size_t a = 0; a < map.anglesDeg.size(); ++a) {
            const double y = map.gridFirstFailure[a];
            if (!(y > 0.0)) continue;
            gridLine.x.push_back(map.anglesDeg[a]);
            gridLine.y.push_back(y);
        }
        if (!gridLine.x.empty()) panel.series.push_back(std::move(gridLine));
        if (hasLinear) {
            panel.series.push_back(Series{"linear limit",
                                          {panel.raster.xEdges.front(), panel.raster.xEdges.back()},
                                          {linear, linear},
                                          kLineColour,
                                          false,
                                          true,
                                          true});
        }
        // The limits' first failures one series each: a line between five release angles would cross the other.
        bool first = true;
        for (const auto& p : limits) {
            if (p.method != map.method || p.bound != StabilityBound::FirstFailure) continue;
            panel.series.push_back(Series{"first failure at the five angles",
                                          {p.theta0Deg},
                                          {p.firstFailureOmegaDt},
                                          kLineColour,
                                          true,
                                          false,
                                          first});
            first = false;
        }
        chart.panels.push_back(std::move(panel));
    }
    chart.panelHeight = 430;
    return chart;
}

std::vector<std::filesystem::path> writeStabilityMaps(const std::vector<StabilityMap>& maps,
                                                      const StabilityMapOptions& options,
                                                      const std::filesystem::path& dir,
                                                      const std::vector<StabilityPoint>& limits) {
    return {writeCsvFile(dir / "stability_map.csv", [&](std::ostream& out) { writeStabilityMapCsv(maps, out); }),
            writeCsvFile(dir / "stability_map_limits.csv",
                         [&](std::ostream& out) { writeStabilityMapLimitsCsv(maps, out); }),
            writeSvg(stabilityMapChart(maps, options, limits), dir / "stability_map.svg")};
}

// ---------------------------------------------------------------------------------------------------
// Seed figures.

std::vector<SeedFigure> runSeedFigures(const SeedFiguresOptions& o, const Progress& progress) {
    if (o.dts.empty() || o.methods.empty() || !(o.seconds > 0.0)) {
        throw std::invalid_argument("seed-figures: need step sizes, methods and a duration > 0");
    }
    const physics::PendulumState initial{degToRad(o.theta0Deg), 0.0};
    const physics::ExactPendulum exact(o.params, initial);
    std::vector<SeedFigure> figures;
    for (const double dt : o.dts) {
        const std::int64_t steps = stepCount(o.seconds, dt);
        if (steps < 1 || steps > kMaxSteps) throw std::invalid_argument("seed-figures: bad step " + formatShort(dt));
        if (progress)
            progress("seed-figures: dt = " + formatShort(dt * 1000.0) + " ms (" + std::to_string(steps) + " steps)");
        SeedFigure fig;
        fig.dt = dt;
        fig.t.reserve(static_cast<std::size_t>(steps) + 1);
        for (std::int64_t k = 0; k <= steps; ++k) fig.t.push_back(static_cast<double>(k) * dt);
        for (const Method m : o.methods) {
            if (m == Method::Exact || m == Method::Count)
                throw std::invalid_argument("seed-figures: exact is always drawn");
            SeedTrace tr;
            tr.method = m;
            physics::Pendulum p(m, o.params, initial);
            for (std::int64_t k = 0; k <= steps; ++k) {
                if (k > 0) p.step(dt);
                const auto s = p.state();
                tr.theta.push_back(s.theta);
                tr.omega.push_back(s.omega);
                tr.energy.push_back(physics::energy(o.params, s));
                if (m == Method::EulerCartesian) tr.thetaFromPosition.push_back(p.thetaFromPosition());
            }
            fig.traces.push_back(std::move(tr));
        }
        SeedTrace ex;
        ex.method = Method::Exact;
        for (const double t : fig.t) {
            const auto s = exact.at(t);
            ex.theta.push_back(s.theta);
            ex.omega.push_back(s.omega);
            ex.energy.push_back(physics::energy(o.params, s));
        }
        fig.traces.push_back(std::move(ex));
        figures.push_back(std::move(fig));
    }
    return figures;
}

std::string seedFigureStem(double dt) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "seed_dt%gms", dt * 1000.0);
    return buf;
}

void writeSeedFigureCsv(const SeedFigure& fig, std::ostream& out) {
    out << 't';
    for (const auto& tr : fig.traces) {
        const std::string m = name(tr.method);
        out << ",theta_" << m << ",omega_" << m << ",energy_" << m;
        if (!tr.thetaFromPosition.empty()) out << ",theta_from_position_" << m;
    }
    out << '\n';
    std::string line;
    for (std::size_t k = 0; k < fig.t.size(); ++k) {
        line.clear();
        appendNumber(line, fig.t[k]);
        for (const auto& tr : fig.traces) {
            for (const auto* col : {&tr.theta, &tr.omega, &tr.energy}) {
                line += ',';
                appendNumber(line, (*col)[k]);
            }
            if (!tr.thetaFromPosition.empty()) {
                line += ',';
                appendNumber(line, tr.thetaFromPosition[k]);
            }
        }
        line += '\n';
        out.write(line.data(), static_cast<std::streamsize>(line.size()));
    }
}

Chart seedFigureChart(const SeedFigure& fig, const SeedFiguresOptions& o) {
    Chart chart;
    chart.title = "Seed figures redone: dt = " + formatShort(fig.dt * 1000.0) + " ms, released from " +
                  formatShort(o.theta0Deg) + "° at rest, L = " + formatShort(o.params.length) +
                  " m, g = " + formatShort(o.params.gravity) + " m/s²";
    const double scale = mgl(o.params);
    const double e0 = physics::energy(o.params, {degToRad(o.theta0Deg), 0.0});
    Panel theta{"Angle",
                {"t (s)", AxisScale::Linear, 0.0, fig.t.back()},
                {"theta (degrees)", AxisScale::Linear, {}, {}},
                {},
                {}};
    Panel omega{"Angular velocity",
                {"t (s)", AxisScale::Linear, 0.0, fig.t.back()},
                {"omega (rad/s)", AxisScale::Linear, {}, {}},
                {},
                {}};
    Panel energy{"Mechanical energy E = -m g L cos(theta) + m L² omega² / 2 (zero at the pivot)",
                 {"t (s)", AxisScale::Linear, 0.0, fig.t.back()},
                 {"E (J)", AxisScale::Linear, {}, {}},
                 {},
                 {}};
    double thetaPeak = 0.0, energyPeak = 0.0;
    std::vector<std::string> overTheTop;
    bool haveEuler = false;
    for (const auto& tr : fig.traces) haveEuler = haveEuler || tr.method == Method::Euler;
    for (const auto& tr : fig.traces) {
        const bool isExact = tr.method == Method::Exact;
        // euler-cartesian steps (theta, omega) exactly as euler does: beside euler only its angle recovered
        // from the stepped position is new, so its own curves would just hide euler's.
        const bool onlyPosition = tr.method == Method::EulerCartesian && haveEuler;
        if (onlyPosition) {
            Series pos{"euler-cartesian, from x, y", fig.t, {}, methodColour(tr.method), false, false, true};
            for (double v : tr.thetaFromPosition) pos.y.push_back(v * 180.0 / kPi);
            theta.series.push_back(std::move(pos));
            continue;
        }
        std::string label = isExact ? "exact (closed form)" : name(tr.method);
        if (tr.method == Method::Euler && fig.traces.size() > 1 &&
            std::any_of(fig.traces.begin(), fig.traces.end(),
                        [](const SeedTrace& t) { return t.method == Method::EulerCartesian; })) {
            label = "euler (= euler-cartesian)";
        }
        Series th{label, fig.t, {}, methodColour(tr.method), false, isExact, true};
        for (double v : tr.theta) th.y.push_back(v * 180.0 / kPi);
        Series om{label, fig.t, tr.omega, methodColour(tr.method), false, isExact, true};
        Series en{label, fig.t, tr.energy, methodColour(tr.method), false, isExact, true};
        for (double v : th.y) thetaPeak = std::max(thetaPeak, std::fabs(v));
        for (double v : tr.energy) energyPeak = std::max(energyPeak, std::fabs(v - e0));
        bool over = false;
        for (double v : tr.theta) over = over || !(std::fabs(v) < kPi);
        if (over) overTheTop.push_back(label);
        theta.series.push_back(std::move(th));
        if (!tr.thetaFromPosition.empty()) {
            Series pos{label + ", from x, y", fig.t, {}, 7, false, false, true};
            for (double v : tr.thetaFromPosition) pos.y.push_back(v * 180.0 / kPi);
            theta.series.push_back(std::move(pos));
        }
        omega.series.push_back(std::move(om));
        energy.series.push_back(std::move(en));
    }
    // A run that goes over the top winds theta up without bound; past half a turn the picture says all
    // there is to say, so the angle axis stops there and the rest is clipped rather than squashing the others.
    if (thetaPeak > 180.0) {
        theta.y.min = -200.0;
        theta.y.max = 200.0;
        std::string who;
        for (const auto& s : overTheTop) who += (who.empty() ? "" : ", ") + s;
        theta.note = who + " went over the top (|theta| > 180°); clipped at ±200°";
    }
    // Likewise energy: beyond 2 m g L above the start the others would be a flat line.
    if (energyPeak > 2.0 * scale) {
        energy.y.min = e0 - 0.25 * scale;
        energy.y.max = e0 + 2.0 * scale;
        energy.note = "clipped at E0 + 2 m g L; see the CSV for the full growth";
    }
    chart.panels = {std::move(theta), std::move(omega), std::move(energy)};
    return chart;
}

std::vector<std::filesystem::path> writeSeedFigures(const std::vector<SeedFigure>& figures,
                                                    const SeedFiguresOptions& options,
                                                    const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> written;
    for (const auto& fig : figures) {
        const std::string stem = seedFigureStem(fig.dt);
        written.push_back(writeSvg(seedFigureChart(fig, options), dir / (stem + ".svg")));
        written.push_back(
            writeCsvFile(dir / (stem + ".csv"), [&](std::ostream& out) { writeSeedFigureCsv(fig, out); }));
    }
    return written;
}

} // namespace lab
