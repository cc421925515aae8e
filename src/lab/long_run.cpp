#include "lab/long_run.h"

#include "lab/lab_util.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace lab {

using physics::Method;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

double degToRad(double deg) { return deg * std::numbers::pi / 180.0; }

std::string name(Method m) { return std::string(physics::methodName(m)); }

double mgl(const physics::PendulumParams& p) { return p.mass * p.gravity * p.length; }

// For each window, the index of the last step ending in it: step k ends at k * dt, and belongs to the first
// window whose end it does not pass (a few ulps of slack, so 20 * 0.05 ends the window ending at 1 s). The last
// window takes every step up to stepCount(seconds, dt), the last of which may end past `seconds`.
std::vector<std::int64_t> lastStepPerWindow(const std::vector<double>& ends, double dt) {
    std::vector<std::int64_t> out;
    out.reserve(ends.size());
    for (std::size_t w = 0; w + 1 < ends.size(); ++w)
        out.push_back(static_cast<std::int64_t>(std::floor(ends[w] / dt * (1.0 + 4.0 * kEps))));
    out.push_back(stepCount(ends.back(), dt));
    return out;
}

} // namespace

std::vector<double> longRunWindowEnds(const LongRunOptions& o) {
    const double span = o.seconds / o.firstWindowEnd;
    // The fewest windows after the first giving at least windowsPerDecade per decade (slack: 10 s from 1 s at 4
    // per decade is 4 windows, not 5).
    const double wanted = o.windowsPerDecade * std::log10(span);
    const int n = std::max(0, static_cast<int>(std::ceil(wanted * (1.0 - 1e-12))));
    std::vector<double> ends;
    ends.reserve(static_cast<std::size_t>(n) + 1);
    ends.push_back(o.firstWindowEnd);
    for (int i = 1; i < n; ++i) ends.push_back(o.firstWindowEnd * std::pow(span, static_cast<double>(i) / n));
    if (n > 0) ends.push_back(o.seconds);
    return ends;
}

std::string validateLongRun(const LongRunOptions& o) {
    if (o.methods.empty()) return "no methods to run";
    for (const Method m : o.methods) {
        if (m == Method::Count || physics::methodName(m).empty()) return "unknown method";
        if (m == Method::Exact) return "method exact takes no steps";
    }
    if (o.dts.empty()) return "no steps (dt) to run";
    for (const double dt : o.dts) {
        if (!std::isfinite(dt) || dt <= 0.0) return "dt must be a finite number > 0 (seconds), got " + formatShort(dt);
    }
    if (!std::isfinite(o.seconds) || o.seconds <= 0.0)
        return "seconds must be a finite number > 0, got " + formatShort(o.seconds);
    if (!std::isfinite(o.firstWindowEnd) || o.firstWindowEnd <= 0.0)
        return "the first window end must be a finite number > 0 (seconds), got " + formatShort(o.firstWindowEnd);
    if (o.firstWindowEnd > o.seconds) {
        return "the first window end (" + formatShort(o.firstWindowEnd) + " s) is past seconds (" +
               formatShort(o.seconds) + " s)";
    }
    if (o.windowsPerDecade < 1 || o.windowsPerDecade > 100)
        return "windows per decade must be in [1, 100], got " + std::to_string(o.windowsPerDecade);
    if (!(o.blowUpError > 0.0)) return "the blow-up error must be > 0 (m g L), got " + formatShort(o.blowUpError);
    if (!std::isfinite(o.theta0Deg)) return "theta0 must be finite (degrees)";
    try {
        physics::validatePendulum(o.params, {degToRad(o.theta0Deg), 0.0});
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    const std::vector<double> ends = longRunWindowEnds(o);
    for (const double dt : o.dts) {
        const std::int64_t steps = stepCount(o.seconds, dt);
        if (steps < 0 || steps > kMaxSteps) {
            return "seconds / dt = " + formatShort(o.seconds) + " / " + formatShort(dt) + " would take " +
                   (steps < 0 ? std::string("too many") : std::to_string(steps)) + " steps; at most " +
                   std::to_string(kMaxSteps) + " per run are allowed";
        }
        const std::vector<std::int64_t> last = lastStepPerWindow(ends, dt);
        for (std::size_t w = 0; w < last.size(); ++w) {
            if (last[w] <= (w == 0 ? 0 : last[w - 1])) {
                return "the window ending at " + formatShort(ends[w]) + " s holds no step at dt = " + formatShort(dt) +
                       " s (make the first window end later or use fewer windows per decade)";
            }
        }
    }
    return {};
}

std::vector<LongRunPoint> runLongRun(const LongRunOptions& o, const Progress& progress) {
    if (const std::string why = validateLongRun(o); !why.empty()) throw std::invalid_argument("long-run: " + why);
    const std::vector<double> ends = longRunWindowEnds(o);
    const physics::PendulumState initial{degToRad(o.theta0Deg), 0.0};
    const double e0 = physics::energy(o.params, initial);
    const double scale = mgl(o.params);

    std::vector<LongRunPoint> points;
    points.reserve(o.methods.size() * o.dts.size() * ends.size());
    for (const Method m : o.methods) {
        for (const double dt : o.dts) {
            const std::vector<std::int64_t> last = lastStepPerWindow(ends, dt);
            const std::int64_t steps = last.back();
            if (progress) {
                progress("long-run: " + name(m) + " at dt = " + formatShort(dt) + " s (" + std::to_string(steps) +
                         " steps)");
            }
            physics::Pendulum p(m, o.params, initial);
            std::size_t w = 0;
            double worst = 0.0, worstSigned = 0.0;
            for (std::int64_t k = 1; k <= steps; ++k) {
                p.step(dt);
                const physics::PendulumState s = p.state();
                const double err = (physics::energy(o.params, s) - e0) / scale;
                // Written so that NaN stops the run too.
                if (!std::isfinite(s.theta) || !std::isfinite(s.omega) || !(std::fabs(err) <= o.blowUpError)) break;
                if (std::fabs(err) > worst) {
                    worst = std::fabs(err);
                    worstSigned = err;
                }
                if (k == last[w]) {
                    points.push_back({m, dt, ends[w], worst, worstSigned});
                    ++w;
                    worst = 0.0;
                    worstSigned = 0.0;
                }
            }
            // Blown up: the window it happened in and every later one.
            for (; w < ends.size(); ++w) points.push_back({m, dt, ends[w], kInf, kInf});
        }
    }
    return points;
}

void writeLongRunCsv(const std::vector<LongRunPoint>& points, std::ostream& out) {
    out << "method,dt,window_end_s,max_energy_error\n";
    std::string line;
    for (const auto& p : points) {
        line = name(p.method);
        for (const double v : {p.dt, p.windowEnd, p.maxEnergyError}) {
            line += ',';
            appendNumber(line, v);
        }
        line += '\n';
        out << line;
    }
}

Chart longRunChart(const std::vector<LongRunPoint>& points, const LongRunOptions& o) {
    Chart chart;
    chart.title = "Pendulum energy over a long run: released from " + formatShort(o.theta0Deg) +
                  "° at rest, L = " + formatShort(o.params.length) + " m, g = " + formatShort(o.params.gravity) +
                  " m/s², " + formatNumber("%.6g", o.seconds) + " s";
    std::vector<double> dts;
    std::vector<Method> methods;
    for (const auto& p : points) {
        if (std::find(dts.begin(), dts.end(), p.dt) == dts.end()) dts.push_back(p.dt);
        if (std::find(methods.begin(), methods.end(), p.method) == methods.end()) methods.push_back(p.method);
    }
    const std::string shapes =
        "flat: bounded error, no drift; slope 1: error growing linearly in time (rk4, dopri5 lose energy); curving up: "
        "exponential growth (euler and trapezoid gain energy); flat, then rising: the leapfrog midpoint's parasitic "
        "mode taking over";
    for (const double dt : dts) {
        Panel panel{
            "dt = " + formatShort(dt * 1000.0) +
                " ms (omega0 · dt = " + formatShort(dt * physics::smallAngleFrequency(o.params)) + ")",
            {"window end (s); each window runs from the previous end", AxisScale::Log10, o.firstWindowEnd, o.seconds},
            {"max |E - E0| / (m g L) in the window", AxisScale::Log10, {}, {}},
            {},
            shapes};
        std::string blown;
        // euler-cartesian steps (theta, omega) exactly as euler does, so its energy is euler's: say so rather than
        // leave a reader wondering where one of the two lines went.
        const bool twins = std::find(methods.begin(), methods.end(), Method::Euler) != methods.end() &&
                           std::find(methods.begin(), methods.end(), Method::EulerCartesian) != methods.end();
        for (const Method m : methods) {
            const std::string label = m == Method::Euler && twins ? "euler (= euler-cartesian)" : name(m);
            Series s{label, {}, {}, methodColour(m), true, false, true};
            for (const auto& p : points) {
                if (p.method != m || p.dt != dt) continue;
                if (std::isfinite(p.maxEnergyError)) {
                    s.x.push_back(p.windowEnd);
                    s.y.push_back(p.maxEnergyError);
                } else {
                    blown += (blown.empty() ? "" : ", ") + name(m) + " by " + formatShort(p.windowEnd) + " s";
                    break;
                }
            }
            panel.series.push_back(std::move(s));
        }
        if (!blown.empty()) {
            panel.note +=
                "; blew up (|E - E0| > " + formatShort(o.blowUpError) + " m g L or not finite), line ends: " + blown;
        }
        chart.panels.push_back(std::move(panel));
    }
    chart.panelHeight = 430;
    return chart;
}

std::vector<std::filesystem::path> writeLongRun(const std::vector<LongRunPoint>& points, const LongRunOptions& options,
                                                const std::filesystem::path& dir) {
    return {writeCsvFile(dir / "long_run.csv", [&](std::ostream& out) { writeLongRunCsv(points, out); }),
            writeSvg(longRunChart(points, options), dir / "long_run.svg")};
}

} // namespace lab
