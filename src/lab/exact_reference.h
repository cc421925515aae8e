// Reference values of the undamped pendulum (g = 9.81 m/s^2, L = 1 m) at 50 significant digits, computed by
// scripts/exact_reference.py with Taylor-series integration in arbitrary precision (mpmath), independently of
// the elliptic-function closed form in physics/pendulum_exact.cpp, which they check (tests and the lab report).
// The starting values are doubles, written so that they read back exactly.
#pragma once

#include <span>

namespace lab {

struct ExactReferenceValue {
    double theta0 = 0.0, omega0 = 0.0; // the start (rad, rad/s) at t = 0
    double t = 0.0;                    // s
    const char* theta = "";            // rad, 50 digits: parse to the nearest double
    const char* omega = "";            // rad/s, 50 digits
};

std::span<const ExactReferenceValue> exactReferenceValues();

} // namespace lab
