#include "lab/hair_chain.h"

#include "lab/lab_util.h"

#include "lab/hair_study.h"      // kMaxHairSteps
#include "lab/pendulum_common.h" // stepCount

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

namespace lab {

namespace {

void validateChain(const ChainParams& p, std::span<const double> theta, std::span<const double> omega) {
    const auto bad = [](const std::string& what) { throw std::invalid_argument("ChainReference: " + what); };
    if (p.links < 1 || p.links > kMaxChainLinks) bad("links must be in 1.." + std::to_string(kMaxChainLinks));
    if (!(std::isfinite(p.length) && p.length > 0.0)) bad("length must be finite and > 0");
    if (!(std::isfinite(p.gravity) && p.gravity >= 0.0)) bad("gravity must be finite and >= 0");
    if (!(std::isfinite(p.mass) && p.mass > 0.0)) bad("mass must be finite and > 0");
    const auto n = static_cast<std::size_t>(p.links);
    if (theta.size() != n || omega.size() != n) bad("theta and omega need one value per link");
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(theta[i]) || !std::isfinite(omega[i])) bad("non-finite initial angle or velocity");
}

std::vector<double> initialState(const ChainParams& p, std::span<const double> theta, std::span<const double> omega) {
    validateChain(p, theta, omega);
    std::vector<double> y(theta.begin(), theta.end());
    y.insert(y.end(), omega.begin(), omega.end());
    return y;
}

std::string number(double v) { return formatNumber("%.9g", v); }

// Node positions and velocities of the solver's strand relative to its root, in double.
struct ChainSnapshot {
    std::vector<double> x, y, z;
};

void capture(const physics::HairSolver& s, ChainSnapshot& out) {
    const int n = s.nodesPerStrand(); // one strand: index = node
    out.x.resize(static_cast<std::size_t>(n));
    out.y.resize(static_cast<std::size_t>(n));
    out.z.resize(static_cast<std::size_t>(n));
    const double rx = s.x()[0], ry = s.y()[0], rz = s.z()[0];
    for (int k = 0; k < n; ++k) {
        const auto i = static_cast<std::size_t>(k);
        out.x[i] = static_cast<double>(s.x()[k]) - rx;
        out.y[i] = static_cast<double>(s.y()[k]) - ry;
        out.z[i] = static_cast<double>(s.z()[k]) - rz;
    }
}

} // namespace

// ---------------------------------------------------------------------------------------------------
// ChainReference

ChainReference::ChainReference(const ChainParams& params, std::span<const double> theta, std::span<const double> omega,
                               const OdeOptions& ode, ChainEquations equations)
    : m_params(params), m_equations(equations),
      m_a(static_cast<std::size_t>(std::clamp(params.links, 1, kMaxChainLinks) *
                                   std::clamp(params.links, 1, kMaxChainLinks))),
      m_b(static_cast<std::size_t>(std::clamp(params.links, 1, kMaxChainLinks))), m_sin(m_b.size()), m_cos(m_b.size()),
      m_ode([this](double, std::span<const double> y, std::span<double> dydt) { derivatives(y, dydt); }, 0.0,
            initialState(params, theta, omega), ode) {}

void ChainReference::derivatives(std::span<const double> y, std::span<double> dydt) const {
    if (m_equations == ChainEquations::Tensions)
        tensionDerivatives(y, dydt);
    else
        massMatrixDerivatives(y, dydt);
}

void ChainReference::tensionDerivatives(std::span<const double> y, std::span<double> dydt) const {
    const auto N = static_cast<std::size_t>(m_params.links);
    const double l = linkLength(), g = m_params.gravity;
    for (std::size_t i = 0; i < N; ++i) {
        m_sin[i] = std::sin(y[i]);
        m_cos[i] = std::cos(y[i]);
        dydt[i] = y[N + i];
    }
    // 0-based k: tau_k of link k (root side node k - 1, with node -1 the root). Thomas algorithm on
    // lower(k) tau_{k-1} + diag(k) tau_k + upper(k) tau_{k+1} = rhs(k), lower(k) = upper(k - 1) (symmetric);
    // m_a holds the eliminated upper coefficients, m_b the eliminated right side.
    const auto cosDiff = [&](std::size_t i, std::size_t j) { return m_cos[i] * m_cos[j] + m_sin[i] * m_sin[j]; };
    const auto sinDiff = [&](std::size_t i, std::size_t j) { return m_sin[i] * m_cos[j] - m_cos[i] * m_sin[j]; };
    for (std::size_t k = 0; k < N; ++k) {
        const double w = y[N + k];
        double rhs = -l * w * w - (k == 0 ? g * m_cos[0] : 0.0);
        double diag = k == 0 ? -1.0 : -2.0;
        if (k > 0) {
            const double lower = cosDiff(k, k - 1);
            diag -= lower * m_a[k - 1];
            rhs -= lower * m_b[k - 1];
        }
        m_a[k] = k + 1 < N ? cosDiff(k, k + 1) / diag : 0.0;
        m_b[k] = rhs / diag;
    }
    for (std::size_t k = N - 1; k-- > 0;) m_b[k] -= m_a[k] * m_b[k + 1]; // m_b: tau
    for (std::size_t k = 0; k < N; ++k) {
        double acc = k == 0 ? -g * m_sin[0] : m_b[k - 1] * sinDiff(k - 1, k);
        if (k + 1 < N) acc += m_b[k + 1] * sinDiff(k + 1, k);
        dydt[N + k] = acc / l;
    }
}

void ChainReference::massMatrixDerivatives(std::span<const double> y, std::span<double> dydt) const {
    const int n = m_params.links;
    const auto N = static_cast<std::size_t>(n);
    const double gl = m_params.gravity * n / m_params.length; // g / l
    for (std::size_t i = 0; i < N; ++i) {
        m_sin[i] = std::sin(y[i]);
        m_cos[i] = std::cos(y[i]);
        dydt[i] = y[N + i];
    }
    // 0-based: c_ij = N - max(i, j); the gravity weight N - i. A (lower triangle) and b.
    for (std::size_t i = 0; i < N; ++i) {
        double bi = -gl * static_cast<double>(N - i) * m_sin[i];
        for (std::size_t j = 0; j < N; ++j) {
            const double c = static_cast<double>(N - std::max(i, j));
            const double sinIJ = m_sin[i] * m_cos[j] - m_cos[i] * m_sin[j]; // sin(theta_i - theta_j)
            const double w = y[N + j];
            bi -= c * sinIJ * w * w;
            if (j <= i) m_a[i * N + j] = c * (m_cos[i] * m_cos[j] + m_sin[i] * m_sin[j]); // c cos(theta_i - theta_j)
        }
        m_b[i] = bi;
    }
    // Cholesky A = L L^T in place (lower triangle), then L z = b, L^T x = z.
    for (std::size_t j = 0; j < N; ++j) {
        double d = m_a[j * N + j];
        for (std::size_t k = 0; k < j; ++k) d -= m_a[j * N + k] * m_a[j * N + k];
        if (!(d > 0.0)) { // cannot happen for a valid state (A is positive definite); NaN in, NaN out
            for (std::size_t i = 0; i < N; ++i) dydt[N + i] = std::numeric_limits<double>::quiet_NaN();
            return;
        }
        const double ljj = std::sqrt(d);
        m_a[j * N + j] = ljj;
        for (std::size_t i = j + 1; i < N; ++i) {
            double s = m_a[i * N + j];
            for (std::size_t k = 0; k < j; ++k) s -= m_a[i * N + k] * m_a[j * N + k];
            m_a[i * N + j] = s / ljj;
        }
    }
    for (std::size_t i = 0; i < N; ++i) {
        double s = m_b[i];
        for (std::size_t k = 0; k < i; ++k) s -= m_a[i * N + k] * m_b[k];
        m_b[i] = s / m_a[i * N + i];
    }
    for (std::size_t ii = N; ii-- > 0;) {
        double s = m_b[ii];
        for (std::size_t k = ii + 1; k < N; ++k) s -= m_a[k * N + ii] * m_b[k];
        m_b[ii] = s / m_a[ii * N + ii];
    }
    for (std::size_t i = 0; i < N; ++i) dydt[N + i] = m_b[i];
}

void ChainReference::advanceTo(double t) { m_ode.advanceTo(t); }

std::vector<ChainPoint> ChainReference::nodes() const {
    const double l = linkLength();
    const auto th = theta();
    std::vector<ChainPoint> out(th.size() + 1);
    for (std::size_t k = 0; k < th.size(); ++k)
        out[k + 1] = {out[k].x + l * std::sin(th[k]), out[k].y - l * std::cos(th[k])};
    return out;
}

ChainPoint ChainReference::tip() const { return nodes().back(); }

double ChainReference::energy() const {
    const double l = linkLength(), m = m_params.mass / m_params.links, g = m_params.gravity;
    const auto th = theta();
    const auto w = omega();
    double y = 0, vx = 0, vy = 0, e = 0;
    for (std::size_t k = 0; k < th.size(); ++k) {
        const double s = std::sin(th[k]), c = std::cos(th[k]);
        y -= l * c;
        vx += l * c * w[k];
        vy += l * s * w[k];
        e += m * (0.5 * (vx * vx + vy * vy) + g * y);
    }
    return e;
}

// ---------------------------------------------------------------------------------------------------
// The study

std::string validateHairChain(const HairChainOptions& o) {
    if (o.solver != "reference") {
        if (std::string why = validateHairSolverName(o.solver); !why.empty()) return why + ", or reference";
    }
    if (o.links < 1 || o.links > kMaxChainLinks)
        return "--links must be in 1.." + std::to_string(kMaxChainLinks) + ", got " + std::to_string(o.links);
    if (!(std::isfinite(o.length) && o.length > 0.0 && o.length <= 10.0))
        return "--length must be a finite number in (0, 10] metres, got " + number(o.length);
    if (!(std::isfinite(o.dt) && o.dt > 0.0 && o.dt <= 1.0))
        return "--dt must be a finite number in (0, 1] seconds, got " + number(o.dt);
    if (!(std::isfinite(o.seconds) && o.seconds > 0.0 && o.seconds <= 600.0))
        return "--seconds must be a finite number in (0, 600], got " + number(o.seconds);
    if (const std::int64_t steps = stepCount(o.seconds, o.dt); steps < 0 || steps > kMaxHairSteps)
        return "--seconds / --dt asks for " + (steps < 0 ? std::string("too many") : std::to_string(steps)) +
               " steps; at most " + std::to_string(kMaxHairSteps) + " are allowed";
    if (std::string why = validatePassCounts(o.iterations, o.substeps); !why.empty()) return why;
    if (!(std::isfinite(o.gravity) && o.gravity > 0.0 && o.gravity <= 1000.0))
        return "gravity must be a finite number in (0, 1000] m/s^2, got " + number(o.gravity);
    return {};
}

physics::HairParams hairChainParams(const HairChainOptions& o) {
    if (const std::string why = validateHairChain(o); !why.empty()) throw std::invalid_argument(why);
    if (o.solver == "reference") throw std::invalid_argument("hairChainParams: the reference solver has no HairParams");
    physics::HairParams p = hairStudyParams(o.solver, o.iterations, o.substeps);
    p.strands = 1;
    p.nodesPerStrand = o.links + 1;
    p.strandLength = static_cast<float>(o.length);
    p.dampingPerSecond = 0.0f;
    p.gravity = static_cast<float>(o.gravity);
    p.sleepSpeed = 0.0f;                                  // never sleep
    if (!o.automaticSubsteps) p.maxSubstepSeconds = 0.0f; // no automatic substeps: the method's own only
    p.hostCollision = false;                              // a free chain
    return p;
}

std::vector<HairChainRow> runHairChain(const HairChainOptions& o) {
    if (const std::string why = validateHairChain(o); !why.empty()) throw std::invalid_argument(why);
    const int n = o.links;
    const auto N = static_cast<std::size_t>(n);
    const double L = o.length, g = o.gravity, l = L / n;
    const double mass = 1.0, node = mass / n, mgl = mass * g * L;
    const float dtF = static_cast<float>(o.dt);
    const double dt = static_cast<double>(dtF);
    const std::int64_t steps = stepCount(o.seconds, o.dt);

    const std::vector<double> theta0(N, std::numbers::pi / 2.0), omega0(N, 0.0);
    // The O(N) tension form (held to the mass-matrix form by the tests): 64 links stay fast.
    ChainReference ref({n, L, g, mass}, theta0, omega0, OdeOptions{}, ChainEquations::Tensions);
    const double refE0 = ref.energy();

    const bool reference = o.solver == "reference";
    std::unique_ptr<physics::HairSolver> solver;
    // The host at the origin: the solver keeps positions in float, whose spacing grows with the coordinates
    // (a strand hung from y = 1 would be rounded four times as coarsely as one hung from the origin).
    const physics::HostPose pose{{0.0f, 0.0f, 0.0f}, {}};
    std::vector<ChainSnapshot> snaps(3); // n - 1, n, n + 1 (rotating)
    std::array<int, 3> substeps{};       // the substeps of the step that reached each snapshot
    if (!reference) {
        solver = std::make_unique<physics::HairSolver>(hairChainParams(o), 1e-3f, pose);
        const glm::vec3 root = solver->rootPosition(pose, 0);
        const float seg = solver->segmentLength();
        std::vector<glm::vec3> strand(N + 1, root);
        for (std::size_t k = 1; k <= N; ++k) strand[k].x = root.x + static_cast<float>(k) * seg;
        solver->setStrand(0, strand);
        capture(*solver, snaps[1]);
        substeps[2] = solver->step(pose, dtF).substeps;
        capture(*solver, snaps[2]);
    }

    std::vector<HairChainRow> rows;
    rows.reserve(static_cast<std::size_t>(steps) + 1);
    double simE0 = 0.0;
    for (std::int64_t step = 0; step <= steps; ++step) {
        HairChainRow r;
        r.t = static_cast<double>(step) * dt;
        ref.advanceTo(r.t);
        const std::vector<ChainPoint> refNodes = ref.nodes();
        r.refTipX = refNodes.back().x;
        r.refTipY = refNodes.back().y;
        const double refEnergyError = (ref.energy() - refE0) / mgl;
        if (reference) {
            r.tipX = r.refTipX;
            r.tipY = r.refTipY;
            r.tipError = 0.0;
            for (std::size_t k = 1; k <= N; ++k)
                r.maxSegmentError = std::max(
                    r.maxSegmentError,
                    std::abs(std::hypot(refNodes[k].x - refNodes[k - 1].x, refNodes[k].y - refNodes[k - 1].y) / l -
                             1.0));
            r.energyError = refEnergyError;
        } else {
            const ChainSnapshot& prev = snaps[0];
            const ChainSnapshot& cur = snaps[1];
            const ChainSnapshot& next = snaps[2];
            r.tipX = cur.x[N];
            r.tipY = cur.y[N];
            r.substeps = step > 0 ? substeps[1] : 0;
            r.tipError = std::sqrt((r.tipX - r.refTipX) * (r.tipX - r.refTipX) +
                                   (r.tipY - r.refTipY) * (r.tipY - r.refTipY) + cur.z[N] * cur.z[N]);
            double e = 0.0;
            for (std::size_t k = 1; k <= N; ++k) {
                const double len = std::sqrt((cur.x[k] - cur.x[k - 1]) * (cur.x[k] - cur.x[k - 1]) +
                                             (cur.y[k] - cur.y[k - 1]) * (cur.y[k] - cur.y[k - 1]) +
                                             (cur.z[k] - cur.z[k - 1]) * (cur.z[k] - cur.z[k - 1]));
                r.maxSegmentError = std::max(r.maxSegmentError, std::abs(len / l - 1.0));
                double v2 = 0.0; // released at rest: zero velocity at t = 0
                if (step > 0) {
                    const double vx = (next.x[k] - prev.x[k]) / (2.0 * dt);
                    const double vy = (next.y[k] - prev.y[k]) / (2.0 * dt);
                    const double vz = (next.z[k] - prev.z[k]) / (2.0 * dt);
                    v2 = vx * vx + vy * vy + vz * vz;
                }
                e += node * (0.5 * v2 + g * cur.y[k]);
            }
            if (step == 0) simE0 = e;
            r.energyError = (e - simE0) / mgl;
            if (step < steps) { // one step past the row ahead, for the next central difference
                std::rotate(snaps.begin(), snaps.begin() + 1, snaps.end());
                std::rotate(substeps.begin(), substeps.begin() + 1, substeps.end());
                substeps[2] = solver->step(pose, dtF).substeps;
                capture(*solver, snaps[2]);
            }
        }
        rows.push_back(r);
    }
    return rows;
}

void writeHairChainCsv(const std::vector<HairChainRow>& rows, std::ostream& out) {
    out << "t,tip_x,tip_y,ref_tip_x,ref_tip_y,tip_error,max_segment_error,energy_error\n";
    for (const HairChainRow& r : rows)
        out << number(r.t) << ',' << number(r.tipX) << ',' << number(r.tipY) << ',' << number(r.refTipX) << ','
            << number(r.refTipY) << ',' << number(r.tipError) << ',' << number(r.maxSegmentError) << ','
            << number(r.energyError) << '\n';
}

double chainTipErrorAt(const std::vector<HairChainRow>& rows, double t) {
    if (rows.empty()) return std::numeric_limits<double>::quiet_NaN();
    const auto it =
        std::lower_bound(rows.begin(), rows.end(), t, [](const HairChainRow& r, double v) { return r.t < v; });
    if (it == rows.begin()) return it->tipError;
    if (it == rows.end()) return rows.back().tipError;
    const auto before = std::prev(it);
    return (t - before->t <= it->t - t) ? before->tipError : it->tipError;
}

namespace {

// Twice the mean time between the swings of x(t) across 0 (see kSwingAmplitude); NaN under two swings.
template <typename X>
double swingPeriod(const std::vector<HairChainRow>& rows, double from, double to, X x) {
    int side = 0;                                               // -1, +1: beyond the amplitude on that side; 0: not yet
    double lastZero = std::numeric_limits<double>::quiet_NaN(); // the last crossing of 0 since then
    double first = 0.0, last = 0.0;
    int swings = 0;
    const HairChainRow* prev = nullptr;
    for (const HairChainRow& r : rows) {
        if (r.t < from || r.t > to) continue;
        const double v = x(r);
        if (prev && (x(*prev) < 0.0) != (v < 0.0)) {
            const double p = x(*prev);
            lastZero = prev->t + (r.t - prev->t) * p / (p - v);
        }
        prev = &r;
        const int now = v > kSwingAmplitude ? 1 : (v < -kSwingAmplitude ? -1 : 0);
        if (now == 0 || now == side) continue;
        if (side != 0 && !std::isnan(lastZero)) {
            if (swings == 0) first = lastZero;
            last = lastZero;
            ++swings;
        }
        side = now;
    }
    return swings < 2 ? std::numeric_limits<double>::quiet_NaN() : 2.0 * (last - first) / (swings - 1);
}

} // namespace

ChainLook chainLook(const std::vector<HairChainRow>& rows, double from, double to) {
    ChainLook look;
    double energy = 0.0, height = 0.0, refHeight = 0.0;
    int n = 0;
    for (const HairChainRow& r : rows) {
        if (r.t < from || r.t > to) continue;
        energy += r.energyError, height += r.tipY, refHeight += r.refTipY;
        ++n;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    look.energy = n > 0 ? energy / n : nan;
    look.meanTipHeight = n > 0 ? height / n : nan;
    look.refMeanTipHeight = n > 0 ? refHeight / n : nan;
    look.swingPeriod = swingPeriod(rows, from, to, [](const HairChainRow& r) { return r.tipX; });
    look.refSwingPeriod = swingPeriod(rows, from, to, [](const HairChainRow& r) { return r.refTipX; });
    return look;
}

} // namespace lab

namespace lab {

namespace {

ChainPoint tipOf(const ChainParams& p, std::span<const double> theta) {
    const double l = p.length / p.links;
    ChainPoint tip;
    for (const double t : theta) {
        tip.x += l * std::sin(t);
        tip.y -= l * std::cos(t);
    }
    return tip;
}

double distance(ChainPoint a, ChainPoint b) { return std::hypot(a.x - b.x, a.y - b.y); }

} // namespace

std::vector<ChainPoint> chainTipsRk4(const ChainParams& chain, std::span<const double> times, double step) {
    if (!(std::isfinite(step) && step > 0.0)) throw std::invalid_argument("chainTipsRk4: the step must be > 0");
    const auto N = static_cast<std::size_t>(chain.links);
    const std::vector<double> theta(N, std::numbers::pi / 2.0), omega(N, 0.0);
    // Only its right-hand side is used (the tension form, O(N)); its own integrator stays at t = 0.
    const ChainReference equations(chain, theta, omega, {}, ChainEquations::Tensions);
    std::vector<double> y(2 * N), k1(2 * N), k2(2 * N), k3(2 * N), k4(2 * N), tmp(2 * N);
    std::copy(theta.begin(), theta.end(), y.begin());
    std::copy(omega.begin(), omega.end(), y.begin() + static_cast<std::ptrdiff_t>(N));
    const auto rk4 = [&](double h) {
        equations.derivatives(y, k1);
        for (std::size_t i = 0; i < y.size(); ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
        equations.derivatives(tmp, k2);
        for (std::size_t i = 0; i < y.size(); ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
        equations.derivatives(tmp, k3);
        for (std::size_t i = 0; i < y.size(); ++i) tmp[i] = y[i] + h * k3[i];
        equations.derivatives(tmp, k4);
        for (std::size_t i = 0; i < y.size(); ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    };
    std::vector<ChainPoint> tips;
    double t = 0.0;
    for (const double target : times) {
        // Whole steps counted from the last sample, so that rounding does not leave a sliver of a step.
        const double span = target - t;
        const auto whole = static_cast<std::int64_t>(std::floor(span / step * (1.0 + 1e-12)));
        for (std::int64_t k = 0; k < whole; ++k) rk4(step);
        const double rest = span - static_cast<double>(whole) * step;
        if (rest > 1e-15) rk4(rest);
        t = target;
        tips.push_back(tipOf(chain, std::span<const double>(y).first(N)));
    }
    return tips;
}

ChainHorizon chainHorizon(const ChainParams& chain, double seconds, double rk4Step) {
    if (!(std::isfinite(seconds) && seconds > 0.0 && seconds <= 60.0))
        throw std::invalid_argument("chainHorizon: seconds must be in (0, 60]");
    ChainHorizon r;
    r.chain = chain;
    r.seconds = seconds;
    r.rk4Step = rk4Step;
    r.horizon = r.exactTo = std::numeric_limits<double>::quiet_NaN();
    const auto N = static_cast<std::size_t>(chain.links);
    std::vector<double> theta(N, std::numbers::pi / 2.0);
    const std::vector<double> omega(N, 0.0);
    ChainReference reference(chain, theta, omega);
    theta[0] += kHorizonPerturbation;
    ChainReference nudged(chain, theta, omega);
    const auto samples = static_cast<std::size_t>(std::llround(seconds * 1000.0));
    std::vector<double> times(samples);
    for (std::size_t k = 0; k < samples; ++k) times[k] = static_cast<double>(k + 1) * 1e-3;
    const std::vector<ChainPoint> second = chainTipsRk4(chain, times, rk4Step);
    for (std::size_t k = 0; k < samples; ++k) {
        reference.advanceTo(times[k]);
        nudged.advanceTo(times[k]);
        const double apart = distance(reference.tip(), nudged.tip());
        const double disagree = distance(reference.tip(), second[k]);
        if (std::isnan(r.exactTo) && disagree >= kExactTipDistance) r.exactTo = times[k];
        if (std::isnan(r.horizon)) {
            r.maxAgreementBefore = std::max(r.maxAgreementBefore, disagree);
            if (apart >= kHorizonTipDistance) r.horizon = times[k];
        }
        if (!std::isnan(r.horizon) && !std::isnan(r.exactTo)) break;
    }
    return r;
}

} // namespace lab
