#include "lab/ode.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace lab {

namespace {

// The Dormand-Prince 5(4) tableau. Nodes c, stage coefficients a (row i: stage i + 1), the fifth-order
// weights b (equal to the last row of a: the seventh stage is f at the new point) and e = b - b*, where b*
// are the embedded fourth-order weights 5179/57600, 0, 7571/16695, 393/640, -92097/339200, 187/2100, 1/40.
constexpr double c2 = 1.0 / 5.0, c3 = 3.0 / 10.0, c4 = 4.0 / 5.0, c5 = 8.0 / 9.0;
constexpr double a21 = 1.0 / 5.0;
constexpr double a31 = 3.0 / 40.0, a32 = 9.0 / 40.0;
constexpr double a41 = 44.0 / 45.0, a42 = -56.0 / 15.0, a43 = 32.0 / 9.0;
constexpr double a51 = 19372.0 / 6561.0, a52 = -25360.0 / 2187.0, a53 = 64448.0 / 6561.0, a54 = -212.0 / 729.0;
constexpr double a61 = 9017.0 / 3168.0, a62 = -355.0 / 33.0, a63 = 46732.0 / 5247.0, a64 = 49.0 / 176.0,
                 a65 = -5103.0 / 18656.0;
constexpr double b1 = 35.0 / 384.0, b3 = 500.0 / 1113.0, b4 = 125.0 / 192.0, b5 = -2187.0 / 6784.0, b6 = 11.0 / 84.0;
constexpr double e1 = 71.0 / 57600.0, e3 = -71.0 / 16695.0, e4 = 71.0 / 1920.0, e5 = -17253.0 / 339200.0,
                 e6 = 22.0 / 525.0, e7 = -1.0 / 40.0;

// Exponents of the PI controller for a method whose error estimate is of order 4 (local error O(h^5)).
constexpr double kBeta = 0.04;
constexpr double kAlpha = 1.0 / 5.0 - 0.75 * kBeta;

bool allFinite(std::span<const double> v) {
    for (const double x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

} // namespace

DormandPrince::DormandPrince(Rhs f, double t0, std::vector<double> y0, const OdeOptions& options)
    : m_f(std::move(f)), m_options(options), m_t(t0), m_y(std::move(y0)) {
    const auto bad = [](const std::string& what) { throw std::invalid_argument("DormandPrince: " + what); };
    if (!m_f) bad("no right-hand side");
    if (m_y.empty()) bad("empty state");
    if (!std::isfinite(t0) || !allFinite(m_y)) bad("non-finite initial time or state");
    const OdeOptions& o = m_options;
    if (!(std::isfinite(o.relTol) && o.relTol > 0.0)) bad("relTol must be finite and > 0");
    if (!(std::isfinite(o.absTol) && o.absTol > 0.0)) bad("absTol must be finite and > 0");
    if (!(o.initialStep >= 0.0 && std::isfinite(o.initialStep))) bad("initialStep must be finite and >= 0");
    if (!(o.maxStep > 0.0)) bad("maxStep must be > 0");
    if (o.maxSteps < 1) bad("maxSteps must be >= 1");
    if (!(o.safety > 0.0 && o.safety <= 1.0)) bad("safety must be in (0, 1]");
    if (!(o.minFactor > 0.0 && o.minFactor <= 1.0 && o.maxFactor >= 1.0 && std::isfinite(o.maxFactor)))
        bad("need 0 < minFactor <= 1 <= maxFactor");
    const std::size_t n = m_y.size();
    m_yNew.assign(n, 0.0);
    m_yStage.assign(n, 0.0);
    for (auto& k : m_k) k.assign(n, 0.0);
    m_f(m_t, m_y, m_k[0]);
    ++m_counters.evaluations;
}

double DormandPrince::errorNorm() const {
    // m_yStage holds the error estimate of the step just attempted.
    const std::size_t n = m_y.size();
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double scale = m_options.absTol + m_options.relTol * std::max(std::abs(m_y[i]), std::abs(m_yNew[i]));
        const double r = m_yStage[i] / scale;
        sum += r * r;
    }
    const double err = std::sqrt(sum / static_cast<double>(n));
    return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
}

double DormandPrince::attempt(double h) {
    const std::size_t n = m_y.size();
    const double t = m_t;
    const auto& k1 = m_k[0];
    auto& k2 = m_k[1];
    auto& k3 = m_k[2];
    auto& k4 = m_k[3];
    auto& k5 = m_k[4];
    auto& k6 = m_k[5];
    auto& k7 = m_k[6];
    auto& s = m_yStage;
    for (std::size_t i = 0; i < n; ++i) s[i] = m_y[i] + h * (a21 * k1[i]);
    m_f(t + c2 * h, s, k2);
    for (std::size_t i = 0; i < n; ++i) s[i] = m_y[i] + h * (a31 * k1[i] + a32 * k2[i]);
    m_f(t + c3 * h, s, k3);
    for (std::size_t i = 0; i < n; ++i) s[i] = m_y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    m_f(t + c4 * h, s, k4);
    for (std::size_t i = 0; i < n; ++i) s[i] = m_y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    m_f(t + c5 * h, s, k5);
    for (std::size_t i = 0; i < n; ++i)
        s[i] = m_y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    m_f(t + h, s, k6);
    for (std::size_t i = 0; i < n; ++i)
        m_yNew[i] = m_y[i] + h * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i]);
    m_f(t + h, m_yNew, k7);
    m_counters.evaluations += 6;
    for (std::size_t i = 0; i < n; ++i)
        s[i] = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
    m_lastErr = errorNorm();
    return m_lastErr;
}

void DormandPrince::accept(double h) {
    std::swap(m_y, m_yNew);
    std::swap(m_k[0], m_k[6]); // first same as last: f at the new point is the next step's first stage
    m_t += h;
    ++m_counters.accepted;
}

double DormandPrince::startingStep(double remaining) {
    // Hairer, Norsett & Wanner, Solving ODEs I, II.4: a step whose explicit Euler error would be about 1 % of
    // the scaled state, then bounded by (0.01 / |f'|)^(1/5) from a trial Euler step.
    const std::size_t n = m_y.size();
    const auto& f0 = m_k[0];
    double d0 = 0.0, d1 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double sk = m_options.absTol + m_options.relTol * std::abs(m_y[i]);
        d0 += (m_y[i] / sk) * (m_y[i] / sk);
        d1 += (f0[i] / sk) * (f0[i] / sk);
    }
    d0 = std::sqrt(d0 / static_cast<double>(n));
    d1 = std::sqrt(d1 / static_cast<double>(n));
    double h0 = (d0 < 1e-10 || d1 < 1e-10) ? 1e-6 : 0.01 * d0 / d1;
    h0 = std::min({h0, m_options.maxStep, remaining});
    for (std::size_t i = 0; i < n; ++i) m_yStage[i] = m_y[i] + h0 * f0[i];
    auto& f1 = m_k[1];
    m_f(m_t + h0, m_yStage, f1);
    ++m_counters.evaluations;
    double d2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double sk = m_options.absTol + m_options.relTol * std::abs(m_y[i]);
        const double r = (f1[i] - f0[i]) / sk;
        d2 += r * r;
    }
    d2 = std::sqrt(d2 / static_cast<double>(n)) / h0;
    const double d = std::max(d1, d2);
    const double h1 = (!std::isfinite(d) || d <= 1e-15) ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / d, 1.0 / 5.0);
    const double h = std::min({100.0 * h0, h1, m_options.maxStep});
    return h > 0.0 && std::isfinite(h) ? h : std::min(1e-6, m_options.maxStep);
}

void DormandPrince::advanceTo(double t) {
    if (!(t >= m_t)) // also NaN
        throw std::invalid_argument("DormandPrince::advanceTo: t = " + std::to_string(t) +
                                    " is before the current time " + std::to_string(m_t));
    if (t == m_t) return;
    if (!std::isfinite(t)) throw std::invalid_argument("DormandPrince::advanceTo: t must be finite");
    if (m_h <= 0.0)
        m_h = m_options.initialStep > 0.0 ? std::min(m_options.initialStep, m_options.maxStep) : startingStep(t - m_t);
    constexpr double eps = std::numeric_limits<double>::epsilon();
    std::int64_t attempts = 0;
    bool rejectedLast = false;
    while (m_t < t) {
        if (++attempts > m_options.maxSteps)
            throw std::runtime_error("DormandPrince: more than " + std::to_string(m_options.maxSteps) +
                                     " steps to reach t = " + std::to_string(t) +
                                     " (stuck at t = " + std::to_string(m_t) + ")");
        const double proposed = std::min(m_h, m_options.maxStep);
        double h = proposed;
        const bool last = m_t + 1.01 * h >= t; // clip to t (and stretch a step within 1 % of it)
        if (last) h = t - m_t;
        if (!last && h <= 16.0 * eps * std::abs(m_t))
            throw std::runtime_error("DormandPrince: step size underflow at t = " + std::to_string(m_t));
        if (!(h > 0.0)) throw std::runtime_error("DormandPrince: step size underflow at t = " + std::to_string(m_t));
        const double err = attempt(h);
        if (err <= 1.0) {
            double factor = m_options.safety * std::pow(std::max(err, 1e-20), -kAlpha) * std::pow(m_errPrev, kBeta);
            factor = std::clamp(factor, m_options.minFactor, rejectedLast ? 1.0 : m_options.maxFactor);
            const double next = h * factor;
            // A step clipped to land on t says little about the step the solution allows: keep the larger.
            m_h = (last && h < proposed && factor >= 1.0) ? std::max(next, proposed) : next;
            m_errPrev = std::max(err, 1e-4);
            accept(h);
            if (last) m_t = t;
            rejectedLast = false;
        } else {
            const double factor = std::isfinite(err)
                                      ? std::max(m_options.minFactor, m_options.safety * std::pow(err, -kAlpha))
                                      : m_options.minFactor;
            m_h = h * std::min(factor, 1.0);
            ++m_counters.rejected;
            rejectedLast = true;
        }
    }
}

void DormandPrince::fixedStep(double h) {
    if (!(h > 0.0 && std::isfinite(h)))
        throw std::invalid_argument("DormandPrince::fixedStep: h must be finite and > 0");
    attempt(h);
    accept(h);
}

} // namespace lab
