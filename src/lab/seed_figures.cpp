#include "lab/seed_figures.h"

#include "lab/lab_util.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace lab {

using detail::degToRad;
using detail::mgl;
using detail::name;
using physics::Method;

namespace {

constexpr double kPi = std::numbers::pi;

} // namespace

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
