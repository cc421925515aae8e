// The closed-form undamped pendulum (ExactPendulum, periodRatio). The elliptic functions themselves come
// from Boost.Math; this file only chooses the regime, reduces arguments and transforms the modulus.
//
// With psi = theta / 2, omega0 = sqrt(g / L) and the invariant k^2 = sin^2(psi) + (omega / (2 omega0))^2:
//   swinging  (k < 1): sin(psi) = k sn(u, k), cos(psi) = dn(u, k), omega = 2 k omega0 cn(u, k), u = omega0 t + u0
//   rotating  (k > 1): psi = s am(v, 1/k), omega = 2 s k omega0 dn(v, 1/k), v = k omega0 t + v0, s = sign(omega)
//   separatrix (k = 1): psi = s gd(u) = s atan(sinh(u)), omega = 2 s omega0 / cosh(u), u = omega0 t + u0
// theta = 2 atan2(k sn, dn) rather than 2 asin(k sn): no loss of digits near the top.
//
// Precision near k = 1. Boost evaluates sn(u, k) from k alone and so rebuilds k' = sqrt(1 - k^2) with a
// relative error of about 1e-16 / k'^2 (1e-12 for a 179 degree swing); F(phi, k) likewise. The physics gives
// k' directly (k'^2 = cos^2(psi) - (omega / (2 omega0))^2, a product of a difference and a sum, with no
// cancellation), so we descend with Landen's transformation, computed from k' only,
//   k1 = (1 - k') / (1 + k'),  k1' = 2 sqrt(k') / (1 + k'),  K(k) = (1 + k1) K(k1),
//   sn(u, k) = (1 + k1) sn / (1 + k1 sn^2),  cn(u, k) = cn dn / (1 + k1 sn^2),
//   dn(u, k) = ((1 - k1) + k1 cn^2) / (1 + k1 sn^2),   with sn, cn, dn at (u / (1 + k1), k1),
//   F(phi, k) = (1 + k1) / 2 * F(phi + atan(k' tan(phi)), k1)    (the angle continued through the branches),
// until the modulus is at most 0.7, where Boost is accurate to an ulp or two. Each step is exact algebra; the
// ladder is a few levels (9 for k' = 1e-300).
#include "physics/pendulum.h"

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace physics {

namespace {

constexpr double kPi = 3.141592653589793238462643383279;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kLandenBelow = 0.7; // descend until the modulus is at most this

// Boost promotes double arguments to long double by default. For sn and cn at a modulus <= 0.7 and an
// argument within one period, double arithmetic is as accurate (checked against 50-digit values) and about
// five times faster; ellint_1 runs only in the constructor and keeps the promotion.
using NoPromotion = boost::math::policies::policy<boost::math::policies::promote_double<false>>;

} // namespace

ExactPendulum::ExactPendulum(const PendulumParams& params, const PendulumState& initial)
    : m_params(params), m_initial(initial) {
    if (params.damping != 0.0)
        throw std::invalid_argument("exact pendulum: the closed form is for the undamped pendulum; damping must be 0");
    validatePendulum(params, initial);

    m_omega0 = smallAngleFrequency(params);
    // Whole turns taken off theta0. Never for |theta0| <= pi: 2 pi is not a double, and near the top even
    // that rounding would move the bob to the other side of it.
    m_offset = std::abs(initial.theta) <= kPi ? 0.0 : kTwoPi * std::round(initial.theta / kTwoPi);
    const double half = 0.5 * (initial.theta - m_offset); // psi0 in [-pi/2, pi/2]
    const double s = std::sin(half);
    const double c = std::cos(half); // >= 0
    const double w = initial.omega / (2.0 * m_omega0);
    const double aw = std::abs(w);
    m_sign = w < 0.0 ? -1.0 : 1.0;
    m_k = std::hypot(s, w);

    const double eps = std::numeric_limits<double>::epsilon();
    const double diff = c - aw; // k'^2 = (c - |w|)(c + |w|)
    const double sum = c + aw;
    double modulus = 0.0;
    double complement = 0.0;
    m_kc = std::sqrt(std::abs(diff) * sum);
    // Within a few roundings of k = 1 the state is taken as on the separatrix (also an exactly upright bob at
    // rest, c = |w| = 0, which no double angle reaches: cos never returns 0; the formula then keeps it there).
    if (std::abs(diff) <= 4.0 * eps * sum) {
        m_regime = Regime::Separatrix;
        m_k = 1.0;
        m_kc = 0.0;
        m_rate = m_omega0;
        m_u0 = std::asinh(m_sign * s / c); // gd^-1(s psi0); atanh(sin) would cancel near the top
        return;
    }
    if (diff > 0.0) {
        m_regime = Regime::Swinging;
        modulus = m_k;
        complement = m_kc;
        m_rate = m_omega0;
    } else {
        m_regime = Regime::Rotating;
        modulus = 1.0 / m_k;
        complement = m_kc / m_k; // sqrt(1 - 1/k^2)
        m_rate = m_k * m_omega0;
    }

    m_ladder[0] = modulus;
    m_ladderC[0] = complement;
    m_levels = 0;
    m_scale = 1.0;
    while (m_ladder[m_levels] > kLandenBelow && m_levels < kMaxLanden) {
        const double kc = m_ladderC[m_levels];
        ++m_levels;
        m_ladder[m_levels] = (1.0 - kc) / (1.0 + kc);
        m_ladderC[m_levels] = 2.0 * std::sqrt(kc) / (1.0 + kc);
        m_scale *= 1.0 + m_ladder[m_levels];
    }
    m_quarter = m_scale * boost::math::ellint_1(m_ladder[m_levels]);

    if (m_regime == Regime::Swinging) {
        // u0 with sn(u0) = s / k, cn(u0) = w / k. Directly, u0 = F(atan2(s, w)); but near a turning point
        // that amplitude lies within a few ulps of pi / 2, where F is steepest (slope up to 1 / k'), so the
        // rounding of the angle alone costs eps / k'. There we use u0 = +-(K - x) instead, which holds when
        // cn(x) / dn(x) = |s| / k and k' sn(x) / dn(x) = w / k, i.e. x = F(chi) with tan(chi) = w / (|s| k'):
        // exactly K at rest. Each form is bad where the other is good; switching where their slopes match
        // (|w| = sqrt(k k')) bounds the error by about eps / sqrt(k'), nothing for k' > 1e-4.
        if (std::abs(w) >= std::sqrt(m_k * complement)) {
            m_u0 = ellipticF(std::atan2(s, w));
        } else {
            const double x = ellipticF(std::atan2(w, std::abs(s) * complement));
            m_u0 = std::copysign(m_quarter - x, s);
        }
    } else {
        m_u0 = ellipticF(m_sign * half); // am(v0) = s psi0
    }
}

double ExactPendulum::ellipticF(double phi) const {
    double weight = 1.0;
    for (int j = 0; j < m_levels; ++j) {
        // atan(k' tan(phi)) continued through the branches: same quadrant as phi, within pi/2 of it.
        const double principal = std::atan2(m_ladderC[j] * std::sin(phi), std::cos(phi));
        phi += principal + kTwoPi * std::round((phi - principal) / kTwoPi);
        weight *= 0.5 * (1.0 + m_ladder[j + 1]);
    }
    return weight * boost::math::ellint_1(m_ladder[m_levels], phi);
}

void ExactPendulum::jacobi(double u, double& sn, double& cn, double& dn) const {
    const double k = m_ladder[m_levels];
    sn = boost::math::jacobi_elliptic(k, u / m_scale, &cn, &dn, NoPromotion());
    // Boost (1.74) forms dn as cos(T0) / cos(T1 - T0), a ratio of two roundings of zero at u = K, 3K...:
    // errors of 1e-3 there. With k <= 0.7 the identity is well conditioned.
    dn = std::sqrt((1.0 - k * sn) * (1.0 + k * sn));
    for (int j = m_levels; j > 0; --j) {
        const double k1 = m_ladder[j];
        const double oneMinusK1 = 2.0 * m_ladderC[j - 1] / (1.0 + m_ladderC[j - 1]); // 1 - k1 without cancellation
        const double sn2 = sn * sn;
        const double den = 1.0 + k1 * sn2;
        const double nextSn = (1.0 + k1) * sn / den;
        const double nextCn = cn * dn / den;
        dn = (oneMinusK1 + k1 * cn * cn) / den;
        sn = nextSn;
        cn = nextCn;
    }
}

PendulumState ExactPendulum::at(double t) const {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(t)) return {nan, nan};
    switch (m_regime) {
    case Regime::Separatrix: {
        const double u = m_rate * t + m_u0;
        return {m_offset + 2.0 * m_sign * std::atan(std::sinh(u)), 2.0 * m_sign * m_omega0 / std::cosh(u)};
    }
    case Regime::Swinging: {
        // remainder() is exact: the only rounding left is in rate * t + u0, so the error grows like |u| ulp.
        const double u = std::remainder(m_rate * t + m_u0, 4.0 * m_quarter);
        double sn = 0.0, cn = 0.0, dn = 0.0;
        jacobi(u, sn, cn, dn);
        return {m_offset + 2.0 * std::atan2(m_k * sn, dn), 2.0 * m_k * m_omega0 * cn};
    }
    case Regime::Rotating: {
        const double v = m_rate * t + m_u0;
        const double halfPeriod = 2.0 * m_quarter; // am(v + 2K) = am(v) + pi
        const double reduced = std::remainder(v, halfPeriod);
        const double turns = std::round((v - reduced) / halfPeriod);
        double sn = 0.0, cn = 0.0, dn = 0.0;
        jacobi(reduced, sn, cn, dn);
        const double psi = std::atan2(sn, cn); // cn >= 0 on [-K, K]
        return {m_offset + m_sign * (kTwoPi * turns + 2.0 * psi), 2.0 * m_sign * m_k * m_omega0 * dn};
    }
    }
    return {nan, nan};
}

double ExactPendulum::period() const {
    switch (m_regime) {
    case Regime::Swinging:
        return 4.0 * m_quarter / m_rate;
    case Regime::Rotating:
        return 2.0 * m_quarter / m_rate;
    case Regime::Separatrix:
        break;
    }
    return std::numeric_limits<double>::infinity();
}

double ExactPendulum::modulus() const { return m_k; }

double periodRatio(double amplitudeRadians) {
    if (!std::isfinite(amplitudeRadians)) return std::numeric_limits<double>::quiet_NaN();
    const PendulumParams params{};
    const ExactPendulum exact(params, {amplitudeRadians, 0.0});
    return exact.period() * smallAngleFrequency(params) / kTwoPi;
}

} // namespace physics
