#include "lab/lab_report.h"

#include "lab/exact_reference.h"
#include "lab/hair_study.h"
#include "lab/lab_util.h"
#include "lab/long_run.h"
#include "lab/pendulum_common.h"
#include "lab/stability.h"
#include "lab/work_precision.h"
#include "physics/pendulum.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace lab {

using physics::Method;

namespace {

std::string g2(double v) { return formatNumber("%.2g", v); }
// Two significant digits, trailing zeros kept (0.30, not 0.3), exponents short (3.4e-5).
std::string sig2(double v) {
    const double a = std::abs(v);
    if (!(a >= 0.01)) {
        if (a == 0.0) return "0";
        std::string s = formatNumber("%.1e", v);
        const auto e = s.find('e');
        std::string exponent = s.substr(e + 1);
        const bool negative = exponent[0] == '-';
        exponent = exponent.substr(exponent.find_first_not_of("+-0"));
        return s.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
    }
    return formatNumber(a < 0.1 ? "%.3f" : a < 1.0 ? "%.2f" : a < 10.0 ? "%.1f" : "%.0f", v);
}
std::string g3(double v) { return formatNumber("%.3g", v); }
std::string f2(double v) { return formatNumber("%.2f", v); }
std::string name(Method m) { return std::string(physics::methodName(m)); }

constexpr double kTick = 10.0 / 633.0; // the sweep's step nearest 1/60 s that divides 10 s: 15.8 ms

// Angle error at 10 s and largest energy error over 60 s at the given steps, without timing.
std::vector<WorkPrecisionPoint> accuracyAt(const std::vector<Method>& methods, double smallDt, double largeDt) {
    WorkPrecisionOptions o;
    o.methods = methods;
    o.minDt = smallDt;
    o.maxDt = largeDt;
    o.stepsInSweep = 2;
    o.timingBatchSeconds = 0.0; // one timed run each: the times are not used here
    o.timingBatches = 1;
    return runWorkPrecision(o);
}

const WorkPrecisionPoint& pointOf(const std::vector<WorkPrecisionPoint>& points, Method m, double dt) {
    for (const auto& p : points)
        if (p.method == m && std::abs(p.dt - dt) <= 1e-12 * dt) return p;
    // A missing run is a bug in the report, not a figure: quoting a default point would print zeros.
    throw std::logic_error("report: no run of " + name(m) + " at dt = " + formatShort(dt));
}

std::string errorPair(const WorkPrecisionPoint& p) { return sig2(p.angleError) + " / " + sig2(p.maxEnergyError); }

// Observed order from the angle errors at steps halving from 16 ms to 0.25 ms: the pair of smallest steps (the
// deepest into the asymptotic range) whose smaller error is still over 1e-11 rad (clear of round-off, which
// the 60 s runs accumulate to about 1e-13). Returns the order and the pair's larger step; NaN when none.
std::pair<double, double> observedOrder(const std::vector<WorkPrecisionPoint>& ladder, Method m) {
    std::vector<const WorkPrecisionPoint*> runs;
    for (const auto& p : ladder)
        if (p.method == m) runs.push_back(&p);
    std::sort(runs.begin(), runs.end(), [](const auto* a, const auto* b) { return a->dt > b->dt; });
    for (std::size_t i = runs.size(); i-- > 1;) {
        if (runs[i]->angleError > 1e-11)
            return {std::log2(runs[i - 1]->angleError / runs[i]->angleError), runs[i - 1]->dt};
    }
    return {std::numeric_limits<double>::quiet_NaN(), 0.0};
}

std::string methodTable() {
    const std::vector<Method> methods = fixedStepMethods();
    const std::vector<WorkPrecisionPoint> table = accuracyAt(methods, 0.001, kTick);
    WorkPrecisionOptions halvingOptions; // 16 ms, 8 ms, ... 0.25 ms: each 10 s / a whole number
    halvingOptions.methods = methods;
    halvingOptions.minDt = 0.016 / 64.0;
    halvingOptions.maxDt = 0.016;
    halvingOptions.stepsInSweep = 7;
    halvingOptions.timingBatchSeconds = 0.0;
    halvingOptions.timingBatches = 1;
    const std::vector<WorkPrecisionPoint> halving = runWorkPrecision(halvingOptions);
    std::string md;
    md += "From 60 degrees at rest (L = 1 m, g = 9.81 m/s²): angle error at 10 s in radians / largest energy error "
          "over 60 s in m g L, at 1 ms and at 15.8 ms (10 s / 633, about one game tick); the observed order: log2 of "
          "the angle error's ratio as the step halves, from the smallest of 16, 8, ... 0.25 ms whose half still "
          "errs by more than 1e-11 rad (named in brackets); force evaluations a step as counted over the 60 s run at "
          "15.8 ms (implicit-midpoint: the sin and cos of its Newton iterations). "
          "`minecrappy-lab work-precision --out DIR` sweeps 16 steps.\n\n";
    md += "| method | dt = 1 ms | dt = 15.8 ms | observed order | evaluations a step at 15.8 ms |\n";
    md += "|---|---|---|---|---|\n";
    for (const Method m : methods) {
        const auto [order, from] = observedOrder(halving, m);
        const double evals = pointOf(table, m, kTick).evalsPerSimSecond * kTick; // counted, not looked up
        md += "| ";
        md += name(m) + " | " + errorPair(pointOf(table, m, 0.001)) + " | " + errorPair(pointOf(table, m, kTick)) +
              " | " + f2(order) + " (" + formatNumber("%g", from * 1e3) + " ms) | " + formatNumber("%.3g", evals) +
              " |\n";
    }
    const WorkPrecisionPoint& rk4 = pointOf(table, Method::Rk4, kTick);
    const WorkPrecisionPoint& verlet = pointOf(table, Method::Verlet, kTick);
    const WorkPrecisionPoint& euler = pointOf(table, Method::Euler, 0.001);
    const WorkPrecisionPoint& symplectic = pointOf(table, Method::SymplecticEuler, 0.001);
    md += "\nAt 15.8 ms rk4's angle error is " + formatNumber("%.0f", verlet.angleError / rk4.angleError) +
          " times smaller than verlet's and its energy error " +
          formatNumber("%.0f", verlet.maxEnergyError / rk4.maxEnergyError) +
          " times smaller, for 4 force evaluations a step against 1. At 1 ms, explicit Euler (the seed's equation 2) "
          "is off by " +
          f2(euler.angleError) + " rad at 10 s and gains " + f2(euler.maxEnergyError) +
          " m g L in a minute; symplectic Euler (what the seed's listing computes) is off by " +
          sig2(symplectic.angleError) + " rad and its energy error stays under " + sig2(symplectic.maxEnergyError) +
          " m g L.\n";
    return md;
}

std::string adaptiveTable() {
    WorkPrecisionOptions o;
    o.methods = {Method::Dopri5};
    o.tolerances = {1e-4, 1e-6, 1e-8, 1e-10, 1e-12};
    o.timingBatchSeconds = 0.0;
    o.timingBatches = 1;
    std::string md;
    md += "\ndopri5 (Dormand-Prince 5(4), adaptive) from the same release, free over 60 s at each tolerance (the "
          "work-precision sweep at every other decade of its tolerances): angle error at 10 s from its dense output, "
          "largest energy "
          "error at its steps, accepted and rejected steps, force evaluations per simulated second.\n\n";
    md += "| tolerance | angle error at 10 s | energy error | accepted | rejected | evaluations / s |\n";
    md += "|---|---|---|---|---|---|\n";
    for (const WorkPrecisionPoint& p : runWorkPrecision(o)) {
        md += "| ";
        md += sig2(p.tolerance) + " | " + sig2(p.angleError) + " | " + sig2(p.maxEnergyError) + " | " +
              std::to_string(p.accepted) + " | " + std::to_string(p.rejected) + " | " +
              formatNumber("%.0f", p.evalsPerSimSecond) + " |\n";
    }
    return md;
}

std::string longRunTable() {
    LongRunOptions o;
    o.dts = {0.05};
    const std::vector<LongRunPoint> points = runLongRun(o);
    std::string md;
    md += "\nOver long horizons (`minecrappy-lab long-run --out DIR`; here dt = 50 ms from 60 degrees): the largest "
          "energy error in m g L in the window ending nearest 10 s and in the last, to 20,000 s, with the sign of "
          "E - E0 there (+ gained, - lost; blown up: past 10 m g L), and their ratio.\n\n";
    md += "| method | window to 10 s | last window | growth |\n|---|---|---|---|\n";
    const std::vector<double> ends = longRunWindowEnds(o);
    double early = ends.front();
    for (const double e : ends)
        if (std::abs(e - 10.0) < std::abs(early - 10.0)) early = e;
    for (const Method m : o.methods) {
        const LongRunPoint *first = nullptr, *last = nullptr;
        for (const auto& p : points) {
            if (p.method != m) continue;
            if (p.windowEnd == early) first = &p;
            last = &p;
        }
        if (!first || !last) continue;
        const auto signedValue = [](const LongRunPoint& p) {
            if (!std::isfinite(p.maxEnergyError)) return std::string("blown up");
            return std::string(p.signedEnergyError < 0.0 ? "-" : "+") + sig2(p.maxEnergyError);
        };
        const double growth = last->maxEnergyError / first->maxEnergyError;
        md += "| ";
        md += name(m) + " | " + signedValue(*first) + " | " + signedValue(*last) + " | " +
              (std::isfinite(growth) ? formatNumber(growth < 10.0 ? "%.2f" : "%.0f", growth) + "x" : std::string("-")) +
              " |\n";
    }
    return md;
}

// A cell of the stability tables: the first failure, * when grid-sensitive, "none to X" when every grid point
// up to X was bounded, 0 when even the floor failed.
std::string stabilityCell(const StabilityPoint& p) {
    switch (p.bound) {
    case StabilityBound::FirstFailure:
        return formatShort(p.firstFailureOmegaDt) + (p.gridSensitive ? " *" : "");
    case StabilityBound::FailsAtFloor:
        return "0";
    case StabilityBound::NeverFails:
        return "none to " + formatShort(p.maxStableOmegaDt);
    }
    return {};
}

// Near the separatrix: the whole-range refined scans, and two unbounded windows below unflagged first failures
// that no grid of the study has a point in, each found by a scan 1e-7 apart around where it lies.
std::string separatrixWindows(const StabilityOptions& o, const std::vector<StabilityPoint>& points) {
    std::string angles;
    long runs = 0, allRuns = 0;
    for (const StabilityPoint& p : points) {
        allRuns += p.runs;
        const auto& whole = o.wholeRangeRefineAnglesDeg;
        if (std::find(whole.begin(), whole.end(), p.theta0Deg) != whole.end()) runs += p.runs;
    }
    for (const double a : o.wholeRangeRefineAnglesDeg) angles += (angles.empty() ? "" : " and ") + formatShort(a) + "°";
    std::string md = " At " + angles + " (near the separatrix) the refined grid covers the whole range instead (" +
                     std::to_string(runs) + " of the study's " + std::to_string(allRuns) +
                     " runs). No grid finds every window:";
    const struct {
        Method method;
        double theta0Deg, near;
    } windows[] = {{Method::ImplicitMidpoint, 179.0, 0.63967}, {Method::Yoshida4, 170.0, 0.79997}};
    const double omega0 = std::sqrt(o.params.gravity / o.params.length);
    bool first = true, seen = false;
    for (const auto& w : windows) {
        double from = std::nan(""), to = std::nan("");
        int failing = 0;
        constexpr int kHalf = 200; // 2e-5 either side, 1e-7 apart
        for (int i = -kHalf; i <= kHalf; ++i) {
            const double x = w.near + i * 1e-7;
            if (staysBounded(w.method, o.params, detail::degToRad(w.theta0Deg), x / omega0, o.seconds,
                             o.energyTolerance))
                continue;
            if (std::isnan(from)) from = x;
            to = x;
            ++failing;
        }
        const auto cell = std::find_if(points.begin(), points.end(), [&](const StabilityPoint& p) {
            return p.method == w.method && p.theta0Deg == w.theta0Deg;
        });
        if (cell == points.end() || failing == 0) continue;
        const double f = cell->firstFailureOmegaDt;
        md += (first ? " " : "; ") + name(w.method) + " from " + formatShort(w.theta0Deg) + "° fails at " +
              std::to_string(failing) + " points 1e-7 apart from " + formatNumber("%.7f", from) + " to " +
              formatNumber("%.7f", to) + ", " + formatNumber("%.1f", 100.0 * (f - from) / f) + " % below " +
              formatShort(f) + (cell->refinedFirstFailureOmegaDt < from ? " (seen by the refined grid)" : "");
        seen |= cell->refinedFirstFailureOmegaDt < from;
        first = false;
    }
    return md + (seen ? "." : "; the refined grid sees neither.");
}

std::string stabilityTable() {
    StabilityOptions o;
    const std::vector<StabilityPoint> points = runStability(o);
    std::string md;
    md += "\nStability of a release from rest: the first omega0 dt at which the run does not stay bounded for " +
          formatShort(o.seconds) + " s (never over the top, energy within " + formatShort(o.energyTolerance) +
          " m g L), on a grid " + formatShort((o.gridRatio - 1.0) * 100.0) +
          " % apart scanned point by point up from a step that stayed bounded (a quarter of a 25 % scan's first "
          "failure); the linear limit of omega0 h from the amplification matrices (`physics::linearStabilityLimit`). "
          "`minecrappy-lab stability --out DIR` writes every figure (stability.csv, stability_islands.csv). "
          "none to X: bounded at every grid point up to X, the largest grid point tried (the grid ends at 4); 0: "
          "unbounded at every step down "
          "to " +
          formatShort(o.floor) + "; *: grid-sensitive (below).\n\n";
    md += "| method | linear |";
    for (const double a : o.anglesDeg) md += ' ' + formatShort(a) + "° |";
    md += "\n|---|---|";
    for (std::size_t i = 0; i < o.anglesDeg.size(); ++i) md += "---|";
    md += "\n";
    int above = 0, withLimit = 0;
    std::string sensitive, islands;
    for (const Method m : o.methods) {
        const double linear = physics::linearStabilityLimit(m);
        md += "| ";
        md += name(m) + " | " + (std::isfinite(linear) ? g3(linear) : std::string("∞")) + " |";
        islands += "| " + name(m) + " |";
        for (const auto& p : points) {
            if (p.method != m) continue;
            md += ' ' + stabilityCell(p) + " |";
            if (linear > 0.0 && std::isfinite(linear)) {
                ++withLimit;
                above += p.maxStableOmegaDt > linear ? 1 : 0;
            }
            const std::string cell = name(m) + " " + formatShort(p.theta0Deg) + "°";
            if (p.gridSensitive) {
                sensitive += sensitive.empty() ? " " : ", ";
                sensitive += cell + ": " + formatShort(p.firstFailureOmegaDt) + " to " +
                             formatShort(p.refinedFirstFailureOmegaDt);
            }
            int gridPoints = 0, failing = 0;
            for (const auto& island : p.islands) {
                gridPoints += island.gridPoints;
                failing += island.failing;
            }
            islands += ' ' +
                       (p.islands.empty()
                            ? std::string("-")
                            : std::to_string(p.islands.size()) + ": " + formatShort(p.islands.front().fromOmegaDt) +
                                  " to " + formatShort(p.islands.back().toOmegaDt) + ", " +
                                  formatNumber("%.0f", 100.0 * failing / gridPoints) + " %") +
                       " |";
        }
        islands += "\n";
        md += "\n";
    }
    md += '\n';
    md += std::to_string(above) + " of the " + std::to_string(withLimit) +
          " cells of the methods with a finite linear limit stay bounded beyond it. Grid-sensitive (the grid refined " +
          std::to_string(o.refine) + " times over the " + formatShort(o.refineWindow * 100.0) +
          " % below the first failure moves it down by more than " + formatShort(o.sensitivity * 100.0) +
          " %):" + (sensitive.empty() ? std::string(" none") : sensitive) + "." + separatrixWindows(o, points) +
          "\n\nBounded again above the first failure, up to " + formatShort(o.scanMax) +
          " (islands: runs of bounded grid points with gaps of up to " + std::to_string(o.islandGapPoints) +
          " unbounded ones; their number, from the first island's bottom to the last one's top, and the share of "
          "unbounded points inside them; each island in stability_islands.csv):\n\n| method |";
    for (const double a : o.anglesDeg) md += ' ' + formatShort(a) + "° |";
    md += "\n|---|";
    for (std::size_t i = 0; i < o.anglesDeg.size(); ++i) md += "---|";
    md += "\n" + islands;
    return md;
}

// The verdict against the criterion itself: the first failure from 60 degrees when the run must stay bounded
// ten times longer, or within a tighter energy band. Explicit Euler is left out: its energy grows as
// exp(omega0 dt omega0 T) in the linear limit, so its first failure falls as 1 / T, and the 600 s scan would
// cost more than all the others together.
std::string stabilityCriteriaTable() {
    struct Criterion {
        double seconds, tolerance;
    };
    const std::vector<Criterion> criteria = {{60.0, 0.5}, {600.0, 0.5}, {60.0, 0.1}, {60.0, 0.02}};
    StabilityOptions o;
    o.methods.clear();
    for (const Method m : fixedStepMethods()) {
        if (m != Method::Euler && m != Method::EulerCartesian) o.methods.push_back(m);
    }
    o.anglesDeg = {60.0};
    o.refine = 0;
    o.scanIslands = false;
    std::vector<std::vector<StabilityPoint>> columns;
    for (const Criterion& c : criteria) {
        o.seconds = c.seconds;
        o.energyTolerance = c.tolerance;
        columns.push_back(runStability(o));
    }
    std::string md;
    md += "\nThe verdict depends on the criterion: the first failure from 60° on the same grid when the run must stay "
          "bounded for 600 s instead of 60, or keep its energy within 0.1 or 0.02 m g L instead of 0.5 (the swing's "
          "own energy above the bottom is 0.5 m g L; explicit Euler left out: its first failure falls as 1 / T):\n\n";
    md += "| method |";
    for (const Criterion& c : criteria) md += ' ' + formatShort(c.seconds) + " s, " + formatShort(c.tolerance) + " |";
    md += "\n|---|";
    for (std::size_t i = 0; i < criteria.size(); ++i) md += "---|";
    md += "\n";
    for (std::size_t m = 0; m < o.methods.size(); ++m) {
        md += "| " + name(o.methods[m]) + " |";
        for (const auto& column : columns) md += ' ' + stabilityCell(column[m]) + " |";
        md += "\n";
    }
    return md;
}

// The closed form against the 50-digit values: the largest difference per regime and horizon.
std::string exactTable() {
    const physics::PendulumParams params{1.0, 9.81, 1.0, 0.0};
    struct Worst {
        double error = 0.0, ulps = 0.0;
    };
    Worst swingMinute, swingLate, rotateMinute, rotateLate;
    int rows = 0;
    for (const ExactReferenceValue& v : exactReferenceValues()) {
        const physics::ExactPendulum exact(params, {v.theta0, v.omega0});
        const double theta = exact.at(v.t).theta;
        const double reference = std::strtod(v.theta, nullptr);
        const double error = std::abs(theta - reference);
        const double ulp =
            std::nextafter(std::abs(reference), std::numeric_limits<double>::infinity()) - std::abs(reference);
        const bool rotating = exact.regime() != physics::ExactPendulum::Regime::Swinging;
        Worst& w = rotating ? (v.t <= 60.0 ? rotateMinute : rotateLate) : (v.t <= 60.0 ? swingMinute : swingLate);
        w.error = std::max(w.error, error);
        w.ulps = std::max(w.ulps, error / ulp);
        ++rows;
    }
    std::string md;
    md += "\nThe closed form (`exact`) against " + std::to_string(rows) +
          " values at 50 digits from Taylor-series integration in arbitrary precision (`scripts/exact_reference.py`, "
          "independent of the elliptic functions; starts at 60 and 179 degrees, (-0.5 rad, 3 rad/s), and rotating "
          "at 7.8 and 20 rad/s; each at t = 1, 10, 60 and 300 s), largest |theta - reference| at those sampled "
          "times (between them the closed form is not compared here: these are not maxima over the interval):\n\n";
    md += "| motion | t = 1, 10, 60 s | t = 300 s |\n|---|---|---|\n";
    md += "| swinging | ";
    md += g2(swingMinute.error) + " rad | " + g2(swingLate.error) + " rad |\n";
    md += "| rotating | ";
    md += g2(rotateMinute.error) + " rad (" + formatNumber("%.0f", rotateMinute.ulps) + " ulp) | " +
          g2(rotateLate.error) + " rad (" + formatNumber("%.0f", rotateLate.ulps) + " ulp) |\n";
    md += "\n(ulp: the spacing of doubles at the reference angle. A rotating angle keeps growing, and so does its "
          "ulp, the floor of any double-precision answer.)\n";
    return md;
}

std::string cpuName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
        }
    }
    return "unknown CPU";
}

} // namespace

std::string pendulumReportMarkdown() {
    return methodTable() + adaptiveTable() + longRunTable() + stabilityTable() + stabilityCriteriaTable() +
           exactTable();
}

std::string timingReportMarkdown(int runs) {
    runs = std::max(runs, 1);
    const std::vector<Method> methods = fixedStepMethods();
    std::vector<std::vector<double>> ns(methods.size());
    for (int r = 0; r < runs; ++r) {
        WorkPrecisionOptions o;
        o.methods = methods;
        o.minDt = kTick;
        o.maxDt = kTick;
        o.stepsInSweep = 2;
        const std::vector<WorkPrecisionPoint> points = runWorkPrecision(o);
        for (std::size_t i = 0; i < methods.size(); ++i)
            ns[i].push_back(pointOf(points, methods[i], kTick).nsPerSimSecond * kTick);
    }
    std::string md;
    md += "Nanoseconds per step at 15.8 ms (the best of 5 timed batches of 60 s runs), median and range of " +
          std::to_string(runs) + " runs on " + cpuName() + ":\n\n";
    md += "| method | ns per step | range |\n|---|---|---|\n";
    std::string hair = "\nThe hair solvers on a 512 x 12 ball at each one's game settings, one thread "
                       "(`minecrappy-lab hair-bench --solver NAME`), median and range of " +
                       std::to_string(runs) +
                       " runs: ms a 1/60 s step, and the ratios to the naive reference and "
                       "the limit kernel measured in the same run.\n\n";
    hair += "| solver | ms a step | range | / naive reference | / limit kernel |\n|---|---|---|---|---|\n";
    const auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    const auto range = [](const std::vector<double>& v, const char* format) {
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        return formatNumber(format, *lo) + " to " + formatNumber(format, *hi);
    };
    for (int m = 0; m < physics::kHairMethodCount; ++m) {
        HairBenchOptions o;
        o.solver = std::string(physics::hairMethodName(static_cast<physics::HairMethod>(m)));
        std::vector<double> ms, naive, limit;
        for (int r = 0; r < runs; ++r) {
            const HairBenchResult b = runHairBench(o);
            ms.push_back(b.msPerStep);
            naive.push_back(b.speedupVsNaive());
            limit.push_back(100.0 * b.fractionOfLimit());
        }
        hair += "| " + o.solver + " | " + formatNumber("%.3f", median(ms)) + " | " + range(ms, "%.3f") + " | " +
                formatNumber("%.1f", median(naive)) + "x (" + range(naive, "%.1f") + ") | " +
                formatNumber("%.0f", median(limit)) + " % (" + range(limit, "%.0f") + ") |\n";
    }
    for (std::size_t i = 0; i < methods.size(); ++i) {
        std::vector<double> v = ns[i];
        std::sort(v.begin(), v.end());
        md += "| ";
        md += name(methods[i]) + " | " + formatNumber("%.0f", v[v.size() / 2]) + " | " +
              formatNumber("%.0f", v.front()) + " to " + formatNumber("%.0f", v.back()) + " |\n";
    }
    return md + hair;
}

} // namespace lab
