#include "lab/pendulum_common.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace lab {

using physics::Method;

namespace {

constexpr double kPi = std::numbers::pi;

} // namespace

std::vector<Method> steppedMethods() {
    std::vector<Method> out;
    for (int i = 0; i < physics::kMethodCount; ++i) {
        if (static_cast<Method>(i) != Method::Exact) out.push_back(static_cast<Method>(i));
    }
    return out;
}

std::vector<Method> fixedStepMethods() {
    std::vector<Method> out;
    for (const Method m : steppedMethods())
        if (m != Method::Dopri5) out.push_back(m);
    return out;
}

int methodColour(Method method) {
    switch (method) {
    case Method::Euler:
        return 0;
    case Method::EulerCartesian:
        return 5;
    case Method::Midpoint:
        return 2;
    case Method::Trapezoid:
        return 3;
    case Method::SymplecticEuler:
        return 1;
    case Method::Verlet:
        return 4;
    case Method::Rk4:
        return 6;
    case Method::ImplicitMidpoint:
        return 7;
    case Method::Yoshida4:
        return 8;
    case Method::Dopri5:
        return 9;
    case Method::Exact:
        return 6; // black too, but always dashed: the reference, never beside rk4's curve
    case Method::Count:
        break;
    }
    return 6;
}

double wrapAngle(double radians) {
    double d = std::remainder(radians, 2.0 * kPi); // [-pi, pi]
    if (d <= -kPi) d += 2.0 * kPi;
    return d;
}

std::int64_t stepCount(double seconds, double dt) {
    if (!std::isfinite(seconds) || !std::isfinite(dt) || dt <= 0.0 || seconds < 0.0) return -1;
    const double ratio = seconds / dt;
    if (!std::isfinite(ratio) || ratio > 9.0e18) return -1;
    // 10 / 0.001 is 10000.000000000002 in doubles: a relative slack of a few ulps keeps it 10000.
    const double steps = std::ceil(ratio * (1.0 - 4.0 * std::numeric_limits<double>::epsilon()));
    return std::max<std::int64_t>(0, static_cast<std::int64_t>(steps));
}

} // namespace lab
