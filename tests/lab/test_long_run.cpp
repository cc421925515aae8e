// The long-run energy study on horizons short enough for a unit test (the whole file: about a second with -O2):
// its window and CSV contract, its validation, and what theory fixes about each method's energy over time:
// bounded for the symplectic ones, growth with the sign of |R(ix)|^2 - 1 for euler, trapezoid and rk4 (at the
// rate linear theory gives, at a small amplitude), and the leapfrog midpoint's late parasitic growth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "lab/long_run.h"

#include "../temp_dir.h"
#include "lab_run.h"

namespace {

using physics::Method;
constexpr double kPi = std::numbers::pi;

using lab_test::lines;

std::vector<std::string> cells(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string f; std::getline(in, f, ',');) out.push_back(f);
    return out;
}

std::filesystem::path freshDir(const std::string& what) {
    return test_util::freshRandomTempDir("mc_long_run_test_", what);
}

lab::LongRunOptions one(Method method, double dt, double seconds, double theta0Deg = 60.0) {
    lab::LongRunOptions o;
    o.methods = {method};
    o.dts = {dt};
    o.seconds = seconds;
    o.theta0Deg = theta0Deg;
    return o;
}

// Runs one method at one step and checks the precondition every behavioural test needs: a point per window,
// in order, every one finite (nothing blew up).
std::vector<lab::LongRunPoint> runFinite(const lab::LongRunOptions& o) {
    std::vector<lab::LongRunPoint> points = lab::runLongRun(o); // not const: returned by move
    const std::vector<double> ends = lab::longRunWindowEnds(o);
    EXPECT_EQ(points.size(), ends.size());
    for (std::size_t i = 0; i < points.size() && i < ends.size(); ++i) {
        EXPECT_EQ(points[i].windowEnd, ends[i]);
        EXPECT_TRUE(std::isfinite(points[i].maxEnergyError)) << "window ending " << ends[i] << " s";
        EXPECT_GT(points[i].maxEnergyError, 0.0) << "window ending " << ends[i] << " s";
        EXPECT_EQ(std::fabs(points[i].signedEnergyError), points[i].maxEnergyError);
    }
    return points;
}

// Energy measured from the bottom, in m g L, of a pendulum released from rest at theta0: the quadratic form
// whose growth factor per step linear theory gives as |R(i omega0 dt)|^2.
double oscillationEnergy(double theta0Deg) { return 1.0 - std::cos(theta0Deg * kPi / 180.0); }

// ---------------------------------------------------------------------------------------------------
// Contract.

TEST(LongRun, WindowEndsAreLogSpacedFromTheFirstToTheHorizon) {
    const lab::LongRunOptions defaults;
    const std::vector<double> ends = lab::longRunWindowEnds(defaults);
    ASSERT_EQ(ends.size(), 19u); // 4 per decade over log10(20000) = 4.3 decades: 18 after the first
    EXPECT_EQ(ends.front(), 1.0);
    EXPECT_EQ(ends.back(), 20000.0);
    const double ratio = std::pow(20000.0, 1.0 / 18.0);
    for (std::size_t i = 1; i < ends.size(); ++i) EXPECT_NEAR(ends[i] / ends[i - 1], ratio, 1e-12) << i;

    lab::LongRunOptions o;
    o.seconds = 1000.0;
    o.windowsPerDecade = 1;
    const std::vector<double> decades = lab::longRunWindowEnds(o);
    ASSERT_EQ(decades.size(), 4u); // exactly three decades: no extra window for rounding
    for (std::size_t i = 0; i < decades.size(); ++i) EXPECT_NEAR(decades[i], std::pow(10.0, i), 1e-12 * decades[i]);

    o.seconds = 1.0;
    EXPECT_EQ(lab::longRunWindowEnds(o), std::vector<double>{1.0});
}

TEST(LongRun, ValidateNamesTheBadValue) {
    EXPECT_EQ(lab::validateLongRun(lab::LongRunOptions{}), "");

    auto expectRejected = [](const lab::LongRunOptions& o, const std::string& mentions) {
        const std::string why = lab::validateLongRun(o);
        EXPECT_NE(why.find(mentions), std::string::npos) << "'" << why << "' should mention '" << mentions << "'";
        EXPECT_THROW(lab::runLongRun(o), std::invalid_argument);
    };
    lab::LongRunOptions o;
    o.methods.clear();
    expectRejected(o, "no methods");
    o = {};
    o.methods = {Method::Verlet, Method::Exact};
    expectRejected(o, "exact");
    o = {};
    o.seconds = -5.0;
    expectRejected(o, "-5");
    o.seconds = 0.0;
    expectRejected(o, "seconds");
    o.seconds = std::nan("");
    expectRejected(o, "nan");
    o = {};
    o.dts = {0.05, 0.0};
    expectRejected(o, "dt");
    o.dts = {-0.25};
    expectRejected(o, "-0.25");
    o.dts.clear();
    expectRejected(o, "no steps");
    o = one(Method::Verlet, 0.005, 1e6); // 2e8 steps
    expectRejected(o, "200000000");
    EXPECT_NE(lab::validateLongRun(o).find(std::to_string(lab::kMaxSteps)), std::string::npos);
    o = one(Method::Verlet, 0.05, 10.0);
    o.firstWindowEnd = 0.03; // (0, 0.03] holds no step of 0.05 s
    expectRejected(o, "0.03");
    o.firstWindowEnd = 20.0;
    expectRejected(o, "20");
    o = {};
    o.windowsPerDecade = 0;
    expectRejected(o, "windows per decade");
}

TEST(LongRun, CsvHasTheHeaderAndOneRowPerMethodStepAndWindow) {
    lab::LongRunOptions o;
    o.methods = {Method::Euler, Method::Verlet};
    o.dts = {0.1, 0.05};
    o.seconds = 10.0;
    o.windowsPerDecade = 1; // windows (0, 1] and (1, 10]
    const auto points = lab::runLongRun(o);
    ASSERT_EQ(points.size(), 2u * 2u * 2u);
    std::ostringstream out;
    lab::writeLongRunCsv(points, out);
    const auto rows = lines(out.str());
    ASSERT_EQ(rows.size(), 1u + 8u);
    EXPECT_EQ(rows[0], "method,dt,window_end_s,max_energy_error");
    const std::vector<std::string> method = {"euler",  "euler",  "euler",  "euler",
                                             "verlet", "verlet", "verlet", "verlet"};
    const std::vector<double> dt = {0.1, 0.1, 0.05, 0.05, 0.1, 0.1, 0.05, 0.05};
    const std::vector<double> end = {1.0, 10.0, 1.0, 10.0, 1.0, 10.0, 1.0, 10.0};
    for (std::size_t i = 0; i < 8; ++i) {
        const auto c = cells(rows[i + 1]);
        ASSERT_EQ(c.size(), 4u) << rows[i + 1];
        EXPECT_EQ(c[0], method[i]);
        EXPECT_EQ(std::stod(c[1]), dt[i]); // full precision: reads back exactly
        EXPECT_EQ(std::stod(c[2]), end[i]);
        EXPECT_EQ(std::stod(c[3]), points[i].maxEnergyError);
        EXPECT_GT(points[i].maxEnergyError, 0.0);
    }
}

TEST(LongRun, ABlownUpRunIsInfinityFromItsWindowOnAndTheChartLeavesItOut) {
    // Euler at 0.05 s gains energy by a factor 1 + (omega0 dt)^2 = 1.0245 a step: over the top in seconds, past
    // 10 m g L (the default blowUpError) in the window from 31.6 to 56.2 s (measured: 7.9 m g L by 31.6 s).
    lab::LongRunOptions o = one(Method::Euler, 0.05, 1000.0);
    o.methods.push_back(Method::Verlet);
    const auto points = lab::runLongRun(o);
    const std::size_t windows = lab::longRunWindowEnds(o).size();
    ASSERT_EQ(points.size(), 2 * windows);
    std::size_t finite = 0;
    while (finite < windows && std::isfinite(points[finite].maxEnergyError)) ++finite;
    ASSERT_GT(finite, 0u);      // the first window is before the blow-up...
    ASSERT_LT(finite, windows); // ...and the blow-up happened
    for (std::size_t i = 0; i < finite; ++i) EXPECT_LE(points[i].maxEnergyError, o.blowUpError);
    for (std::size_t i = finite; i < windows; ++i) {
        EXPECT_EQ(points[i].maxEnergyError, std::numeric_limits<double>::infinity()) << i;
        EXPECT_EQ(points[i].method, Method::Euler);
    }
    for (std::size_t i = windows; i < 2 * windows; ++i) EXPECT_TRUE(std::isfinite(points[i].maxEnergyError));

    std::ostringstream out;
    lab::writeLongRunCsv(points, out);
    const auto rows = lines(out.str());
    ASSERT_EQ(rows.size(), 1 + 2 * windows);
    EXPECT_EQ(cells(rows[1 + finite])[3], "inf");
    EXPECT_EQ(cells(rows.back())[0], "verlet");

    const lab::Chart chart = lab::longRunChart(points, o);
    ASSERT_EQ(chart.panels.size(), 1u);
    const lab::Panel& panel = chart.panels[0];
    ASSERT_EQ(panel.series.size(), 2u);
    EXPECT_EQ(panel.series[0].name, "euler");
    EXPECT_EQ(panel.series[0].x.size(), finite); // nothing drawn for the windows after the blow-up
    for (double y : panel.series[0].y) EXPECT_TRUE(std::isfinite(y));
    EXPECT_EQ(panel.series[1].x.size(), windows);
    EXPECT_NE(panel.note.find("blew up"), std::string::npos) << panel.note;
    EXPECT_NE(panel.note.find("euler"), std::string::npos) << panel.note;
}

TEST(LongRun, ChartHasAPanelPerStepAndASeriesPerMethodAndBothFilesAreWritten) {
    lab::LongRunOptions o;
    o.methods = {Method::SymplecticEuler, Method::Rk4, Method::Midpoint};
    o.dts = {0.05, 0.025};
    o.seconds = 30.0;
    const auto points = lab::runLongRun(o);
    const lab::Chart chart = lab::longRunChart(points, o);
    ASSERT_EQ(chart.panels.size(), 2u);
    for (const auto& panel : chart.panels) {
        EXPECT_EQ(panel.x.scale, lab::AxisScale::Log10);
        EXPECT_EQ(panel.y.scale, lab::AxisScale::Log10);
        ASSERT_EQ(panel.series.size(), 3u);
        for (std::size_t s = 0; s < 3; ++s) {
            EXPECT_EQ(panel.series[s].name, physics::methodName(o.methods[s]));
            EXPECT_EQ(panel.series[s].colour, lab::methodColour(o.methods[s]));
            EXPECT_EQ(panel.series[s].x.size(), lab::longRunWindowEnds(o).size());
        }
        EXPECT_EQ(panel.note.find("blew up"), std::string::npos);
    }
    const auto dir = freshDir("write");
    const auto written = lab::writeLongRun(points, o, dir);
    ASSERT_EQ(written.size(), 2u);
    EXPECT_EQ(written[0], dir / "long_run.csv");
    EXPECT_EQ(written[1], dir / "long_run.svg");
    std::ifstream csv(written[0]);
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header, "method,dt,window_end_s,max_energy_error");
    std::ifstream svg(written[1]);
    const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("<svg"), std::string::npos);
    EXPECT_NE(text.find("</svg>"), std::string::npos);
    std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------------
// What theory fixes.

// Symplectic-euler and verlet conserve a modified energy within O(dt^p) forever: |E - E0| oscillates within
// each swing and never drifts, so any window longer than a swing sees the same maximum. Compared: the last of
// 20000 s (19 windows, 8500 s long) against the first window at least two periods (2.15 s at 60 degrees) long,
// 9.0 to 15.7 s. Measured at 60 degrees: symplectic-euler 3.9265e-2 against 3.9234e-2 (dt = 0.05) and 1.25082e-2
// against 1.25082e-2 (1/60); verlet 2.8105e-3 against 2.8093e-3 and 3.1224e-4 against 3.1224e-4: ratios 1.0000 to
// 1.0008. A drift would be linear in time: even one of 1 % over the first 15 s would be 1300 % by 20000 s.
TEST(LongRun, SymplecticMethodsHaveNoSecularDrift) {
    const double period = 2.0 * kPi / physics::smallAngleFrequency({}) * physics::periodRatio(60.0 * kPi / 180.0);
    for (const Method m : {Method::SymplecticEuler, Method::Verlet}) {
        for (const double dt : {0.05, 1.0 / 60.0}) {
            SCOPED_TRACE(std::string(physics::methodName(m)) + " at dt = " + std::to_string(dt));
            const lab::LongRunOptions o = one(m, dt, 20000.0);
            const auto points = runFinite(o);
            ASSERT_EQ(points.size(), 19u);
            std::size_t early = 1;
            while (early < points.size() && points[early].windowEnd - points[early - 1].windowEnd < 2.0 * period)
                ++early;
            ASSERT_LT(points[early].windowEnd, 20.0); // an early window
            const double ratio = points.back().maxEnergyError / points[early].maxEnergyError;
            EXPECT_LT(ratio, 1.5);
            EXPECT_GT(ratio, 1.0 / 1.5);
        }
    }
}

// Euler's step map on the linearised pendulum has |R(ix)|^2 = 1 + x^2 and Heun's (trapezoid) 1 + x^4 / 4: both
// above 1, so both gain energy, in every window and more in each window than in the last. Measured at 60 degrees:
// euler at 0.005 s from 2.1e-2 (first second) to 2.6 (window ending at 100 s, 124 times more); trapezoid at
// 0.05 s from 1.16e-3 to 0.74 (ending at 500 s, 641 times). Required besides: ten times the first window's.
TEST(LongRun, EulerAndTrapezoidGainEnergyWindowAfterWindow) {
    for (const auto& o : {one(Method::Euler, 0.005, 100.0), one(Method::Trapezoid, 0.05, 500.0)}) {
        SCOPED_TRACE(std::string(physics::methodName(o.methods[0])));
        const auto points = runFinite(o);
        ASSERT_GE(points.size(), 9u);
        for (std::size_t i = 0; i < points.size(); ++i) {
            EXPECT_GT(points[i].signedEnergyError, 0.0) << "window ending " << points[i].windowEnd;
            if (i > 0) {
                EXPECT_GT(points[i].maxEnergyError, points[i - 1].maxEnergyError) << points[i].windowEnd;
            }
        }
        EXPECT_GT(points.back().maxEnergyError, 10.0 * points.front().maxEnergyError);
    }
}

// rk4: |R(ix)|^2 = 1 - x^6 / 72 < 1, so it loses energy, and as slowly as that says: the loss is linear in time
// (x^6 / 72 a step, compounding negligibly), so max |E - E0| / t is the same in every window once the drift
// dominates the bounded part. Measured at 60 degrees, dt = 0.05: E - E0 < 0 in every window, |E - E0| / t between
// 1.430e-6 and 1.436e-6 per second in the windows from 132 to 2000 s (the first windows, shorter than a swing or
// two, from 1.37e-6 to 1.96e-6). Allowed: 0.8 to 1.25 times the last window's from 100 s on.
TEST(LongRun, Rk4LosesEnergyLinearlyInTime) {
    const auto points = runFinite(one(Method::Rk4, 0.05, 2000.0));
    ASSERT_EQ(points.size(), 15u);
    const double lastRate = points.back().maxEnergyError / points.back().windowEnd;
    for (const auto& p : points) {
        EXPECT_LT(p.signedEnergyError, 0.0) << "window ending " << p.windowEnd;
        if (p.windowEnd < 100.0) continue;
        const double rate = p.maxEnergyError / p.windowEnd;
        EXPECT_GT(rate, 0.8 * lastRate) << "window ending " << p.windowEnd;
        EXPECT_LT(rate, 1.25 * lastRate) << "window ending " << p.windowEnd;
    }
}

// At 10 degrees the pendulum is linear to about 1 % (frequency shift theta0^2 / 16 = 0.2 %, to the sixth power
// for rk4), so the energy measured from the bottom, E_osc, changes by |R(ix)|^2 per step, x = omega0 dt:
// rk4 |E - E0| = E_osc x^6 / 72 t / dt, trapezoid E_osc ((1 + x^4 / 4)^(t / dt) - 1), euler E_osc ((1 + x^2)^(t /
// dt) - 1). Measured against these: rk4 0.981 to 0.985 (dt = 0.05, 10 to 2000 s), trapezoid 0.979 to 0.991
// (0.05, 10 to 300 s), euler 0.980 to 0.995 (0.005, 1 to 30 s), the ratio falling slowly as the amplitude (and
// with it the nonlinearity) changes. Allowed: 10 %.
TEST(LongRun, DriftRatesMatchLinearTheoryAtSmallAmplitude) {
    const double theta0 = 10.0;
    const double eOsc = oscillationEnergy(theta0);
    const double omega0 = physics::smallAngleFrequency({});
    struct Case {
        Method method;
        double dt;
        double seconds;
        double fromTime; // windows before this are dominated by the bounded oscillation of E
    };
    for (const Case c : {Case{Method::Rk4, 0.05, 2000.0, 10.0}, Case{Method::Trapezoid, 0.05, 300.0, 10.0},
                         Case{Method::Euler, 0.005, 30.0, 1.0}}) {
        SCOPED_TRACE(std::string(physics::methodName(c.method)));
        lab::LongRunOptions o = one(c.method, c.dt, c.seconds, theta0);
        o.firstWindowEnd = c.fromTime;
        const auto points = runFinite(o);
        ASSERT_GE(points.size(), 4u);
        const double x = omega0 * c.dt;
        for (const auto& p : points) {
            const double steps = std::floor(p.windowEnd / c.dt + 1e-9); // the window's last step
            double theory = 0.0;
            if (c.method == Method::Rk4) theory = eOsc * std::pow(x, 6) / 72.0 * steps;
            if (c.method == Method::Trapezoid) theory = eOsc * std::expm1(steps * std::log1p(std::pow(x, 4) / 4.0));
            if (c.method == Method::Euler) theory = eOsc * std::expm1(steps * std::log1p(x * x));
            const double ratio = p.maxEnergyError / theory;
            EXPECT_GT(ratio, 0.9) << "window ending " << p.windowEnd;
            EXPECT_LT(ratio, 1.1) << "window ending " << p.windowEnd;
            EXPECT_EQ(p.signedEnergyError > 0.0, c.method != Method::Rk4) << "window ending " << p.windowEnd;
        }
    }
}

// The leapfrog midpoint is second order like verlet and, like it, keeps the energy error flat at first (1.1e-3 at
// 0.05 s up to 50 s), but its parasitic mode (the root near -1 of its two-step map) is not damped on the nonlinear
// pendulum: the error then grows about linearly, to 0.175 by 20000 s (157 times the early level; 1.16e-2 by
// 1277 s, so a 2000 s horizon would show only about 15 times). Required: growth window after window from 500 s
// on, and 20 times the early level by the end. 400,000 steps: about 20 ms.
TEST(LongRun, MidpointParasiticModeGrowsOverALongRun) {
    const auto points = runFinite(one(Method::Midpoint, 0.05, 20000.0));
    ASSERT_EQ(points.size(), 19u);
    double early = 0.0;
    for (const auto& p : points)
        if (p.windowEnd <= 30.0) early = std::max(early, p.maxEnergyError);
    ASSERT_GT(early, 0.0);
    EXPECT_GT(points.back().maxEnergyError, 20.0 * early);
    for (std::size_t i = 1; i < points.size(); ++i) {
        if (points[i - 1].windowEnd < 500.0) continue;
        EXPECT_GT(points[i].maxEnergyError, points[i - 1].maxEnergyError) << "window ending " << points[i].windowEnd;
    }
}

} // namespace
