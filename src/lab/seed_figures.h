// The seed-figures study of minecrappy-lab (`minecrappy-lab seed-figures`).
#pragma once
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "lab/pendulum_common.h"
#include "lab/svg_chart.h"
#include "physics/pendulum.h"

namespace lab {

// The seed write-up's figures, redone: theta, omega and energy over time for its methods beside the
// exact solution, one figure per step size. The seed released a 1 m pendulum from 20 degrees at rest
// with g = 9.80665 and plotted theta in degrees; its Euler moved the bob in x, y (euler-cartesian) and
// also plotted the angle recovered from that position, so both Euler variants are drawn.

struct SeedFiguresOptions {
    std::vector<double> dts = {0.001, 0.016, 0.033}; // s
    std::vector<physics::Method> methods = {physics::Method::Euler, physics::Method::EulerCartesian,
                                            physics::Method::Midpoint, physics::Method::Trapezoid};
    physics::PendulumParams params{1.0, 9.80665, 1.0, 0.0};
    double theta0Deg = 20.0;
    double seconds = 20.0;
};

struct SeedTrace {
    physics::Method method = physics::Method::Exact; // Exact: the closed form on the same time grid
    std::vector<double> theta, omega, energy;        // rad, rad/s, J
    std::vector<double> thetaFromPosition;           // euler-cartesian only; empty otherwise
};

struct SeedFigure {
    double dt = 0.0;
    std::vector<double> t;
    std::vector<SeedTrace> traces; // options.methods in order, then the exact solution
};

std::vector<SeedFigure> runSeedFigures(const SeedFiguresOptions& options, const Progress& progress = {});
// "seed_dt1ms", "seed_dt16ms", "seed_dt0.5ms": the file stem for one step size.
std::string seedFigureStem(double dt);
// Wide CSV: t, then theta_M,omega_M,energy_M per method M (+ theta_from_position_euler-cartesian), exact last.
void writeSeedFigureCsv(const SeedFigure& figure, std::ostream& out);
Chart seedFigureChart(const SeedFigure& figure, const SeedFiguresOptions& options);
// Writes <stem>.svg and <stem>.csv per figure into `dir`; returns the paths written.
std::vector<std::filesystem::path> writeSeedFigures(const std::vector<SeedFigure>& figures,
                                                    const SeedFiguresOptions& options,
                                                    const std::filesystem::path& dir);

} // namespace lab
