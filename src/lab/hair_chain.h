// The hair-chain study of minecrappy-lab: a strand with no damping and no collider, root pinned, is a planar
// N-link pendulum with equal point masses at its N free nodes and massless rigid links of length l = L / N.
// ChainReference integrates its exact equations of motion (joint angles, Dormand-Prince 5(4) at 1e-12);
// runHairChain releases a straight horizontal strand from rest in both the reference and physics::HairSolver
// (any HairMethod) and reports, every step, how far the solver's tip is from the truth, how far its
// segments are from their length and how far its energy has drifted.
// It must never touch a terminal or exit: results are returned; lab_cli writes them.
#pragma once

#include "lab/ode.h"
#include "physics/hair.h"

#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <vector>

namespace lab {

inline constexpr int kMaxChainLinks = 64;

// The chain, in the vertical plane: x horizontal, y up, the root at (0, 0).
struct ChainParams {
    int links = 11;        // N, 1 .. kMaxChainLinks
    double length = 0.45;  // L (m), root to tip, finite and > 0; each link is L / N
    double gravity = 9.81; // g (m/s^2) along -y, finite and >= 0
    double mass = 1.0;     // total mass of the N free nodes (kg), finite and > 0; each node has mass / N
};

struct ChainPoint {
    double x = 0.0, y = 0.0;
};

// Joint angles theta_j (j = 1..N) from straight down: node k sits at x_k = l sum_{j<=k} sin(theta_j),
// y_k = -l sum_{j<=k} cos(theta_j). With node mass m, the Lagrangian gives (1-based, c_ij = N - max(i, j) + 1)
//   sum_j c_ij cos(theta_i - theta_j) theta_j'' = -sum_j c_ij sin(theta_i - theta_j) theta_j'^2
//                                                 - (g / l) (N - i + 1) sin(theta_i),
// the mass matrix m l^2 c_ij cos(theta_i - theta_j) divided out; it is symmetric positive definite and solved
// by Cholesky at every evaluation. N = 1 is the simple pendulum (physics::ExactPendulum).
// The same motion follows from the link tensions in O(N) (ChainEquations::Tensions): with tau_k = T_k / m
// (link k pulls node k - 1 and node k together, tau_{N+1} = 0), the rigid links give a tridiagonal system
//   -d_k tau_k + cos(theta_k - theta_{k+1}) tau_{k+1} + cos(theta_k - theta_{k-1}) tau_{k-1}
//       = -l theta_k'^2 - [k = 1] g cos(theta_1),            d_1 = 1, d_k = 2 otherwise,
// (weakly diagonally dominant, one row strictly: solved without pivoting), and then
//   l theta_k'' = tau_{k+1} sin(theta_{k+1} - theta_k) + tau_{k-1} sin(theta_{k-1} - theta_k) - [k = 1] g sin(theta_1).
// The two are derived independently (Lagrange; Newton on the nodes) and the tests hold them to each other.
enum class ChainEquations : std::uint8_t {
    MassMatrix, // the Lagrangian equations above, O(N^3) per evaluation (Cholesky)
    Tensions,   // the tension form, O(N) per evaluation
};

class ChainReference {
public:
    // theta, omega: N angles (rad) and angular velocities (rad/s). Throws std::invalid_argument for params
    // outside their ranges, wrong sizes or non-finite values (and for bad ODE options).
    ChainReference(const ChainParams& params, std::span<const double> theta, std::span<const double> omega,
                   const OdeOptions& ode = {}, ChainEquations equations = ChainEquations::MassMatrix);
    ChainReference(const ChainReference&) = delete; // the integrator calls back into this object
    ChainReference& operator=(const ChainReference&) = delete;

    // Integrates to exactly t >= time() (see DormandPrince::advanceTo; throws what it throws).
    void advanceTo(double t);
    double time() const { return m_ode.time(); }

    const ChainParams& params() const { return m_params; }
    ChainEquations equations() const { return m_equations; }
    double linkLength() const { return m_params.length / m_params.links; }
    std::span<const double> theta() const { return m_ode.state().first(static_cast<std::size_t>(m_params.links)); }
    std::span<const double> omega() const { return m_ode.state().last(static_cast<std::size_t>(m_params.links)); }
    // N + 1 points, the root (0, 0) first, the tip last.
    std::vector<ChainPoint> nodes() const;
    ChainPoint tip() const;
    // Kinetic plus potential energy (J), the potential m g y_k summed over the free nodes (zero at the root's
    // height). Computed from the node velocities, not from the mass matrix of the equations above, so its
    // conservation also checks the equations.
    double energy() const;
    const DormandPrince& integrator() const { return m_ode; }

    // The right-hand side: y = (theta_1..N, omega_1..N) -> (omega, theta''). For tests.
    void derivatives(std::span<const double> y, std::span<double> dydt) const;

private:
    void massMatrixDerivatives(std::span<const double> y, std::span<double> dydt) const;
    void tensionDerivatives(std::span<const double> y, std::span<double> dydt) const;

    ChainParams m_params;
    ChainEquations m_equations;
    mutable std::vector<double> m_a, m_b, m_sin, m_cos; // scratch of derivatives(): matrix, right side, sin, cos
    DormandPrince m_ode;                                // last: built after the scratch it uses
};

struct HairChainOptions {
    std::string solver = "dftl"; // a physics::hairMethodName, or "reference" (the solver replaced by the reference)
    int links = 11;
    double length = 0.45;
    double dt = 1.0 / 60.0;
    double seconds = 2.0;
    int iterations = 0; // 0 = the method's default (physics::hairMethodDefaults)
    int substeps = 0;   // 0 = the method's default
    double gravity = 9.81;
    // As in the game: steps longer than 1/60 s split, and shake's substeps chosen from the turn of its segments
    // (physics::hairSubstepsFor). Off: the method's own substeps only, so that a step is the step studied.
    bool automaticSubsteps = false;
};

// An empty string when the options are usable; otherwise what is wrong, naming the flag and the value.
std::string validateHairChain(const HairChainOptions& options);

// The parameters runHairChain gives physics::HairSolver for these options (one strand of links + 1 nodes, no
// damping, no host collision, no sleep, no automatic substeps; iterations and substeps from the method's
// defaults unless given). Throws std::invalid_argument for invalid options or the "reference" solver.
physics::HairParams hairChainParams(const HairChainOptions& options);

struct HairChainRow {
    double t = 0;              // s
    double tipX = 0, tipY = 0; // simulated tip relative to the root (m): x along the released strand, y up
    double refTipX = 0, refTipY = 0;
    double tipError = 0;        // m, distance between the simulated and the reference tip (any z drift included)
    double maxSegmentError = 0; // max over segments of | |segment| / l - 1 |
    double energyError = 0;     // (E - E0) / (M g L), M the strand's total mass (its N free nodes)
    int substeps = 0;           // substeps the solver ran in the step ending at this row (0 at t = 0, reference)
};

// Releases a straight horizontal strand at rest along +x from the root (theta_j = pi / 2) and returns one row
// per step, t = 0 included: rows n = 0 .. ceil(seconds / dt), at t = n dt with dt rounded to float (the step
// the solver takes, so that the reference is sampled at the solver's times). The solver's energy uses
// central-difference velocities (x_{n+1} - x_{n-1}) / (2 dt) (zero at t = 0, the release), so the solver is
// stepped once past the last row. Throws std::invalid_argument for invalid options (validateHairChain), and
// std::runtime_error when the reference cannot be integrated.
std::vector<HairChainRow> runHairChain(const HairChainOptions& options);

// t,tip_x,tip_y,ref_tip_x,ref_tip_y,tip_error,max_segment_error,energy_error; numbers as %.9g.
void writeHairChainCsv(const std::vector<HairChainRow>& rows, std::ostream& out);

// tipError of the row whose t is nearest t (the earlier on a tie); NaN for no rows. Rows in increasing t.
double chainTipErrorAt(const std::vector<HairChainRow>& rows, double t);

// What the eye sees of a run over the rows with t in [from, to], the simulated chain's and the reference's side
// by side: past the predictability horizon (ChainHorizon), where a tip error compares nothing, these are what
// the charts compare. NaN where a figure has nothing to stand on (no rows; fewer than two swings).
struct ChainLook {
    double energy = 0.0;           // mean (E - E0) / (M g L) of the simulated chain (the reference keeps 0)
    double meanTipHeight = 0.0;    // m: the simulated tip's mean y (the root at 0; hanging at rest: -L)
    double refMeanTipHeight = 0.0; // m: the reference tip's
    double swingPeriod = 0.0;      // s: the simulated tip's, see kSwingAmplitude
    double refSwingPeriod = 0.0;   // s: the reference tip's
};
// A swing: the tip crosses x = 0 (at the time interpolated between rows) and then gets this far beyond it on
// the other side, so the tremor of a chain at rest counts for nothing; the period is twice the mean time
// between successive swings.
inline constexpr double kSwingAmplitude = 0.01; // m
ChainLook chainLook(const std::vector<HairChainRow>& rows, double from, double to);

} // namespace lab

namespace lab {

// How far the released chain (straight and horizontal, at rest) can be predicted, and how far the reference is
// exact (the hair report's horizon table; HAIR.md):
// - horizon: the first time two references started 1e-9 rad apart (the first joint's angle) have tips 1 mm
//   apart. Past it the motion is chaotic: what a 1e-9 rad change does, any method's error does too, so
//   tip errors compare nothing there, and the charts compare what the eye sees (energy, mean tip height).
// - exactTo: the first time the reference (Dormand-Prince 5(4) at 1e-12 on the Lagrange equations) and a
//   second integrator (classic fourth-order Runge-Kutta at a fixed step of `rk4Step` on the tension
//   equations: another method and other equations) have tips 1 micrometre apart.
// Both are sampled every millisecond up to `seconds`; NaN where the threshold is not reached by then.
struct ChainHorizon {
    ChainParams chain;
    double seconds = 0.0;
    double rk4Step = 0.0;
    double horizon = 0.0;            // s
    double exactTo = 0.0;            // s
    double maxAgreementBefore = 0.0; // m: the largest reference-to-second-integrator tip distance before horizon
};
inline constexpr double kHorizonPerturbation = 1e-9; // rad
inline constexpr double kHorizonTipDistance = 1e-3;  // m
inline constexpr double kExactTipDistance = 1e-6;    // m

// Throws std::invalid_argument for chain params outside their ranges or seconds outside (0, 60], and
// std::runtime_error when the reference cannot be integrated.
ChainHorizon chainHorizon(const ChainParams& chain, double seconds, double rk4Step = 2.5e-6);

// The second integrator on its own, for tests: the released chain's tip at each of `times` (increasing), by
// classic RK4 at a fixed step (the last step into each time shortened to land on it).
std::vector<ChainPoint> chainTipsRk4(const ChainParams& chain, std::span<const double> times, double step);

} // namespace lab
