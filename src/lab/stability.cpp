#include "lab/stability.h"

#include "lab/lab_util.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace lab {

using detail::degToRad;
using detail::methodSeries;
using detail::methodsInOrder;
using detail::mgl;
using detail::name;
using detail::parallelFor;
using physics::Method;

namespace {

constexpr double kPi = std::numbers::pi;

} // namespace

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
        const bool wholeRange = std::find(o.wholeRangeRefineAnglesDeg.begin(), o.wholeRangeRefineAnglesDeg.end(),
                                          theta0Deg) != o.wholeRangeRefineAnglesDeg.end();
        int j = wholeRange ? 0
                           : std::max(0, static_cast<int>(
                                             std::ceil(o.refine * std::log(f / (1.0 + o.refineWindow) / out.gridStart) /
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

} // namespace lab
