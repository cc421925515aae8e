// An adaptive explicit Runge-Kutta integrator for y' = f(t, y), y a vector of doubles: the Dormand-Prince
// 5(4) pair (Dormand & Prince 1980, "A family of embedded Runge-Kutta formulae"), advanced with the fifth-order
// solution (local extrapolation), its embedded fourth-order solution giving the error estimate. Seven stages,
// the last evaluated at the new point and reused as the next step's first, so every attempted step costs six
// evaluations (FSAL). The lab's reference solutions (the N-link chain of the hair study; later the pendulum
// studies) use it at tight tolerances (1e-12).
//
// Step-size control: the error of a step is the root mean square over components of
// e_i / (atol + rtol max(|y_i|, |y_new_i|)); a step is accepted when that is <= 1. The next step is
// h * safety * err^-alpha * errPrev^beta (a PI controller, Gustafsson's, with Hairer's alpha = 0.17,
// beta = 0.04 for order 5), limited to [minFactor, maxFactor] times h and to no growth right after a rejection.
// advanceTo(t) lands on t exactly: the last step is clipped to it, without spoiling the step size proposed for
// the steps after it.
//
// Plain arithmetic: no clock, no I/O, no global state. Everything is allocated in the constructor.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

namespace lab {

struct OdeOptions {
    double relTol = 1e-12;    // relative tolerance, > 0 (finite)
    double absTol = 1e-12;    // absolute tolerance, > 0 (finite)
    double initialStep = 0.0; // first step (s); 0 = chosen from f at the start (Hairer's starting-step heuristic)
    double maxStep = std::numeric_limits<double>::infinity(); // > 0
    std::int64_t maxSteps = 10'000'000; // attempted steps (accepted + rejected) per advanceTo call, >= 1
    double safety = 0.9;
    double minFactor = 0.2;  // the step shrinks by at most 5x...
    double maxFactor = 10.0; // ...and grows by at most 10x per step
};

struct OdeCounters {
    std::int64_t accepted = 0;
    std::int64_t rejected = 0;
    std::int64_t evaluations = 0; // calls of f
};

class DormandPrince {
public:
    // dydt = f(t, y); dydt has y's size on entry and must be filled (it may hold anything on entry).
    using Rhs = std::function<void(double t, std::span<const double> y, std::span<double> dydt)>;

    // Throws std::invalid_argument for an empty or non-finite y0, a non-finite t0, a missing f, or options
    // outside their ranges (tolerances and maxStep > 0, safety in (0, 1], 0 < minFactor <= 1 <= maxFactor).
    DormandPrince(Rhs f, double t0, std::vector<double> y0, const OdeOptions& options = {});

    // Integrates forward to exactly t (time() == t afterwards). t < time() throws std::invalid_argument,
    // t == time() does nothing. Throws std::runtime_error (the state left at the last accepted step) when
    // more than options.maxSteps steps are attempted in this call, when the step falls below the resolution
    // of t, or when f returns non-finite values that no smaller step avoids.
    void advanceTo(double t);

    // One step of exactly h > 0 with the fifth-order solution and no error control (accepted whatever the
    // error estimate, which lastErrorNorm() then reports): for measuring the method's order with fixed steps.
    void fixedStep(double h);

    double time() const { return m_t; }
    std::span<const double> state() const { return m_y; }
    // f at (time(), state()), already evaluated (first same as last).
    std::span<const double> derivative() const { return m_k[0]; }
    const OdeCounters& counters() const { return m_counters; }
    const OdeOptions& options() const { return m_options; }
    double proposedStep() const { return m_h; }        // the step the next advanceTo starts with; 0 before the first
    double lastErrorNorm() const { return m_lastErr; } // scaled error of the last step attempted (accept <= 1)

private:
    // Takes one step of h from (m_t, m_y): the five stages and the new point into m_yNew and m_k[6]; returns
    // the scaled error norm (+infinity when anything is non-finite).
    double attempt(double h);
    void accept(double h);                 // moves the new point into the state (FSAL: k7 becomes k1)
    double startingStep(double remaining); // first step for a run of `remaining` seconds
    double errorNorm() const;

    Rhs m_f;
    OdeOptions m_options;
    double m_t = 0.0;
    std::vector<double> m_y, m_yNew, m_yStage;
    std::vector<double> m_k[7];
    double m_h = 0.0;        // proposed next step (> 0 once chosen)
    double m_errPrev = 1e-4; // PI controller memory: error of the last accepted step
    double m_lastErr = 0.0;
    OdeCounters m_counters;
};

} // namespace lab
