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
        // Half a step of slack: the rows' times are floats (the row of 2 s at 1/60 s reads 2.0000001).
        if (r.t > T + 0.5 * dt) break;
        f.worstTip = std::max(f.worstTip, r.tipError);
        f.worstSegment = std::max(f.worstSegment, r.maxSegmentError);
        f.worstEnergy = std::max(f.worstEnergy, std::abs(r.energyError));
        f.finalEnergy = r.energyError;
    }
    return f;
}

// The method table: every method on the chain, tip errors within the horizon, segment and energy errors.
std::string methodTable() {
    std::string md;
    md += "Every method at the game's settings for it, on the 11-link chain released horizontally (0.45 m, no "
          "damping, no collider) against its exact solution: the largest tip error over the first 0.5 s at the "
          "game's tick and as the step halves, the order that gives (from 1/120 to 1/480 s), the largest segment "
          "error (at 1/60 s and below), and the energy gained (+) or lost (-) by 2 s at 1/30, 1/60 and 1/240 s, (E - "
          "E0) / (M g "
          "L). Flags: each cell is one `minecrappy-lab hair-chain --solver NAME --dt S --seconds T --csv FILE` "
          "(its defaults: 11 links, 0.45 m, the method's iterations and substeps); a tip error is the largest "
          "`tip_error` of `--seconds 0.5`, the segment error the largest `max_segment_error`, an energy the last "
          "`energy_error` of `--seconds 2`.\n\n";
    md += "| method | passes a step | tip error, 1/60 s | 1/120 s | 1/240 s | 1/480 s | order | segment error | energy "
          "by 2 s, 1/30 s | 1/60 s | 1/240 s |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (int m = 0; m < physics::kHairMethodCount; ++m) {
        const auto method = static_cast<physics::HairMethod>(m);
        const std::string name(physics::hairMethodName(method));
        const ChainFigures tick = chainFigures(name, 1.0 / 60.0, 0.5), a = chainFigures(name, 1.0 / 120.0, 0.5),
                           b = chainFigures(name, 1.0 / 240.0, 0.5), c = chainFigures(name, 1.0 / 480.0, 0.5),
                           e30 = chainFigures(name, 1.0 / 30.0, 2.0), e = chainFigures(name, 1.0 / 60.0, 2.0),
                           e240 = chainFigures(name, 1.0 / 240.0, 2.0);
        const double order = 0.5 * std::log2(a.worstTip / c.worstTip);
        const double segment = std::max(
            {tick.worstSegment, a.worstSegment, b.worstSegment, c.worstSegment, e.worstSegment, e240.worstSegment});
        md += "| " + name + " | " +
              std::to_string(physics::hairProjectionsPerNode(physics::hairMethodDefaults(method))) + " | " +
              g3(tick.worstTip) + " m | " + g3(a.worstTip) + " m | " + g3(b.worstTip) + " m | " + g3(c.worstTip) +
              " m | " + f2(order) + " | " + g3(segment) + " | " + withSign(e30.finalEnergy) + " | " +
              withSign(e.finalEnergy) + " | " + withSign(e240.finalEnergy) + " |\n";
    }
    return md;
}

// shake against dftl as the game runs them, at 1/60 s with automatic substeps.
std::string gameTickLine() {
    std::string md;
    {
        // The game runs every method with automatic substeps; only shake's differ at 1/60 s (its turn-chosen
        // substeps), so the table's 1/60 s column is the game's for the others.
        HairChainOptions o;
        o.automaticSubsteps = true;
        o.seconds = 0.5;
        const auto worst = [&](const std::string& solver) {
            o.solver = solver;
            double w = 0.0;
            for (const HairChainRow& r : runHairChain(o)) w = std::max(w, r.tipError);
            return w;
        };
        const double shake = worst("shake"), dftl = worst("dftl");
        md += "\nAs the game runs them at 1/60 s, with automatic substeps (shake's chosen so that no segment turns "
              "more than 10 degrees in one): tip error over the first 0.5 s, shake " +
              g3(shake) + " m, dftl " + g3(dftl) + " m (" + g3(dftl / shake) +
              " times closer; the largest `tip_error` of `hair-chain --solver NAME --auto-substeps --seconds 0.5`).\n";
    }
    return md;
}

std::string settled(double seconds) { return seconds > 0.0 ? g3(seconds) + " s" : std::string("no"); }

// hair-check at the game's tick rates: the default's figures, its drop distribution, every solver's settles.
std::string hairCheckTables() {
    std::string md;
    const int rates[] = {30, 60, 144, 240};
    md += "\n`hair-check` for the default (dftl), at the ticks of 30, 60, 144 and 240 Hz: the worst over spin, carry, "
          "a 0.25 s frame spike and a drop onto blocks, then the seconds until the hair is at rest after the drop and "
          "for a new ball resting on the blocks. Flags: `minecrappy-lab hair-check --dt S` (each phase `--seconds "
          "2`).\n\n";
    md += "| tick | max segment error | max penetration | NaN | settle after the drop | new ball on blocks |\n";
    md += "|---|---|---|---|---|---|\n";
    for (const int hz : rates) {
        HairCheckOptions o;
        o.dt = 1.0 / hz;
        const HairCheckResult r = runHairCheck(o);
        md += "| 1/" + std::to_string(hz) + " s | " + g3(r.maxSegmentError) + " | " + g3(r.maxPenetration) + " m | " +
              (r.nan ? "yes" : "no") + " | " + settled(r.settleSeconds) + " | " + settled(r.restSettleSeconds) + " |\n";
    }
    md += "\nThe settle time after the drop is one sample of a chaotic motion; over 20 runs whose spin axes differ "
          "by about 0.1 mrad (`lab::hairDropSettles`, run by `minecrappy-lab hair-report` only), the default's median "
          "and range:\n\n| tick | median | range | not within 30 s |\n|---|---|---|---|\n";
    for (const int hz : rates) {
        HairCheckOptions o;
        o.dt = 1.0 / hz;
        const HairDropSettles d = hairDropSettles(o, 20);
        md += "| 1/" + std::to_string(hz) + " s | " + g3(d.median) + " s | " + g3(d.min) + " - " + g3(d.max) + " s | " +
              std::to_string(d.unsettled) + " |\n";
    }
    md += "\nThe same for every solver at its game settings: seconds until the hair sleeps after the drop / for a new "
          "ball on the blocks (no: not within 30 s). Flags: `minecrappy-lab hair-check --solver NAME --dt S`.\n\n| "
          "solver |";
    for (const int hz : rates) md += " 1/" + std::to_string(hz) + " s |";
    md += "\n|---|---|---|---|---|\n";
    for (int m = 0; m < physics::kHairMethodCount; ++m) {
        const std::string name(physics::hairMethodName(static_cast<physics::HairMethod>(m)));
        md += "| " + name + " |";
        for (const int hz : rates) {
            HairCheckOptions o;
            o.solver = name;
            o.dt = 1.0 / hz;
            const HairCheckResult r = runHairCheck(o);
            md += ' ' + settled(r.settleSeconds) + " / " + settled(r.restSettleSeconds) + " |";
        }
        md += "\n";
    }
    return md;
}

std::string when(double seconds) { return std::isnan(seconds) ? std::string("no") : g3(seconds) + " s"; }

// The horizon table; returns the first chain's horizon (the lab's 11-link chain) through `horizon`.
std::string horizonTable(double& horizon) {
    std::string md;
    md += "\nHow far the released chains can be predicted: the time at which two exact chains started 1e-9 rad apart "
          "have tips 1 mm apart (past it the motion is chaotic, and a tip error compares nothing), and the time to "
          "which the reference is exact: where it and a second integrator (classic Runge-Kutta 4 at a fixed 2.5 us "
          "step on the tension equations) first have tips 1 um apart, with their largest distance before the "
          "horizon (no: not within 4 s). Flags: none; `lab::chainHorizon` over 4 s, run by `minecrappy-lab "
          "hair-report` and checked by the `ChainHorizon.*` tests.\n\n";
    md += "| chain | horizon | reference exact to | reference against the second integrator, before the horizon |\n";
    md += "|---|---|---|---|\n";
    bool first = true;
    for (const auto& [links, length] : {std::pair{11, 0.45}, std::pair{11, 0.2}, std::pair{20, 0.45}}) {
        ChainParams chain;
        chain.links = links;
        chain.length = length;
        const ChainHorizon h = chainHorizon(chain, 4.0);
        if (first) horizon = h.horizon;
        first = false;
        md += "| " + std::to_string(links) + " links, " + g3(length) + " m | " + when(h.horizon) + " | " +
              when(h.exactTo) + " | " + g3(h.maxAgreementBefore) + " m |\n";
    }
    return md;
}

// Past the horizon: what the eye sees of every method as the game runs it, against the reference.
std::string lookTable(double horizon, double until) {
    const auto period = [](double s) { return std::isnan(s) ? std::string("none") : g3(s) + " s"; };
    std::string md = "\nPast the horizon only what the eye sees compares: over " + g3(horizon) + " to " + g3(until) +
                     " s on the 11-link chain, every method as the game runs it (1/60 s, automatic substeps) against "
                     "the reference: the mean energy, (E - E0) / (M g L), the tip's mean height (hanging at rest: "
                     "-0.45 m) and the swing period (the tip's crossings of the vertical through the root, counted "
                     "once it swings 1 cm past it; none: at rest). Flags: the rows from " +
                     g3(horizon) + " s of `minecrappy-lab hair-chain --solver NAME --auto-substeps --seconds " +
                     g3(until) + "`, and of `--solver reference` for the reference.\n\n";
    md += "| method | energy | tip's mean height | swing period |\n|---|---|---|---|\n";
    HairChainOptions o;
    o.automaticSubsteps = true;
    o.seconds = until;
    ChainLook reference;
    for (int m = 0; m < physics::kHairMethodCount; ++m) {
        o.solver = physics::hairMethodName(static_cast<physics::HairMethod>(m));
        const ChainLook look = chainLook(runHairChain(o), horizon, until);
        md += "| " + o.solver + " | " + withSign(look.energy) + " | " + g3(look.meanTipHeight) + " m | " +
              period(look.swingPeriod) + " |\n";
        reference = look;
    }
    md += "| reference | 0 | " + g3(reference.refMeanTipHeight) + " m | " + period(reference.refSwingPeriod) + " |\n";
    return md;
}

} // namespace

std::string hairReportMarkdown() {
    double horizon = 0.0;
    std::string md = methodTable() + gameTickLine() + hairCheckTables() + horizonTable(horizon);
    md += lookTable(horizon, 10.0);
    return md;
}

} // namespace lab
