// The closed-form pendulum (ExactPendulum, periodRatio), checked against known periods, against rk4 at a
// tiny step, against independent closed forms (small-angle series, the separatrix's 4 atan(e^t) - pi), and
// against its own invariants: energy, symmetry in time, periodicity far from t = 0.
#include "physics/pendulum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace {

using physics::ExactPendulum;
using physics::PendulumParams;
using physics::PendulumState;

constexpr double kPi = 3.141592653589793238462643383279;
constexpr double kDegree = kPi / 180.0;
const PendulumParams kParams; // L = 1 m, g = 9.81 m/s^2
const double kOmega0 = physics::smallAngleFrequency(kParams);
const double kT0 = 2.0 * kPi / kOmega0;

std::string describe(const PendulumState& s) {
    return "theta0=" + std::to_string(s.theta) + " omega0=" + std::to_string(s.omega);
}

// rk4 with a step of 5e-4 s: its own error at 10 s is below 1e-11 rad for these states.
PendulumState rk4At(const PendulumState& initial, double t, double h = 5e-4) {
    PendulumState s = initial;
    const int steps = static_cast<int>(std::lround(t / h));
    for (int i = 0; i < steps; ++i) s = physics::stepRk4(kParams, s, h);
    return s;
}

// The n-th time theta crosses zero going in `direction` (+1 up, -1 down) after t = 0, by bisection.
double zeroCrossing(const ExactPendulum& exact, int n, double direction) {
    const double dt = 1e-3;
    double t = 0.0;
    double before = exact.at(t).theta;
    for (int found = 0;;) {
        const double after = exact.at(t + dt).theta;
        if (direction * before < 0.0 && direction * after >= 0.0 && ++found == n) break;
        before = after;
        t += dt;
    }
    double lo = t;
    double hi = t + dt;
    for (int i = 0; i < 80; ++i) {
        const double mid = 0.5 * (lo + hi);
        (direction * exact.at(mid).theta < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// ---------------------------------------------------------------------------------------------------------
// Periods

TEST(PendulumExactPeriod, PeriodRatioMatchesTheTabulatedValues) {
    // T / T0 = 2 K(sin(a / 2)) / pi, tabulated to six figures.
    EXPECT_NEAR(physics::periodRatio(60.0 * kDegree), 1.07318, 5e-6);
    EXPECT_NEAR(physics::periodRatio(90.0 * kDegree), 1.18034, 5e-6);
    EXPECT_NEAR(physics::periodRatio(179.0 * kDegree), 3.90107, 5e-6);
    EXPECT_NEAR(physics::periodRatio(0.0), 1.0, 1e-15);
    EXPECT_EQ(physics::periodRatio(-1.0), physics::periodRatio(1.0));
}

TEST(PendulumExactPeriod, SmallAmplitudesFollowTheSeries) {
    // T / T0 = 1 + a^2 / 16 + 11 a^4 / 3072 + 173 a^6 / 737280 + O(a^8).
    for (double a : {1e-4, 1e-2, 0.05, 0.1}) {
        const double series = 1.0 + a * a / 16.0 + 11.0 * std::pow(a, 4) / 3072.0 + 173.0 * std::pow(a, 6) / 737280.0;
        EXPECT_NEAR(physics::periodRatio(a), series, 1e-12) << a;
    }
}

TEST(PendulumExactPeriod, ZeroCrossingsOfTheSolutionRepeatWithThePeriod) {
    const struct {
        double amplitude;
        double ratio;
    } cases[] = {{60.0, 1.07318}, {90.0, 1.18034}, {179.0, 3.90107}};
    for (const auto& c : cases) {
        SCOPED_TRACE(std::to_string(c.amplitude) + " degrees");
        const ExactPendulum exact(kParams, {c.amplitude * kDegree, 0.0});
        // Released from rest at a > 0 it first crosses zero going down, at T / 4.
        const double first = zeroCrossing(exact, 1, -1.0);
        const double second = zeroCrossing(exact, 2, -1.0);
        const double measured = (second - first) / kT0;
        EXPECT_NEAR(measured, c.ratio, 5e-6);
        EXPECT_NEAR(measured, physics::periodRatio(c.amplitude * kDegree), 1e-10);
        EXPECT_NEAR(exact.period() / kT0, measured, 1e-10);
        EXPECT_NEAR(first, exact.period() / 4.0, 1e-10);
        const double upward = zeroCrossing(exact, 1, +1.0);
        EXPECT_NEAR(upward - first, exact.period() / 2.0, 1e-10);
    }
}

TEST(PendulumExactPeriod, TurningPointsAreReachedExactly) {
    // Released from rest at a: theta(T/2) = -a, theta(T) = a, omega = 0 at both; also near the top, where
    // dn(u) must be right at u = K, 3K (Boost's own dn is not).
    for (double a : {30.0, 90.0, 150.0, 179.0, 179.9}) {
        SCOPED_TRACE(std::to_string(a) + " degrees");
        const ExactPendulum exact(kParams, {a * kDegree, 0.0});
        const double period = exact.period();
        EXPECT_NEAR(exact.at(0.5 * period).theta, -a * kDegree, 1e-13);
        EXPECT_NEAR(exact.at(period).theta, a * kDegree, 1e-13);
        EXPECT_NEAR(exact.at(0.5 * period).omega, 0.0, 1e-12);
        EXPECT_NEAR(exact.at(1.5 * period).theta, -a * kDegree, 1e-13);
        EXPECT_NEAR(exact.at(0.0).theta, a * kDegree, 1e-15);
        EXPECT_NEAR(exact.at(0.0).omega, 0.0, 1e-15);
    }
}

// ---------------------------------------------------------------------------------------------------------
// Agreement with an independent integration

TEST(PendulumExactAgreement, MatchesRk4AtATinyStepForSwingingAndRotatingStates) {
    const PendulumState states[] = {
        {60.0 * kDegree, 0.0}, {90.0 * kDegree, 0.0}, {-0.5, 3.0}, // swinging, moving, negative angle
        {2.0, -1.5},           {-2.9, 0.4},           {0.0, -6.0}, // swinging high, from the bottom
        {0.0, 2.5 * kOmega0},  {1.0, -7.0},           {-2.0, 9.0}, // rotating both ways
    };
    for (const PendulumState& s : states) {
        SCOPED_TRACE(describe(s));
        const ExactPendulum exact(kParams, s);
        for (double t : {2.5, 10.0}) {
            const PendulumState reference = rk4At(s, t);
            EXPECT_NEAR(exact.at(t).theta, reference.theta, 1e-10) << "t=" << t;
            EXPECT_NEAR(exact.at(t).omega, reference.omega, 1e-10) << "t=" << t;
        }
    }
}

TEST(PendulumExactAgreement, ReproducesTheInitialStateForAnyStart) {
    const PendulumState states[] = {{0.0, 0.0},   {1e-9, 0.0},     {-0.5, 3.0},
                                    {3.1, 0.01},  {-3.14159, 0.0}, {0.0, 2.0 * kOmega0 * (1.0 - 1e-12)},
                                    {0.0, -30.0}, {20.0, 1.0},     {-8.0, -0.5}};
    for (const PendulumState& s : states) {
        SCOPED_TRACE(describe(s));
        const ExactPendulum exact(kParams, s);
        EXPECT_NEAR(exact.at(0.0).theta, s.theta, 4e-15 * std::max(1.0, std::abs(s.theta)));
        EXPECT_NEAR(exact.at(0.0).omega, s.omega, 4e-15 * std::max(1.0, std::abs(s.omega)));
    }
}

TEST(PendulumExactAgreement, WholeTurnsInTheInitialAngleOnlyShiftTheAngle) {
    const ExactPendulum base(kParams, {0.4, 1.2});
    const ExactPendulum turned(kParams, {0.4 + 4.0 * kPi, 1.2});
    for (double t : {0.0, 0.7, 3.3, 12.0}) {
        EXPECT_NEAR(turned.at(t).theta - base.at(t).theta, 4.0 * kPi, 1e-13);
        EXPECT_NEAR(turned.at(t).omega, base.at(t).omega, 1e-13);
    }
}

// ---------------------------------------------------------------------------------------------------------
// Invariants

TEST(PendulumExactInvariants, EnergyIsConservedForMinutes) {
    const PendulumState states[] = {
        {60.0 * kDegree, 0.0}, {179.0 * kDegree, 0.0}, {-0.5, 3.0}, {0.0, 2.5 * kOmega0}, {1.0, -7.0}};
    const double scale = kParams.mass * kParams.gravity * kParams.length; // energies are of this size
    for (const PendulumState& s : states) {
        SCOPED_TRACE(describe(s));
        const ExactPendulum exact(kParams, s);
        const double e0 = physics::energy(kParams, s);
        double worst = 0.0;
        for (double t = 0.0; t <= 600.0; t += 0.0137) {
            worst = std::max(worst, std::abs(physics::energy(kParams, exact.at(t)) - e0));
        }
        EXPECT_LT(worst, 1e-12 * scale);
    }
}

TEST(PendulumExactInvariants, TimeReversalFromRest) {
    // Released from rest, the motion is even in t: theta(-t) = theta(t), omega(-t) = -omega(t).
    const ExactPendulum exact(kParams, {2.0, 0.0});
    for (double t : {0.1, 1.7, 9.3, 61.0}) {
        EXPECT_NEAR(exact.at(-t).theta, exact.at(t).theta, 1e-13);
        EXPECT_NEAR(exact.at(-t).omega, -exact.at(t).omega, 1e-13);
    }
}

TEST(PendulumExactInvariants, FarFromTheStartTheArgumentReductionKeepsFullAccuracy) {
    // at(t) must equal at(t mod T), and after n whole periods the initial state must come back: this is what
    // reducing the elliptic argument by the period buys (unreduced, the error grows with |t|).
    const PendulumState states[] = {{60.0 * kDegree, 0.0}, {-0.5, 3.0}, {170.0 * kDegree, 0.0}, {0.0, 2.5 * kOmega0}};
    for (const PendulumState& s : states) {
        SCOPED_TRACE(describe(s));
        const ExactPendulum exact(kParams, s);
        const double period = exact.period();
        const bool rotating = exact.modulus() > 1.0;
        for (double t : {300.0, 599.9, -300.0}) {
            const double turns = std::floor(t / period);
            const double reduced = t - turns * period;
            const double wrap = rotating ? 2.0 * kPi * turns * (s.omega > 0 ? 1.0 : -1.0) : 0.0;
            EXPECT_NEAR(exact.at(t).theta, exact.at(reduced).theta + wrap, 1e-11) << "t=" << t;
            EXPECT_NEAR(exact.at(t).omega, exact.at(reduced).omega, 1e-11) << "t=" << t;
        }
        for (int n : {1, 10, 100, 250}) {
            const double wrap = rotating ? 2.0 * kPi * n * (s.omega > 0 ? 1.0 : -1.0) : 0.0;
            EXPECT_NEAR(exact.at(n * period).theta, s.theta + wrap, 2e-12) << "n=" << n;
            EXPECT_NEAR(exact.at(n * period).omega, s.omega, 2e-12) << "n=" << n;
        }
    }
}

// ---------------------------------------------------------------------------------------------------------
// Over the top and on the separatrix

TEST(PendulumExactRegimes, RotatingPendulumTurnsMonotonicallyWithPeriodicSpeed) {
    for (double direction : {1.0, -1.0}) {
        const PendulumState start{0.3, direction * 2.5 * kOmega0};
        SCOPED_TRACE(describe(start));
        const ExactPendulum exact(kParams, start);
        EXPECT_GT(exact.modulus(), 1.0);
        EXPECT_EQ(exact.regime(), ExactPendulum::Regime::Rotating);
        const double period = exact.period();
        ASSERT_TRUE(std::isfinite(period));
        double previous = exact.at(0.0).theta;
        for (double t = 0.005; t < 20.0; t += 0.005) {
            const PendulumState s = exact.at(t);
            ASSERT_GT(direction * (s.theta - previous), 0.0) << "t=" << t;
            ASSERT_GT(direction * s.omega, 0.0) << "t=" << t;
            // One period later: omega repeats, theta has gained one full turn.
            const PendulumState later = exact.at(t + period);
            ASSERT_NEAR(later.omega, s.omega, 1e-12);
            ASSERT_NEAR(later.theta - s.theta, direction * 2.0 * kPi, 1e-12);
            previous = s.theta;
        }
        // The slowest speed is at the top, where energy gives omega^2 = 4 omega0^2 (k^2 - 1).
        const double k = exact.modulus();
        const double topSpeed = 2.0 * kOmega0 * std::sqrt(k * k - 1.0);
        double slowest = std::numeric_limits<double>::infinity();
        for (double t = 0.0; t < period; t += period / 4000.0) slowest = std::min(slowest, std::abs(exact.at(t).omega));
        EXPECT_NEAR(slowest, topSpeed, 1e-4);
        const PendulumState reference = rk4At(start, 10.0);
        EXPECT_NEAR(exact.at(10.0).theta, reference.theta, 1e-10);
    }
}

TEST(PendulumExactRegimes, SeparatrixApproachesTheTopAndNeverArrives) {
    for (double direction : {1.0, -1.0}) {
        const PendulumState start{0.0, direction * 2.0 * kOmega0}; // exactly the energy of the top
        SCOPED_TRACE(describe(start));
        const ExactPendulum exact(kParams, start);
        EXPECT_EQ(exact.modulus(), 1.0);
        EXPECT_EQ(exact.regime(), ExactPendulum::Regime::Separatrix);
        EXPECT_EQ(exact.complementaryModulus(), 0.0);
        EXPECT_TRUE(std::isinf(exact.period()));
        double previous = 0.0;
        for (double t = 0.01; t <= 30.0; t += 0.01) {
            const PendulumState s = exact.at(t);
            // theta = 4 atan(exp(omega0 t)) - pi, an independent closed form.
            const double closed = direction * (4.0 * std::atan(std::exp(kOmega0 * t)) - kPi);
            ASSERT_NEAR(s.theta, closed, 1e-14) << "t=" << t;
            ASSERT_LE(std::abs(s.theta), kPi) << "t=" << t; // pi - theta drops below an ulp of pi after 12 s
            ASSERT_GE(direction * (s.theta - previous), 0.0) << "t=" << t;
            previous = s.theta;
        }
        EXPECT_LT(kPi - std::abs(exact.at(10.0).theta), 1e-12);
        // The saddle amplifies every error by exp(omega0 t): rk4's 1e-14 per step becomes ~1e-9 by 3 s.
        for (double t : {1.0, 2.0, 3.0}) {
            const PendulumState reference = rk4At(start, t, 1e-3);
            EXPECT_NEAR(exact.at(t).theta, reference.theta, 1e-8) << "t=" << t;
            EXPECT_NEAR(exact.at(t).omega, reference.omega, 1e-8) << "t=" << t;
        }
    }
}

TEST(PendulumExactRegimes, SeparatrixFromAnyPointOnItAndItsNeighboursOnBothSides) {
    // On the separatrix, omega = 2 omega0 cos(theta / 2) wherever the bob is.
    const double theta0 = 1.0;
    const double omegaOn = 2.0 * kOmega0 * std::cos(0.5 * theta0);
    const ExactPendulum on(kParams, {theta0, omegaOn});
    EXPECT_EQ(on.modulus(), 1.0);
    EXPECT_LT(kPi - on.at(15.0).theta, 1e-12);
    // Just below it swings back, just above it goes over; for the first seconds all three agree closely.
    const ExactPendulum below(kParams, {theta0, omegaOn * (1.0 - 1e-9)});
    const ExactPendulum above(kParams, {theta0, omegaOn * (1.0 + 1e-9)});
    EXPECT_EQ(on.regime(), ExactPendulum::Regime::Separatrix);
    EXPECT_EQ(below.regime(), ExactPendulum::Regime::Swinging);
    EXPECT_EQ(above.regime(), ExactPendulum::Regime::Rotating);
    EXPECT_LT(below.modulus(), 1.0);
    EXPECT_GT(above.modulus(), 1.0);
    for (double t : {0.5, 1.0, 2.0}) {
        EXPECT_NEAR(below.at(t).theta, on.at(t).theta, 1e-6) << t;
        EXPECT_NEAR(above.at(t).theta, on.at(t).theta, 1e-6) << t;
    }
    EXPECT_LT(below.at(below.period() / 2.0).theta, 0.0);                 // came back down and over the bottom
    EXPECT_GT(above.at(above.period()).theta - theta0, 2.0 * kPi - 1e-9); // one full turn later
    EXPECT_TRUE(std::isfinite(below.period()));
    EXPECT_TRUE(std::isfinite(above.period()));
}

TEST(PendulumExactRegimes, AlmostUprightAtRestEventuallyFalls) {
    // pi is not a double: the nearest one is 1.2e-16 rad short of the top, so the pendulum falls back after
    // about ln(8 / 1.2e-16) / omega0 = 12.4 s and swings with the period 4 K(k) / omega0 = 49.4 s.
    const ExactPendulum exact(kParams, {kPi, 0.0});
    EXPECT_EQ(exact.modulus(), 1.0); // k = 1 - 2e-33 rounds to 1; the regime and k' still know better
    EXPECT_EQ(exact.regime(), ExactPendulum::Regime::Swinging);
    EXPECT_NEAR(exact.complementaryModulus(), std::cos(0.5 * kPi), 1e-30);
    EXPECT_NEAR(exact.at(5.0).theta, kPi, 1e-8);
    EXPECT_LT(exact.at(14.0).theta, 0.0);
    EXPECT_NEAR(exact.period(), 49.447, 1e-3);
    EXPECT_NEAR(exact.at(exact.period() / 2.0).theta, -kPi, 1e-12);
}

// ---------------------------------------------------------------------------------------------------------
// Contract

TEST(PendulumExactContract, RejectsDampingAndBadInput) {
    PendulumParams damped;
    damped.damping = 0.05;
    EXPECT_THROW(ExactPendulum(damped, {0.5, 0.0}), std::invalid_argument);
    PendulumParams bad;
    bad.length = -1.0;
    EXPECT_THROW(ExactPendulum(bad, {0.5, 0.0}), std::invalid_argument);
    EXPECT_THROW(ExactPendulum(kParams, {std::numeric_limits<double>::quiet_NaN(), 0.0}), std::invalid_argument);
    const ExactPendulum exact(kParams, {0.5, 0.0});
    EXPECT_TRUE(std::isnan(exact.at(std::numeric_limits<double>::infinity()).theta));
}

TEST(PendulumExactContract, ThePendulumWrapperFollowsTheClosedFormAtItsAccumulatedTime) {
    const PendulumState start{-1.2, 0.8};
    physics::Pendulum pendulum(physics::Method::Exact, kParams, start);
    const ExactPendulum exact(kParams, start);
    for (int i = 0; i < 600; ++i) pendulum.step(1.0 / 60.0);
    EXPECT_NEAR(pendulum.time(), 10.0, 1e-13);
    EXPECT_NEAR(pendulum.state().theta, exact.at(10.0).theta, 1e-12);
    EXPECT_EQ(pendulum.rodLength(), kParams.length);
}

TEST(PendulumExactContract, OtherLengthsAndGravityScaleTime) {
    // Same angles, time scaled by omega0: a 4 m pendulum on the Moon.
    PendulumParams moon;
    moon.length = 4.0;
    moon.gravity = 1.62;
    const double ratio = physics::smallAngleFrequency(kParams) / physics::smallAngleFrequency(moon);
    const ExactPendulum earth(kParams, {1.0, 2.0});
    const ExactPendulum there(moon, {1.0, 2.0 / ratio});
    for (double t : {0.3, 2.0, 7.0}) {
        EXPECT_NEAR(there.at(t * ratio).theta, earth.at(t).theta, 1e-12);
        EXPECT_NEAR(there.at(t * ratio).omega * ratio, earth.at(t).omega, 1e-12);
    }
    EXPECT_NEAR(there.period(), earth.period() * ratio, 1e-12);
}

} // namespace
