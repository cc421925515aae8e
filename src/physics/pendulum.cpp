// The integrators and the Pendulum wrapper. Every stepper is a handful of multiply-adds around its sin
// calls, computes g / L once, and touches nothing but its arguments (see pendulum.h for the contract).
#include "physics/pendulum.h"

#include "core/quote.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace physics {

namespace {

constexpr std::array<std::string_view, kMethodCount> kMethodNames = {
    "euler",    "euler-cartesian", "midpoint", "trapezoid", "symplectic-euler", "verlet", "rk4", "implicit-midpoint",
    "yoshida4", "dopri5",          "exact"};

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Angular acceleration for a given (-(g/L) sin(theta)) term already computed.
inline double accel(double w2Sin, double damping, double omega) { return -w2Sin - damping * omega; }

// Yoshida's triple-jump weights: w1 = 1 / (2 - 2^(1/3)) and w0 = -2^(1/3) w1, to 20 digits (mpmath), so
// that w1 + w0 + w1 = 1 and w1^3 + w0^3 + w1^3 = 0 (the third-order error terms cancel) to rounding.
constexpr double kYoshidaOuter = 1.3512071919596576340;
constexpr double kYoshidaInner = -1.7024143839193152681;

constexpr double kInverseSqrt2 = 0.70710678118654752440; // for the root mean square of two components

// Dormand-Prince 5(4) (Dormand and Prince 1980; Hairer, Norsett, Wanner, Solving ODEs I, table II.5.2),
// nodes 0, 1/5, 3/10, 4/5, 8/9, 1, 1. Rows of the stage matrix:
constexpr std::array<double, 1> kDopriA2 = {1.0 / 5.0};
constexpr std::array<double, 2> kDopriA3 = {3.0 / 40.0, 9.0 / 40.0};
constexpr std::array<double, 3> kDopriA4 = {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0};
constexpr std::array<double, 4> kDopriA5 = {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0};
constexpr std::array<double, 5> kDopriA6 = {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0,
                                            -5103.0 / 18656.0};
// Fifth-order weights, also the last stage's row: its stage is f at the new point (first same as last).
constexpr std::array<double, 6> kDopriB = {35.0 / 384.0,     0.0,        500.0 / 1113.0, 125.0 / 192.0,
                                           -2187.0 / 6784.0, 11.0 / 84.0};
// Fifth- minus fourth-order weights (the fourth order's are 5179/57600, 0, 7571/16695, 393/640,
// -92097/339200, 187/2100, 1/40): h times their combination of the stages is the error estimate.
constexpr std::array<double, 7> kDopriE = {71.0 / 57600.0,      0.0,          -71.0 / 16695.0, 71.0 / 1920.0,
                                           -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};
// The continuous extension's free term r5 = h sum d_i k_i (Dormand and Prince's dense output, as Hairer
// gives it). With r2 = y1 - y0, r3 = h k1 - r2 and r4 = r2 - h k7 - r3 the weights of
// y0 + s (r2 + (1 - s) (r3 + s (r4 + (1 - s) r5))) satisfy the eight order conditions up to order 4
// identically in s (checked in exact rational arithmetic), equal the fifth-order weights at s = 1, and
// have slope k1 at s = 0 and k7 at s = 1.
constexpr std::array<double, 7> kDopriDense = {-12715105075.0 / 11282082432.0,  0.0,
                                               87487479700.0 / 32700410799.0,   -10690763975.0 / 1880347072.0,
                                               701980252875.0 / 199316789632.0, -1453857185.0 / 822651844.0,
                                               69997945.0 / 29380423.0};
// Step-size controller: h_new = h clamp(kSafety err^(-1/5), kMinGrowth, kMaxGrowth).
constexpr double kSafety = 0.9, kMinGrowth = 0.2, kMaxGrowth = 10.0;

// The stages k_i = f(y_i), each a (dtheta/dt, domega/dt) pair.
using DopriStages = std::array<PendulumState, 7>;

// f(y) = (omega, -(g/L) sin(theta) - c omega): one force evaluation.
PendulumState slopeAt(double w2, double damping, const PendulumState& y) {
    return {y.omega, accel(w2 * std::sin(y.theta), damping, y.omega)};
}

// y + h sum_j a_j k_j over the first N stages.
template <std::size_t N>
PendulumState combine(const PendulumState& y, double h, const std::array<double, N>& a, const DopriStages& k) {
    double dTheta = 0.0;
    double dOmega = 0.0;
    for (std::size_t j = 0; j < N; ++j) {
        dTheta += a[j] * k[j].theta;
        dOmega += a[j] * k[j].omega;
    }
    return {y.theta + h * dTheta, y.omega + h * dOmega};
}

// Factor for the next step from a scaled error: kSafety err^(-1/5), within [kMinGrowth, maxGrowth]. An
// error of 0 allows maxGrowth; NaN (a non-finite stage) shrinks as far as allowed.
double stepFactor(double err, double maxGrowth) {
    if (std::isnan(err)) return kMinGrowth;
    if (err == 0.0) return maxGrowth;
    return std::clamp(kSafety * std::pow(err, -0.2), kMinGrowth, maxGrowth);
}

void validateTolerance(double tolerance) {
    if (!(tolerance >= kDopri5MinTolerance && tolerance <= kDopri5MaxTolerance))
        throw std::invalid_argument("dopri5: tolerance must be within [1e-14, 1], got " +
                                    core::numberForMessage(tolerance));
}

bool validIndex(Method method) {
    const int i = static_cast<int>(method);
    return i >= 0 && i < kMethodCount;
}

} // namespace

std::string_view methodName(Method method) {
    return validIndex(method) ? kMethodNames[static_cast<std::size_t>(method)] : std::string_view{};
}

std::optional<Method> methodFromName(std::string_view name) {
    for (int i = 0; i < kMethodCount; ++i) {
        if (kMethodNames[static_cast<std::size_t>(i)] == name) return static_cast<Method>(i);
    }
    return std::nullopt;
}

int evaluationsPerStep(Method method) {
    switch (method) {
    case Method::Euler:
        return 1;
    case Method::EulerCartesian:
        return 1;
    case Method::Midpoint:
        return 1;
    case Method::Trapezoid:
        return 2;
    case Method::SymplecticEuler:
        return 1;
    case Method::Verlet:
        return 1;
    case Method::Rk4:
        return 4;
    case Method::ImplicitMidpoint:
        return 0; // varies: see Pendulum::evaluations()
    case Method::Yoshida4:
        return 3;
    case Method::Dopri5:
        return 0; // varies: see Pendulum::evaluations()
    case Method::Exact:
        return 0;
    case Method::Count:
        break;
    }
    return -1;
}

double linearStabilityLimit(Method method) {
    switch (method) {
    case Method::Euler:
    case Method::EulerCartesian:
    case Method::Trapezoid:
        return 0.0;
    case Method::Midpoint:
        return 1.0;
    case Method::SymplecticEuler:
    case Method::Verlet:
        return 2.0;
    case Method::Rk4:
        return 2.0 * std::sqrt(2.0);
    case Method::Yoshida4:
        return kYoshida4StabilityLimit;
    case Method::ImplicitMidpoint: // A-stable
    case Method::Dopri5:           // adaptive: the controller shrinks the step (see pendulum.h)
    case Method::Exact:
        return std::numeric_limits<double>::infinity();
    case Method::Count:
        break;
    }
    return 0.0;
}

double energy(const PendulumParams& p, const PendulumState& s) {
    const double speed = p.length * s.omega;
    return p.mass * (-p.gravity * p.length * std::cos(s.theta) + 0.5 * speed * speed);
}

double smallAngleFrequency(const PendulumParams& p) { return std::sqrt(p.gravity / p.length); }

PendulumState stepEuler(const PendulumParams& p, const PendulumState& s, double h) {
    const double w2 = p.gravity / p.length;
    return {s.theta + h * s.omega, s.omega + h * accel(w2 * std::sin(s.theta), p.damping, s.omega)};
}

PendulumState stepTrapezoid(const PendulumParams& p, const PendulumState& s, double h) {
    const double w2 = p.gravity / p.length;
    const double a0 = accel(w2 * std::sin(s.theta), p.damping, s.omega);
    const double thetaP = s.theta + h * s.omega; // Euler predictor
    const double omegaP = s.omega + h * a0;
    const double a1 = accel(w2 * std::sin(thetaP), p.damping, omegaP);
    return {s.theta + 0.5 * h * (s.omega + omegaP), s.omega + 0.5 * h * (a0 + a1)};
}

PendulumState stepSymplecticEuler(const PendulumParams& p, const PendulumState& s, double h) {
    const double w2 = p.gravity / p.length;
    const double theta = s.theta + h * s.omega;
    return {theta, s.omega + h * accel(w2 * std::sin(theta), p.damping, s.omega)};
}

PendulumState stepVerletFsal(const PendulumParams& p, const PendulumState& s, double h, double& sinTheta) {
    const double w2 = p.gravity / p.length;
    const double halfH = 0.5 * h;
    const double omegaHalf = s.omega + halfH * accel(w2 * sinTheta, p.damping, s.omega);
    const double theta = s.theta + h * omegaHalf;
    sinTheta = std::sin(theta);
    // omega1 = omegaHalf + h/2 (-w2 sin(theta1) - c omega1), solved for omega1.
    const double omega = (omegaHalf - halfH * w2 * sinTheta) / (1.0 + halfH * p.damping);
    return {theta, omega};
}

PendulumState stepVerlet(const PendulumParams& p, const PendulumState& s, double h) {
    double sinTheta = std::sin(s.theta);
    return stepVerletFsal(p, s, h, sinTheta);
}

PendulumState stepRk4(const PendulumParams& p, const PendulumState& s, double h) {
    const double w2 = p.gravity / p.length;
    const double c = p.damping;
    const double halfH = 0.5 * h;
    const double t1 = s.omega;
    const double o1 = accel(w2 * std::sin(s.theta), c, s.omega);
    const double t2 = s.omega + halfH * o1;
    const double o2 = accel(w2 * std::sin(s.theta + halfH * t1), c, t2);
    const double t3 = s.omega + halfH * o2;
    const double o3 = accel(w2 * std::sin(s.theta + halfH * t2), c, t3);
    const double t4 = s.omega + h * o3;
    const double o4 = accel(w2 * std::sin(s.theta + h * t3), c, t4);
    const double sixth = h / 6.0;
    return {s.theta + sixth * (t1 + 2.0 * (t2 + t3) + t4), s.omega + sixth * (o1 + 2.0 * (o2 + o3) + o4)};
}

EulerCartesianState stepEulerCartesian(const PendulumParams& p, const EulerCartesianState& s, double h) {
    const double w2 = p.gravity / p.length;
    const double sinT = std::sin(s.angular.theta);
    const double speed = h * s.angular.omega * p.length; // arc length travelled this step
    EulerCartesianState out;
    out.x = s.x + speed * std::cos(s.angular.theta);
    out.y = s.y - speed * sinT; // y down: d(L cos theta) = -L sin(theta) dtheta
    out.angular = {s.angular.theta + h * s.angular.omega,
                   s.angular.omega + h * accel(w2 * sinT, p.damping, s.angular.omega)};
    return out;
}

PendulumState stepMidpoint(const PendulumParams& p, const PendulumState& previous, const PendulumState& current,
                           double h) {
    const double w2 = p.gravity / p.length;
    const double twoH = 2.0 * h;
    return {previous.theta + twoH * current.omega,
            previous.omega + twoH * accel(w2 * std::sin(current.theta), p.damping, current.omega)};
}

PendulumState stepImplicitMidpoint(const PendulumParams& p, const PendulumState& s, double h, int* evaluations) {
    const double w2 = p.gravity / p.length;
    const double halfH = 0.5 * h;
    // The midpoint is (x, omegaMid) with x = theta0 + h/2 omegaMid and omegaMid = omega0 + h/2 (-w2 sin(x) -
    // c omegaMid), so omegaMid (1 + c h/2) = omega0 - h/2 w2 sin(x) and F(x) = x - b + k sin(x) = 0.
    const double damp = 1.0 + halfH * p.damping;
    const double b = s.theta + halfH * s.omega / damp; // the midpoint angle if there were no force
    const double k = halfH * halfH * w2 / damp;
    // F(b - |k|) = -|k| + k sin(.) <= 0 <= F(b + |k|) = |k| + k sin(.): a root lies in between. The bracket
    // [lo, hi] keeps F(lo) <= 0 <= F(hi) as it shrinks.
    double lo = b - std::abs(k);
    double hi = b + std::abs(k);
    double x = b;
    double sinX = 0.0;
    double previousUpdate = hi - lo;
    int count = 0;
    bool converged = false;
    for (int i = 0; i < kImplicitMidpointMaxIterations; ++i) {
        const double sinI = std::sin(x);
        const double cosI = std::cos(x);
        count += 2;
        const double f = x - b + k * sinI;
        if (f == 0.0) {
            sinX = sinI;
            converged = true;
            break;
        }
        (f < 0.0 ? lo : hi) = x;
        // Newton unless it leaves the bracket or fails to halve the previous update (then bisect, which
        // halves the bracket). A zero slope gives an infinite Newton point, which fails the test. An update
        // within the tolerance is taken as it is: rounding can put x + update on the bracket's edge.
        const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * std::abs(x);
        const double slope = 1.0 + k * cosI;
        const double newtonUpdate = -f / slope;
        const double newton = x + newtonUpdate;
        const bool byNewton = std::abs(newtonUpdate) <= tolerance ||
                              (lo < newton && newton < hi && std::abs(newtonUpdate) <= 0.5 * std::abs(previousUpdate));
        const double next = byNewton ? newton : 0.5 * (lo + hi);
        const double update = next - x;
        x = next;
        previousUpdate = update;
        // Converged when the update is within the tolerance, or when Newton's own error bound says the next
        // one would be: from x + u the error is at most max|F''| u^2 / (2 |F'|) <= |k| u^2 / (2 |slope|)
        // (the slope barely changes over u), which saves the iteration that would only confirm it. u^2 below
        // the tolerance also keeps the Taylor step of sin below.
        const double square = update * update;
        if (std::abs(update) <= tolerance ||
            (byNewton && square <= tolerance && std::abs(k) * square <= 2.0 * std::abs(slope) * tolerance)) {
            converged = true;
            if (byNewton) {
                sinX = sinI + cosI * update; // sin(x + u) - (sin x + u cos x) = O(u^2): within the tolerance
            } else {
                sinX = std::sin(x);
                ++count;
            }
            break;
        }
    }
    if (!converged) { // iteration limit: the last iterate, inside the bracket
        sinX = std::sin(x);
        ++count;
    }
    if (evaluations) *evaluations += count;
    const double omegaMid = (s.omega - halfH * w2 * sinX) / damp;
    return {s.theta + h * omegaMid, s.omega + h * accel(w2 * sinX, p.damping, omegaMid)};
}

PendulumState stepYoshida4(const PendulumParams& p, const PendulumState& s, double h, double& sinTheta) {
    const PendulumState first = stepVerletFsal(p, s, kYoshidaOuter * h, sinTheta);
    const PendulumState second = stepVerletFsal(p, first, kYoshidaInner * h, sinTheta);
    return stepVerletFsal(p, second, kYoshidaOuter * h, sinTheta);
}

PendulumState stepYoshida4(const PendulumParams& p, const PendulumState& s, double h) {
    double sinTheta = std::sin(s.theta);
    return stepYoshida4(p, s, h, sinTheta);
}

// ---------------------------------------------------------------------------------------------------------

Dopri5::Dopri5(const PendulumParams& params, const PendulumState& initial, double tolerance, double firstStep,
               double startTime)
    : m_params(params), m_tolerance(tolerance), m_state(initial), m_time(startTime) {
    validateTolerance(tolerance);
    if (!(std::isfinite(firstStep) && firstStep >= 0.0))
        throw std::invalid_argument("dopri5: first step must be finite and >= 0 (0 picks one), got " +
                                    core::numberForMessage(firstStep));
    if (!std::isfinite(startTime))
        throw std::invalid_argument("dopri5: start time must be finite, got " + core::numberForMessage(startTime));
    validatePendulum(params, PendulumState{}); // the parameters only: any finite state may resume
    if (!std::isfinite(initial.theta) || !std::isfinite(initial.omega))
        throw std::invalid_argument("dopri5: initial theta and omega must be finite");
    m_w2 = params.gravity / params.length;
    const double timeScale = 1.0 / std::sqrt(m_w2); // 1 / omega0 (s)
    m_maxStep = 10.0 * timeScale;
    m_minStep = 16.0 * std::numeric_limits<double>::epsilon() * timeScale;
    m_slope = slopeAt(m_w2, params.damping, initial);
    m_stats.evaluations = 1;
    if (firstStep > 0.0) {
        m_next = std::min(firstStep, m_maxStep);
        return;
    }
    // Hairer's starting step, all norms scaled as in the error test: h0 = 0.01 |y0| / |f(y0)| (an Euler step
    // that changes y by 1 %), then h1 with h1^5 max(|f(y0)|, |f(y0 + h0 f(y0)) - f(y0)| / h0) = 0.01 (the
    // second term a measure of the second derivative: one evaluation), and the smaller of h1 and 100 h0.
    // The constants 1e-5, 1e-6 and 1e-15 are the heuristic's guards for a zero state or slope; its times are
    // taken in units of 1 / omega0.
    const double tol = m_tolerance;
    auto scaled = [&](double theta, double omega) {
        return std::hypot(theta / (tol + tol * std::abs(initial.theta)),
                          omega / (tol + tol * std::abs(initial.omega))) *
               kInverseSqrt2;
    };
    const double d0 = scaled(initial.theta, initial.omega);
    const double d1 = scaled(m_slope.theta, m_slope.omega);
    const double h0 = std::min(d0 < 1e-5 || d1 < 1e-5 ? 1e-6 * timeScale : 0.01 * d0 / d1, m_maxStep);
    const PendulumState probe{initial.theta + h0 * m_slope.theta, initial.omega + h0 * m_slope.omega};
    const PendulumState probeSlope = slopeAt(m_w2, params.damping, probe);
    ++m_stats.evaluations;
    const double d2 = scaled(probeSlope.theta - m_slope.theta, probeSlope.omega - m_slope.omega) / h0;
    const double d = std::max(d1, d2);
    const double h1 = d <= 1e-15 ? std::max(1e-6 * timeScale, 1e-3 * h0) : std::pow(0.01 / d, 0.2);
    m_next = std::min({100.0 * h0, h1, m_maxStep});
}

void Dopri5::step(double tEnd) {
    if (std::isnan(tEnd)) throw std::invalid_argument("dopri5: step end must not be NaN");
    if (tEnd == m_time) return;
    const double direction = tEnd > m_time ? 1.0 : -1.0;
    const double c = m_params.damping;
    bool afterReject = false;
    for (;;) {
        const double remaining = tEnd - m_time; // +-infinity for an open end
        const bool lands = std::abs(remaining) <= 1.01 * m_next;
        const double h = lands ? remaining : direction * m_next;
        // Too short a step to make progress (a stiff damping the explicit method cannot follow, or a state
        // far outside what validatePendulum admits): stop rather than creep. A landing step is the caller's.
        if (!lands &&
            !(m_next > m_minStep && m_next > 16.0 * std::numeric_limits<double>::epsilon() * std::abs(m_time)))
            throw std::runtime_error("dopri5: step size underflow at t = " + core::numberForMessage(m_time) +
                                     " s (step " + core::numberForMessage(m_next) +
                                     " s): the error test cannot be passed");
        const PendulumState& y0 = m_state;
        DopriStages k{};
        k[0] = m_slope;
        k[1] = slopeAt(m_w2, c, combine(y0, h, kDopriA2, k));
        k[2] = slopeAt(m_w2, c, combine(y0, h, kDopriA3, k));
        k[3] = slopeAt(m_w2, c, combine(y0, h, kDopriA4, k));
        k[4] = slopeAt(m_w2, c, combine(y0, h, kDopriA5, k));
        k[5] = slopeAt(m_w2, c, combine(y0, h, kDopriA6, k));
        const PendulumState y1 = combine(y0, h, kDopriB, k);
        k[6] = slopeAt(m_w2, c, y1);
        m_stats.evaluations += 6;
        const PendulumState estimate = combine(PendulumState{}, h, kDopriE, k);
        const double sTheta = m_tolerance + m_tolerance * std::max(std::abs(y0.theta), std::abs(y1.theta));
        const double sOmega = m_tolerance + m_tolerance * std::max(std::abs(y0.omega), std::abs(y1.omega));
        const double err = std::hypot(estimate.theta / sTheta, estimate.omega / sOmega) * kInverseSqrt2;
        if (err <= 1.0) {
            const PendulumState change{y1.theta - y0.theta, y1.omega - y0.omega};
            m_r1 = y0;
            m_r2 = change;
            m_r3 = {h * k[0].theta - change.theta, h * k[0].omega - change.omega};
            m_r4 = {change.theta - h * k[6].theta - m_r3.theta, change.omega - h * k[6].omega - m_r3.omega};
            m_r5 = combine(PendulumState{}, h, kDopriDense, k);
            m_denseStart = m_time;
            m_denseStep = h;
            m_state = y1;
            m_slope = k[6];
            m_time = lands ? tEnd : m_time + h;
            ++m_stats.accepted;
            // A landing step is as long as tEnd makes it, not as the controller chose: keep the proposal.
            if (!lands) m_next = std::min(std::abs(h) * stepFactor(err, afterReject ? 1.0 : kMaxGrowth), m_maxStep);
            return;
        }
        ++m_stats.rejected;
        afterReject = true;
        m_next = std::abs(h) * stepFactor(err, 1.0); // at most 0.9 |h|: the loop ends at the floor above
    }
}

void Dopri5::advanceTo(double t) {
    if (!std::isfinite(t))
        throw std::invalid_argument("dopri5: target time must be finite, got " + core::numberForMessage(t));
    while (m_time != t) step(t);
}

PendulumState Dopri5::interpolate(double t) const {
    if (m_denseStep == 0.0) throw std::logic_error("dopri5: no step taken yet, nothing to interpolate");
    const double s = (t - m_denseStart) / m_denseStep;
    const double u = 1.0 - s;
    auto at = [&](double r1, double r2, double r3, double r4, double r5) {
        return r1 + s * (r2 + u * (r3 + s * (r4 + u * r5)));
    };
    return {at(m_r1.theta, m_r2.theta, m_r3.theta, m_r4.theta, m_r5.theta),
            at(m_r1.omega, m_r2.omega, m_r3.omega, m_r4.omega, m_r5.omega)};
}

// ---------------------------------------------------------------------------------------------------------

void validatePendulum(const PendulumParams& p, const PendulumState& s) {
    auto positive = [](double v, const char* what) {
        if (!(std::isfinite(v) && v > 0.0))
            throw std::invalid_argument(std::string("pendulum: ") + what + " must be finite and > 0, got " +
                                        std::to_string(v));
    };
    positive(p.length, "length");
    positive(p.gravity, "gravity");
    positive(p.mass, "mass");
    if (!(std::isfinite(p.damping) && p.damping >= 0.0))
        throw std::invalid_argument("pendulum: damping must be finite and >= 0, got " + std::to_string(p.damping));
    if (!std::isfinite(s.theta) || !std::isfinite(s.omega))
        throw std::invalid_argument("pendulum: initial theta and omega must be finite");
    // Bounds that keep every method meaningful in doubles. An angle of 1e6 rad still places the bob within
    // a turn to 1e-10 rad; past about 1e15 the whole turns cannot even be taken off (the fuzzer found a
    // saved exact_theta0 of -5e234, which made the closed form's elliptic integral NaN). |omega| <= 1e6
    // omega0 keeps the energy, and the exact solution's modulus omega / (2 omega0), far from overflow.
    const double omega0 = std::sqrt(p.gravity / p.length);
    if (!(std::isfinite(omega0) && omega0 > 0.0))
        throw std::invalid_argument("pendulum: sqrt(gravity / length) must be finite and > 0");
    if (std::abs(s.theta) > kMaxInitialAngle)
        throw std::invalid_argument("pendulum: |initial theta| must be at most 1e6 rad, got " +
                                    core::numberForMessage(s.theta));
    if (std::abs(s.omega) > kMaxFrequencyRatio * omega0)
        throw std::invalid_argument("pendulum: |initial omega| must be at most 1e6 sqrt(g / L) = " +
                                    core::numberForMessage(kMaxFrequencyRatio * omega0) + " rad/s, got " +
                                    core::numberForMessage(s.omega));
}

Pendulum::Pendulum(Method method, const PendulumParams& params, const PendulumState& initial, MidpointStart start,
                   double tolerance)
    : m_method(method), m_params(params), m_start(start), m_tolerance(tolerance) {
    if (!validIndex(method)) throw std::invalid_argument("pendulum: method out of range");
    if (method == Method::Exact && params.damping != 0.0)
        throw std::invalid_argument("pendulum: method 'exact' is the undamped closed form; damping must be 0");
    validateTolerance(tolerance);
    reset(initial);
}

void Pendulum::reset(const PendulumState& initial) {
    validatePendulum(m_params, initial);
    if (m_method == Method::Exact) m_exact.emplace(m_params, initial);
    if (m_method == Method::Dopri5) m_dopri5.emplace(m_params, initial, m_tolerance);
    m_state = initial;
    m_previous = initial;
    m_time = 0.0;
    m_timeCarry = 0.0;
    m_lastStep = 0.0;
    m_x = m_params.length * std::sin(initial.theta);
    m_y = m_params.length * std::cos(initial.theta);
    m_sinTheta = std::sin(initial.theta);
    // verlet and yoshida4 use that sin as their first force evaluation (first same as last).
    m_evaluations = m_method == Method::Verlet || m_method == Method::Yoshida4 ? 1 : 0;
}

void Pendulum::step(double h) {
    if (!std::isfinite(h)) throw std::invalid_argument("pendulum: step must be finite");
    if (h == 0.0) return;

    // Kahan summation: many small steps (60 Hz for hours) must not drift the clock of the exact solution.
    const double y = h - m_timeCarry;
    const double t = m_time + y;
    const double carry = (t - m_time) - y;
    if (m_method == Method::Dopri5) {
        // The one step that can throw (step-size underflow): advance a copy so that a throw changes nothing.
        Dopri5 next = *m_dopri5;
        next.advanceTo(t);
        *m_dopri5 = next;
    }
    m_timeCarry = carry;
    m_time = t;

    switch (m_method) {
    case Method::Euler:
        m_state = stepEuler(m_params, m_state, h);
        m_evaluations += 1;
        break;
    case Method::EulerCartesian: {
        const EulerCartesianState next = stepEulerCartesian(m_params, {m_state, m_x, m_y}, h);
        m_state = next.angular;
        m_x = next.x;
        m_y = next.y;
        m_evaluations += 1;
        break;
    }
    case Method::Midpoint: {
        if (h != m_lastStep) {
            // (Re)start: y[1] from y[0] by one one-step method; unequal leapfrog steps would be first order.
            m_previous = m_state;
            m_state = m_start == MidpointStart::Rk4 ? stepRk4(m_params, m_state, h) : stepEuler(m_params, m_state, h);
            m_lastStep = h;
            m_evaluations += m_start == MidpointStart::Rk4 ? 4 : 1;
        } else {
            const PendulumState next = stepMidpoint(m_params, m_previous, m_state, h);
            m_previous = m_state;
            m_state = next;
            m_evaluations += 1;
        }
        break;
    }
    case Method::Trapezoid:
        m_state = stepTrapezoid(m_params, m_state, h);
        m_evaluations += 2;
        break;
    case Method::SymplecticEuler:
        m_state = stepSymplecticEuler(m_params, m_state, h);
        m_evaluations += 1;
        break;
    case Method::Verlet:
        m_state = stepVerletFsal(m_params, m_state, h, m_sinTheta);
        m_evaluations += 1;
        break;
    case Method::Rk4:
        m_state = stepRk4(m_params, m_state, h);
        m_evaluations += 4;
        break;
    case Method::ImplicitMidpoint: {
        int evaluations = 0;
        m_state = stepImplicitMidpoint(m_params, m_state, h, &evaluations);
        m_evaluations += evaluations;
        break;
    }
    case Method::Yoshida4:
        m_state = stepYoshida4(m_params, m_state, h, m_sinTheta);
        m_evaluations += 3;
        break;
    case Method::Dopri5:
        m_state = m_dopri5->state(); // advanced above, to exactly m_time
        break;
    case Method::Exact:
        m_state = m_exact->at(m_time);
        break;
    case Method::Count:
        break;
    }
}

Pendulum::Internals Pendulum::internals() const {
    Internals in;
    in.state = m_state;
    in.time = m_time;
    in.timeCarry = m_timeCarry;
    in.previous = m_previous;
    in.lastStep = m_method == Method::Dopri5 ? m_dopri5->nextStep() : m_lastStep;
    in.x = m_x;
    in.y = m_y;
    in.sinTheta = m_sinTheta;
    in.exactInitial = m_exact ? m_exact->initial() : m_state;
    in.counts = Internals::Counts{m_evaluations, m_dopri5 ? m_dopri5->stats() : Dopri5Stats{}};
    return in;
}

void Pendulum::setInternals(const Internals& in) {
    const double values[] = {in.state.theta,        in.state.omega,       in.time, in.timeCarry, in.previous.theta,
                             in.previous.omega,     in.lastStep,          in.x,    in.y,         in.sinTheta,
                             in.exactInitial.theta, in.exactInitial.omega};
    for (const double v : values) {
        if (!std::isfinite(v)) throw std::invalid_argument("pendulum: internal state must be finite");
    }
    if (m_method == Method::Exact)
        m_exact = ExactPendulum(m_params, in.exactInitial); // validates; throws before any change
    if (m_method == Method::Dopri5) // cannot throw once the values are finite; f(state) is evaluated afresh
        m_dopri5.emplace(m_params, in.state, m_tolerance, in.lastStep > 0.0 ? in.lastStep : 0.0, in.time);
    m_evaluations = in.counts ? in.counts->evaluations : 0;
    if (m_dopri5 && in.counts) m_dopri5->restoreStats(in.counts->dopri5);
    m_state = in.state;
    m_time = in.time;
    m_timeCarry = in.timeCarry;
    m_previous = in.previous;
    m_lastStep = in.lastStep;
    m_x = in.x;
    m_y = in.y;
    m_sinTheta = in.sinTheta;
}

std::int64_t Pendulum::evaluations() const {
    return m_method == Method::Dopri5 ? m_dopri5->stats().evaluations : m_evaluations;
}

double Pendulum::bobX() const {
    return m_method == Method::EulerCartesian ? m_x : m_params.length * std::sin(m_state.theta);
}

double Pendulum::bobY() const {
    return m_method == Method::EulerCartesian ? m_y : m_params.length * std::cos(m_state.theta);
}

double Pendulum::thetaFromPosition() const {
    if (m_method != Method::EulerCartesian) return m_state.theta;
    const double principal = std::atan2(m_x, m_y); // angle from +y (down) towards +x
    return principal + kTwoPi * std::round((m_state.theta - principal) / kTwoPi);
}

double Pendulum::rodLength() const {
    return m_method == Method::EulerCartesian ? std::hypot(m_x, m_y) : m_params.length;
}

} // namespace physics
