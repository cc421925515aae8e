// The simple pendulum: its equations, every integrator the lab compares, and the closed-form solution
// they are measured against. theta'' = -(g / L) sin(theta) - damping * theta', unit-free state (theta, omega).
// Everything here is plain arithmetic on doubles: no GL, no clock, no allocation in any step, no I/O, and no
// hidden global state, so the game, the lab and the tests all step the very same code.
//
// Notes on the seed write-up (seed/, "Pendulum Simulation"), whose formulas these follow:
// - Its equation (2), x(t0 + h) = x0 + h f(x0), is explicit Euler: `euler` here. Its code listing, though,
//   updates theta first and then uses the NEW theta for omega; that is symplectic Euler (`symplectic-euler`),
//   which is why its "benchmark" does not visibly gain energy while true explicit Euler does.
// - Its equation (3) steps the bob's position by dx = omega R cos(theta) dt, dy = omega R sin(theta) dt;
//   the sign of dy there is for y pointing up, while its equation (1) has y pointing down. Here y points down
//   (x right), as in (1), so the step is dy = -omega R sin(theta) dt: the same motion, one convention.
// - Its midpoint, x(t0 + 2h) = x(t0) + f(t0 + h) 2h, is the two-step leapfrog y[n+1] = y[n-1] + 2h f(y[n]).
// - Its trapezoid, slope = (f(t0) + f(t0 + h)) / 2 with the end point predicted by Euler, is Heun's method.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

namespace physics {

struct PendulumParams {
    double length = 1.0;   // rod length L (m), > 0
    double gravity = 9.81; // g (m/s^2), > 0
    double mass = 1.0;     // bob mass (kg), > 0; only scales the energy, never the motion
    double damping = 0.0;  // linear damping c (1/s), >= 0: domega/dt = -(g/L) sin(theta) - c * omega
};

struct PendulumState {
    double theta = 0.0; // angle from straight down (rad), bob at (L sin, L cos) with x right, y down; not wrapped
    double omega = 0.0; // angular velocity dtheta/dt (rad/s)
};

enum class Method {
    Euler,
    EulerCartesian,
    Midpoint,
    Trapezoid,
    SymplecticEuler,
    Verlet,
    Rk4,
    ImplicitMidpoint,
    Yoshida4,
    Dopri5,
    Exact,
    Count
};
inline constexpr int kMethodCount = static_cast<int>(Method::Count);

// "euler", "euler-cartesian", "midpoint", "trapezoid", "symplectic-euler", "verlet", "rk4",
// "implicit-midpoint", "yoshida4", "dopri5", "exact"; "" for Method::Count or any value outside the enum.
// Saves store methods by these names, never by number.
std::string_view methodName(Method method);
// Exact (case-sensitive) inverse of methodName; nullopt for anything else, Count included.
std::optional<Method> methodFromName(std::string_view name);
// Force (sin) evaluations per step, the cost unit of the lab's work-precision charts: euler 1,
// euler-cartesian 1 (its extra cos for the position is not a force evaluation), midpoint 1 (after a
// start that costs one rk4 or euler step), trapezoid 2, symplectic-euler 1, verlet 1 (first same as last:
// the Pendulum class and stepVerletFsal reuse sin of the end point; stepVerlet alone costs 2), rk4 4,
// yoshida4 3 (three verlet substeps sharing their sin, first same as last), exact 0 (it evaluates elliptic
// functions instead; time it separately). implicit-midpoint and dopri5: 0, meaning "varies; see
// Pendulum::evaluations()" (the Newton iteration and the step-size controller decide). -1 for Count.
int evaluationsPerStep(Method method);
// Largest h * omega0 for which the method applied to the undamped linearised pendulum
// theta'' = -omega0^2 theta has no growing mode (spectral radius of its step map <= 1):
// 0 for euler, euler-cartesian and trapezoid (they grow at every h > 0: |1 + i x| > 1, |1 + i x - x^2/2| > 1),
// 1 for the leapfrog midpoint (roots i x +- sqrt(1 - x^2)), 2 for symplectic-euler and verlet
// (trace 2 - x^2, determinant 1), 2 sqrt(2) for rk4 (|R(ix)|^2 = 1 - x^6/72 + x^8/576),
// kYoshida4StabilityLimit = 1.5734 for yoshida4 (see there), +infinity for implicit-midpoint (A-stable:
// R(ix) = (1 + i x / 2) / (1 - i x / 2) has modulus 1 at every step), for dopri5 (no fixed step: the
// controller shrinks the step until the error test passes; its fixed-step map alone would be stable on the
// imaginary axis only up to x = 0.9972, where |1 + ix + ... + (ix)^5 / 120 + (ix)^6 / 600| reaches 1) and
// for exact. Below the limit symplectic-euler, verlet, midpoint, implicit-midpoint and yoshida4 keep the
// amplitude exactly, rk4 slowly loses it.
double linearStabilityLimit(Method method);

// yoshida4's limit. Its step map on the linear pendulum is the product of three verlet matrices
// [[1 - y^2/2, y], [-y (1 - y^2/4), 1 - y^2/2]] with y = w1 x, w0 x, w1 x: determinant 1, trace
// 2 - x^2 + x^4/12 + c6 x^6 with c6 = (2 * 2^(2/3) - 2^(1/3) - 2) / (144 (7 + 2 * 2^(1/3) - 6 * 2^(2/3)))
// = 0.12950839900935530 (expanded exactly with sympy). The trace stays within [1.11, 2] until it returns to
// 2 where -1 + x^2/12 + c6 x^4 = 0, i.e. x^2 = (sqrt(1/144 + 4 c6) - 1/12) / (2 c6), and exceeds 2 for
// every larger x (-1 + x^2/12 + c6 x^4 grows with x): no stable island beyond. Evaluated to 40 digits (mpmath):
// x = 1.5734019474345400566. (Each substep alone would break verlet's limit 2 from x = 2 / 1.7024 = 1.175,
// the composition is stable further.)
inline constexpr double kYoshida4StabilityLimit = 1.5734019474345400566;

// Largest initial |theta| (rad) and |omega| / sqrt(g / L) that validatePendulum accepts.
// The rods and gravities the game's sets and the lab's runs take: a rod of 1 mm (shorter is no pendulum
// anyone sees) to 16 m (the panel's 3 m with headroom; longer swings through the terrain around a set's post),
// and gravity up to a thousand times the Earth's.
inline constexpr double kMinPendulumLength = 1.0e-3, kMaxPendulumLength = 16.0; // m
inline constexpr double kMaxPendulumGravity = 1.0e4;                            // m/s^2
inline constexpr double kMaxInitialAngle = 1.0e6, kMaxFrequencyRatio = 1.0e6;

// Throws std::invalid_argument, naming the field, unless length, gravity and mass are finite and > 0,
// sqrt(g / L) is finite and > 0, damping is finite and >= 0, |theta| <= kMaxInitialAngle and
// |omega| <= kMaxFrequencyRatio sqrt(g / L). Pendulum and ExactPendulum call it.
void validatePendulum(const PendulumParams& params, const PendulumState& state);

double energy(const PendulumParams& params, const PendulumState& state); // J, zero at the pivot's height
double smallAngleFrequency(const PendulumParams& params);                // omega0 = sqrt(g / L) (rad/s)

// One-step methods as pure functions of (state, h). None of them checks its input (the hot loop of the lab
// benchmark calls them); Pendulum validates. Damping is included in every one of them.
PendulumState stepEuler(const PendulumParams& params, const PendulumState& state, double h);
PendulumState stepTrapezoid(const PendulumParams& params, const PendulumState& state, double h);
// theta first, then omega from the NEW theta (the seed's listing). Symplectic when damping == 0.
PendulumState stepSymplecticEuler(const PendulumParams& params, const PendulumState& state, double h);
// Velocity Verlet (Stormer-Verlet): half kick, drift, half kick. Damping enters the last half kick
// implicitly (solved in closed form, it is linear), which keeps the undamped scheme time-reversible.
PendulumState stepVerlet(const PendulumParams& params, const PendulumState& state, double h);
// The same step reusing sin(theta) of the previous step's end: sinTheta must hold sin(state.theta) on entry
// and holds sin of the returned theta on exit. Bit-identical to stepVerlet.
PendulumState stepVerletFsal(const PendulumParams& params, const PendulumState& state, double h, double& sinTheta);
PendulumState stepRk4(const PendulumParams& params, const PendulumState& state, double h);

// Implicit midpoint rule y1 = y0 + h f((y0 + y1) / 2), damping included. Symplectic when damping == 0 and
// A-stable: on the linear pendulum its amplitude is kept exactly at every h, and decays with damping.
// Solved as one equation in the midpoint angle x: omega_mid = (omega0 - (h/2) (g/L) sin(x)) / (1 + h c / 2)
// is linear in sin(x), so x - b + k sin(x) = 0 with b = theta0 + (h/2) omega0 / (1 + h c / 2) and
// k = (h/2)^2 (g/L) / (1 + h c / 2). |sin| <= 1 puts a root in [b - |k|, b + |k|]; a Newton iteration from b
// is kept inside that bracket (bisection whenever Newton would leave it or fails to halve its previous
// step) and stops once its update is within 4 eps |x|, or once Newton's quadratic error bound puts the next
// update there, or after kImplicitMidpointMaxIterations. For |k| < 1 the root is unique; for larger steps
// (h omega0 > 2) there can be several and the iteration returns the one it reaches from b, which for small
// amplitudes is the linear solution's. Typical cost: two iterations up to h omega0 = 0.1, five or so at
// h omega0 = 3. Adds to *evaluations (when not null) every sin and every cos it evaluated: two per iteration
// (the force sin(x) and the Jacobian's cos(x)) and one more sin only when it stopped on a bisection or at
// the iteration limit; after a converged Newton update sin of the final x is sin + cos * update instead
// (exact to the update's square, below rounding there). Finite for finite input as long as
// 1 + h damping / 2 != 0 (h = -2 / damping, backwards in time, is the method's pole: R(z) = (1 + z/2) /
// (1 - z/2)) and (h/2)^2 g / L does not overflow.
inline constexpr int kImplicitMidpointMaxIterations = 60;
PendulumState stepImplicitMidpoint(const PendulumParams& params, const PendulumState& state, double h,
                                   int* evaluations = nullptr);
// Yoshida's fourth-order triple jump of velocity verlet (the same method as Forest-Ruth's): verlet steps of
// w1 h, w0 h, w1 h with w1 = 1 / (2 - 2^(1/3)) = 1.3512 and w0 = -2^(1/3) w1 = -1.7024 (so the middle one
// runs backwards). verlet is symmetric, damping included, so the composition is fourth order with damping
// too, and symplectic without. The substeps go through stepVerletFsal: sinTheta must hold sin(state.theta)
// on entry and holds sin of the returned theta on exit (3 sin per step). With damping the backward substep's
// implicit half kick divides by 1 - 0.8512 h damping: keep h damping below 1.17 (at h damping = 1.1748 it
// divides by zero).
PendulumState stepYoshida4(const PendulumParams& params, const PendulumState& state, double h, double& sinTheta);
PendulumState stepYoshida4(const PendulumParams& params, const PendulumState& state, double h); // 4 sin

// The two methods that carry more than (theta, omega), as pure functions too (additions to the Pendulum API).
struct EulerCartesianState {
    PendulumState angular; // stepped by explicit Euler
    double x = 0.0;        // bob position relative to the pivot, x right (m)
    double y = 0.0;        // y down (m); starts at (L sin(theta), L cos(theta))
};
// Position first, from the OLD theta and omega (seed equation 3), then (theta, omega) by explicit Euler.
EulerCartesianState stepEulerCartesian(const PendulumParams& params, const EulerCartesianState& state, double h);
// Leapfrog: returns y[n+1] = y[n-1] + 2h f(y[n]) from previous = y[n-1] and current = y[n].
PendulumState stepMidpoint(const PendulumParams& params, const PendulumState& previous, const PendulumState& current,
                           double h);

// The undamped pendulum in closed form through Jacobi elliptic functions (Boost.Math), from any
// (theta0, omega0) at t = 0: swinging (k < 1), rotating over the top (k > 1; theta unbounded and monotonic)
// and the separatrix (k = 1; theta creeps towards +-pi and never arrives).
// Accuracy, against 50-digit evaluations: within 6e-14 rad over the first minute and 1e-13 rad at +-300 s
// for swings up to 179.9999 degrees; a few 1e-13 for rotation at 300 s, where the ulp of theta itself (which
// keeps growing) sets the floor. Far out the error grows like |t| ulp only, since the elliptic argument is
// reduced into one period exactly (std::remainder) before any function is evaluated. A modulus near 1 is
// brought down by descending Landen steps computed from k' (see pendulum_exact.cpp), because Boost alone
// loses a factor 1 / k'^2 there. Close to the separatrix the motion itself is ill-conditioned: one ulp of
// the initial omega moves theta by about 2e-16 sqrt(g / L) t / (K k'^2) rad (2e-6 rad after two minutes for
// 1 - k = 1e-9, the size of the disagreement with 50-digit evaluations there). A state within a few
// roundings of the separatrix is treated as on it, which is right until t reaches about
// ln(1 / k') / sqrt(g / L).
// Cost: about 0.3 us to construct, 0.2 us per at().
class ExactPendulum {
public:
    enum class Regime { Swinging, Rotating, Separatrix };

    // Throws std::invalid_argument for damping != 0 (no closed form here), a non-positive or non-finite
    // length, gravity or mass, or a non-finite initial state.
    ExactPendulum(const PendulumParams& params, const PendulumState& initial);
    PendulumState at(double t) const; // any t, negative too (s)
    // Time to return to the initial state (s): 4 K(k) / omega0 swinging; for rotation the time for theta to
    // gain or lose 2 pi (omega repeats exactly, theta repeats modulo 2 pi); +infinity on the separatrix.
    double period() const;
    // k = sqrt(sin^2(theta0 / 2) + (omega0 / (2 sqrt(g / L)))^2): < 1 swinging, > 1 rotating, exactly 1
    // on the separatrix (and, rounded, for states within 1e-16 of it: regime() tells them apart).
    double modulus() const;
    // sqrt(|1 - k^2|), from the state without cancellation: it tells 1 - 1e-33 from 1 where modulus() cannot
    // (fl(pi) at rest has k' = 6e-17 and k == 1.0 in doubles, yet it swings). 0 on the separatrix.
    double complementaryModulus() const { return m_kc; }
    Regime regime() const { return m_regime; }
    const PendulumParams& params() const { return m_params; }
    PendulumState initial() const { return m_initial; }

private:
    static constexpr int kMaxLanden = 12; // enough to bring any representable modulus below 0.7

    // sn, cn, dn of the regime's elliptic modulus, after reducing the argument into one period.
    void jacobi(double u, double& sn, double& cn, double& dn) const;
    double ellipticF(double phi) const; // F(phi | regime's modulus), through the same Landen chain

    PendulumParams m_params;
    PendulumState m_initial;
    Regime m_regime = Regime::Swinging;
    double m_omega0 = 0.0;  // sqrt(g / L)
    double m_k = 0.0;       // physical modulus as modulus() reports it
    double m_kc = 0.0;      // sqrt(|1 - k^2|)
    double m_rate = 0.0;    // du/dt of the elliptic argument: omega0 swinging/separatrix, k omega0 rotating
    double m_u0 = 0.0;      // elliptic argument at t = 0
    double m_quarter = 0.0; // K of the elliptic modulus used (1/k when rotating)
    double m_offset = 0.0;  // multiple of 2 pi taken off theta0 so the formulas see theta0 in [-pi, pi]
    double m_sign = 1.0;    // direction of travel (rotating and separatrix)
    int m_levels = 0;       // Landen levels used
    double m_ladder[kMaxLanden + 1] = {};  // moduli k_0 (the elliptic modulus) > k_1 > ... > k_levels
    double m_ladderC[kMaxLanden + 1] = {}; // complementary moduli sqrt(1 - k_j^2), computed without cancellation
    double m_scale = 1.0; // product of (1 + k_j), j = 1..levels: u at level 0 = scale * u at the bottom
};

// T / T0 for a pendulum released from rest at the given amplitude (rad, any sign, taken modulo 2 pi):
// 2 K(|sin(a / 2)|) / pi. Unbounded towards |a| = pi; fl(pi) itself, 1.2e-16 short of the top, gives 24.6.
// NaN for a non-finite amplitude.
double periodRatio(double amplitudeRadians);

// Dormand-Prince 5(4): the embedded explicit Runge-Kutta pair of Dormand and Prince (1980), 7 stages with
// the last one at the new point (first same as last: 6 new force evaluations per attempted step), advancing
// the fifth-order solution and testing the error estimate of the embedded fourth-order one. Error test:
// sqrt(((e_theta / s_theta)^2 + (e_omega / s_omega)^2) / 2) <= 1 with s = tol + tol max(|y0|, |y1|) per
// component (absolute and relative tolerance both tol; theta in rad, omega in rad/s). Step-size controller:
// h_new = h * clamp(0.9 err^(-1/5), 0.2, 10), not growing on the step right after a rejection, and never
// above 10 / sqrt(g / L) (without a ceiling a pendulum at rest, whose error estimate is exactly 0, would run
// the step up to infinity). Dense output: the continuous extension of Dormand and Prince (fourth order at
// every point of the step, the end values and end slopes matched), its coefficients checked against the
// order conditions up to order 4 for every fraction of the step (exact rational arithmetic).
struct Dopri5Stats {
    std::int64_t accepted = 0;    // steps taken
    std::int64_t rejected = 0;    // attempts the error test refused, each retried with a smaller step
    std::int64_t evaluations = 0; // force evaluations: 1 for f at the initial state, 1 more when the first
                                  // step is chosen by the heuristic, then 6 * (accepted + rejected)
};

// Accepted dopri5 tolerances, and the one Pendulum uses unless told otherwise. Below 1e-14 the error test
// asks for less than the rounding of the state itself; above 1 it asks for nothing.
inline constexpr double kDopri5MinTolerance = 1e-14, kDopri5MaxTolerance = 1.0, kDefaultDopri5Tolerance = 1e-8;

class Dopri5 {
public:
    // Throws std::invalid_argument, naming the value, for a tolerance outside [kDopri5MinTolerance,
    // kDopri5MaxTolerance] (NaN included), a negative or non-finite firstStep, a non-finite startTime,
    // parameters that validatePendulum rejects, or a non-finite initial state (any finite angle is accepted,
    // so that a saved run resumes however far it has turned). firstStep (s, a magnitude): the step the
    // controller tries first; 0 picks one with Hairer's starting-step heuristic (Hairer, Norsett, Wanner,
    // Solving ODEs I, II.4), which costs one force evaluation. Evaluates f at the initial state (the first
    // stage of the first step).
    Dopri5(const PendulumParams& params, const PendulumState& initial, double tolerance, double firstStep = 0.0,
           double startTime = 0.0);

    // Takes one accepted step towards tEnd (retrying rejected ones with smaller steps), never past tEnd:
    // when tEnd is within 1.01 times the proposed step the step lands on tEnd exactly (stretched by at most
    // 1 %, so no sliver is left over), and such a landing step, once accepted, does not replace the
    // controller's proposal (a rejected one shrinks it as any other). tEnd below time() steps backwards in
    // time; tEnd == time() does nothing. Throws std::invalid_argument for a NaN tEnd, and std::runtime_error
    // (the last accepted state kept, the step size and counts as they came) when the step to try is not
    // above 16 eps max(|t|, 1 / sqrt(g / L)), as after rejections under a damping too stiff for an explicit
    // method (h damping must stay below about 3.3): stop rather than loop. A damping stiff but not that stiff
    // is followed, slowly: about damping / 3 steps per second.
    void step(double tEnd = std::numeric_limits<double>::infinity());
    // Steps until time() == t exactly (the last step landing on t), for the game's fixed ticks. Throws
    // std::invalid_argument for a non-finite t, and what step throws.
    void advanceTo(double t);

    double time() const { return m_time; } // s
    PendulumState state() const { return m_state; }
    // The dense output of the last accepted step, which spans [time() - lastStep(), time()] (reversed when
    // stepping backwards): fourth order, exact at both ends up to rounding. Outside the step it extrapolates
    // the polynomial, with no accuracy promised. Throws std::logic_error before the first step.
    PendulumState interpolate(double t) const;
    double lastStep() const { return m_denseStep; } // signed size of the last accepted step (s); 0 before any
    double nextStep() const { return m_next; }      // magnitude of the step the controller tries next (s), > 0
    double tolerance() const { return m_tolerance; }
    const Dopri5Stats& stats() const { return m_stats; }
    void restoreStats(const Dopri5Stats& stats) { m_stats = stats; } // a keyframe's counts (Pendulum::Internals)

private:
    PendulumParams m_params;
    double m_tolerance = kDefaultDopri5Tolerance;
    double m_w2 = 0.0;      // g / L
    double m_maxStep = 0.0; // ceiling of nextStep: 10 / sqrt(g / L)
    double m_minStep = 0.0; // 16 eps / sqrt(g / L): floor of the step to try, besides 16 eps |time|
    PendulumState m_state;
    PendulumState m_slope; // f(m_state): the first stage of the next step (first same as last)
    double m_time = 0.0;
    double m_next = 0.0; // magnitude of the next step to try
    Dopri5Stats m_stats;
    // Dense output of the last accepted step, y(t0 + s h) = r1 + s (r2 + (1 - s) (r3 + s (r4 + (1 - s) r5))).
    double m_denseStart = 0.0; // t0
    double m_denseStep = 0.0;  // h, signed; 0 = no step yet
    PendulumState m_r1, m_r2, m_r3, m_r4, m_r5;
};

// How the second starting value y[1] of the two-step midpoint is made (y[0] is the initial state).
// The leapfrog's solution is a smooth principal part plus a parasitic part that flips sign every step (the
// root near -1), seen as a sawtooth on the curve; the start sets its size. Theory (the principal part obeys
// a modified equation whose O(h^2) term makes it miss the exact y(h) by O(h^3)) and the tests agree:
// - Rk4 (default): y[1] accurate to O(h^5), so the sawtooth is O(h^3), one order below the O(h^2) error; an
//   exact y[1] does no better, and rk4 also works with damping, where there is no exact solution. The one
//   start step costs 4 evaluations once.
// - Euler (as the seed would do it): y[1] off by O(h^2), so the sawtooth is O(h^2), as large as the error
//   itself. The method stays second order; the error at a given time can come out larger or smaller (the
//   sawtooth shifts the phase of one of the two interleaved step chains), so only the sawtooth is reliably
//   worse. (From rest, Euler's omega[1] happens to be O(h^3) accurate, so there only theta[1] is off.)
// With damping > 0 the parasitic part grows like exp(damping * t / 2) whatever the start (the leapfrog is
// weakly unstable for dissipative problems) while the motion decays like exp(-damping * t / 2); a better
// start only delays the moment it takes over.
enum class MidpointStart { Rk4, Euler };

// Any Method behind one interface, for the game and the lab.
class Pendulum {
public:
    // Throws std::invalid_argument for invalid parameters or initial state (see ExactPendulum), for
    // Method::Count, for Method::Exact with damping != 0 (the closed form is for the undamped pendulum), and
    // for a dopri5 tolerance outside [kDopri5MinTolerance, kDopri5MaxTolerance] (checked for every method;
    // only dopri5 uses it).
    Pendulum(Method method, const PendulumParams& params, const PendulumState& initial,
             MidpointStart start = MidpointStart::Rk4, double tolerance = kDefaultDopri5Tolerance);

    // Advance by h (s). Any finite h, varying from call to call; h == 0 does nothing; a non-finite h throws
    // std::invalid_argument. Midpoint: when h differs from the previous step's, the two-step history is
    // dropped and restarted from the current state with one start step (MidpointStart), since a leapfrog
    // with unequal steps is only first order. Exact: evaluates the closed form at the accumulated time.
    // Dopri5: Dopri5::advanceTo the accumulated time, in as many adaptive steps as the tolerance needs (the
    // last one landing on it), so its cost per call varies; it throws what advanceTo throws, the pendulum
    // unchanged then.
    void step(double h);
    PendulumState state() const { return m_state; }
    double time() const { return m_time; } // accumulated with compensated summation (s)
    Method method() const { return m_method; }
    MidpointStart midpointStart() const { return m_start; }
    double tolerance() const { return m_tolerance; } // dopri5's (see Dopri5); stored for every method
    // Force (sin) evaluations made so far, every method counted: evaluationsPerStep per step for the fixed
    // ones plus their start-up (verlet and yoshida4: 1 for sin of the initial angle, their first same as
    // last; midpoint: the 4 or 1 of each start step), implicit-midpoint the sin and cos its Newton iterations
    // made (see stepImplicitMidpoint), dopri5 its Dopri5Stats::evaluations, exact 0. reset() restarts the
    // count as construction does; setInternals() restarts it at 0, plus for dopri5 what its restart evaluates
    // (1, or 2 when it picks a fresh first step).
    std::int64_t evaluations() const;
    const PendulumParams& params() const { return m_params; }
    double energy() const { return physics::energy(m_params, m_state); } // J

    // Bob position relative to the pivot, x right and y down (m). euler-cartesian: the stepped position;
    // every other method: (L sin(theta), L cos(theta)).
    double bobX() const;
    double bobY() const;
    // euler-cartesian: atan2(x, y) of the stepped position, on the branch (multiple of 2 pi) nearest the
    // stepped theta so the two can be compared after full turns; others: theta.
    double thetaFromPosition() const;
    // euler-cartesian: |position|; others: L.
    double rodLength() const;
    // New initial state, time back to 0, history (midpoint, position, dopri5's step size) rebuilt,
    // evaluations restarted. Same validation as the constructor.
    void reset(const PendulumState& initial);

    // Everything a Pendulum carries besides its method, parameters, midpoint start and tolerance, so that a
    // saved world resumes bit for bit (src/save). Plain values; setInternals(internals()) changes nothing
    // but the evaluation count. dopri5 needs nothing more than its state, time and next step: the first
    // stage of its next step, f(state), is recomputed from the state, bit for bit what the last step left.
    struct Internals {
        PendulumState state;
        double time = 0.0;
        double timeCarry = 0.0;     // Kahan compensation of time
        PendulumState previous;     // midpoint: y[n-1]
        double lastStep = 0.0;      // midpoint: h of the history; 0 = none. dopri5: the step the controller
                                    // tries next (s); <= 0 = pick a fresh first step
        double x = 0.0, y = 0.0;    // euler-cartesian position (m)
        double sinTheta = 0.0;      // verlet, yoshida4: sin(state.theta)
        PendulumState exactInitial; // exact: the state the closed form starts from at time 0
        // What it cost so far (the panel's cost column and work-precision dot): a keyframe's. None (a save keeps
        // none): counted afresh from the restore.
        struct Counts {
            std::int64_t evaluations = 0; // every method but dopri5
            Dopri5Stats dopri5{};
        };
        std::optional<Counts> counts;
    };
    Internals internals() const;
    // Throws std::invalid_argument (nothing changed) unless every value is finite (and, for exact, the
    // initial state passes validatePendulum).
    void setInternals(const Internals& in);

private:
    Method m_method;
    PendulumParams m_params;
    MidpointStart m_start;
    double m_tolerance; // dopri5's
    PendulumState m_state;
    double m_time = 0.0;
    double m_timeCarry = 0.0; // Kahan compensation for m_time
    PendulumState m_previous; // midpoint: y[n-1]
    double m_lastStep = 0.0;  // midpoint: h of the history; 0 = no history
    double m_x = 0.0;         // euler-cartesian position (m)
    double m_y = 0.0;
    double m_sinTheta = 0.0;        // verlet, yoshida4: sin(m_state.theta), first same as last
    std::int64_t m_evaluations = 0; // every method but dopri5, whose Dopri5 counts its own
    std::optional<ExactPendulum> m_exact;
    std::optional<Dopri5> m_dopri5; // dopri5: the integrator, its time kept equal to m_time
};

} // namespace physics
