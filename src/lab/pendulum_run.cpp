#include "lab/pendulum_run.h"

#include "lab/lab_util.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>

namespace lab {

using detail::mgl;
using physics::Method;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

} // namespace

std::string validateRun(const PendulumRun& run) {
    const auto& p = run.params;
    if (run.method == Method::Count || physics::methodName(run.method).empty()) return "unknown method";
    if (!std::isfinite(run.dt) || run.dt <= 0.0) return "the step must be a finite number > 0 (seconds)";
    if (!std::isfinite(run.seconds) || run.seconds <= 0.0) return "the duration must be a finite number > 0 (seconds)";
    if (!(p.length >= physics::kMinPendulumLength && p.length <= physics::kMaxPendulumLength))
        return "--length must be in [0.001, 16] m (the game's rods), got " + formatShort(p.length);
    if (!(p.gravity > 0.0 && p.gravity <= physics::kMaxPendulumGravity))
        return "--g must be in (0, 1e4] m/s^2 (the game's gravities), got " + formatShort(p.gravity);
    if (!(p.mass > 0.0 && p.mass <= kMaxLabMass)) return "--mass must be in (0, 1e6] kg, got " + formatShort(p.mass);
    if (!std::isfinite(p.damping) || p.damping < 0.0) return "the damping must be a finite number >= 0 (1/s)";
    if (!std::isfinite(run.initial.theta) || !std::isfinite(run.initial.omega))
        return "the initial state must be finite";
    const std::int64_t steps = stepCount(run.seconds, run.dt);
    if (steps < 0 || steps > kMaxSteps) {
        return "the run would take " + (steps < 0 ? std::string("too many") : std::to_string(steps)) +
               " steps (seconds / dt); at most " + std::to_string(kMaxSteps) + " are allowed";
    }
    if (run.method == Method::Exact && p.damping != 0.0) return "the exact solution is for the undamped pendulum";
    if (run.method == Method::Dopri5 &&
        !(run.tolerance >= physics::kDopri5MinTolerance && run.tolerance <= physics::kDopri5MaxTolerance)) {
        return "the tolerance must be in [" + formatShort(physics::kDopri5MinTolerance) + ", " +
               formatShort(physics::kDopri5MaxTolerance) + "], got " + formatShort(run.tolerance);
    }
    return {};
}

void writePendulumCsv(const PendulumRun& run, std::ostream& out) {
    if (const std::string why = validateRun(run); !why.empty()) throw std::invalid_argument(why);
    const std::int64_t steps = stepCount(run.seconds, run.dt);
    const bool cartesian = run.method == Method::EulerCartesian;
    const bool adaptive = run.method == Method::Dopri5;
    physics::Pendulum pendulum(run.method, run.params, run.initial, physics::MidpointStart::Rk4, run.tolerance);
    std::optional<physics::Dopri5> free;
    if (adaptive) free.emplace(run.params, run.initial, run.tolerance);
    std::optional<physics::ExactPendulum> exact;
    if (run.params.damping == 0.0) exact.emplace(run.params, run.initial);
    const double e0 = physics::energy(run.params, run.initial);
    const double scale = mgl(run.params);

    out << "t,theta,omega,energy,theta_exact,energy_error" << (cartesian ? ",theta_from_position,rod_length" : "")
        << (adaptive ? ",steps" : "") << '\n';
    std::string line;
    for (std::int64_t k = 0; k <= steps; ++k) {
        // Time as k * dt rather than a running sum, so row k is exactly where the exact solution is taken.
        const double t = static_cast<double>(k) * run.dt;
        physics::PendulumState s;
        if (adaptive) {
            while (free->time() < t) free->step();
            s = k == 0 ? run.initial : free->interpolate(t);
        } else {
            if (k > 0) pendulum.step(run.dt);
            s = pendulum.state();
        }
        const double e = physics::energy(run.params, s);
        line.clear();
        appendNumber(line, t);
        line += ',';
        appendNumber(line, s.theta);
        line += ',';
        appendNumber(line, s.omega);
        line += ',';
        appendNumber(line, e);
        line += ',';
        appendNumber(line, exact ? exact->at(t).theta : kNaN);
        line += ',';
        appendNumber(line, (e - e0) / scale);
        if (cartesian) {
            line += ',';
            appendNumber(line, pendulum.thetaFromPosition());
            line += ',';
            appendNumber(line, pendulum.rodLength());
        }
        if (adaptive) line += ',' + std::to_string(free->stats().accepted);
        line += '\n';
        out.write(line.data(), static_cast<std::streamsize>(line.size()));
    }
}

void writePendulumCsv(const PendulumRun& run, const std::filesystem::path& path) {
    if (const std::string why = validateRun(run); !why.empty()) throw std::invalid_argument(why);
    writeCsvFile(path, [&](std::ostream& out) { writePendulumCsv(run, out); });
}

} // namespace lab
