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

enum class Method { Euler, EulerCartesian, Midpoint, Trapezoid, SymplecticEuler, Verlet, Rk4, Exact, Count };
inline constexpr int kMethodCount = static_cast<int>(Method::Count);

// "euler", "euler-cartesian", "midpoint", "trapezoid", "symplectic-euler", "verlet", "rk4", "exact";
// "" for Method::Count or any value outside the enum.
std::string_view methodName(Method method);
// Exact (case-sensitive) inverse of methodName; nullopt for anything else, Count included.
std::optional<Method> methodFromName(std::string_view name);
// Force (sin) evaluations per step, the cost unit of the lab's work-precision charts: euler 1,
// euler-cartesian 1 (its extra cos for the position is not a force evaluation), midpoint 1 (after a
// start that costs one rk4 or euler step), trapezoid 2, symplectic-euler 1, verlet 1 (first same as last:
// the Pendulum class and stepVerletFsal reuse sin of the end point; stepVerlet alone costs 2), rk4 4,
// exact 0 (it evaluates elliptic functions instead; time it separately). -1 for Count.
int evaluationsPerStep(Method method);
// Largest h * omega0 for which the method applied to the undamped linearised pendulum
// theta'' = -omega0^2 theta has no growing mode (spectral radius of its step map <= 1):
// 0 for euler, euler-cartesian and trapezoid (they grow at every h > 0: |1 + i x| > 1, |1 + i x - x^2/2| > 1),
// 1 for the leapfrog midpoint (roots i x +- sqrt(1 - x^2)), 2 for symplectic-euler and verlet
// (trace 2 - x^2, determinant 1), 2 sqrt(2) for rk4 (|R(ix)|^2 = 1 - x^6/72 + x^8/576), +infinity for exact.
// Below the limit symplectic-euler, verlet and midpoint keep the amplitude exactly, rk4 slowly loses it.
double linearStabilityLimit(Method method);

// Largest initial |theta| (rad) and |omega| / sqrt(g / L) that validatePendulum accepts.
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
    // Method::Count, and for Method::Exact with damping != 0 (the closed form is for the undamped pendulum).
    Pendulum(Method method, const PendulumParams& params, const PendulumState& initial,
             MidpointStart start = MidpointStart::Rk4);

    // Advance by h (s). Any finite h, varying from call to call; h == 0 does nothing; a non-finite h throws
    // std::invalid_argument. Midpoint: when h differs from the previous step's, the two-step history is
    // dropped and restarted from the current state with one start step (MidpointStart), since a leapfrog
    // with unequal steps is only first order. Exact: evaluates the closed form at the accumulated time.
    void step(double h);
    PendulumState state() const { return m_state; }
    double time() const { return m_time; } // accumulated with compensated summation (s)
    Method method() const { return m_method; }
    MidpointStart midpointStart() const { return m_start; }
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
    // New initial state, time back to 0, history (midpoint, position) rebuilt. Same validation as the
    // constructor.
    void reset(const PendulumState& initial);

    // Everything a Pendulum carries besides its method, parameters and midpoint start, so that a saved
    // world resumes bit for bit (src/save). Plain values; setInternals(internals()) changes nothing.
    struct Internals {
        PendulumState state;
        double time = 0.0;
        double timeCarry = 0.0;     // Kahan compensation of time
        PendulumState previous;     // midpoint: y[n-1]
        double lastStep = 0.0;      // midpoint: h of the history; 0 = none
        double x = 0.0, y = 0.0;    // euler-cartesian position (m)
        double sinTheta = 0.0;      // verlet: sin(state.theta)
        PendulumState exactInitial; // exact: the state the closed form starts from at time 0
    };
    Internals internals() const;
    // Throws std::invalid_argument (nothing changed) unless every value is finite (and, for exact, the
    // initial state passes validatePendulum).
    void setInternals(const Internals& in);

private:
    Method m_method;
    PendulumParams m_params;
    MidpointStart m_start;
    PendulumState m_state;
    double m_time = 0.0;
    double m_timeCarry = 0.0; // Kahan compensation for m_time
    PendulumState m_previous; // midpoint: y[n-1]
    double m_lastStep = 0.0;  // midpoint: h of the history; 0 = no history
    double m_x = 0.0;         // euler-cartesian position (m)
    double m_y = 0.0;
    double m_sinTheta = 0.0; // verlet: sin(m_state.theta), first same as last
    std::optional<ExactPendulum> m_exact;
};

} // namespace physics
