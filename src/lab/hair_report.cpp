#include "lab/hair_report.h"

#include "lab/hair_chain.h"
#include "lab/hair_study.h"
#include "lab/lab_util.h"
#include "physics/hair.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace lab {

namespace {

std::string g3(double v) { return formatNumber("%.3g", v); }
std::string f2(double v) { return formatNumber("%.2f", v); }
std::string withSign(double v) { return formatNumber("%+.3g", v); }

struct ChainFigures {
    double worstTip = 0.0, worstSegment = 0.0, worstEnergy = 0.0;
    double finalEnergy = 0.0; // (E - E0) / (M g L) at T, signed: a gain or a loss
};

// The largest tip, segment and |energy| errors over [0, T] of one run at the method's game defaults.
ChainFigures chainFigures(const std::string& solver, double dt, double T) {
    HairChainOptions o;
    o.solver = solver;
    o.dt = dt;
    o.seconds = T;
    ChainFigures f;
    for (const HairChainRow& r : runHairChain(o)) {
        if (r.t > T + 1e-9) break;
        f.worstTip = std::max(f.worstTip, r.tipError);
        f.worstSegment = std::max(f.worstSegment, r.maxSegmentError);
        f.worstEnergy = std::max(f.worstEnergy, std::abs(r.energyError));
        f.finalEnergy = r.energyError;
    }
    return f;
}

} // namespace

std::string hairReportMarkdown() {
    std::string md;
    md += "Every method at the game's settings for it, on the 11-link chain released horizontally (0.45 m, no "
          "damping, no collider) against its exact solution: the largest tip error over the first 0.5 s as the "
          "step halves, the order that gives, the largest segment error, and the energy gained (+) or lost (-) by "
          "2 s at 1/60 and 1/240 s, (E - E0) / (M g L).\n\n";
    md += "| method | passes a step | tip error, 1/120 s | 1/240 s | 1/480 s | order | segment error | energy by 2 s, "
          "1/60 s | 1/240 s |\n";
    md += "|---|---|---|---|---|---|---|---|---|\n";
    for (int m = 0; m < physics::kHairMethodCount; ++m) {
        const auto method = static_cast<physics::HairMethod>(m);
        const std::string name(physics::hairMethodName(method));
        const ChainFigures a = chainFigures(name, 1.0 / 120.0, 0.5), b = chainFigures(name, 1.0 / 240.0, 0.5),
                           c = chainFigures(name, 1.0 / 480.0, 0.5), e = chainFigures(name, 1.0 / 60.0, 2.0),
                           e240 = chainFigures(name, 1.0 / 240.0, 2.0);
        const double order = 0.5 * std::log2(a.worstTip / c.worstTip);
        const double segment =
            std::max({a.worstSegment, b.worstSegment, c.worstSegment, e.worstSegment, e240.worstSegment});
        md += "| " + name + " | " +
              std::to_string(physics::hairProjectionsPerNode(physics::hairMethodDefaults(method))) + " | " +
              g3(a.worstTip) + " m | " + g3(b.worstTip) + " m | " + g3(c.worstTip) + " m | " + f2(order) + " | " +
              g3(segment) + " | " + withSign(e.finalEnergy) + " | " + withSign(e240.finalEnergy) + " |\n";
    }
    md += "\n`hair-check` for the default (dftl), at the ticks of 30, 60 and 144 Hz: the worst over spin, carry, a "
          "0.25 s frame spike and a drop onto blocks, then the seconds until the hair is at rest after the drop and "
          "for a new ball resting on the blocks.\n\n";
    md += "| tick | max segment error | max penetration | NaN | settle after the drop | new ball on blocks |\n";
    md += "|---|---|---|---|---|---|\n";
    for (const int hz : {30, 60, 144}) {
        HairCheckOptions o;
        o.dt = 1.0 / hz;
        const HairCheckResult r = runHairCheck(o);
        md += "| 1/" + std::to_string(hz) + " s | " + g3(r.maxSegmentError) + " | " + g3(r.maxPenetration) + " m | " +
              (r.nan ? "yes" : "no") + " | " + g3(r.settleSeconds) + " s | " + g3(r.restSettleSeconds) + " s |\n";
    }
    return md;
}

} // namespace lab
