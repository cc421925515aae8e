// The pendulum integrators, checked against what theory fixes: the order of convergence when the step
// halves, the direction of energy drift, the linear stability limit of each step map, the drift of the
// seed's position-stepping Euler, and what the midpoint's start does. The closed form they are measured
// against has its own tests in test_pendulum_exact.cpp.
#include "physics/pendulum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using physics::ExactPendulum;
using physics::Method;
using physics::MidpointStart;
using physics::Pendulum;
using physics::PendulumParams;
using physics::PendulumState;

constexpr double kPi = 3.141592653589793238462643383279;
const PendulumState kSixtyDegrees{kPi / 3.0, 0.0};

std::string nameOf(Method m) { return std::string(physics::methodName(m)); }

// stepImplicitMidpoint without its evaluation counter, as a plain StepFn.
PendulumState implicitMidpoint(const PendulumParams& p, const PendulumState& s, double h) {
    return physics::stepImplicitMidpoint(p, s, h);
}

// Steps `steps` equal steps to tEnd and returns theta(tEnd) - exact theta(tEnd).
double angleError(Method method, int steps, double tEnd = 10.0, const PendulumState& initial = kSixtyDegrees,
                  MidpointStart start = MidpointStart::Rk4) {
    const PendulumParams params;
    Pendulum pendulum(method, params, initial, start);
    const double h = tEnd / steps;
    for (int i = 0; i < steps; ++i) pendulum.step(h);
    return pendulum.state().theta - ExactPendulum(params, initial).at(tEnd).theta;
}

double observedOrder(double coarseError, double fineError) { return std::log2(std::abs(coarseError / fineError)); }

// ---------------------------------------------------------------------------------------------------------
// Names, costs, bookkeeping

TEST(PendulumMethods, NamesRoundTripAndRejectUnknown) {
    const std::array<const char*, physics::kMethodCount> expected = {"euler",
                                                                     "euler-cartesian",
                                                                     "midpoint",
                                                                     "trapezoid",
                                                                     "symplectic-euler",
                                                                     "verlet",
                                                                     "rk4",
                                                                     "implicit-midpoint",
                                                                     "yoshida4",
                                                                     "dopri5",
                                                                     "exact"};
    ASSERT_EQ(physics::kMethodCount, 11);
    EXPECT_EQ(static_cast<int>(Method::Exact), physics::kMethodCount - 1); // exact stays last
    for (int i = 0; i < physics::kMethodCount; ++i) {
        const auto method = static_cast<Method>(i);
        EXPECT_EQ(physics::methodName(method), expected[static_cast<std::size_t>(i)]);
        EXPECT_EQ(physics::methodFromName(expected[static_cast<std::size_t>(i)]), method);
    }
    EXPECT_EQ(physics::methodName(Method::Count), "");
    EXPECT_FALSE(physics::methodFromName("").has_value());
    EXPECT_FALSE(physics::methodFromName("RK4").has_value());
    EXPECT_FALSE(physics::methodFromName("leapfrog").has_value());
}

TEST(PendulumMethods, EvaluationsPerStepAreTheForceCallsOfEachScheme) {
    EXPECT_EQ(physics::evaluationsPerStep(Method::Euler), 1);
    EXPECT_EQ(physics::evaluationsPerStep(Method::EulerCartesian), 1);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Midpoint), 1);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Trapezoid), 2);
    EXPECT_EQ(physics::evaluationsPerStep(Method::SymplecticEuler), 1);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Verlet), 1);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Rk4), 4);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Yoshida4), 3);
    // Varying costs report 0: Pendulum::evaluations() counts them (tests below).
    EXPECT_EQ(physics::evaluationsPerStep(Method::ImplicitMidpoint), 0);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Dopri5), 0);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Exact), 0);
    EXPECT_EQ(physics::evaluationsPerStep(Method::Count), -1);
}

TEST(PendulumBasics, EnergyAndFrequencyFollowTheirDefinitions) {
    PendulumParams params;
    params.length = 2.0;
    params.gravity = 9.0;
    params.mass = 3.0;
    EXPECT_DOUBLE_EQ(physics::smallAngleFrequency(params), 1.5 * std::sqrt(2.0));
    EXPECT_DOUBLE_EQ(physics::energy(params, {0.0, 0.0}), -3.0 * 9.0 * 2.0);
    EXPECT_NEAR(physics::energy(params, {kPi / 2.0, 1.0}), 0.5 * 3.0 * 4.0 * 1.0, 1e-13);
    EXPECT_NEAR(physics::energy(params, {kPi, 0.0}), 3.0 * 9.0 * 2.0, 1e-12);
}

TEST(PendulumClass, OneStepMethodsAreExactlyTheirPureFunctions) {
    PendulumParams params;
    params.damping = 0.3;
    const PendulumState start{-0.4, 2.5};
    const double h = 1.0 / 60.0;
    struct Case {
        Method method;
        PendulumState (*step)(const PendulumParams&, const PendulumState&, double);
    };
    const Case cases[] = {{Method::Euler, physics::stepEuler},
                          {Method::Trapezoid, physics::stepTrapezoid},
                          {Method::SymplecticEuler, physics::stepSymplecticEuler},
                          {Method::Verlet, physics::stepVerlet},
                          {Method::Rk4, physics::stepRk4},
                          {Method::ImplicitMidpoint, implicitMidpoint},
                          {Method::Yoshida4, physics::stepYoshida4}};
    for (const Case& c : cases) {
        SCOPED_TRACE(nameOf(c.method));
        Pendulum pendulum(c.method, params, start);
        PendulumState s = start;
        for (int i = 0; i < 500; ++i) {
            pendulum.step(h);
            s = c.step(params, s, h);
        }
        // Bitwise: the verlet and yoshida4 wrappers reuse sin of the last end point (FSAL) and must not
        // differ at all.
        EXPECT_EQ(pendulum.state().theta, s.theta);
        EXPECT_EQ(pendulum.state().omega, s.omega);
    }
}

TEST(PendulumClass, TimeAccumulatesWithoutDriftAndZeroStepIsANoOp) {
    Pendulum pendulum(Method::Rk4, PendulumParams{}, kSixtyDegrees);
    for (int i = 0; i < 60 * 3600; ++i) pendulum.step(1.0 / 60.0); // an hour of game ticks
    EXPECT_NEAR(pendulum.time(), 3600.0, 1e-12);
    const PendulumState before = pendulum.state();
    pendulum.step(0.0);
    EXPECT_EQ(pendulum.state().theta, before.theta);
    EXPECT_EQ(pendulum.time(), 3600.0);
}

TEST(PendulumClass, ResetReturnsToTimeZeroFromTheNewState) {
    for (int i = 0; i < physics::kMethodCount; ++i) {
        const auto method = static_cast<Method>(i);
        SCOPED_TRACE(nameOf(method));
        Pendulum fresh(method, PendulumParams{}, {0.3, -1.0});
        Pendulum used(method, PendulumParams{}, kSixtyDegrees);
        for (int k = 0; k < 37; ++k) used.step(0.01);
        used.reset({0.3, -1.0});
        EXPECT_EQ(used.time(), 0.0);
        for (int k = 0; k < 50; ++k) {
            fresh.step(0.02);
            used.step(0.02);
        }
        EXPECT_EQ(used.state().theta, fresh.state().theta);
        EXPECT_EQ(used.state().omega, fresh.state().omega);
        EXPECT_EQ(used.rodLength(), fresh.rodLength());
    }
}

// A saved exact_theta0 of -5e234 (found by the world fuzzer) made Boost's elliptic integral throw from the
// exact solution. Initial states are bounded: |theta| <= 1e6 rad, |omega| <= 1e6 sqrt(g / L), with the
// bound itself accepted and every method, exact included, finite there.
TEST(PendulumClass, InitialStateBeyondDoublePrecisionIsRejected) {
    const PendulumParams good; // L = 1, g = 9.81
    const double omegaLimit = physics::kMaxFrequencyRatio * std::sqrt(good.gravity / good.length);
    const PendulumState tooFar[] = {{-5.316847517969733e234, 1.0},
                                    {std::nextafter(physics::kMaxInitialAngle, 2e6), 0.0},
                                    {0.5, std::nextafter(omegaLimit, 2.0 * omegaLimit)},
                                    {0.5, -1e300}};
    for (const auto& st : tooFar) {
        for (int m = 0; m < static_cast<int>(Method::Count); ++m) {
            EXPECT_THROW(Pendulum(static_cast<Method>(m), good, st), std::invalid_argument)
                << methodName(static_cast<Method>(m)) << " theta " << st.theta << " omega " << st.omega;
        }
        EXPECT_THROW(ExactPendulum(good, st), std::invalid_argument) << st.theta << " " << st.omega;
    }
    for (const PendulumState st :
         {PendulumState{physics::kMaxInitialAngle, 0.0}, PendulumState{-physics::kMaxInitialAngle, omegaLimit},
          PendulumState{0.5, -omegaLimit}}) {
        const ExactPendulum exact(good, st);
        const PendulumState later = exact.at(10.0);
        EXPECT_TRUE(std::isfinite(later.theta) && std::isfinite(later.omega)) << st.theta << " " << st.omega;
        EXPECT_NEAR(energy(good, later), energy(good, st), 1e-9 * std::abs(energy(good, st)))
            << st.theta << " " << st.omega;
    }
}

TEST(PendulumClass, RejectsBadInputClearly) {
    const PendulumParams good;
    PendulumParams damped;
    damped.damping = 0.1;
    EXPECT_THROW(Pendulum(Method::Exact, damped, kSixtyDegrees), std::invalid_argument);
    EXPECT_THROW(Pendulum(Method::Count, good, kSixtyDegrees), std::invalid_argument);
    PendulumParams bad = good;
    bad.length = 0.0;
    EXPECT_THROW(Pendulum(Method::Rk4, bad, kSixtyDegrees), std::invalid_argument);
    bad = good;
    bad.gravity = -9.81;
    EXPECT_THROW(Pendulum(Method::Rk4, bad, kSixtyDegrees), std::invalid_argument);
    bad = good;
    bad.damping = -1.0;
    EXPECT_THROW(Pendulum(Method::Rk4, bad, kSixtyDegrees), std::invalid_argument);
    bad = good;
    bad.mass = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(Pendulum(Method::Rk4, bad, kSixtyDegrees), std::invalid_argument);
    EXPECT_THROW(Pendulum(Method::Rk4, good, {std::numeric_limits<double>::infinity(), 0.0}), std::invalid_argument);
    bad = good;
    bad.gravity = 1e300;
    bad.length = 1e-300; // each finite, but sqrt(g / L) overflows
    EXPECT_THROW(Pendulum(Method::Rk4, bad, kSixtyDegrees), std::invalid_argument);

    Pendulum pendulum(Method::Verlet, good, kSixtyDegrees);
    EXPECT_THROW(pendulum.step(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(pendulum.reset({0.0, std::numeric_limits<double>::quiet_NaN()}), std::invalid_argument);
    // Damped methods other than exact are fine.
    EXPECT_NO_THROW(Pendulum(Method::Midpoint, damped, kSixtyDegrees));
    try {
        const Pendulum exact(Method::Exact, damped, kSixtyDegrees);
        ADD_FAILURE() << "exact with damping was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("damping"), std::string::npos) << e.what();
    }
}

// ---------------------------------------------------------------------------------------------------------
// Convergence: e(h) / e(h/2) -> 2^p. The steps are chosen inside each method's asymptotic range, where the
// leading error term dominates: from 60 degrees at rest (omega0 = 3.13 rad/s, period 2.15 s) to t = 10 s.

struct OrderCase {
    Method method;
    int expectedOrder;
    int coarseSteps; // steps to t = 10 s at the coarsest of three step sizes
    const char* why;
};

const OrderCase kOrderCases[] = {
    // Euler multiplies the energy by about 1 + (h omega0)^2 every step, so the amplitude grows like
    // exp(h omega0^2 t / 2): only linear in h once h << 2 / (omega0^2 t) = 0.02 s. At h = 1.25e-3 the
    // exponent is 0.06 and the error is first order.
    {Method::Euler, 1, 8000, "exponential amplitude growth must be small"},
    // O(h) with a visible O(h^2) correction until h is a few ms.
    {Method::SymplecticEuler, 1, 4000, "O(h^2) term below 2%"},
    // Second order from h = 0.01: the O(h^4) phase term is then 1e-4 of the leading one.
    {Method::Midpoint, 2, 1000, "asymptotic from 0.01 s"},
    {Method::Verlet, 2, 1000, "asymptotic from 0.01 s"},
    // Heun gains energy as (1 + (h omega0)^4 / 4) per step, and its O(h^3) term is 7% at h = 0.01.
    {Method::Trapezoid, 2, 4000, "h = 2.5e-3 and below"},
    // Errors from 7.5e-9 down to 3e-11: above the rounding floor (~1e-13 after 8000 steps) and small enough
    // that the O(h^5) term is under 2%.
    {Method::Rk4, 4, 2000, "between the h^5 term and rounding"},
    // Measured 1.9992 and 1.9998 here, 2.0000 from the moving state, 2.0007 with damping.
    {Method::ImplicitMidpoint, 2, 1000, "asymptotic from 0.01 s"},
    // Errors from 1.4e-5 down to 5e-8 (3.9996 to 4.0000 in all three tests); below h = 6e-4 the rounding
    // floor (~1e-13) takes over.
    {Method::Yoshida4, 4, 500, "between the h^6 term and rounding"},
};

TEST(PendulumConvergence, HalvingTheStepShrinksTheErrorByTwoToTheOrder) {
    for (const OrderCase& c : kOrderCases) {
        SCOPED_TRACE(nameOf(c.method) + ": " + c.why);
        const double e1 = angleError(c.method, c.coarseSteps);
        const double e2 = angleError(c.method, 2 * c.coarseSteps);
        const double e3 = angleError(c.method, 4 * c.coarseSteps);
        EXPECT_NEAR(observedOrder(e1, e2), c.expectedOrder, 0.15) << e1 << " " << e2;
        EXPECT_NEAR(observedOrder(e2, e3), c.expectedOrder, 0.15) << e2 << " " << e3;
    }
}

TEST(PendulumConvergence, OrdersHoldFromAMovingStateWithNegativeAngle) {
    const PendulumState moving{-0.5, 3.0};
    for (const OrderCase& c : kOrderCases) {
        SCOPED_TRACE(nameOf(c.method));
        const double e1 = angleError(c.method, 2 * c.coarseSteps, 10.0, moving);
        const double e2 = angleError(c.method, 4 * c.coarseSteps, 10.0, moving);
        EXPECT_NEAR(observedOrder(e1, e2), c.expectedOrder, 0.15) << e1 << " " << e2;
    }
}

TEST(PendulumConvergence, OrdersHoldWithDamping) {
    // No closed form with damping: the reference is rk4 at a step of 1e-4 s (error ~1e-14 rad at 10 s).
    PendulumParams params;
    params.damping = 0.5;
    PendulumState reference = kSixtyDegrees;
    for (int i = 0; i < 100000; ++i) reference = physics::stepRk4(params, reference, 1e-4);
    auto error = [&](Method method, int steps) {
        Pendulum pendulum(method, params, kSixtyDegrees);
        for (int i = 0; i < steps; ++i) pendulum.step(10.0 / steps);
        return pendulum.state().theta - reference.theta;
    };
    for (const OrderCase& c : kOrderCases) {
        SCOPED_TRACE(nameOf(c.method));
        const double e1 = error(c.method, 2 * c.coarseSteps);
        const double e2 = error(c.method, 4 * c.coarseSteps);
        EXPECT_NEAR(observedOrder(e1, e2), c.expectedOrder, 0.15) << e1 << " " << e2;
    }
}

// ---------------------------------------------------------------------------------------------------------
// Energy: mean of E - E0 over the first and the last five seconds of a minute (a mean, so the drift is not
// confused with the oscillation of E within a swing).

struct EnergyWindows {
    double early = 0.0;
    double late = 0.0;
};

EnergyWindows energyWindows(Method method, double h, double minutes = 1.0) {
    const PendulumParams params;
    Pendulum pendulum(method, params, kSixtyDegrees);
    const double e0 = physics::energy(params, kSixtyDegrees);
    const int steps = static_cast<int>(std::lround(60.0 * minutes / h));
    const int window = static_cast<int>(std::lround(5.0 / h));
    EnergyWindows w;
    for (int i = 1; i <= steps; ++i) {
        pendulum.step(h);
        if (i <= window) w.early += pendulum.energy() - e0;
        if (i > steps - window) w.late += pendulum.energy() - e0;
    }
    w.early /= window;
    w.late /= window;
    return w;
}

TEST(PendulumEnergy, EulerAndTrapezoidGainEnergy) {
    // Euler: |1 + i h omega0|^2 = 1 + (h omega0)^2 > 1 per step; the seed's 1 ms step gains 2.9 J of the
    // 4.9 J it needs to reach the top within a minute. Heun: |R(ix)|^2 = 1 + x^4 / 4.
    const struct {
        Method method;
        double h;
    } cases[] = {{Method::Euler, 1e-3},
                 {Method::Euler, 1.0 / 600.0},
                 {Method::Trapezoid, 1.0 / 60.0},
                 {Method::Trapezoid, 0.05}};
    for (const auto& c : cases) {
        SCOPED_TRACE(nameOf(c.method) + " h=" + std::to_string(c.h));
        const EnergyWindows w = energyWindows(c.method, c.h);
        EXPECT_GT(w.early, 0.0);
        EXPECT_GT(w.late, 5.0 * w.early); // grows, and keeps growing
    }
}

TEST(PendulumEnergy, Rk4LosesEnergy) {
    // |R(ix)|^2 = 1 - x^6 / 72 + x^8 / 576 < 1 below 2 sqrt(2): a slow, steady loss.
    for (double h : {1.0 / 60.0, 0.05, 0.1}) {
        SCOPED_TRACE("h=" + std::to_string(h));
        const EnergyWindows w = energyWindows(Method::Rk4, h);
        EXPECT_LT(w.early, 0.0);
        EXPECT_LT(w.late, 5.0 * w.early);
    }
}

TEST(PendulumEnergy, SymplecticMethodsHaveNoSecularDrift) {
    // A symplectic map conserves a modified energy within O(h^p) of E, so |E - E0| stays within the band
    // it reaches in the first minute, for ever (here: ten minutes).
    const PendulumParams params;
    const double e0 = physics::energy(params, kSixtyDegrees);
    for (Method method : {Method::SymplecticEuler, Method::Verlet, Method::ImplicitMidpoint, Method::Yoshida4}) {
        for (double h : {1.0 / 60.0, 0.05}) {
            SCOPED_TRACE(nameOf(method) + " h=" + std::to_string(h));
            Pendulum pendulum(method, params, kSixtyDegrees);
            double firstMinute = 0.0;
            double lateMinutes = 0.0;
            const int steps = static_cast<int>(std::lround(600.0 / h));
            for (int i = 1; i <= steps; ++i) {
                pendulum.step(h);
                const double t = i * h;
                const double deviation = std::abs(pendulum.energy() - e0);
                if (t <= 60.0) firstMinute = std::max(firstMinute, deviation);
                if (t >= 300.0) lateMinutes = std::max(lateMinutes, deviation);
            }
            EXPECT_GT(firstMinute, 0.0);
            EXPECT_NEAR(lateMinutes / firstMinute, 1.0, 0.1);
        }
    }
}

TEST(PendulumEnergy, DampingOnlyEverRemovesEnergy) {
    // dE/dt = -c m L^2 omega^2 <= 0. Sampled every half second, rk4 must show it.
    PendulumParams params;
    params.damping = 0.4;
    Pendulum pendulum(Method::Rk4, params, {2.5, 0.0});
    double previous = pendulum.energy();
    for (int i = 1; i <= 20 * 120; ++i) {
        pendulum.step(1.0 / 240.0);
        if (i % 120 == 0) {
            EXPECT_LT(pendulum.energy(), previous) << "t=" << pendulum.time();
            previous = pendulum.energy();
        }
    }
}

// ---------------------------------------------------------------------------------------------------------
// Linear stability: each step applied to the linearised pendulum theta'' = -omega0^2 theta is a linear map.
// Its matrix is read off the real steppers at an amplitude of 1e-7 rad (sin(x) = x to 2e-15 there; every
// step is an odd function, so there is no offset), with omega0 = 1 so that h = h omega0.

struct Mat2 {
    double a, b, c, d;
};

using StepFn = PendulumState (*)(const PendulumParams&, const PendulumState&, double);

const PendulumParams kUnitFrequency{1.0, 1.0, 1.0, 0.0};

Mat2 stepMatrix(StepFn step, double h) {
    constexpr double eps = 1e-7;
    const PendulumState col1 = step(kUnitFrequency, {eps, 0.0}, h);
    const PendulumState col2 = step(kUnitFrequency, {0.0, eps}, h);
    return {col1.theta / eps, col2.theta / eps, col1.omega / eps, col2.omega / eps};
}

double spectralRadius(const Mat2& m) {
    const double halfTrace = 0.5 * (m.a + m.d);
    const double det = m.a * m.d - m.b * m.c;
    const double disc = halfTrace * halfTrace - det;
    if (disc < 0.0) return std::sqrt(det); // complex pair, |lambda|^2 = det
    return std::abs(halfTrace) + std::sqrt(disc);
}

// The leapfrog maps (y[n-1], y[n]) to (y[n], y[n-1] + 2h J y[n]); its blocks commute, so its eigenvalues are
// the roots of xi^2 - 2 h lambda xi - 1 = 0 for each eigenvalue lambda of the Jacobian J, read off stepMidpoint.
double midpointSpectralRadius(double h) {
    constexpr double eps = 1e-7;
    const PendulumState zero{};
    const PendulumState c1 = physics::stepMidpoint(kUnitFrequency, zero, {eps, 0.0}, h);
    const PendulumState c2 = physics::stepMidpoint(kUnitFrequency, zero, {0.0, eps}, h);
    const double scale = 2.0 * h * eps;
    const double a = c1.theta / scale, b = c2.theta / scale, c = c1.omega / scale, d = c2.omega / scale;
    const std::complex<double> halfTrace = 0.5 * (a + d);
    const std::complex<double> root = std::sqrt(halfTrace * halfTrace - (a * d - b * c));
    double radius = 0.0;
    for (const std::complex<double> lambda : {halfTrace + root, halfTrace - root}) {
        const std::complex<double> hl = h * lambda;
        const std::complex<double> s = std::sqrt(hl * hl + 1.0);
        radius = std::max({radius, std::abs(hl + s), std::abs(hl - s)});
    }
    return radius;
}

struct StabilityCase {
    Method method;
    StepFn step; // nullptr: the midpoint's two-step map
    double (*theory)(double x);
};

double radiusOf(const StabilityCase& c, double x) {
    return c.step ? spectralRadius(stepMatrix(c.step, x)) : midpointSpectralRadius(x);
}

double verletTheory(double x) { // trace 2 - x^2, determinant 1
    const double halfTrace = 1.0 - 0.5 * x * x;
    return std::abs(halfTrace) <= 1.0 ? 1.0 : std::abs(halfTrace) + std::sqrt(halfTrace * halfTrace - 1.0);
}

// yoshida4: the product of three verlet matrices (steps w1 x, w0 x, w1 x) has determinant 1 and trace
// 2 - x^2 + x^4/12 + c6 x^6 (expanded with sympy; c6 is given in pendulum.h).
double yoshidaTheory(double x) {
    const double r = std::cbrt(2.0);
    const double c6 = (2.0 * r * r - r - 2.0) / (144.0 * (7.0 + 2.0 * r - 6.0 * r * r));
    const double halfTrace = 0.5 * (2.0 - x * x + std::pow(x, 4) / 12.0 + c6 * std::pow(x, 6));
    return std::abs(halfTrace) <= 1.0 ? 1.0 : std::abs(halfTrace) + std::sqrt(halfTrace * halfTrace - 1.0);
}

const StabilityCase kStabilityCases[] = {
    {Method::Euler, physics::stepEuler, [](double x) { return std::sqrt(1.0 + x * x); }},
    {Method::Trapezoid, physics::stepTrapezoid, [](double x) { return std::sqrt(1.0 + std::pow(x, 4) / 4.0); }},
    {Method::SymplecticEuler, physics::stepSymplecticEuler, verletTheory},
    {Method::Verlet, physics::stepVerlet, verletTheory},
    {Method::Rk4, physics::stepRk4,
     [](double x) { return std::sqrt(1.0 - std::pow(x, 6) / 72.0 + std::pow(x, 8) / 576.0); }},
    {Method::Midpoint, nullptr, [](double x) { return x <= 1.0 ? 1.0 : x + std::sqrt(x * x - 1.0); }},
    {Method::Yoshida4, physics::stepYoshida4, yoshidaTheory},
};

TEST(PendulumStability, SpectralRadiusOnAGridMatchesTheoryAndTheLimit) {
    for (const StabilityCase& c : kStabilityCases) {
        const double limit = physics::linearStabilityLimit(c.method);
        for (int i = 1; i <= 80; ++i) {
            const double x = 0.05 * i;
            SCOPED_TRACE(nameOf(c.method) + " h*omega0=" + std::to_string(x));
            const double radius = radiusOf(c, x);
            EXPECT_NEAR(radius, c.theory(x), 1e-9 * c.theory(x));
            if (std::abs(x - limit) < 0.03) continue; // a double root sits on the limit: skip its neighbourhood
            if (x < limit) {
                EXPECT_LE(radius, 1.0 + 1e-12);
            } else {
                EXPECT_GT(radius, 1.0 + 1e-9);
            }
        }
    }
}

TEST(PendulumStability, SymplecticMapsKeepTheAmplitudeExactlyBelowTheLimitAndRk4Damps) {
    for (int i = 1; i < 40; ++i) {
        const double x = 0.05 * i;
        EXPECT_NEAR(spectralRadius(stepMatrix(physics::stepVerlet, x)), 1.0, 1e-13) << x;
        EXPECT_NEAR(spectralRadius(stepMatrix(physics::stepSymplecticEuler, x)), 1.0, 1e-13) << x;
        EXPECT_NEAR(spectralRadius(stepMatrix(implicitMidpoint, x)), 1.0, 1e-13) << x;
        if (x < 1.0) {
            EXPECT_NEAR(midpointSpectralRadius(x), 1.0, 1e-13) << x;
        }
        if (x < physics::kYoshida4StabilityLimit) {
            EXPECT_NEAR(spectralRadius(stepMatrix(physics::stepYoshida4, x)), 1.0, 1e-13) << x;
        }
        EXPECT_LT(spectralRadius(stepMatrix(physics::stepRk4, x)), 1.0) << x;
    }
}

TEST(PendulumStability, BisectedBoundaryIsTheDocumentedLimit) {
    for (const StabilityCase& c : kStabilityCases) {
        SCOPED_TRACE(nameOf(c.method));
        const double limit = physics::linearStabilityLimit(c.method);
        if (limit == 0.0) {
            // Unstable at every step: even a tiny one grows (Heun's excess is x^4 / 8, so not too tiny).
            EXPECT_GT(radiusOf(c, 0.02), 1.0 + 0.5 * (c.theory(0.02) - 1.0));
            continue;
        }
        double stable = 0.5 * limit;
        double unstable = 1.5 * limit;
        ASSERT_LE(radiusOf(c, stable), 1.0 + 1e-12);
        ASSERT_GT(radiusOf(c, unstable), 1.0 + 1e-9);
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (stable + unstable);
            (radiusOf(c, mid) > 1.0 + 1e-9 ? unstable : stable) = mid;
        }
        EXPECT_NEAR(stable, limit, 1e-6);
    }
    EXPECT_DOUBLE_EQ(physics::linearStabilityLimit(Method::Rk4), 2.0 * std::sqrt(2.0));
    EXPECT_EQ(physics::linearStabilityLimit(Method::EulerCartesian), 0.0);
    // yoshida4's limit from its closed form, computed here: the trace of the step map returns to 2 where
    // x^2 = (sqrt(1/144 + 4 c6) - 1/12) / (2 c6), c6 from the triple jump's cube roots (pendulum.h). Catches a
    // mistyped constant (1.5735 is 6e-5 off). c6's denominator cancels to -0.0046 from terms near 9.5, about
    // 2,000 units of rounding: in double that left 1.7e-14 (g++) and 6.9e-14 (clang) in c6, so it is computed
    // in long double (x87's 64-bit mantissa here, 2,000 times finer than the double it is compared as) and
    // held to 4 ulp of the double result.
    const long double r1 = std::cbrt(2.0L), r2 = r1 * r1;
    const long double c6 = (2.0L * r2 - r1 - 2.0L) / (144.0L * (7.0L + 2.0L * r1 - 6.0L * r2));
    const long double closedForm = std::sqrt((std::sqrt(1.0L / 144.0L + 4.0L * c6) - 1.0L / 12.0L) / (2.0L * c6));
    EXPECT_NEAR(static_cast<double>(c6), 0.12950839900935530, 1e-15);
    EXPECT_NEAR(physics::linearStabilityLimit(Method::Yoshida4), static_cast<double>(closedForm), 1e-15);
    EXPECT_TRUE(std::isinf(physics::linearStabilityLimit(Method::ImplicitMidpoint)));
    EXPECT_TRUE(std::isinf(physics::linearStabilityLimit(Method::Dopri5)));
    EXPECT_TRUE(std::isinf(physics::linearStabilityLimit(Method::Exact)));
}

// The largest |theta| of `steps` steps of h omega0 = `x` of a whole Pendulum (start included) stepped by `method`,
// released at the tiny amplitude 1e-12 rad, where the problem is linear.
double largestAngle(Method method, double x, int steps) {
    Pendulum p(method, kUnitFrequency, {1e-12, 0.0});
    double largest = 0.0;
    for (int i = 0; i < steps; ++i) {
        p.step(x);
        largest = std::max(largest, std::abs(p.state().theta));
    }
    return largest;
}

TEST(PendulumStability, MidpointInstanceGrowsAtTheTheoreticalRateAboveItsLimit) {
    // The whole Pendulum (start included) at a tiny amplitude: below h omega0 = 1 it stays bounded; above,
    // it grows by x + sqrt(x^2 - 1) per step.
    const auto amplitudeAfter = [](double x, int steps) { return largestAngle(Method::Midpoint, x, steps); };
    EXPECT_LT(amplitudeAfter(0.9, 20000), 1e-11);
    const double x = 1.1;
    const double rate = std::log(amplitudeAfter(x, 60) / amplitudeAfter(x, 40)) / 20.0;
    EXPECT_NEAR(rate, std::log(x + std::sqrt(x * x - 1.0)), 0.02);
}

TEST(PendulumStability, Yoshida4IsBoundedJustBelowItsLimitAndGrowsJustAbove) {
    // The whole Pendulum at a tiny amplitude, as for the midpoint: at 0.99 of the limit the largest angle of
    // 20,000 steps is the initial one (the eigenvalues lie on the unit circle); at 1.01 the amplitude grows
    // by the larger real eigenvalue of the triple-jump matrix per step (1.352, measured to 5 digits).
    const auto amplitudeAfter = [](double x, int steps) { return largestAngle(Method::Yoshida4, x, steps); };
    const double limit = physics::kYoshida4StabilityLimit;
    EXPECT_LT(amplitudeAfter(0.99 * limit, 20000), 1.5e-12);
    const double x = 1.01 * limit;
    ASSERT_LT(amplitudeAfter(x, 60), 1e-3); // still linear: sin(theta) = theta
    const double rate = std::log(amplitudeAfter(x, 60) / amplitudeAfter(x, 40)) / 20.0;
    EXPECT_NEAR(rate, std::log(yoshidaTheory(x)), 0.02);
}

TEST(PendulumStability, ImplicitMidpointIsAStableWhereVerletExplodes) {
    // At 1e-6 rad the problem is linear; the implicit midpoint's R(ix) = (1 + ix/2) / (1 - ix/2) has modulus 1
    // at every step, so sqrt(theta^2 + (omega / omega0)^2) is kept to rounding even at h omega0 = 10 and 100,
    // where verlet's root of x^2 - 2 - x sqrt(x^2 - 4) per step (98 at x = 10) blows it up within steps.
    for (const double x : {10.0, 100.0}) {
        SCOPED_TRACE("h*omega0=" + std::to_string(x));
        Pendulum implicit(Method::ImplicitMidpoint, kUnitFrequency, {1e-6, 0.0});
        Pendulum verlet(Method::Verlet, kUnitFrequency, {1e-6, 0.0});
        double largest = 0.0;
        double smallest = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 1000; ++i) {
            implicit.step(x);
            const double amplitude = std::hypot(implicit.state().theta, implicit.state().omega);
            largest = std::max(largest, amplitude);
            smallest = std::min(smallest, amplitude);
        }
        ASSERT_EQ(implicit.time(), 1000.0 * x);
        EXPECT_NEAR(largest, 1e-6, 1e-16);
        EXPECT_NEAR(smallest, 1e-6, 1e-16);
        double verletLargest = 0.0;
        for (int i = 0; i < 10; ++i) {
            verlet.step(x);
            verletLargest = std::max(verletLargest, std::abs(verlet.state().theta));
        }
        EXPECT_GT(verletLargest, 1e-2);

        // With damping the amplitude decays instead: |R| < 1 for every eigenvalue with negative real part.
        PendulumParams damped = kUnitFrequency;
        damped.damping = 0.5;
        Pendulum decaying(Method::ImplicitMidpoint, damped, {1e-6, 0.0});
        double before = 1e-6;
        for (int i = 0; i < 20; ++i) {
            decaying.step(x);
            const double amplitude = std::hypot(decaying.state().theta, decaying.state().omega);
            EXPECT_LT(amplitude, before) << i;
            before = amplitude;
        }
    }
}

// ---------------------------------------------------------------------------------------------------------
// The implicit midpoint's solve and the symplectic methods' energy over a long run.

TEST(PendulumImplicitMidpoint, SolvesItsImplicitEquationToRounding) {
    // y1 = y0 + h f((y0 + y1) / 2), re-evaluated from the returned y1: the residual is a few ulp of the state,
    // over steps from tiny to beyond h omega0 = 3, backwards too, with damping.
    PendulumParams params;
    params.damping = 0.3;
    const double w2 = params.gravity / params.length;
    int checked = 0;
    for (const double h : {1e-3, 1.0 / 60.0, 0.05, 0.3, 1.0, -0.05}) {
        SCOPED_TRACE("h=" + std::to_string(h));
        PendulumState s{2.5, -1.0};
        for (int i = 0; i < 200; ++i) {
            int evaluations = 0;
            const PendulumState next = physics::stepImplicitMidpoint(params, s, h, &evaluations);
            ASSERT_GE(evaluations, 2); // one iteration at least: a sin and a cos
            ASSERT_LE(evaluations, 2 * physics::kImplicitMidpointMaxIterations + 1);
            const PendulumState mid{0.5 * (s.theta + next.theta), 0.5 * (s.omega + next.omega)};
            const double scale =
                std::max({1.0, std::abs(s.theta), std::abs(s.omega), std::abs(next.theta), std::abs(next.omega)});
            EXPECT_NEAR(next.theta, s.theta + h * mid.omega, 1e-14 * scale);
            EXPECT_NEAR(next.omega, s.omega + h * (-w2 * std::sin(mid.theta) - params.damping * mid.omega),
                        1e-14 * scale);
            s = next;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 1200);

    // Cost at the game's tick: two Newton iterations (4 evaluations) per step measured, never more than 5 on
    // average.
    Pendulum tick(Method::ImplicitMidpoint, PendulumParams{}, kSixtyDegrees);
    for (int i = 0; i < 600; ++i) tick.step(1.0 / 60.0);
    EXPECT_GE(tick.evaluations(), 2 * 600);
    EXPECT_LE(tick.evaluations(), 5 * 600);
}

TEST(PendulumImplicitMidpoint, ZeroStepAndRestAreFixedPoints) {
    const PendulumParams params;
    int evaluations = 0;
    const PendulumState same = physics::stepImplicitMidpoint(params, {0.7, -0.2}, 0.0, &evaluations);
    EXPECT_EQ(same.theta, 0.7);
    EXPECT_EQ(same.omega, -0.2);
    const PendulumState rest = physics::stepImplicitMidpoint(params, {0.0, 0.0}, 0.1, &evaluations);
    EXPECT_EQ(rest.theta, 0.0);
    EXPECT_EQ(rest.omega, 0.0);
    EXPECT_EQ(evaluations, 4); // each solved at its first point, F(b) == 0: one sin and one cos
}

TEST(PendulumEnergy, SymplecticMethodsKeepTheirEnergyBandForTenThousandSeconds) {
    // h = 0.05 s (h omega0 = 0.16), 200,000 steps from 60 degrees: the largest |E - E0| over the last tenth
    // of the run against the first tenth's (measured 1.0000 for both). rk4, which is not symplectic, fails
    // the same test by far (9.9): it keeps losing energy.
    const PendulumParams params;
    const double e0 = physics::energy(params, kSixtyDegrees);
    const double h = 0.05;
    const int steps = 200000;
    auto bandRatio = [&](Method method) {
        Pendulum pendulum(method, params, kSixtyDegrees);
        double first = 0.0;
        double last = 0.0;
        for (int i = 1; i <= steps; ++i) {
            pendulum.step(h);
            const double deviation = std::abs(pendulum.energy() - e0);
            if (i <= steps / 10) first = std::max(first, deviation);
            if (i > steps - steps / 10) last = std::max(last, deviation);
        }
        EXPECT_NEAR(pendulum.time(), 10000.0, 1e-9);
        EXPECT_GT(first, 0.0);
        return last / first;
    };
    for (Method method : {Method::ImplicitMidpoint, Method::Yoshida4}) {
        SCOPED_TRACE(nameOf(method));
        EXPECT_LT(bandRatio(method), 2.0);
    }
    EXPECT_GT(bandRatio(Method::Rk4), 5.0);
}

// ---------------------------------------------------------------------------------------------------------
// dopri5: the tolerance controls the error, every attempt and evaluation is counted, the dense output is
// fourth order inside each step, and fixed ticks land exactly.

TEST(PendulumDopri5, ErrorFallsWithTheTolerance) {
    // The error test bounds each step's local error by tol (1 + |y|); over 10 s (about five periods) the
    // global error at 60 degrees came out 35 to 63 times tol, falling tenfold per decade.
    const PendulumParams params;
    const double exact = ExactPendulum(params, kSixtyDegrees).at(10.0).theta;
    double previous = std::numeric_limits<double>::infinity();
    for (int decade = 4; decade <= 10; ++decade) {
        const double tol = std::pow(10.0, -decade);
        SCOPED_TRACE("tol=" + std::to_string(tol));
        physics::Dopri5 dopri(params, kSixtyDegrees, tol);
        dopri.advanceTo(10.0);
        ASSERT_EQ(dopri.time(), 10.0);
        ASSERT_GT(dopri.stats().accepted, 20);
        const double error = std::abs(dopri.state().theta - exact);
        EXPECT_LT(error, 100.0 * tol * kSixtyDegrees.theta);
        EXPECT_LT(error, previous / 3.0);
        previous = error;
    }
}

TEST(PendulumDopri5, CountsAttemptsAndEvaluations) {
    // First same as last: 1 evaluation for f at the initial state, 1 for the starting-step heuristic's probe
    // (none when the first step is given), then 6 per attempted step, accepted or rejected.
    const PendulumParams params;
    physics::Dopri5 loose(params, kSixtyDegrees, 1e-4);
    EXPECT_EQ(loose.stats().evaluations, 2);
    EXPECT_EQ(loose.stats().accepted, 0);
    loose.advanceTo(10.0);
    ASSERT_GT(loose.stats().rejected, 0); // at 1e-4 the controller overshoots now and then (14 of 59 measured)
    ASSERT_GT(loose.stats().accepted, 0);
    EXPECT_EQ(loose.stats().evaluations, 6 * (loose.stats().accepted + loose.stats().rejected) + 2);

    physics::Dopri5 given(params, kSixtyDegrees, 1e-8, 0.01);
    EXPECT_EQ(given.nextStep(), 0.01);
    EXPECT_EQ(given.stats().evaluations, 1);
    given.advanceTo(10.0);
    ASSERT_GT(given.stats().accepted, 0);
    EXPECT_EQ(given.stats().evaluations, 6 * (given.stats().accepted + given.stats().rejected) + 1);
}

TEST(PendulumDopri5, DenseOutputIsFourthOrderInsideEachStep) {
    // Against the exact solution started from each step's own start, at a quarter, half and three quarters of
    // the step: within a few tol (4.3 to 5.3 tol measured for tol = 1e-4 .. 1e-10; the interpolant is one
    // order below the step). Against the exact solution from t = 0 at mid-step: as close as the step ends
    // are (the global error dominates). The ends are the step's own values.
    const PendulumParams params;
    const ExactPendulum global(params, kSixtyDegrees);
    const double omegaScale = std::sqrt(2.0 * params.gravity / params.length * (1.0 - std::cos(kPi / 3.0)));
    for (const double tol : {1e-6, 1e-9}) {
        SCOPED_TRACE("tol=" + std::to_string(tol));
        physics::Dopri5 dopri(params, kSixtyDegrees, tol);
        EXPECT_THROW((void)dopri.interpolate(0.0), std::logic_error);
        int steps = 0;
        double local = 0.0;
        double globalTheta = 0.0;
        double globalOmega = 0.0;
        while (dopri.time() < 10.0) {
            const double t0 = dopri.time();
            const PendulumState y0 = dopri.state();
            dopri.step(10.0);
            ++steps;
            const double h = dopri.lastStep();
            ASSERT_GT(h, 0.0);
            const PendulumState start = dopri.interpolate(t0);
            EXPECT_EQ(start.theta, y0.theta);
            EXPECT_EQ(start.omega, y0.omega);
            const PendulumState end = dopri.interpolate(dopri.time());
            EXPECT_NEAR(end.theta, dopri.state().theta, 1e-13);
            EXPECT_NEAR(end.omega, dopri.state().omega, 1e-13);
            const ExactPendulum fromStart(params, y0);
            for (const double s : {0.25, 0.5, 0.75}) {
                const PendulumState dense = dopri.interpolate(t0 + s * h);
                const PendulumState exact = fromStart.at(s * h);
                local = std::max({local, std::abs(dense.theta - exact.theta), std::abs(dense.omega - exact.omega)});
            }
            const PendulumState dense = dopri.interpolate(t0 + 0.5 * h);
            const PendulumState exact = global.at(t0 + 0.5 * h);
            globalTheta = std::max(globalTheta, std::abs(dense.theta - exact.theta));
            globalOmega = std::max(globalOmega, std::abs(dense.omega - exact.omega));
        }
        ASSERT_GT(steps, 20);
        EXPECT_GT(local, 0.0);
        EXPECT_LT(local, 20.0 * tol);
        EXPECT_LT(globalTheta, 100.0 * tol * kSixtyDegrees.theta);
        EXPECT_LT(globalOmega, 100.0 * tol * omegaScale);
    }
}

TEST(PendulumDopri5, AdvanceToLandsExactlyAndLandingKeepsTheProposal) {
    const PendulumParams params;
    physics::Dopri5 dopri(params, kSixtyDegrees, 1e-8);
    for (const double t : {0.1, 1.0 / 3.0, 2.0, 2.0 + 1e-9, 7.77, 7.0}) { // the last one backwards
        dopri.advanceTo(t);
        EXPECT_EQ(dopri.time(), t);
    }
    EXPECT_NEAR(dopri.state().theta, ExactPendulum(params, kSixtyDegrees).at(7.0).theta, 1e-6);
    const auto before = dopri.stats().accepted;
    while (dopri.time() < 9.5) {
        dopri.step(9.5);
        ASSERT_LE(dopri.time(), 9.5);
    }
    ASSERT_GT(dopri.stats().accepted, before + 5);
    EXPECT_EQ(dopri.time(), 9.5);

    // A step cut short to land on tEnd leaves the proposal as the controller made it.
    dopri.step();
    dopri.step();
    const double proposal = dopri.nextStep();
    const auto rejected = dopri.stats().rejected;
    const double start = dopri.time();
    dopri.step(start + 0.3 * proposal);
    ASSERT_EQ(dopri.stats().rejected, rejected);
    EXPECT_EQ(dopri.time(), start + 0.3 * proposal);
    EXPECT_EQ(dopri.nextStep(), proposal);
    // An open step takes the proposal.
    const double t1 = dopri.time();
    dopri.step();
    ASSERT_EQ(dopri.stats().rejected, rejected);
    EXPECT_EQ(dopri.time(), t1 + proposal);
}

TEST(PendulumDopri5, RejectsInvalidArgumentsNamingThem) {
    const PendulumParams params;
    const struct {
        double tolerance;
        const char* shown;
    } bad[] = {{0.0, "got 0"},
               {-1e-8, "got -1e-08"},
               {1e-15, "got 1e-15"},
               {2.0, "got 2"},
               {std::numeric_limits<double>::quiet_NaN(), "got nan"},
               {std::numeric_limits<double>::infinity(), "got inf"}};
    for (const auto& b : bad) {
        SCOPED_TRACE(b.shown);
        try {
            const physics::Dopri5 dopri(params, kSixtyDegrees, b.tolerance);
            ADD_FAILURE() << "accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("tolerance"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(b.shown), std::string::npos) << e.what();
        }
        EXPECT_THROW(Pendulum(Method::Dopri5, params, kSixtyDegrees, MidpointStart::Rk4, b.tolerance),
                     std::invalid_argument);
    }
    EXPECT_NO_THROW(physics::Dopri5(params, kSixtyDegrees, physics::kDopri5MinTolerance));
    EXPECT_NO_THROW(physics::Dopri5(params, kSixtyDegrees, physics::kDopri5MaxTolerance));
    EXPECT_THROW(physics::Dopri5(params, kSixtyDegrees, 1e-8, -0.01), std::invalid_argument);
    EXPECT_THROW(physics::Dopri5(params, kSixtyDegrees, 1e-8, std::numeric_limits<double>::infinity()),
                 std::invalid_argument);
    EXPECT_THROW(physics::Dopri5(params, {std::numeric_limits<double>::quiet_NaN(), 0.0}, 1e-8), std::invalid_argument);
    physics::Dopri5 dopri(params, kSixtyDegrees, 1e-8);
    EXPECT_THROW(dopri.advanceTo(std::numeric_limits<double>::infinity()), std::invalid_argument);
    EXPECT_THROW(dopri.step(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_EQ(dopri.time(), 0.0);
    const Pendulum pendulum(Method::Dopri5, params, kSixtyDegrees);
    EXPECT_EQ(pendulum.tolerance(), physics::kDefaultDopri5Tolerance);
}

TEST(PendulumDopri5, StopsWithAnErrorWhenTheStepUnderflows) {
    // A damping of 1e20 / s needs h < 3.3e-20 s, below the floor of 16 eps / omega0 = 1.1e-15 s: the
    // controller shrinks by 0.2 per rejection from the given 1 ms, then stops with an error instead of
    // looping; nothing accepted, nothing moved.
    PendulumParams stiff;
    stiff.damping = 1e20;
    physics::Dopri5 dopri(stiff, {0.5, 1.0}, 1e-8, 1e-3);
    EXPECT_THROW(dopri.advanceTo(1.0), std::runtime_error);
    EXPECT_GT(dopri.stats().rejected, 10);
    EXPECT_EQ(dopri.stats().accepted, 0);
    EXPECT_EQ(dopri.time(), 0.0);
    EXPECT_EQ(dopri.state().theta, 0.5);
    // The Pendulum is left as it was, and says so again on the next step.
    Pendulum pendulum(Method::Dopri5, stiff, {0.5, 1.0});
    EXPECT_THROW(pendulum.step(0.01), std::runtime_error);
    EXPECT_EQ(pendulum.time(), 0.0);
    EXPECT_EQ(pendulum.state().omega, 1.0);
    EXPECT_THROW(pendulum.step(0.01), std::runtime_error);
}

// ---------------------------------------------------------------------------------------------------------
// Pendulum::evaluations and the dopri5 pendulum's saved internals.

TEST(PendulumClass, EvaluationsCountEveryForceEvaluation) {
    const PendulumParams params;
    const int steps = 250;
    const double h = 0.02;
    // Fixed costs: evaluationsPerStep each step, plus verlet's and yoshida4's sin of the initial angle
    // (their first same as last).
    const struct {
        Method method;
        int start;
    } fixed[] = {{Method::Euler, 0},           {Method::EulerCartesian, 0}, {Method::Trapezoid, 0},
                 {Method::SymplecticEuler, 0}, {Method::Verlet, 1},         {Method::Rk4, 0},
                 {Method::Yoshida4, 1},        {Method::Exact, 0}};
    for (const auto& f : fixed) {
        SCOPED_TRACE(nameOf(f.method));
        Pendulum pendulum(f.method, params, kSixtyDegrees);
        EXPECT_EQ(pendulum.evaluations(), f.start);
        for (int i = 0; i < steps; ++i) pendulum.step(h);
        ASSERT_NEAR(pendulum.time(), steps * h, 1e-12);
        EXPECT_EQ(pendulum.evaluations(), f.start + steps * physics::evaluationsPerStep(f.method));
        pendulum.reset(kSixtyDegrees);
        EXPECT_EQ(pendulum.evaluations(), f.start);
    }
    EXPECT_EQ(Pendulum(Method::Verlet, params, kSixtyDegrees).evaluations(), 1);
    EXPECT_EQ(Pendulum(Method::Rk4, params, kSixtyDegrees).evaluations(), 0);

    // Midpoint: the start step at its own cost (rk4 4, euler 1), 1 per leapfrog step, and a new start when
    // the step changes.
    for (const MidpointStart start : {MidpointStart::Rk4, MidpointStart::Euler}) {
        Pendulum midpoint(Method::Midpoint, params, kSixtyDegrees, start);
        for (int i = 0; i < 10; ++i) midpoint.step(h);
        const int startCost = start == MidpointStart::Rk4 ? 4 : 1;
        EXPECT_EQ(midpoint.evaluations(), startCost + 9);
        midpoint.step(2.0 * h);
        EXPECT_EQ(midpoint.evaluations(), 2 * startCost + 9);
    }

    // Implicit midpoint: what its pure function reports, sin and cos alike.
    Pendulum implicit(Method::ImplicitMidpoint, params, kSixtyDegrees);
    PendulumState state = kSixtyDegrees;
    int reported = 0;
    for (int i = 0; i < steps; ++i) {
        implicit.step(h);
        state = physics::stepImplicitMidpoint(params, state, h, &reported);
    }
    EXPECT_EQ(implicit.state().theta, state.theta);
    EXPECT_GE(reported, 2 * steps);
    EXPECT_EQ(implicit.evaluations(), reported);

    // dopri5: its Dopri5's count, the Pendulum being exactly Dopri5::advanceTo its accumulated time.
    Pendulum dopri(Method::Dopri5, params, kSixtyDegrees);
    physics::Dopri5 reference(params, kSixtyDegrees, physics::kDefaultDopri5Tolerance);
    EXPECT_EQ(dopri.evaluations(), 2);
    for (int i = 0; i < steps; ++i) {
        dopri.step(i % 7 == 0 ? 0.15 : h); // some ticks longer than the controller's step
        reference.advanceTo(dopri.time());
        ASSERT_EQ(dopri.state().theta, reference.state().theta);
        ASSERT_EQ(dopri.state().omega, reference.state().omega);
    }
    ASSERT_GE(reference.stats().accepted, steps);
    EXPECT_EQ(dopri.evaluations(), reference.stats().evaluations);
    EXPECT_EQ(dopri.evaluations(), 6 * (reference.stats().accepted + reference.stats().rejected) + 2);

    // Internals with their counts (a keyframe's) go on from them; without (a save keeps none) setInternals
    // restarts the count: 0, or dopri5's f at the restored state.
    Pendulum verlet(Method::Verlet, params, kSixtyDegrees);
    verlet.step(h);
    const std::int64_t verletCount = verlet.evaluations(), dopriCount = dopri.evaluations();
    ASSERT_GT(verletCount, 0);
    Pendulum::Internals verletIn = verlet.internals(), dopriIn = dopri.internals();
    verlet.setInternals(verletIn);
    EXPECT_EQ(verlet.evaluations(), verletCount);
    dopri.setInternals(dopriIn);
    EXPECT_EQ(dopri.evaluations(), dopriCount);
    verletIn.counts.reset();
    dopriIn.counts.reset();
    verlet.setInternals(verletIn);
    EXPECT_EQ(verlet.evaluations(), 0);
    dopri.setInternals(dopriIn);
    EXPECT_EQ(dopri.evaluations(), 1);
}

TEST(PendulumClass, Dopri5ResumesBitForBitFromItsInternals) {
    const PendulumParams params;
    const PendulumState start{2.0, 1.0};
    Pendulum untouched(Method::Dopri5, params, start);
    Pendulum restored(Method::Dopri5, params, start);
    for (int i = 0; i < 137; ++i) {
        untouched.step(0.013);
        restored.step(0.013);
    }
    ASSERT_GT(untouched.evaluations(), 137 * 6);
    Pendulum::Internals in = restored.internals();
    EXPECT_EQ(in.time, untouched.time());
    EXPECT_GT(in.lastStep, 0.0); // the controller's next step
    restored.setInternals(in);
    EXPECT_EQ(restored.internals().lastStep, in.lastStep);
    for (int i = 0; i < 500; ++i) {
        const double h = 0.013 + 0.02 * (i % 3); // ticks shorter and longer than the controller's step
        untouched.step(h);
        restored.step(h);
        ASSERT_EQ(restored.state().theta, untouched.state().theta) << i;
        ASSERT_EQ(restored.state().omega, untouched.state().omega) << i;
        ASSERT_EQ(restored.time(), untouched.time()) << i;
    }

    // lastStep <= 0: a fresh first step is picked (one more evaluation, the heuristic's probe); the run goes
    // on as accurately, if not in the same bits.
    for (const double lastStep : {0.0, -1.0}) {
        in = untouched.internals();
        in.lastStep = lastStep;
        in.counts.reset(); // counted afresh, as after a load
        Pendulum fresh(Method::Dopri5, params, start);
        fresh.setInternals(in);
        EXPECT_EQ(fresh.evaluations(), 2);
        EXPECT_GT(fresh.internals().lastStep, 0.0);
        Pendulum reference = untouched;
        for (int i = 0; i < 100; ++i) {
            fresh.step(0.05);
            reference.step(0.05);
        }
        EXPECT_NEAR(fresh.state().theta, reference.state().theta, 1e-6);
    }
}

// ---------------------------------------------------------------------------------------------------------
// The seed's euler-cartesian: the position is stepped along the tangent of the Euler theta, so it leaves the
// circle (each step adds about h^2 v^2 / 2L to the radius: O(h) in all) and its angle parts from theta.

struct CartesianDrift {
    double rod = 0.0;       // rodLength - L at t = 10 s
    double angle = 0.0;     // |thetaFromPosition - theta| at t = 10 s
    double fromEuler = 0.0; // largest |theta - Euler's theta|: the angle is Euler's (up to FMA contraction)
};

CartesianDrift cartesianDrift(double h) {
    const PendulumParams params;
    Pendulum cartesian(Method::EulerCartesian, params, kSixtyDegrees);
    Pendulum euler(Method::Euler, params, kSixtyDegrees);
    CartesianDrift d;
    const int steps = static_cast<int>(std::lround(10.0 / h));
    for (int i = 0; i < steps; ++i) {
        cartesian.step(h);
        euler.step(h);
        d.fromEuler = std::max({d.fromEuler, std::abs(cartesian.state().theta - euler.state().theta),
                                std::abs(cartesian.state().omega - euler.state().omega)});
    }
    d.rod = cartesian.rodLength() - params.length;
    d.angle = std::abs(cartesian.thetaFromPosition() - cartesian.state().theta);
    return d;
}

TEST(PendulumEulerCartesian, RodLengthAndPositionAngleDriftInProportionToTheStep) {
    const CartesianDrift coarse = cartesianDrift(1e-3);
    const CartesianDrift mid = cartesianDrift(5e-4);
    const CartesianDrift fine = cartesianDrift(2.5e-4);
    EXPECT_LT(coarse.fromEuler, 1e-12);
    EXPECT_LT(fine.fromEuler, 1e-12);
    for (const CartesianDrift* d : {&coarse, &mid, &fine}) {
        EXPECT_GT(d->rod, 0.0); // stepping along a tangent only ever leaves the circle outwards
        EXPECT_GT(d->angle, 0.0);
    }
    // First order: halving the step halves the drift (the ratios measured are 1.94 and 1.97 for the rod).
    EXPECT_NEAR(coarse.rod / mid.rod, 2.0, 0.2);
    EXPECT_NEAR(mid.rod / fine.rod, 2.0, 0.2);
    EXPECT_NEAR(coarse.angle / mid.angle, 2.0, 0.3);
    EXPECT_NEAR(mid.angle / fine.angle, 2.0, 0.2);
    // At the game's tick the drift is gross.
    EXPECT_GT(cartesianDrift(1.0 / 60.0).rod, 0.1);
}

TEST(PendulumEulerCartesian, StartsOnTheCircleAndOtherMethodsReportTheirTheta) {
    const PendulumParams params;
    Pendulum cartesian(Method::EulerCartesian, params, {0.7, 0.0});
    EXPECT_DOUBLE_EQ(cartesian.rodLength(), params.length);
    EXPECT_NEAR(cartesian.thetaFromPosition(), 0.7, 1e-15);
    // One step from rest moves nothing (omega was 0): position still matches the starting angle.
    cartesian.step(0.01);
    EXPECT_NEAR(cartesian.bobX(), std::sin(0.7), 1e-15);

    Pendulum rk4(Method::Rk4, params, {7.0, 1.0}); // one full turn and a bit: theta is not wrapped
    for (int i = 0; i < 100; ++i) rk4.step(0.01);
    EXPECT_EQ(rk4.thetaFromPosition(), rk4.state().theta);
    EXPECT_EQ(rk4.rodLength(), params.length);
    EXPECT_DOUBLE_EQ(rk4.bobX(), std::sin(rk4.state().theta));
    EXPECT_DOUBLE_EQ(rk4.bobY(), std::cos(rk4.state().theta));
}

TEST(PendulumEulerCartesian, PositionAngleFollowsThetaThroughFullTurns) {
    // Rotating over the top: theta from the position is reported on theta's branch, not wrapped to (-pi, pi].
    Pendulum cartesian(Method::EulerCartesian, PendulumParams{}, {0.0, 9.0});
    for (int i = 0; i < 300; ++i) cartesian.step(1e-4);
    for (int i = 0; i < 30000; ++i) {
        cartesian.step(1e-4);
        ASSERT_LT(std::abs(cartesian.thetaFromPosition() - cartesian.state().theta), 0.1) << cartesian.time();
    }
    EXPECT_GT(cartesian.state().theta, 4.0 * kPi);
}

TEST(PendulumEulerCartesian, PureFunctionMatchesThePendulum) {
    const PendulumParams params;
    physics::EulerCartesianState s;
    s.angular = {0.9, -0.3};
    s.x = std::sin(0.9);
    s.y = std::cos(0.9);
    Pendulum p(Method::EulerCartesian, params, s.angular);
    for (int i = 0; i < 200; ++i) {
        s = physics::stepEulerCartesian(params, s, 0.01);
        p.step(0.01);
    }
    EXPECT_EQ(s.x, p.bobX());
    EXPECT_EQ(s.y, p.bobY());
    EXPECT_EQ(s.angular.theta, p.state().theta);
}

// ---------------------------------------------------------------------------------------------------------
// The midpoint's start. Theory: y[n] = u(t) + (-1)^n v(t); any start accurate to o(h^3) leaves a parasitic
// sawtooth v = O(h^3), Euler's O(h^2) start leaves v = O(h^2); both are second order overall.

// Amplitude of the sawtooth over the last two seconds before tEnd: the sixth difference of theta divided by
// 2^6 (a sawtooth is multiplied by 64, the smooth motion by h^6 theta^(6)).
double sawtooth(double h, MidpointStart start, double tEnd, const PendulumState& initial = kSixtyDegrees,
                double damping = 0.0) {
    PendulumParams params;
    params.damping = damping;
    Pendulum p(Method::Midpoint, params, initial, start);
    const int steps = static_cast<int>(std::lround(tEnd / h));
    const int window = static_cast<int>(std::lround(2.0 / h));
    std::vector<double> theta;
    theta.reserve(static_cast<std::size_t>(steps) + 1);
    theta.push_back(p.state().theta);
    for (int i = 0; i < steps; ++i) {
        p.step(h);
        theta.push_back(p.state().theta);
    }
    constexpr std::array<double, 7> kBinomial = {1, -6, 15, -20, 15, -6, 1};
    double largest = 0.0;
    for (int n = steps - window; n + 6 <= steps; ++n) {
        double d6 = 0.0;
        for (int j = 0; j < 7; ++j)
            d6 += kBinomial[static_cast<std::size_t>(j)] *
                  theta[static_cast<std::size_t>(n) + static_cast<std::size_t>(j)];
        largest = std::max(largest, std::abs(d6) / 64.0);
    }
    return largest;
}

TEST(PendulumMidpointStart, BothStartsAreSecondOrder) {
    for (const PendulumState& initial : {kSixtyDegrees, PendulumState{-0.5, 3.0}}) {
        for (MidpointStart start : {MidpointStart::Rk4, MidpointStart::Euler}) {
            SCOPED_TRACE(start == MidpointStart::Rk4 ? "rk4 start" : "euler start");
            const double e1 = angleError(Method::Midpoint, 2000, 10.0, initial, start);
            const double e2 = angleError(Method::Midpoint, 4000, 10.0, initial, start);
            const double e3 = angleError(Method::Midpoint, 8000, 10.0, initial, start);
            EXPECT_NEAR(observedOrder(e1, e2), 2.0, 0.1);
            EXPECT_NEAR(observedOrder(e2, e3), 2.0, 0.1);
        }
    }
}

TEST(PendulumMidpointStart, EulerStartLeavesAnOrderHSquaredSawtoothRk4StartOnlyHCubed) {
    for (const PendulumState& initial : {kSixtyDegrees, PendulumState{-0.5, 3.0}}) {
        const double euler1 = sawtooth(0.01, MidpointStart::Euler, 10.0, initial);
        const double euler2 = sawtooth(0.005, MidpointStart::Euler, 10.0, initial);
        const double rk1 = sawtooth(0.01, MidpointStart::Rk4, 10.0, initial);
        const double rk2 = sawtooth(0.005, MidpointStart::Rk4, 10.0, initial);
        const double rk3 = sawtooth(0.0025, MidpointStart::Rk4, 10.0, initial);
        EXPECT_NEAR(observedOrder(euler1, euler2), 2.0, 0.2) << euler1 << " " << euler2;
        EXPECT_NEAR(observedOrder(rk1, rk2), 3.0, 0.3) << rk1 << " " << rk2;
        EXPECT_NEAR(observedOrder(rk2, rk3), 3.0, 0.3) << rk2 << " " << rk3;
        // Their ratio grows like 1 / h; at h = 0.01 s it is already over an order of magnitude (30 to 750).
        EXPECT_GT(euler1, 10.0 * rk1);
    }
}

TEST(PendulumMidpointStart, WithDampingTheParasiticModeGrowsLikeExpHalfDampingT) {
    // Parasitic root for y' = lambda y is -(1 - h lambda) + O(h^2): |.| = 1 + h c / 2 for the damped
    // oscillator's lambda = -c/2 +- i omega. Measured between 40 s and 80 s, while it is still small.
    const double c = 0.2;
    const double at40 = sawtooth(0.01, MidpointStart::Rk4, 40.0, kSixtyDegrees, c);
    const double at80 = sawtooth(0.01, MidpointStart::Rk4, 80.0, kSixtyDegrees, c);
    EXPECT_NEAR(std::log(at80 / at40) / 40.0, c / 2.0, 0.15 * c / 2.0);
}

TEST(PendulumMidpointStart, ChangingTheStepRestartsTheHistoryFromTheCurrentState) {
    const PendulumParams params;
    for (MidpointStart start : {MidpointStart::Rk4, MidpointStart::Euler}) {
        Pendulum p(Method::Midpoint, params, kSixtyDegrees, start);
        EXPECT_EQ(p.midpointStart(), start);
        auto startStep = [&](const PendulumState& s, double h) {
            return start == MidpointStart::Rk4 ? physics::stepRk4(params, s, h) : physics::stepEuler(params, s, h);
        };
        // First step is the start step; then leapfrog steps.
        PendulumState previous = kSixtyDegrees;
        PendulumState current = startStep(previous, 0.01);
        p.step(0.01);
        EXPECT_EQ(p.state().theta, current.theta);
        for (int i = 0; i < 10; ++i) {
            const PendulumState next = physics::stepMidpoint(params, previous, current, 0.01);
            previous = current;
            current = next;
            p.step(0.01);
            EXPECT_EQ(p.state().theta, current.theta);
            EXPECT_EQ(p.state().omega, current.omega);
        }
        // A new step size: one start step from the current state, then leapfrog with the new size.
        previous = current;
        current = startStep(current, 0.004);
        p.step(0.004);
        EXPECT_EQ(p.state().theta, current.theta);
        EXPECT_EQ(p.state().omega, current.omega);
        const PendulumState next = physics::stepMidpoint(params, previous, current, 0.004);
        p.step(0.004);
        EXPECT_EQ(p.state().theta, next.theta);
        EXPECT_NEAR(p.time(), 0.11 + 0.008, 1e-15);
    }
}

TEST(PendulumMidpointStart, VariableStepsStillConvergeAtFirstOrderAtWorst) {
    // Alternating steps restart every time: the scheme degenerates to its start method, which converges.
    const PendulumParams params;
    Pendulum p(Method::Midpoint, params, kSixtyDegrees);
    for (int i = 0; i < 1000; ++i) p.step(i % 2 == 0 ? 0.004 : 0.006);
    EXPECT_NEAR(p.state().theta, ExactPendulum(params, kSixtyDegrees).at(p.time()).theta, 1e-7);
}

} // namespace
