#include "lab/hair_charts.h"

#include "lab/lab_util.h"

#include "lab/hair_chain.h"
#include "lab/hair_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <glm/gtc/quaternion.hpp>

namespace lab {

using physics::HairMethod;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kProgram = "minecrappy-lab";

using Clock = std::chrono::steady_clock;

std::string name(HairMethod m) { return std::string(physics::hairMethodName(m)); }

// The worst so far, where a NaN (a run that blew up) wins over any number and stays.
void worst(double& acc, double v) {
    if (std::isnan(v) || std::isnan(acc)) {
        acc = kNaN;
    } else {
        acc = std::max(acc, v);
    }
}

// The spin axis of the timing ball and the stability scans: tilted, so no strand is on the axis.
glm::vec3 spinAxis() { return glm::normalize(glm::vec3(0.3f, 1.0f, 0.1f)); }

std::string iterationText(const HairWorkPrecisionRow& r) {
    if (r.automatic) return std::to_string(r.iterations) + " Newton iterations, automatic substeps";
    if (r.method == HairMethod::XpbdSubsteps)
        return std::to_string(r.substeps) + " substep" + (r.substeps == 1 ? "" : "s");
    return std::to_string(r.iterations) + (r.method == HairMethod::Shake ? " Newton iteration" : " iteration") +
           (r.iterations == 1 ? "" : "s");
}

// ns per node-step of a ball with this method and counts (see HairWorkPrecisionOptions).
double timeHairSolver(HairMethod method, int iterations, int substeps, const HairWorkPrecisionOptions& o) {
    physics::HairParams base;
    base.strands = o.timingStrands;
    base.nodesPerStrand = o.timingNodes;
    base.strandLength = static_cast<float>(o.length);
    base.gravity = static_cast<float>(o.gravity);
    physics::HairParams p = physics::hairMethodDefaults(method, base);
    p.iterations = iterations;
    p.substeps = substeps;
    p.sleepSpeed = 0.0f;        // never asleep: time the work, not the shortcut
    p.maxSubstepSeconds = 0.0f; // exactly `substeps` substeps a step, whatever timingDt is
    p.hostCollision = true;
    physics::HostPose pose{{0.0f, 2.0f, 0.0f}, {}};
    physics::HairSolver solver(p, static_cast<float>(o.timingRadius), pose);
    const float dt = static_cast<float>(o.timingDt);
    const glm::vec3 axis = spinAxis();
    double angle = 0.0;
    auto step = [&] {
        // 2 rad/s: the hair swings out and slides over the ball, as it does in play.
        angle = std::fmod(angle + 2.0 * o.timingDt, 2.0 * kPi);
        pose.orientation = glm::angleAxis(static_cast<float>(angle), axis);
        solver.step(pose, dt, {}, nullptr, 1);
    };
    for (int i = 0; i < o.timingWarmupSteps; ++i) step();
    const double best = bestSecondsPerStep(o.timingSteps, step);
    return best * 1e9 / (static_cast<double>(o.timingStrands) * static_cast<double>(o.timingNodes));
}

} // namespace

std::vector<HairMethod> hairMethods() {
    std::vector<HairMethod> out;
    out.reserve(physics::kHairMethodCount);
    for (int i = 0; i < physics::kHairMethodCount; ++i) out.push_back(static_cast<HairMethod>(i));
    return out;
}

int hairMethodColour(HairMethod method) {
    switch (method) {
    case HairMethod::Ftl:
        return 1; // vermillion
    case HairMethod::Dftl:
        return 4; // orange: ftl's relative
    case HairMethod::Pbd:
        return 0; // blue
    case HairMethod::XpbdSubsteps:
        return 5; // sky blue: pbd's relative
    case HairMethod::Shake:
        return 2; // bluish green
    case HairMethod::Count:
        break;
    }
    return 6;
}

// ---------------------------------------------------------------------------------------------------
// Work-precision.

HairWorkPrecisionOptions HairWorkPrecisionOptions::quick() {
    HairWorkPrecisionOptions o;
    o.dts = {1.0 / 30.0, 1.0 / 60.0};
    o.seconds = 4.0;
    o.lookFrom = 2.5;
    o.lookTo = 4.0;
    o.timingStrands = 64;
    o.timingWarmupSteps = 2;
    o.timingSteps = 3;
    return o;
}

std::vector<HairWorkPrecisionRow> hairWorkPrecisionCells(const HairWorkPrecisionOptions& o) {
    if (o.methods.empty() || o.dts.empty()) throw std::invalid_argument("hair-work-precision: no methods or no steps");
    for (const double dt : o.dts) {
        if (!(std::isfinite(dt) && dt > 0.0)) throw std::invalid_argument("hair-work-precision: steps must be > 0");
    }
    const auto counts = [](const std::vector<int>& v, const char* what) {
        if (v.empty()) throw std::invalid_argument(std::string("hair-work-precision: no ") + what);
        for (const int n : v) {
            if (n < 1 || n > 1000)
                throw std::invalid_argument(std::string("hair-work-precision: ") + what + " must be in 1..1000");
        }
        return v;
    };
    std::vector<HairWorkPrecisionRow> cells;
    for (const HairMethod m : o.methods) {
        if (physics::hairMethodName(m).empty()) throw std::invalid_argument("hair-work-precision: unknown method");
        std::vector<std::pair<int, int>> variants; // (iterations, substeps)
        if (m == HairMethod::XpbdSubsteps) {
            for (const int s : counts(o.substeps, "substeps")) variants.emplace_back(1, s);
        } else {
            const bool shake = m == HairMethod::Shake;
            for (const int it :
                 counts(shake ? o.shakeIterations : o.iterations, shake ? "shakeIterations" : "iterations"))
                variants.emplace_back(it, 1);
        }
        for (const auto& [iterations, substeps] : variants) {
            for (const double dt : o.dts) {
                HairWorkPrecisionRow r;
                r.method = m;
                r.dt = dt;
                r.iterations = iterations;
                r.substeps = substeps;
                physics::HairParams p = physics::hairMethodDefaults(m);
                p.iterations = iterations;
                p.substeps = substeps;
                r.projectionsPerNode = physics::hairProjectionsPerNode(p);
                r.meanSubsteps = substeps;
                cells.push_back(r);
            }
        }
        if (m == HairMethod::Shake && o.shakeAutomatic) {
            const physics::HairParams p = physics::hairMethodDefaults(m);
            for (const double dt : o.dts) {
                HairWorkPrecisionRow r;
                r.method = m;
                r.dt = dt;
                r.iterations = p.iterations;
                r.substeps = p.substeps;
                r.automatic = true;
                r.projectionsPerNode = physics::hairProjectionsPerNode(p); // scaled by the substeps taken
                cells.push_back(r);
            }
        }
    }
    return cells;
}

std::vector<HairWorkPrecisionRow> runHairWorkPrecision(const HairWorkPrecisionOptions& o, const Progress& progress) {
    std::vector<HairWorkPrecisionRow> rows = hairWorkPrecisionCells(o);
    if (!(std::isfinite(o.seconds) && o.seconds > 0.0) || !(o.earlyTime >= 0.0 && o.earlyTime <= o.seconds) ||
        !(o.lateTime >= 0.0 && o.lateTime <= o.seconds) ||
        !(o.lookFrom >= 0.0 && o.lookFrom < o.lookTo && o.lookTo <= o.seconds)) {
        throw std::invalid_argument(
            "hair-work-precision: need 0 <= earlyTime, lateTime <= seconds and 0 <= lookFrom < lookTo <= seconds");
    }
    if (o.timingStrands < 1 || o.timingNodes < 2 || o.timingWarmupSteps < 0 || o.timingSteps < 1 ||
        !(o.timingDt > 0.0) || !(o.timingRadius > 0.0)) {
        throw std::invalid_argument("hair-work-precision: the timing ball needs strands >= 1, nodes >= 2, steps >= 1, "
                                    "dt > 0 and radius > 0");
    }
    // The reference's look, sampled every millisecond (the rows of one step would sample it at that step).
    HairChainOptions ref;
    ref.solver = "reference";
    ref.links = o.links;
    ref.length = o.length;
    ref.dt = 1e-3;
    ref.seconds = o.lookTo;
    ref.gravity = o.gravity;
    if (const std::string why = validateHairChain(ref); !why.empty())
        throw std::invalid_argument("hair-work-precision: " + why);
    const ChainLook reference = chainLook(runHairChain(ref), o.lookFrom, o.lookTo);
    // Timing depends on (method, iterations, substeps) only: once each, reused for every step.
    struct Timed {
        HairMethod method;
        int iterations, substeps;
        double ns;
    };
    std::vector<Timed> timed;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        HairWorkPrecisionRow& r = rows[i];
        const auto known = std::find_if(timed.begin(), timed.end(), [&](const Timed& t) {
            return t.method == r.method && t.iterations == r.iterations && t.substeps == r.substeps;
        });
        if (known != timed.end()) {
            r.nsPerNodeStep = known->ns;
        } else {
            r.nsPerNodeStep = timeHairSolver(r.method, r.iterations, r.substeps, o);
            timed.push_back({r.method, r.iterations, r.substeps, r.nsPerNodeStep});
            if (progress) {
                progress("hair-work-precision: timed " + name(r.method) + ", " + iterationText(r) + ": " +
                         formatShort(r.nsPerNodeStep) + " ns per node-step");
            }
        }

        HairChainOptions c;
        c.solver = name(r.method);
        c.links = o.links;
        c.length = o.length;
        c.dt = r.dt;
        c.seconds = o.seconds;
        c.iterations = r.iterations; // explicit: 0 would mean the method's default
        c.substeps = r.substeps;
        c.gravity = o.gravity;
        c.automaticSubsteps = r.automatic;
        if (const std::string why = validateHairChain(c); !why.empty())
            throw std::invalid_argument("hair-work-precision: " + why);
        if (progress) {
            progress("hair-work-precision: " + name(r.method) + ", " + iterationText(r) + ", dt = " +
                     formatShort(r.dt) + " s (" + std::to_string(i + 1) + "/" + std::to_string(rows.size()) + ")");
        }
        const std::vector<HairChainRow> chain = runHairChain(c);
        r.tipErrorEarly = chainTipErrorAt(chain, o.earlyTime);
        r.tipErrorLate = chainTipErrorAt(chain, o.lateTime);
        r.maxSegmentError = 0.0;
        r.maxEnergyError = 0.0;
        double substeps = 0.0;
        for (const HairChainRow& row : chain) {
            worst(r.maxSegmentError, std::fabs(row.maxSegmentError));
            worst(r.maxEnergyError, std::fabs(row.energyError));
            substeps += row.substeps;
        }
        r.look = chainLook(chain, o.lookFrom, o.lookTo);
        r.look.refMeanTipHeight = reference.refMeanTipHeight;
        r.look.refSwingPeriod = reference.refSwingPeriod;
        if (r.automatic) {
            // The timing ran one substep a step: the cost of the substeps this run took on average.
            r.meanSubsteps = chain.size() > 1 ? substeps / static_cast<double>(chain.size() - 1) : 1.0;
            r.projectionsPerNode *= r.meanSubsteps;
            r.nsPerNodeStep *= r.meanSubsteps;
        }
    }
    return rows;
}

void writeHairWorkPrecisionCsv(const std::vector<HairWorkPrecisionRow>& rows, std::ostream& out) {
    out << "method,dt,iterations,substeps,automatic,mean_substeps,projections_per_node,ns_per_node_step,"
           "tip_error_0_5s,tip_error_2s,max_segment_error,max_energy_error,look_energy,look_mean_tip_height,"
           "look_swing_period,ref_mean_tip_height,ref_swing_period\n";
    std::string line;
    for (const auto& r : rows) {
        line = name(r.method);
        line += ',';
        appendNumber(line, r.dt);
        line += ',' + std::to_string(r.iterations) + ',' + std::to_string(r.substeps) + ',' + (r.automatic ? "1" : "0");
        for (const double v : {r.meanSubsteps, r.projectionsPerNode, r.nsPerNodeStep, r.tipErrorEarly, r.tipErrorLate,
                               r.maxSegmentError, r.maxEnergyError, r.look.energy, r.look.meanTipHeight,
                               r.look.swingPeriod, r.look.refMeanTipHeight, r.look.refSwingPeriod}) {
            line += ',';
            appendNumber(line, v);
        }
        line += '\n';
        out << line;
    }
}

Chart hairWorkPrecisionChart(const std::vector<HairWorkPrecisionRow>& rows, const HairWorkPrecisionOptions& o) {
    const std::string tipLabel = "|tip - reference tip| at t = " + formatShort(o.earlyTime) + " s (m)";
    const std::string costLabel = "ns per node per simulated second (measured ns per node-step / dt)";
    const std::string timing = "cost timed on a " + formatShort(o.timingRadius) + " m ball of " +
                               std::to_string(o.timingStrands) + " strands x " + std::to_string(o.timingNodes) +
                               " nodes, ball collision on, one thread";
    Chart chart;
    chart.title = "Hair work-precision: a " + std::to_string(o.links) + "-link, " + formatShort(o.length) +
                  " m strand released horizontal at rest (root pinned, no damping, g = " + formatShort(o.gravity) +
                  " m/s²)";
    const std::string lines = "one line per iteration (xpbd-substeps: substep) count, through dt from large to "
                              "small (left to right); the reference is DOPRI5 at tolerance 1e-12";
    Panel byTime{"Tip error at " + formatShort(o.earlyTime) + " s against measured cost",
                 {costLabel, AxisScale::Log10, {}, {}},
                 {tipLabel, AxisScale::Log10, {}, {}},
                 {},
                 lines + "; lower left is better; " + timing};
    Panel byProjections{"Tip error at " + formatShort(o.earlyTime) + " s against constraint projections",
                        {"projections per free node per simulated second (physics::hairProjectionsPerNode / dt)",
                         AxisScale::Log10,
                         {},
                         {}},
                        {tipLabel, AxisScale::Log10, {}, {}},
                        {},
                        "ftl, dftl, pbd: iterations x substeps; xpbd-substeps: substeps; shake: Newton iterations "
                        "+ 1 contact pass"};
    Panel segments{"Largest segment error over " + formatShort(o.seconds) + " s against measured cost",
                   {costLabel, AxisScale::Log10, {}, {}},
                   {"max | |segment| / rest length - 1 |", AxisScale::Log10, {}, {}},
                   {},
                   "ftl, dftl and shake keep lengths to float rounding (an exact 0 cannot be drawn); pbd only in the "
                   "limit of many iterations, xpbd-substeps in the limit of many substeps"};
    const std::string window = formatShort(o.lookFrom) + " to " + formatShort(o.lookTo) + " s";
    const std::string past = "past the predictability horizon, where tip errors compare nothing; the reference "
                             "dashed; " +
                             lines;
    Panel energy{"Mean energy over " + window + " against measured cost",
                 {costLabel, AxisScale::Log10, {}, {}},
                 {"(E - E0) / (M g L)", AxisScale::Linear, {}, {}},
                 {},
                 past};
    Panel height{"The tip's mean height over " + window + " against measured cost",
                 {costLabel, AxisScale::Log10, {}, {}},
                 {"mean tip height below the root (m; hanging at rest: -" + formatShort(o.length) + ")",
                  AxisScale::Linear,
                  {},
                  {}},
                 {},
                 past};
    Panel period{
        "The tip's swing period over " + window + " against measured cost",
        {costLabel, AxisScale::Log10, {}, {}},
        {"swing period (s; none drawn: the tip did not swing 1 cm past the vertical)", AxisScale::Linear, {}, {}},
        {},
        past};
    std::vector<HairMethod> seen;
    for (const auto& r : rows) {
        if (std::find(seen.begin(), seen.end(), r.method) == seen.end()) seen.push_back(r.method);
    }
    using Variant = std::tuple<int, int, bool>; // iterations, substeps, automatic
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const HairMethod m : seen) {
        std::vector<Variant> variants;
        for (const auto& r : rows) {
            const Variant v{r.iterations, r.substeps, r.automatic};
            if (r.method == m && std::find(variants.begin(), variants.end(), v) == variants.end())
                variants.push_back(v);
        }
        bool first = true;
        for (const auto& v : variants) {
            const bool automatic = std::get<2>(v);
            Series a{automatic ? name(m) + ", automatic substeps" : name(m),
                     {},
                     {},
                     automatic ? 3 : hairMethodColour(m),
                     true,
                     false,
                     first || automatic};
            Series b = a, c = a, d = a, e = a, f = a;
            for (const auto& r : rows) {
                if (r.method != m || Variant{r.iterations, r.substeps, r.automatic} != v) continue;
                const double perSecond = 1.0 / r.dt, cost = r.nsPerNodeStep * perSecond;
                lo = std::min(lo, cost), hi = std::max(hi, cost);
                a.x.push_back(cost), a.y.push_back(r.tipErrorEarly);
                b.x.push_back(r.projectionsPerNode * perSecond), b.y.push_back(r.tipErrorEarly);
                c.x.push_back(cost), c.y.push_back(r.maxSegmentError);
                d.x.push_back(cost), d.y.push_back(r.look.energy);
                e.x.push_back(cost), e.y.push_back(r.look.meanTipHeight);
                f.x.push_back(cost), f.y.push_back(r.look.swingPeriod);
            }
            byTime.series.push_back(std::move(a));
            byProjections.series.push_back(std::move(b));
            segments.series.push_back(std::move(c));
            energy.series.push_back(std::move(d));
            height.series.push_back(std::move(e));
            period.series.push_back(std::move(f));
            if (!automatic) first = false;
        }
    }
    if (!rows.empty() && hi > 0.0) {
        // The reference's look is the same in every row (runHairWorkPrecision: one run sampled every millisecond).
        const ChainLook& ref = rows.front().look;
        const auto line = [&](double y) { return Series{"reference", {lo, hi}, {y, y}, 9, false, true, true}; };
        energy.series.push_back(line(0.0));
        height.series.push_back(line(ref.refMeanTipHeight));
        period.series.push_back(line(ref.refSwingPeriod));
    }
    chart.panels = {std::move(byTime), std::move(byProjections), std::move(segments),
                    std::move(energy), std::move(height),        std::move(period)};
    chart.panelHeight = 460;
    return chart;
}

std::vector<std::filesystem::path> writeHairWorkPrecision(const std::vector<HairWorkPrecisionRow>& rows,
                                                          const HairWorkPrecisionOptions& options,
                                                          const std::filesystem::path& dir) {
    return {
        writeCsvFile(dir / "hair_work_precision.csv", [&](std::ostream& out) { writeHairWorkPrecisionCsv(rows, out); }),
        writeSvg(hairWorkPrecisionChart(rows, options), dir / "hair_work_precision.svg")};
}

// ---------------------------------------------------------------------------------------------------
// Stability.

namespace {
// What a hair-stability scan varies: its name (as the CSV and the messages write it) and its unit.
struct ScanText {
    std::string_view name, unit;
};

ScanText scanText(HairScan scan) {
    switch (scan) {
    case HairScan::Step:
        return {"dt", "s"};
    case HairScan::Spin:
        return {"spin", "rad/s"};
    case HairScan::Carry:
        return {"carry", "m/s"};
    }
    return {"", ""};
}
} // namespace

std::string_view hairScanName(HairScan scan) { return scanText(scan).name; }

std::string_view hairScanUnit(HairScan scan) { return scanText(scan).unit; }

std::vector<double> geometricGrid(double lo, double hi, double ratio) {
    if (!(lo > 0.0 && hi >= lo && std::isfinite(hi) && ratio > 1.0 && std::isfinite(ratio)))
        throw std::invalid_argument("geometricGrid: need 0 < lo <= hi, finite, and ratio > 1");
    std::vector<double> out;
    // Powers rather than repeated products, so 1/480 * sqrt(2)^2 is 1/240 to the last bit or two; a value
    // within a part in 1e9 of hi is hi itself.
    for (int k = 0;; ++k) {
        const double v = lo * std::pow(ratio, k);
        if (!(v < hi * (1.0 - 1e-9))) break;
        out.push_back(v);
    }
    out.push_back(hi);
    return out;
}

HairStabilityOptions HairStabilityOptions::quick() {
    HairStabilityOptions o;
    o.strands = 32;
    o.seconds = 1.0;
    o.dts = {1.0 / 240.0, 1.0 / 60.0, 1.0 / 15.0, 0.25};
    o.spins = {0.0, 20.0, 200.0};
    o.carrySpeeds = {0.0, 5.0, 50.0};
    return o;
}

const std::vector<double>& hairStabilityGrid(HairScan scan, const HairStabilityOptions& o) {
    switch (scan) {
    case HairScan::Step:
        return o.dts;
    case HairScan::Spin:
        return o.spins;
    case HairScan::Carry:
        break;
    }
    return o.carrySpeeds;
}

namespace {

void validateStability(const HairStabilityOptions& o) {
    const auto bad = [](const std::string& what) { throw std::invalid_argument("hair-stability: " + what); };
    if (o.methods.empty()) bad("no methods");
    for (const HairMethod m : o.methods) {
        if (physics::hairMethodName(m).empty()) bad("unknown method");
    }
    if (o.strands < 1 || o.nodes < 2) bad("need strands >= 1 and nodes >= 2");
    if (!(o.strandLength > 0.0 && std::isfinite(o.strandLength)) || !(o.radius > 0.0 && std::isfinite(o.radius)) ||
        !std::isfinite(o.height))
        bad("need a finite strand length and radius > 0 and a finite height");
    if (!(o.seconds > 0.0 && std::isfinite(o.seconds))) bad("seconds must be > 0");
    if (!(o.scanDt > 0.0 && std::isfinite(o.scanDt))) bad("scanDt must be > 0");
    if (!(o.carryPeriod > 0.0 && std::isfinite(o.carryPeriod))) bad("carryPeriod must be > 0");
    if (!(o.spinRampSeconds >= 0.0 && std::isfinite(o.spinRampSeconds))) bad("spinRampSeconds must be >= 0");
    if (!std::isfinite(o.stepScanSpin)) bad("stepScanSpin must be finite");
    for (int s = 0; s < kHairScanCount; ++s) {
        const auto scan = static_cast<HairScan>(s);
        const auto& grid = hairStabilityGrid(scan, o);
        const std::string what(hairScanName(scan));
        if (grid.empty()) bad("the " + what + " scan has no values");
        for (std::size_t i = 0; i < grid.size(); ++i) {
            if (!std::isfinite(grid[i]) || grid[i] < 0.0 || (scan == HairScan::Step && !(grid[i] > 0.0)))
                bad("the " + what + " scan's values must be finite and >= 0 (steps > 0)");
            if (i > 0 && !(grid[i] > grid[i - 1])) bad("the " + what + " scan's values must increase");
        }
    }
    const double smallest = std::min(o.dts.front(), o.scanDt);
    if (o.seconds / smallest > kMaxHairSteps)
        bad("a run would take more than " + std::to_string(kMaxHairSteps) + " steps");
}

} // namespace

HairStabilityRow runHairStabilityCase(HairMethod method, HairScan scan, double value, const HairStabilityOptions& o) {
    if (physics::hairMethodName(method).empty()) throw std::invalid_argument("hair-stability: unknown method");
    if (!std::isfinite(value) || value < 0.0 || (scan == HairScan::Step && !(value > 0.0)))
        throw std::invalid_argument("hair-stability: a scan value must be finite and >= 0 (a step > 0)");
    HairStabilityRow row;
    row.method = method;
    row.scan = scan;
    row.value = value;

    physics::HairParams base;
    base.strands = o.strands;
    base.nodesPerStrand = o.nodes;
    base.strandLength = static_cast<float>(o.strandLength);
    base.hostCollision = true;
    physics::HairParams p = physics::hairMethodDefaults(method, base);
    const double dt = scan == HairScan::Step ? value : o.scanDt;
    if (scan == HairScan::Step) p.maxSubstepSeconds = 0.0f; // the method's own limit, not the automatic splitting
    const double spin = scan == HairScan::Step ? o.stepScanSpin : scan == HairScan::Spin ? value : 0.0;
    const double omega = 2.0 * kPi / o.carryPeriod;
    const double amplitude = scan == HairScan::Carry ? value / omega : 0.0;
    const auto centreAt = [&](double t) {
        return glm::vec3(static_cast<float>(-amplitude * std::cos(omega * t)), static_cast<float>(o.height), 0.0f);
    };

    // Blocks for y in [-2, 0), x and z in [-16, 16): room for the carry scan's swing (up to ~8 m at 50 m/s).
    const physics::VoxelOccupancy floor = physics::blockFloor(16);
    physics::HostPose pose{centreAt(0.0), {}};
    physics::HairSolver hair(p, static_cast<float>(o.radius), pose);
    const std::int64_t steps = stepCount(o.seconds, dt);
    if (steps < 1 || steps > kMaxHairSteps)
        throw std::invalid_argument("hair-stability: a run would take more than " + std::to_string(kMaxHairSteps) +
                                    " steps");
    const glm::vec3 axis = spinAxis();
    const double reachLimit = o.strandLength * (1.0 + kHairStableSegmentError) + kHairReachSlack;
    const std::size_t S = static_cast<std::size_t>(hair.strands());
    const std::size_t N = static_cast<std::size_t>(hair.nodesPerStrand());
    double angle = 0.0;
    double maxReachMetres = 0.0;
    for (std::int64_t k = 1; k <= steps; ++k) {
        const double t = static_cast<double>(k) * dt;
        const double ramp = o.spinRampSeconds > 0.0 ? std::min(1.0, t / o.spinRampSeconds) : 1.0;
        angle = std::fmod(angle + spin * ramp * dt, 2.0 * kPi);
        pose.orientation = glm::angleAxis(static_cast<float>(angle), axis);
        pose.centre = centreAt(t);
        const physics::HairStepStats stats = hair.step(pose, static_cast<float>(dt), {}, &floor);
        worst(row.maxSegmentError, static_cast<double>(stats.maxSegmentError));
        worst(row.maxPenetration, static_cast<double>(stats.maxPenetration));
        row.nan = row.nan || stats.nan || std::isnan(row.maxSegmentError) || std::isnan(row.maxPenetration);
        // Node 0 of each strand is its root (node-major SoA: index = node * strands + strand).
        const float* x = hair.x();
        const float* y = hair.y();
        const float* z = hair.z();
        for (std::size_t s = 0; s < S; ++s) {
            const double rx = x[s], ry = y[s], rz = z[s];
            for (std::size_t n = 0; n < N; ++n) {
                const std::size_t i = n * S + s;
                const double dx = x[i] - rx, dy = y[i] - ry, dz = z[i] - rz;
                const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
                if (!std::isfinite(d)) {
                    row.nan = true;
                } else {
                    maxReachMetres = std::max(maxReachMetres, d);
                }
            }
        }
        // Written so that NaN fails every test.
        const bool ok = !row.nan && row.maxSegmentError < kHairStableSegmentError &&
                        row.maxPenetration <= kHairPenetrationSlack && maxReachMetres <= reachLimit;
        if (!ok) {
            row.failedAt = t;
            break;
        }
    }
    row.maxReach = maxReachMetres / o.strandLength;
    row.bounded = row.failedAt < 0.0;
    return row;
}

std::vector<HairStabilityRow> runHairStability(const HairStabilityOptions& o, const Progress& progress) {
    validateStability(o);
    std::size_t total = 0;
    for (int s = 0; s < kHairScanCount; ++s) total += hairStabilityGrid(static_cast<HairScan>(s), o).size();
    total *= o.methods.size();
    std::vector<HairStabilityRow> rows;
    rows.reserve(total);
    for (const HairMethod m : o.methods) {
        for (int s = 0; s < kHairScanCount; ++s) {
            const auto scan = static_cast<HairScan>(s);
            for (const double v : hairStabilityGrid(scan, o)) {
                rows.push_back(runHairStabilityCase(m, scan, v, o));
                if (progress) {
                    const HairStabilityRow& r = rows.back();
                    std::string line = "hair-stability: " + name(m) + " " + std::string(hairScanName(scan)) + " = " +
                                       formatShort(v) + " " + std::string(hairScanUnit(scan)) + " (" +
                                       std::to_string(rows.size()) + "/" + std::to_string(total) + "): ";
                    if (r.bounded) {
                        line += "bounded";
                    } else {
                        line += "unbounded at t = " + formatShort(r.failedAt) + " s (" +
                                (r.nan ? std::string("NaN")
                                       : "segment error " + formatShort(r.maxSegmentError) + ", penetration " +
                                             formatShort(r.maxPenetration) + " m, reach " + formatShort(r.maxReach) +
                                             " L") +
                                ")";
                    }
                    progress(line);
                }
            }
        }
    }
    return rows;
}

HairScanSummary summariseHairScan(const std::vector<double>& values, const std::vector<bool>& bounded) {
    if (values.size() != bounded.size())
        throw std::invalid_argument("summariseHairScan: one bounded flag per value is needed");
    HairScanSummary s;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!bounded[i]) {
            if (!s.firstFailure) s.firstFailure = values[i];
        } else if (!s.firstFailure) {
            s.lastBounded = values[i];
        } else {
            s.islands.push_back(values[i]);
        }
    }
    return s;
}

std::vector<HairStabilityLimit> hairStabilityLimits(const std::vector<HairStabilityRow>& rows) {
    std::vector<std::pair<HairMethod, HairScan>> keys;
    for (const auto& r : rows) {
        const std::pair<HairMethod, HairScan> k{r.method, r.scan};
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    }
    std::vector<HairStabilityLimit> out;
    for (const auto& [method, scan] : keys) {
        std::vector<double> values;
        std::vector<bool> bounded;
        for (const auto& r : rows) {
            if (r.method != method || r.scan != scan) continue;
            values.push_back(r.value);
            bounded.push_back(r.bounded);
        }
        out.push_back({method, scan, summariseHairScan(values, bounded)});
    }
    return out;
}

void writeHairStabilityCsv(const std::vector<HairStabilityRow>& rows, std::ostream& out) {
    out << "method,scan,value,bounded,max_segment_error,max_penetration,nan\n";
    std::string line;
    for (const auto& r : rows) {
        line = name(r.method) + ',' + std::string(hairScanName(r.scan)) + ',';
        appendNumber(line, r.value);
        line += r.bounded ? ",1," : ",0,";
        appendNumber(line, r.maxSegmentError);
        line += ',';
        appendNumber(line, r.maxPenetration);
        line += r.nan ? ",1\n" : ",0\n";
        out << line;
    }
}

void writeHairStabilityLimitsCsv(const std::vector<HairStabilityLimit>& limits, std::ostream& out) {
    out << "method,scan,first_failure,islands\n";
    std::string line;
    for (const auto& l : limits) {
        line = name(l.method) + ',' + std::string(hairScanName(l.scan)) + ',';
        if (l.summary.firstFailure) {
            appendNumber(line, *l.summary.firstFailure);
        } else {
            line += "none";
        }
        line += ',';
        for (std::size_t i = 0; i < l.summary.islands.size(); ++i) {
            if (i > 0) line += ';';
            appendNumber(line, l.summary.islands[i]);
        }
        line += '\n';
        out << line;
    }
}

Chart hairStabilityChart(const std::vector<HairStabilityRow>& rows, const HairStabilityOptions& o) {
    Chart chart;
    chart.title = "Hair stability at each method's defaults: a " + formatShort(o.radius) + " m ball, " +
                  std::to_string(o.strands) + " strands x " + std::to_string(o.nodes) + " nodes of " +
                  formatShort(o.strandLength) + " m, over blocks, for " + formatShort(o.seconds) + " s";
    std::vector<HairMethod> methods;
    std::vector<HairScan> scans;
    for (const auto& r : rows) {
        if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
        if (std::find(scans.begin(), scans.end(), r.scan) == scans.end()) scans.push_back(r.scan);
    }
    std::string order;
    for (const HairMethod m : methods) order += (order.empty() ? "" : ", ") + name(m);
    const double top = static_cast<double>(methods.size()) - 0.5;
    const std::string criteria = "bounded: no NaN, segment error < " + formatShort(kHairStableSegmentError) +
                                 ", penetration <= " + formatShort(kHairPenetrationSlack) +
                                 " m, no node beyond 1.05 strand lengths from its root";
    for (const HairScan scan : scans) {
        Panel panel;
        switch (scan) {
        case HairScan::Step:
            panel.title = "Step: host spinning at " + formatShort(o.stepScanSpin) + " rad/s, no automatic substeps";
            panel.x = {"step dt (s)", AxisScale::Log10, {}, {}};
            break;
        case HairScan::Spin:
            panel.title = "Spin rate (ramped up over " + formatShort(o.spinRampSeconds) +
                          " s) at dt = " + formatShort(o.scanDt) + " s";
            panel.x = {"spin (rad/s)", AxisScale::Linear, 0.0, {}};
            break;
        case HairScan::Carry:
            panel.title = "Carry back and forth (period " + formatShort(o.carryPeriod) +
                          " s) at dt = " + formatShort(o.scanDt) + " s";
            panel.x = {"peak carry speed (m/s)", AxisScale::Linear, 0.0, {}};
            break;
        }
        panel.y = {"method (row)", AxisScale::Linear, -0.5, top};
        panel.note = "rows top to bottom: ";
        panel.note += order;
        panel.note += "; solid: bounded, dashed black: unbounded; ";
        panel.note += criteria;
        bool unboundedInLegend = false;
        for (std::size_t mi = 0; mi < methods.size(); ++mi) {
            const HairMethod m = methods[mi];
            const double rowY = static_cast<double>(methods.size() - 1 - mi);
            bool methodInLegend = false, hadRows = false;
            // Runs of equal outcome, each its own series, so a failure leaves a visible break.
            Series current;
            bool open = false, currentBounded = false;
            const auto close = [&] {
                if (!open) return;
                if (currentBounded) {
                    current.inLegend = !methodInLegend;
                    methodInLegend = true;
                } else {
                    current.inLegend = !unboundedInLegend;
                    unboundedInLegend = true;
                }
                panel.series.push_back(std::move(current));
                current = Series{};
                open = false;
            };
            for (const auto& r : rows) {
                if (r.method != m || r.scan != scan) continue;
                hadRows = true;
                if (open && r.bounded != currentBounded) close();
                if (!open) {
                    current = r.bounded ? Series{name(m), {}, {}, hairMethodColour(m), true, false, false}
                                        : Series{"unbounded", {}, {}, 6, false, true, false};
                    currentBounded = r.bounded;
                    open = true;
                }
                current.x.push_back(r.value);
                current.y.push_back(rowY);
            }
            close();
            if (hadRows && !methodInLegend) { // never bounded: still named in the legend
                panel.series.push_back(
                    Series{name(m) + " (never bounded)", {}, {}, hairMethodColour(m), true, false, true});
            }
        }
        chart.panels.push_back(std::move(panel));
    }
    chart.panelHeight = 300;
    return chart;
}

std::vector<std::filesystem::path> writeHairStability(const std::vector<HairStabilityRow>& rows,
                                                      const HairStabilityOptions& options,
                                                      const std::filesystem::path& dir) {
    const auto limits = hairStabilityLimits(rows);
    return {writeCsvFile(dir / "hair_stability.csv", [&](std::ostream& out) { writeHairStabilityCsv(rows, out); }),
            writeCsvFile(dir / "hair_stability_limits.csv",
                         [&](std::ostream& out) { writeHairStabilityLimitsCsv(limits, out); }),
            writeSvg(hairStabilityChart(rows, options), dir / "hair_stability.svg")};
}

// ---------------------------------------------------------------------------------------------------
// Commands.

namespace {
// One line a method and scan on `out`: up to where the balls stayed bounded, the first failure and the islands.
void printHairStabilityLimits(const std::vector<HairStabilityRow>& rows, const std::string& command,
                              std::ostream& out) {
    for (const auto& l : hairStabilityLimits(rows)) {
        out << command << ": " << name(l.method) << " " << hairScanName(l.scan) << ": ";
        const std::string unit(hairScanUnit(l.scan));
        if (!l.summary.firstFailure) {
            out << "bounded over the whole scan";
        } else {
            out << (l.summary.lastBounded ? "bounded up to " + formatShort(*l.summary.lastBounded) + " " + unit
                                          : std::string("unbounded from the first value"))
                << ", first failure " << formatShort(*l.summary.firstFailure) << " " << unit;
            if (!l.summary.islands.empty()) {
                out << ", bounded again at";
                for (const double v : l.summary.islands) out << " " << formatShort(v);
                out << " " << unit;
            }
        }
        out << "\n";
    }
}

// The frame of a hair study command: makes `outDir`, runs `study` (handing it a writer of progress lines to
// `err`), says on `err` how many `what` it made and in how long, and hands them to `report`, which prints and
// writes the files. A std::exception on the way is reported as "minecrappy-lab COMMAND: ..." with exit code 1.
template <class Study, class Report>
int runHairStudyCommand(const std::string& command, const std::string& what, const std::string& outDir,
                        std::ostream& err, Study study, Report report) {
    if (!prepareOutDir(outDir, command, err)) return 2;
    try {
        const auto start = Clock::now();
        const auto rows = study([&err](const std::string& line) { err << line << "\n" << std::flush; });
        err << command << ": " << rows.size() << " " << what << " in " << formatShort(secondsSince(start)) << " s\n";
        report(rows);
    } catch (const std::exception& e) {
        err << kProgram << " " << command << ": " << e.what() << "\n";
        return 1;
    }
    return 0;
}
} // namespace

int runHairWorkPrecisionCommand(const std::string& outDir, bool quick, std::ostream& out, std::ostream& err) {
    const std::string command = "hair-work-precision";
    const HairWorkPrecisionOptions options = quick ? HairWorkPrecisionOptions::quick() : HairWorkPrecisionOptions{};
    return runHairStudyCommand(
        command, "cells", outDir, err,
        [&](const Progress& progress) { return runHairWorkPrecision(options, progress); },
        [&](const std::vector<HairWorkPrecisionRow>& rows) {
            reportWritten(out, command, writeHairWorkPrecision(rows, options, outDir));
        });
}

int runHairStabilityCommand(const std::string& outDir, bool quick, std::ostream& out, std::ostream& err) {
    const std::string command = "hair-stability";
    const HairStabilityOptions options = quick ? HairStabilityOptions::quick() : HairStabilityOptions{};
    return runHairStudyCommand(
        command, "runs", outDir, err, [&](const Progress& progress) { return runHairStability(options, progress); },
        [&](const std::vector<HairStabilityRow>& rows) {
            printHairStabilityLimits(rows, command, out);
            reportWritten(out, command, writeHairStability(rows, options, outDir));
        });
}

} // namespace lab
