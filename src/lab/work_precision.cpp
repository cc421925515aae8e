#include "lab/work_precision.h"

#include "lab/lab_util.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lab {

using detail::degToRad;
using detail::methodSeries;
using detail::methodsInOrder;
using detail::mgl;
using detail::name;
using physics::Method;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

} // namespace

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

} // namespace lab
