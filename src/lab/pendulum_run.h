// The one-run study of minecrappy-lab (`minecrappy-lab pendulum`): one method's every step written as CSV.
#pragma once
#include <filesystem>
#include <ostream>
#include <string>

#include "lab/pendulum_common.h"
#include "physics/pendulum.h"

namespace lab {

inline constexpr double kMaxLabMass = 1.0e6; // kg: the mass scales the energy column only

struct PendulumRun {
    physics::Method method = physics::Method::Rk4;
    physics::PendulumParams params{};
    physics::PendulumState initial{};                    // theta (rad) from straight down, omega (rad/s)
    double dt = 0.01;                                    // step (s), finite and > 0; dopri5: the output step (rows)
    double seconds = 10.0;                               // simulated time (s), finite and > 0
    double tolerance = physics::kDefaultDopri5Tolerance; // dopri5 only: in [kDopri5MinTolerance, kDopri5MaxTolerance]
};

// An empty string when the run can be done; otherwise what is wrong with it, in words.
std::string validateRun(const PendulumRun& run);

// Header `t,theta,omega,energy,theta_exact,energy_error` (+ `,theta_from_position,rod_length` for
// euler-cartesian, + `,steps` for dopri5: its accepted steps so far, the rows then at the output step from its
// dense output while it steps freely), then one row per step including t = 0, full precision. energy_error is
// (E - E0) / (m g L). theta_exact is empty-valued (nan) when the closed form does not apply (damping).
// Throws std::invalid_argument when validateRun() objects.
void writePendulumCsv(const PendulumRun& run, std::ostream& out);
void writePendulumCsv(const PendulumRun& run, const std::filesystem::path& path); // throws runtime_error

} // namespace lab
