// The integrators and the Pendulum wrapper. Every stepper is a handful of multiply-adds around its sin
// calls, computes g / L once, and touches nothing but its arguments (see pendulum.h for the contract).
#include "physics/pendulum.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace physics {

namespace {

// %g, not std::to_string: a rejected 1e300 should read as 1e+300, not as 301 digits.
std::string shortNumber(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

constexpr std::array<std::string_view, kMethodCount> kMethodNames = {
    "euler", "euler-cartesian", "midpoint", "trapezoid", "symplectic-euler", "verlet", "rk4", "exact"};

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Angular acceleration for a given (-(g/L) sin(theta)) term already computed.
inline double accel(double w2Sin, double damping, double omega) { return -w2Sin - damping * omega; }

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
        throw std::invalid_argument("pendulum: |initial theta| must be at most 1e6 rad, got " + shortNumber(s.theta));
    if (std::abs(s.omega) > kMaxFrequencyRatio * omega0)
        throw std::invalid_argument("pendulum: |initial omega| must be at most 1e6 sqrt(g / L) = " +
                                    shortNumber(kMaxFrequencyRatio * omega0) + " rad/s, got " + shortNumber(s.omega));
}

Pendulum::Pendulum(Method method, const PendulumParams& params, const PendulumState& initial, MidpointStart start)
    : m_method(method), m_params(params), m_start(start) {
    if (!validIndex(method)) throw std::invalid_argument("pendulum: method out of range");
    if (method == Method::Exact && params.damping != 0.0)
        throw std::invalid_argument("pendulum: method 'exact' is the undamped closed form; damping must be 0");
    reset(initial);
}

void Pendulum::reset(const PendulumState& initial) {
    validatePendulum(m_params, initial);
    if (m_method == Method::Exact) m_exact.emplace(m_params, initial);
    m_state = initial;
    m_previous = initial;
    m_time = 0.0;
    m_timeCarry = 0.0;
    m_lastStep = 0.0;
    m_x = m_params.length * std::sin(initial.theta);
    m_y = m_params.length * std::cos(initial.theta);
    m_sinTheta = std::sin(initial.theta);
}

void Pendulum::step(double h) {
    if (!std::isfinite(h)) throw std::invalid_argument("pendulum: step must be finite");
    if (h == 0.0) return;

    // Kahan summation: many small steps (60 Hz for hours) must not drift the clock of the exact solution.
    const double y = h - m_timeCarry;
    const double t = m_time + y;
    m_timeCarry = (t - m_time) - y;
    m_time = t;

    switch (m_method) {
    case Method::Euler:
        m_state = stepEuler(m_params, m_state, h);
        break;
    case Method::EulerCartesian: {
        const EulerCartesianState next = stepEulerCartesian(m_params, {m_state, m_x, m_y}, h);
        m_state = next.angular;
        m_x = next.x;
        m_y = next.y;
        break;
    }
    case Method::Midpoint: {
        if (h != m_lastStep) {
            // (Re)start: y[1] from y[0] by one one-step method; unequal leapfrog steps would be first order.
            m_previous = m_state;
            m_state = m_start == MidpointStart::Rk4 ? stepRk4(m_params, m_state, h) : stepEuler(m_params, m_state, h);
            m_lastStep = h;
        } else {
            const PendulumState next = stepMidpoint(m_params, m_previous, m_state, h);
            m_previous = m_state;
            m_state = next;
        }
        break;
    }
    case Method::Trapezoid:
        m_state = stepTrapezoid(m_params, m_state, h);
        break;
    case Method::SymplecticEuler:
        m_state = stepSymplecticEuler(m_params, m_state, h);
        break;
    case Method::Verlet:
        m_state = stepVerletFsal(m_params, m_state, h, m_sinTheta);
        break;
    case Method::Rk4:
        m_state = stepRk4(m_params, m_state, h);
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
    in.lastStep = m_lastStep;
    in.x = m_x;
    in.y = m_y;
    in.sinTheta = m_sinTheta;
    in.exactInitial = m_exact ? m_exact->initial() : m_state;
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
    m_state = in.state;
    m_time = in.time;
    m_timeCarry = in.timeCarry;
    m_previous = in.previous;
    m_lastStep = in.lastStep;
    m_x = in.x;
    m_y = in.y;
    m_sinTheta = in.sinTheta;
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
