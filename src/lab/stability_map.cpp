#include "lab/stability_map.h"

#include "lab/lab_util.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lab {

using detail::degToRad;
using detail::name;
using detail::parallelFor;
using physics::Method;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

} // namespace lab
