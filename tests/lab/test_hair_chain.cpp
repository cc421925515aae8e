// The exact reference for hair (the N-link chain), the integrator under it, and the hair-chain command:
// Dormand-Prince against closed forms and at its order; the chain against the closed-form pendulum, its own
// energy and a second, independently derived form of its equations; then every hair method against the chain,
// held to what theory says each one can do.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "lab/hair_chain.h"
#include "lab/hair_charts.h"
#include "lab/ode.h"
#include "lab_run.h"
#include "physics/hair.h"
#include "physics/pendulum.h"

namespace {

using lab::ChainEquations;
using lab::ChainReference;
using lab::DormandPrince;
using lab_test::runLab;

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------------
// Dormand-Prince 5(4)

TEST(DormandPrince, ExponentialDecayMatchesTheClosedForm) {
    DormandPrince ode([](double, std::span<const double> y, std::span<double> f) { f[0] = -y[0]; }, 0.0, {1.0});
    for (const double t : {0.1, 1.0, 3.0, 10.0}) {
        ode.advanceTo(t);
        EXPECT_EQ(ode.time(), t); // lands on the output time exactly
        EXPECT_NEAR(ode.state()[0], std::exp(-t), 1e-10) << "t = " << t;
    }
    const auto& c = ode.counters();
    EXPECT_GT(c.accepted, 0);
    // One evaluation at the start, one for the starting-step estimate, then six an attempted step (FSAL).
    EXPECT_EQ(c.evaluations, 2 + 6 * (c.accepted + c.rejected));
}

TEST(DormandPrince, HarmonicOscillatorMatchesTheClosedForm) {
    const double w = 2.0;
    DormandPrince ode(
        [w](double, std::span<const double> y, std::span<double> f) {
            f[0] = y[1];
            f[1] = -w * w * y[0];
        },
        0.0, {1.0, 0.0});
    for (const double t : {0.25, 1.0, 2.5, 5.0, 10.0}) {
        ode.advanceTo(t);
        EXPECT_NEAR(ode.state()[0], std::cos(w * t), 1e-10) << "t = " << t;
        EXPECT_NEAR(ode.state()[1], -w * std::sin(w * t), 1e-10) << "t = " << t;
    }
}

TEST(DormandPrince, FixedStepsConvergeAtOrderFive) {
    const auto errorWith = [](int steps) {
        DormandPrince ode(
            [](double, std::span<const double> y, std::span<double> f) {
                f[0] = y[1];
                f[1] = -4.0 * y[0];
            },
            0.0, {1.0, 0.0});
        for (int i = 0; i < steps; ++i) ode.fixedStep(2.0 / steps);
        return std::hypot(ode.state()[0] - std::cos(4.0), ode.state()[1] + 2.0 * std::sin(4.0));
    };
    const double e20 = errorWith(20), e40 = errorWith(40), e80 = errorWith(80);
    EXPECT_NEAR(std::log2(e20 / e40), 5.0, 0.3);
    EXPECT_NEAR(std::log2(e40 / e80), 5.0, 0.3);
}

TEST(DormandPrince, RefusesWhatItCannotDo) {
    const auto decay = [](double, std::span<const double> y, std::span<double> f) { f[0] = -y[0]; };
    DormandPrince ode(decay, 0.0, {1.0});
    ode.advanceTo(0.5);
    EXPECT_THROW(ode.advanceTo(0.25), std::invalid_argument); // backwards
    EXPECT_NO_THROW(ode.advanceTo(0.5));                      // no-op
    lab::OdeOptions few;
    few.maxSteps = 3;
    DormandPrince limited(decay, 0.0, {1.0}, few);
    EXPECT_THROW(limited.advanceTo(1000.0), std::runtime_error);
    EXPECT_THROW(DormandPrince(decay, 0.0, {}), std::invalid_argument);
    lab::OdeOptions bad;
    bad.relTol = 0.0;
    EXPECT_THROW(DormandPrince(decay, 0.0, {1.0}, bad), std::invalid_argument);
    // A right-hand side that turns non-finite: the step shrinks until it underflows, then it throws.
    DormandPrince blowUp([](double t, std::span<const double>, std::span<double> f) { f[0] = t < 0.5 ? 1.0 : NAN; },
                         0.0, {0.0});
    EXPECT_THROW(blowUp.advanceTo(1.0), std::runtime_error);
}

// ---------------------------------------------------------------------------------------------------
// The chain

TEST(ChainReference, OneLinkIsTheExactPendulum) {
    const double L = 0.45, g = 9.81;
    const physics::ExactPendulum exact({L, g, 1.0, 0.0}, {kPi / 2.0, 0.0});
    for (const ChainEquations eq : {ChainEquations::MassMatrix, ChainEquations::Tensions}) {
        const std::vector<double> theta{kPi / 2.0}, omega{0.0};
        ChainReference chain({1, L, g, 1.0}, theta, omega, {}, eq);
        for (const double t : {0.1, 0.37, 0.8, 1.3, 2.0}) {
            chain.advanceTo(t);
            const physics::PendulumState s = exact.at(t);
            EXPECT_NEAR(chain.theta()[0], s.theta, 1e-10) << "t = " << t;
            EXPECT_NEAR(chain.omega()[0], s.omega, 1e-10) << "t = " << t;
            EXPECT_NEAR(chain.tip().x, L * std::sin(s.theta), 1e-10) << "t = " << t;
            EXPECT_NEAR(chain.tip().y, -L * std::cos(s.theta), 1e-10) << "t = " << t; // y up
        }
    }
}

TEST(ChainReference, ElevenLinksConserveEnergy) {
    const int n = 11;
    const double L = 0.45, g = 9.81, mass = 1.0;
    for (const ChainEquations eq : {ChainEquations::MassMatrix, ChainEquations::Tensions}) {
        const std::vector<double> theta(n, kPi / 2.0), omega(n, 0.0);
        ChainReference chain({n, L, g, mass}, theta, omega, {}, eq);
        EXPECT_NEAR(chain.energy(), 0.0, 1e-15); // horizontal, at rest, at the root's height
        double worst = 0.0;
        for (int i = 1; i <= 120; ++i) {
            chain.advanceTo(i / 60.0);
            worst = std::max(worst, std::abs(chain.energy()) / (mass * g * L));
        }
        EXPECT_LT(worst, 1e-10);
        // It did fall: the tip is well below the root after 2 s.
        EXPECT_LT(chain.tip().y, -0.1);
    }
}

TEST(ChainReference, TensionFormEqualsTheMassMatrixForm) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (const int n : {1, 2, 5, 11, 64}) {
        std::vector<double> theta(static_cast<std::size_t>(n)), omega(theta.size());
        for (int trial = 0; trial < 10; ++trial) {
            for (std::size_t i = 0; i < theta.size(); ++i) {
                theta[i] = u(rng);
                omega[i] = 3.0 * u(rng);
            }
            const ChainReference a({n, 0.45, 9.81, 1.0}, theta, omega, {}, ChainEquations::MassMatrix);
            const ChainReference b({n, 0.45, 9.81, 1.0}, theta, omega, {}, ChainEquations::Tensions);
            std::vector<double> y(theta);
            y.insert(y.end(), omega.begin(), omega.end());
            std::vector<double> fa(y.size()), fb(y.size());
            a.derivatives(y, fa);
            b.derivatives(y, fb);
            double scale = 0.0;
            for (const double v : fa) scale = std::max(scale, std::abs(v));
            for (std::size_t i = 0; i < y.size(); ++i)
                EXPECT_NEAR(fa[i], fb[i], 1e-12 * scale) << n << " links, component " << i;
        }
    }
    // And the motions agree (11 links for 1 s; the chain is chaotic, so not for long at many links).
    const std::vector<double> theta(11, kPi / 2.0), omega(11, 0.0);
    ChainReference a({11, 0.45, 9.81, 1.0}, theta, omega, {}, ChainEquations::MassMatrix);
    ChainReference b({11, 0.45, 9.81, 1.0}, theta, omega, {}, ChainEquations::Tensions);
    a.advanceTo(1.0);
    b.advanceTo(1.0);
    EXPECT_NEAR(a.tip().x, b.tip().x, 1e-9);
    EXPECT_NEAR(a.tip().y, b.tip().y, 1e-9);
}

TEST(ChainReference, RefusesBadInput) {
    const std::vector<double> one{0.0}, two{0.0, 0.0};
    EXPECT_THROW(ChainReference({0, 0.45, 9.81, 1.0}, {}, {}), std::invalid_argument);
    EXPECT_THROW(ChainReference({65, 0.45, 9.81, 1.0}, std::vector<double>(65), std::vector<double>(65)),
                 std::invalid_argument);
    EXPECT_THROW(ChainReference({2, 0.45, 9.81, 1.0}, one, two), std::invalid_argument);
    EXPECT_THROW(ChainReference({1, -1.0, 9.81, 1.0}, one, one), std::invalid_argument);
    const std::vector<double> nan{NAN};
    EXPECT_THROW(ChainReference({1, 0.45, 9.81, 1.0}, nan, one), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// The study with the reference in place of the solver, validation and the command

TEST(HairChain, ReferenceSolverHasNoErrorAndConservesEnergy) {
    lab::HairChainOptions o;
    o.solver = "reference";
    const auto rows = lab::runHairChain(o);
    ASSERT_EQ(rows.size(), 121u); // t = 0 and 120 steps of 1/60 s
    EXPECT_EQ(rows[0].t, 0.0);
    EXPECT_NEAR(rows[0].tipX, o.length, 1e-15); // released horizontal along +x
    EXPECT_NEAR(rows[0].tipY, 0.0, 1e-15);
    // (With --solver reference the simulated columns are the reference's by construction: what can fail here
    // is the reference itself.)
    for (const auto& r : rows) EXPECT_LT(std::abs(r.energyError), 1e-10) << "t = " << r.t;
    EXPECT_NEAR(rows.back().t, 2.0, 1e-6);
    EXPECT_LT(rows.back().refTipY, -0.1); // it fell
}

TEST(HairChain, TipErrorAtPicksTheNearestRow) {
    std::vector<lab::HairChainRow> rows(4);
    for (int i = 0; i < 4; ++i) {
        rows[static_cast<std::size_t>(i)].t = 0.1 * i;
        rows[static_cast<std::size_t>(i)].tipError = 10.0 + i;
    }
    EXPECT_EQ(lab::chainTipErrorAt(rows, -5.0), 10.0);
    EXPECT_EQ(lab::chainTipErrorAt(rows, 0.14), 11.0);
    EXPECT_EQ(lab::chainTipErrorAt(rows, 0.16), 12.0);
    EXPECT_EQ(lab::chainTipErrorAt(rows, 9.0), 13.0);
    EXPECT_TRUE(std::isnan(lab::chainTipErrorAt({}, 0.0)));
}

TEST(HairChain, CsvHasTheHeaderAndOneLinePerRow) {
    lab::HairChainOptions o;
    o.solver = "reference";
    o.links = 3;
    o.seconds = 0.1;
    o.dt = 0.02;
    const auto rows = lab::runHairChain(o);
    std::ostringstream s;
    lab::writeHairChainCsv(rows, s);
    std::istringstream in(s.str());
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "t,tip_x,tip_y,ref_tip_x,ref_tip_y,tip_error,max_segment_error,energy_error");
    std::size_t count = 0;
    while (std::getline(in, line)) {
        ++count;
        EXPECT_EQ(std::count(line.begin(), line.end(), ','), 7) << line;
    }
    EXPECT_EQ(count, rows.size());
    EXPECT_EQ(count, 6u);
}

TEST(HairChain, ValidationNamesTheFlagAndTheValue) {
    const auto why = [](auto change) {
        lab::HairChainOptions o;
        change(o);
        return lab::validateHairChain(o);
    };
    EXPECT_EQ(why([](lab::HairChainOptions&) {}), "");
    EXPECT_EQ(why([](lab::HairChainOptions& o) { o.solver = "reference"; }), "");
    for (const std::string name : {"ftl", "dftl", "pbd", "xpbd-substeps", "shake"})
        EXPECT_EQ(why([&](lab::HairChainOptions& o) { o.solver = name; }), "") << name;
    const std::string links = why([](lab::HairChainOptions& o) { o.links = 0; });
    EXPECT_NE(links.find("--links"), std::string::npos) << links;
    EXPECT_NE(links.find('0'), std::string::npos) << links;
    EXPECT_NE(why([](lab::HairChainOptions& o) { o.links = 65; }).find("--links"), std::string::npos);
    const std::string dt = why([](lab::HairChainOptions& o) { o.dt = -0.01; });
    EXPECT_NE(dt.find("--dt"), std::string::npos) << dt;
    EXPECT_NE(dt.find("-0.01"), std::string::npos) << dt;
    EXPECT_NE(why([](lab::HairChainOptions& o) { o.dt = NAN; }).find("--dt"), std::string::npos);
    EXPECT_NE(why([](lab::HairChainOptions& o) { o.length = 0.0; }).find("--length"), std::string::npos);
    EXPECT_NE(why([](lab::HairChainOptions& o) { o.length = 11.0; }).find("--length"), std::string::npos);
    EXPECT_NE(why([](lab::HairChainOptions& o) { o.seconds = 601.0; }).find("--seconds"), std::string::npos);
    EXPECT_NE(why([](lab::HairChainOptions& o) {
                  o.seconds = 600.0;
                  o.dt = 1e-4;
              }).find("steps"),
              std::string::npos);
    EXPECT_NE(why([](lab::HairChainOptions& o) { o.iterations = -1; }).find("--iterations"), std::string::npos);
    EXPECT_NE(why([](lab::HairChainOptions& o) { o.substeps = 1001; }).find("--substeps"), std::string::npos);
    const std::string solver = why([](lab::HairChainOptions& o) { o.solver = "xyz"; });
    EXPECT_NE(solver.find("--solver"), std::string::npos) << solver;
    EXPECT_NE(solver.find("'xyz'"), std::string::npos) << solver;
    EXPECT_NE(solver.find(physics::hairMethodNames()), std::string::npos) << solver;
    EXPECT_NE(solver.find("reference"), std::string::npos) << solver;
    EXPECT_THROW(lab::runHairChain([] {
                     lab::HairChainOptions o;
                     o.links = 0;
                     return o;
                 }()),
                 std::invalid_argument);
}

TEST(HairChain, CommandWritesTheCsvAndRefusesBadValues) {
    const auto dir = std::filesystem::temp_directory_path() / "mc_hair_chain_test";
    std::filesystem::create_directories(dir);
    const auto csv = dir / "chain.csv";
    std::filesystem::remove(csv);
    const auto r =
        runLab({"hair-chain", "--solver", "reference", "--links", "4", "--seconds", "0.5", "--csv", csv.string()});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("wrote"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("tip error"), std::string::npos) << r.out;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "t,tip_x,tip_y,ref_tip_x,ref_tip_y,tip_error,max_segment_error,energy_error");

    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--links", "0"}, "--links"},
        {{"--links", "65"}, "--links"},
        {{"--dt", "-0.01"}, "--dt"},
        {{"--dt", "0"}, "--dt"},
        {{"--dt", "nan"}, "--dt"},
        {{"--length", "-1"}, "--length"},
        {{"--seconds", "1e9"}, "--seconds"},
        {{"--iterations", "-2"}, "--iterations"},
        {{"--substeps", "5000"}, "--substeps"},
        {{"--solver", "xyz"}, "--solver 'xyz' is not a hair solver"},
    };
    const auto stamp = std::filesystem::last_write_time(csv);
    for (const auto& [flags, expected] : cases) {
        std::vector<std::string> args{"hair-chain", "--csv", csv.string()};
        args.insert(args.end(), flags.begin(), flags.end());
        const auto bad = runLab(args);
        EXPECT_EQ(bad.code, 2) << flags[0] << " " << flags[1];
        EXPECT_NE(bad.err.find("minecrappy-lab hair-chain: "), std::string::npos) << bad.err;
        EXPECT_NE(bad.err.find(expected), std::string::npos) << bad.err;
    }
    EXPECT_EQ(std::filesystem::last_write_time(csv), stamp);            // a refused run leaves the file alone
    EXPECT_EQ(runLab({"hair-chain", "--solver", "reference"}).code, 2); // --csv is required
    EXPECT_EQ(runLab({"hair-chain", "--solver", "reference", "--csv", dir.string()}).code, 2); // a folder
    std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------------
// The hair methods against the chain (these run physics::HairSolver).
//
// What theory says, for a free chain with the root pinned (equal masses, Verlet positions, h the step):
// - shake projects along the constraint gradients at the START of the step: with the Verlet step that is
//   SHAKE/RATTLE, second order, provided the release is started as Verlet from rest requires
//   (x_1 = x_0 + a h^2 / 2; starting with prev = x_0 gives x_1 = x_0 + a h^2, an initial velocity error a h / 2
//   that makes any method first order).
// - ftl, dftl, pbd and xpbd-substeps move nodes along the directions at the END of the step (the nearest point
//   on the constraint, or Gauss-Seidel sweeps converging near it). For one link that is the radial projection:
//   expanding it against SHAKE's, the step's angle increment loses Delta h^2 (theta'^2 + (g / L) cos(theta)) =
//   h^2 theta' T / (m L), a drag of O(h) (theta'' gains -h theta' T / (m L), T the rod's tension), so they are
//   FIRST order, however many iterations (pbd converged is still the end-of-step projection). For one link
//   dftl is ftl (its velocity correction feeds the root, which is pinned).
// - For many links ftl moves only children, which is not a consistent discretisation at all (order ~0: the
//   finding the hair charts show).

// The largest tip error over [0, T] (a norm over the interval: the error at one instant can pass near zero
// as the phase error swings, which makes a single-time order meaningless).
double worstTipError(const std::string& solver, int links, int divisions, double T, int iterations = 0,
                     bool automaticSubsteps = false) {
    lab::HairChainOptions o;
    o.automaticSubsteps = automaticSubsteps;
    o.solver = solver;
    o.links = links;
    o.dt = 1.0 / divisions;
    o.seconds = T;
    o.iterations = iterations;
    double worst = 0.0;
    for (const auto& r : lab::runHairChain(o)) {
        if (!std::isfinite(r.tipError)) return r.tipError;
        if (r.t <= T + 1e-9) worst = std::max(worst, r.tipError);
    }
    return worst;
}

// The largest tip error over t in [0, T] of SHAKE/RATTLE itself on one link, in double, as the recurrence it is
// in the angle: the tangential part of the Verlet prediction is kept and the radial part removed along the old
// rod, so sin(theta_{n+1} - theta_n) = sin(theta_n - theta_{n-1}) - (g h^2 / L) sin(theta_n), started from rest
// with half the kick (sin(theta_1 - theta_0) = -(g h^2 / 2L) sin(theta_0)).
double rattleOneLinkWorstTipError(double L, double g, double h, double T) {
    const physics::ExactPendulum exact({L, g, 1.0, 0.0}, {kPi / 2.0, 0.0});
    double theta = kPi / 2.0;
    double sinDelta = -(g * h * h / (2.0 * L)) * std::sin(theta);
    double worst = 0.0;
    for (int n = 1; n * h <= T + 1e-12; ++n) {
        theta += std::asin(sinDelta);
        const double te = exact.at(n * h).theta;
        worst = std::max(worst, std::hypot(L * (std::sin(theta) - std::sin(te)), L * (std::cos(theta) - std::cos(te))));
        sinDelta -= (g * h * h / L) * std::sin(theta);
    }
    return worst;
}

TEST(HairChainSolvers, OneLinkEveryMethodAgainstTheExactPendulum) {
    const double L = 0.45, g = 9.81;
    const double h = static_cast<double>(static_cast<float>(1.0 / 240.0)); // the step the solver takes
    const double rattle = rattleOneLinkWorstTipError(L, g, h, 1.0);
    std::printf("[ one link ] SHAKE/RATTLE in double, dt 1/240: worst tip error over 1 s %.3g m\n", rattle);
    for (int m = 0; m < physics::kHairMethodCount; ++m) {
        const std::string name(physics::hairMethodName(static_cast<physics::HairMethod>(m)));
        lab::HairChainOptions o;
        o.solver = name;
        o.links = 1;
        o.dt = 1.0 / 240.0;
        o.seconds = 1.0;
        const auto rows = lab::runHairChain(o);
        double worstTip = 0.0, worstSegment = 0.0;
        for (const auto& r : rows) {
            ASSERT_TRUE(std::isfinite(r.tipError)) << name << " t = " << r.t;
            worstTip = std::max(worstTip, r.tipError);
            worstSegment = std::max(worstSegment, r.maxSegmentError);
        }
        const double coarse = worstTipError(name, 1, 120, 0.5), fine = worstTipError(name, 1, 240, 0.5);
        const double order = std::log2(coarse / fine);
        std::printf("[ one link ] %-14s worst tip error %.3g m, segment error %.2g, order (1/120 -> 1/240 over "
                    "0.5 s) %.2f\n",
                    name.c_str(), worstTip, worstSegment, order);
        RecordProperty("one_link_order_" + name, std::to_string(order));
        // One link: every method keeps the length to float rounding (measured at most 1.1e-7; 1e-6 is ten
        // times that, a few ulps of a 0.45 m coordinate).
        EXPECT_LT(worstSegment, 1e-6) << name;
        if (name == "shake") {
            // Second order: it is RATTLE, so its error is RATTLE's own in double (9.0e-5 m), plus the float
            // solver's rounding (measured 1.1e-6 m apart).
            EXPECT_NEAR(worstTip, rattle, 5e-6) << name;
            EXPECT_NEAR(order, 2.0, 0.2) << name;
        } else {
            // The end-of-step projection: first order (see above).
            EXPECT_NEAR(order, 1.0, 0.2) << name;
        }
    }
}

// shake at the game's tick, with the game's automatic substeps (a step split where a segment would turn more
// than 10 degrees, up to 4 substeps): on the 11-link chain over the first 0.5 s (well within its 2.5 s
// horizon), its error does not grow with Newton iterations (measured 0.0164, 0.00148, 0.00147, 0.00147 m for
// 1 to 4: converged from 2), and at its game setting (2) it is far the most accurate exact-length method:
// measured 140 times closer than dftl (0.207 m), held to 50. Without the turn-chosen substeps: 0.029, 0.120,
// 0.162 m for 1 to 3, 1.7 times closer than dftl (caught).
TEST(HairChainSolvers, ShakeAtTheGamesTickIsConvergedAndFarCloserThanDftl) {
    std::vector<double> errors;
    for (int iterations = 1; iterations <= 4; ++iterations)
        errors.push_back(worstTipError("shake", 11, 60, 0.5, iterations, true));
    for (std::size_t k = 1; k < errors.size(); ++k)
        EXPECT_LE(errors[k], 1.1 * errors[k - 1])
            << "iterations " << k + 1 << ": " << errors[k] << " after " << errors[k - 1];
    const double shake = worstTipError("shake", 11, 60, 0.5, 0, true);
    const double dftl = worstTipError("dftl", 11, 60, 0.5, 0, true);
    ASSERT_EQ(physics::hairMethodDefaults(physics::HairMethod::Shake).iterations, 2) << "precondition";
    EXPECT_EQ(shake, errors[1]);
    EXPECT_LT(50.0 * shake, dftl) << shake << " against " << dftl;
}

// The solver keeps positions in float, and a Verlet position recurrence gathers rounding like n^2: the halvings
// stop at 1/480 s, where shake's error (2.8e-4 m) is still far above it.
TEST(HairChainSolvers, ElevenLinksObservedOrderAsTheStepHalves) {
    const int links = 11;
    const double t = 0.5;
    struct Case {
        const char* solver;
        int iterations;
    };
    // shake: Newton iterations; pbd: Gauss-Seidel sweeps (many: converged); the rest at their defaults.
    for (const Case c :
         {Case{"shake", 20}, Case{"pbd", 200}, Case{"ftl", 0}, Case{"dftl", 0}, Case{"xpbd-substeps", 0}}) {
        const double e120 = worstTipError(c.solver, links, 120, t, c.iterations);
        const double e240 = worstTipError(c.solver, links, 240, t, c.iterations);
        const double e480 = worstTipError(c.solver, links, 480, t, c.iterations);
        const double order = 0.5 * std::log2(e120 / e480); // over the two halvings
        std::printf("[ %d links ] %-14s worst tip error up to %.1f s: dt 1/120 %.3g, 1/240 %.3g, 1/480 %.3g m; "
                    "order %.2f\n",
                    links, c.solver, t, e120, e240, e480, order);
        RecordProperty(std::string("chain_order_") + c.solver, std::to_string(order));
        ASSERT_TRUE(std::isfinite(e120) && std::isfinite(e240) && std::isfinite(e480)) << c.solver;
        const std::string name = c.solver;
        if (name == "shake") {
            EXPECT_GT(order, 1.5); // measured 2.03
        } else if (name == "pbd" || name == "xpbd-substeps") {
            // The end-of-step projection (converged Gauss-Seidel, or small steps of one pass): first order
            // (measured 0.64 for pbd at 200 passes, still approaching 1; 0.99 for small steps), never second.
            EXPECT_GT(order, 0.5);
            EXPECT_LT(order, 1.3);
        } else {
            // Follow-the-leader moves only the child: not a consistent discretisation, its error does not
            // shrink with the step (measured -0.02 and -0.30). The finding the charts show; a change that made
            // it converge would be news for docs/HAIR.md. An order alone is satisfied by any broken solver, so
            // the errors themselves are held to what was measured (ftl 0.816 / 0.827 / 0.836 m, dftl 0.406 /
            // 0.549 / 0.613 m, a tip 5.5 m out) within 25 %: a solver that froze the chain (tip error up to
            // 2 x 5.5 m) fails, and so does dftl without its velocity feedback (it is then ftl: 0.82 m at 1/120 s).
            EXPECT_LT(order, 0.5);
            EXPECT_GT(order, -0.6);
            const bool ftl = name == "ftl";
            const double measured[3] = {ftl ? 0.816 : 0.406, ftl ? 0.827 : 0.549, ftl ? 0.836 : 0.613};
            const double errors[3] = {e120, e240, e480};
            for (int i = 0; i < 3; ++i) {
                EXPECT_GT(errors[i], measured[i] / 1.25) << name << " halving " << i;
                EXPECT_LT(errors[i], measured[i] * 1.25) << name << " halving " << i;
            }
        }
    }
}

} // namespace

namespace {

// The second integrator (classic RK4 on the tension equations) is fourth order: before the whip (0.3 s on the
// 11-link chain), halving its step divides its tip's distance from the reference by about 16. Steps of 2 and
// 1 ms keep its own error far above the reference's. Catches a wrong stage weight (order 2 or 1).
TEST(ChainHorizon, TheSecondIntegratorIsFourthOrder) {
    const lab::ChainParams chain; // 11 links, 0.45 m
    const std::vector<double> times = {0.3};
    lab::ChainReference reference(chain, std::vector<double>(11, std::numbers::pi / 2.0), std::vector<double>(11, 0.0));
    reference.advanceTo(0.3);
    const auto errorAt = [&](double step) {
        const lab::ChainPoint tip = lab::chainTipsRk4(chain, times, step)[0];
        return std::hypot(tip.x - reference.tip().x, tip.y - reference.tip().y);
    };
    // Measured: 4.9e-8, 2.3e-9 and 1.2e-10 m at 2, 1 and 0.5 ms, orders 4.41 and 4.26 (nearing 4 as the step
    // shrinks). Held: the finer pair's order within 4 +- 0.5, and nearer 4 than the coarser pair's.
    const double e1 = errorAt(2e-3), e2 = errorAt(1e-3), e3 = errorAt(5e-4);
    ASSERT_GT(e3, 1e-11) << "precondition: the RK4 error is far above the reference's";
    const double coarseOrder = std::log2(e1 / e2), fineOrder = std::log2(e2 / e3);
    EXPECT_NEAR(fineOrder, 4.0, 0.5) << e1 << " " << e2 << " " << e3;
    EXPECT_LT(std::abs(fineOrder - 4.0), std::abs(coarseOrder - 4.0));
}

// The horizon as the hair report states it, checked against a pair made otherwise: RK4 on the tension
// equations from the start and Dormand-Prince on the tension equations from the nudged start reach 1 mm apart
// within 1 % of the time the pair of references (Lagrange equations) does. And the reference is exact past the horizon:
// its tips and the second integrator's stay within 1 um until after it, so within the horizon a tip error is measured
// against a reference good to 1 um.
TEST(ChainHorizon, TheHorizonAgreesWithAnIndependentPairAndTheReferenceIsExactBeyondIt) {
    lab::ChainParams chain;
    chain.links = 11;
    chain.length = 0.45;
    const lab::ChainHorizon h = lab::chainHorizon(chain, 4.0);
    ASSERT_FALSE(std::isnan(h.horizon)) << "precondition: the chain loses predictability within 4 s";
    std::vector<double> times;
    for (double t = 1e-3; t <= h.horizon * 1.2; t += 1e-3) times.push_back(t);
    const auto a = lab::chainTipsRk4(chain, times, h.rk4Step);
    // The same RK4 from the nudged start: the second integrator's own pair.
    const std::size_t N = 11;
    std::vector<double> theta(N, std::numbers::pi / 2.0);
    theta[0] += lab::kHorizonPerturbation;
    lab::ChainReference nudged(chain, theta, std::vector<double>(N, 0.0), {}, lab::ChainEquations::Tensions);
    double rk4Horizon = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < times.size() && std::isnan(rk4Horizon); ++k) {
        nudged.advanceTo(times[k]);
        if (std::hypot(a[k].x - nudged.tip().x, a[k].y - nudged.tip().y) >= lab::kHorizonTipDistance)
            rk4Horizon = times[k];
    }
    ASSERT_FALSE(std::isnan(rk4Horizon));
    EXPECT_NEAR(rk4Horizon, h.horizon, 0.01 * h.horizon);
    EXPECT_TRUE(std::isnan(h.exactTo) || h.exactTo > h.horizon) << h.exactTo << " " << h.horizon;
    EXPECT_LT(h.maxAgreementBefore, lab::kExactTipDistance);
    // hair-work-precision reads what the eye sees from this chain's horizon on: its default window must start
    // there (measured 2.5 s; a window set to 2 s, inside the predictable motion, fails here).
    EXPECT_NEAR(lab::HairWorkPrecisionOptions{}.lookFrom, h.horizon, 0.01);
}

} // namespace

namespace {

// What the eye sees, against closed forms: the single link released from horizontal is the simple pendulum
// from 90 degrees. Its period is 4 sqrt(L / 2g) I(-1/2) and its time-averaged cos(theta) is I(1/2) / I(-1/2),
// with I(p) = int_0^{pi/2} cos^p = sqrt(pi) / 2 Gamma((p + 1) / 2) / Gamma(p / 2 + 1) (energy: theta'^2 =
// (2g / L) cos theta). Over ten periods the reference's look must match them: measured period error under 1e-9 s
// and mean-height error 4.4e-7 m (rows 1 ms apart); held to 1e-7 s and 5e-6 m, about ten times those. Catches a period
// missing its factor 2.
TEST(ChainLook, TheSinglePendulumsPeriodAndMeanHeightMatchTheClosedForms) {
    const double L = 0.45, g = 9.81;
    const double iMinus = std::sqrt(std::numbers::pi) / 2.0 * std::tgamma(0.25) / std::tgamma(0.75);
    const double iPlus = std::sqrt(std::numbers::pi) / 2.0 * std::tgamma(0.75) / std::tgamma(1.25);
    const double period = 4.0 * std::sqrt(L / (2.0 * g)) * iMinus;
    const double meanHeight = -L * iPlus / iMinus;
    lab::HairChainOptions o;
    o.solver = "reference";
    o.links = 1;
    o.length = L;
    o.dt = 1e-3;
    o.seconds = 10.0 * period + 0.1;
    const std::vector<lab::HairChainRow> rows = lab::runHairChain(o);
    ASSERT_GT(rows.back().t, 10.0 * period) << "precondition: the run covers ten periods";
    const lab::ChainLook look = lab::chainLook(rows, 0.0, 10.0 * period);
    std::printf("[ measured ] period %.9f s (closed form %.9f), mean tip height %.9f m (closed form %.9f)\n",
                look.refSwingPeriod, period, look.refMeanTipHeight, meanHeight);
    EXPECT_NEAR(look.refSwingPeriod, period, 1e-7);
    EXPECT_NEAR(look.refMeanTipHeight, meanHeight, 5e-6);
    // The "reference" solver is the reference: both columns agree.
    EXPECT_EQ(look.swingPeriod, look.refSwingPeriod);
    EXPECT_EQ(look.meanTipHeight, look.refMeanTipHeight);
    EXPECT_NEAR(look.energy, 0.0, 1e-6);
}

// A chain at rest has no swing, however its tip trembles: dftl at 1/30 s has stopped the 11-link chain by 4 s
// (energy -0.545 M g L, the hanging chain's). Its period is NaN and its mean height -L within 1 mm, while the
// reference keeps swinging higher. Catches counting every zero crossing (kSwingAmplitude 0: a period of the
// tremor) and the reference's mean taken from the simulated column.
TEST(ChainLook, AChainAtRestHasNoSwingAndHangsAtItsLength) {
    lab::HairChainOptions o;
    o.dt = 1.0 / 30.0;
    o.seconds = 8.0;
    const lab::ChainLook look = lab::chainLook(lab::runHairChain(o), 4.0, 8.0);
    ASSERT_LT(look.energy, -0.5) << "precondition: dftl at 1/30 s has stopped the chain";
    EXPECT_TRUE(std::isnan(look.swingPeriod)) << look.swingPeriod;
    EXPECT_NEAR(look.meanTipHeight, -o.length, 1e-3);
    EXPECT_FALSE(std::isnan(look.refSwingPeriod));
    EXPECT_GT(look.refMeanTipHeight, -0.8 * o.length);
}

} // namespace
