#include "game/pendulum_set.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace game {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr glm::vec3 kArmDirection[kPendulumSlots] = {{0, 0, -1}, {1, 0, 0}, {0, 0, 1}, {-1, 0, 0}};

physics::PendulumState releaseState(const PendulumSetDef& def) { return {def.releaseDegrees * kPi / 180.0, 0.0}; }

physics::PendulumParams paramsOf(const PendulumSetDef& def) {
    physics::PendulumParams p;
    p.length = def.length;
    p.gravity = def.gravity;
    return p;
}

// The rest (gravity, the release state) is checked by physics::validatePendulum as the slots are built.
// A step multiplier outside (0, 1e6] would step backwards, not at all, or past any use; a rod outside
// [kMinPendulumLength, kMaxPendulumLength] is too short to see or would swing through the terrain around the post (the
// panel offers 0.25-3 m), and the room a set needs (game/space.h) grows with it. Gravity beyond kMaxPendulumGravity is
// no world's (the loader refused it while the game let a panel edit through, so the game saved worlds it would not
// load).
const PendulumSetDef& checked(const PendulumSetDef& def) {
    if (!(def.stepMultiplier > 0.0 && def.stepMultiplier <= 1.0e6))
        throw std::invalid_argument("pendulum set: step multiplier must be in (0, 1e6]");
    if (!(def.length >= kMinPendulumLength && def.length <= kMaxPendulumLength))
        throw std::invalid_argument("pendulum set: length must be in [0.001, 16] m");
    if (!(def.gravity > 0.0 && def.gravity <= kMaxPendulumGravity))
        throw std::invalid_argument("pendulum set: gravity must be in (0, 1e4] m/s^2");
    return def;
}

physics::Pendulum makeSlot(const PendulumSetDef& def, int i) {
    return physics::Pendulum(def.methods[static_cast<std::size_t>(i)], paramsOf(def), releaseState(def));
}

bool finiteState(const physics::PendulumState& s) { return std::isfinite(s.theta) && std::isfinite(s.omega); }
} // namespace

std::string_view compassName(int slot) {
    static constexpr std::string_view kNames[kPendulumSlots] = {"north", "east", "south", "west"};
    return kNames[static_cast<std::size_t>(slot)];
}

glm::vec3 methodColour(physics::Method m) {
    switch (m) {
    case physics::Method::Exact:
        return {0.95f, 0.95f, 0.95f};
    case physics::Method::Euler:
        return {0.90f, 0.25f, 0.20f};
    case physics::Method::EulerCartesian:
        return {0.95f, 0.55f, 0.15f};
    case physics::Method::Midpoint:
        return {0.95f, 0.85f, 0.20f};
    case physics::Method::Trapezoid:
        return {0.25f, 0.55f, 0.95f};
    case physics::Method::SymplecticEuler:
        return {0.70f, 0.40f, 0.90f};
    case physics::Method::Verlet:
        return {0.30f, 0.80f, 0.35f};
    case physics::Method::Rk4:
        return {0.20f, 0.85f, 0.85f};
    case physics::Method::ImplicitMidpoint:
        return {0.95f, 0.45f, 0.70f};
    case physics::Method::Yoshida4:
        return {0.60f, 0.90f, 0.30f};
    case physics::Method::Dopri5:
        return {0.55f, 0.65f, 1.00f};
    case physics::Method::Count:
        break;
    }
    return {0.5f, 0.5f, 0.5f};
}

physics::PendulumState PendulumSet::drawnState(int i, double alpha) const {
    const auto& cur = m_slots[static_cast<std::size_t>(i)];
    if (cur.method() == physics::Method::Exact && !m_diverged[static_cast<std::size_t>(i)]) {
        const double t = m_previousTime + alpha * (time() - m_previousTime);
        return m_exact.at(t);
    }
    const physics::PendulumState& a = m_previous[static_cast<std::size_t>(i)];
    const physics::PendulumState b = cur.state();
    return {a.theta + alpha * (b.theta - a.theta), a.omega + alpha * (b.omega - a.omega)};
}

PendulumSet::PendulumSet(glm::ivec3 base, const PendulumSetDef& def)
    : m_base(base),
      m_def(checked(def)), m_slots{makeSlot(def, 0), makeSlot(def, 1), makeSlot(def, 2), makeSlot(def, 3)},
      m_exact(paramsOf(def), releaseState(def)) {
    release();
}

physics::PendulumParams PendulumSet::params() const { return paramsOf(m_def); }

double PendulumSet::initialEnergy() const { return physics::energy(params(), releaseState(m_def)); }

double PendulumSet::energyError(int i) const {
    const physics::PendulumParams p = params();
    return (physics::energy(p, slot(i).state()) - initialEnergy()) / (p.mass * p.gravity * p.length);
}

double PendulumSet::angleError(int i) const {
    const physics::Pendulum& p = slot(i);
    if (!(time() > 0.0) || diverged(i) || p.method() == physics::Method::Exact)
        return std::numeric_limits<double>::quiet_NaN();
    const double d = std::remainder(p.state().theta - m_exact.at(time()).theta, 2.0 * std::numbers::pi);
    return std::abs(d);
}

double PendulumSet::evaluationsPerSecond(int i) const {
    const physics::Pendulum& p = slot(i);
    if (!(time() > 0.0) || diverged(i) || p.method() == physics::Method::Exact)
        return std::numeric_limits<double>::quiet_NaN();
    return static_cast<double>(p.evaluations()) / time();
}

void PendulumSet::setDef(const PendulumSetDef& def) {
    // Everything that can throw first: a def the physics refuses leaves the set as it was.
    physics::ExactPendulum exact(paramsOf(checked(def)), releaseState(def));
    std::array<physics::Pendulum, kPendulumSlots> slots{makeSlot(def, 0), makeSlot(def, 1), makeSlot(def, 2),
                                                        makeSlot(def, 3)};
    m_def = def;
    m_exact = exact;
    m_slots = slots;
    reset();
}

void PendulumSet::reset() {
    for (int i = 0; i < kPendulumSlots; ++i) {
        m_slots[static_cast<std::size_t>(i)].reset(releaseState(m_def));
        m_previous[static_cast<std::size_t>(i)] = releaseState(m_def);
    }
    m_diverged.fill(false);
    m_previousTime = 0.0;
    m_released = false;
    m_trace = {};
    record();
}

void PendulumSet::release() {
    reset();
    m_released = true;
}

void PendulumSet::hold() {
    m_previousTime = time();
    for (int i = 0; i < kPendulumSlots; ++i)
        m_previous[static_cast<std::size_t>(i)] = m_slots[static_cast<std::size_t>(i)].state();
}

void PendulumSet::tick(double dt) {
    hold();
    if (!m_released) return;
    const double h = dt * m_def.stepMultiplier;
    for (int i = 0; i < kPendulumSlots; ++i) {
        auto& slot = m_slots[static_cast<std::size_t>(i)];
        if (m_diverged[static_cast<std::size_t>(i)]) continue;
        // Step a copy first: a method pushed past its stability limit overflows, and the player should
        // see its last finite state (marked diverged), not NaN.
        physics::Pendulum next = slot;
        next.step(h);
        const physics::PendulumState s = next.state();
        if (!finiteState(s) || std::abs(s.omega) > 1e6) {
            m_diverged[static_cast<std::size_t>(i)] = true;
            continue;
        }
        slot = next;
    }
    record();
}

void PendulumSet::record() {
    PendulumTrace& t = m_trace;
    if (t.time.empty()) {
        t.time.assign(PendulumTrace::kSamples, 0.0f);
        t.exactTheta.assign(PendulumTrace::kSamples, 0.0f);
        for (auto& v : t.theta) v.assign(PendulumTrace::kSamples, 0.0f);
        for (auto& v : t.energyError) v.assign(PendulumTrace::kSamples, 0.0f);
    }
    t.time[t.head] = static_cast<float>(time());
    t.exactTheta[t.head] = static_cast<float>(m_exact.at(time()).theta);
    for (int i = 0; i < kPendulumSlots; ++i) {
        t.theta[static_cast<std::size_t>(i)][t.head] =
            static_cast<float>(m_slots[static_cast<std::size_t>(i)].state().theta);
        t.energyError[static_cast<std::size_t>(i)][t.head] = static_cast<float>(energyError(i));
    }
    t.head = (t.head + 1) % PendulumTrace::kSamples;
    t.size = std::min(t.size + 1, PendulumTrace::kSamples);
}

PendulumSet::Internals PendulumSet::internals() const {
    Internals in;
    in.released = m_released;
    in.previousTime = m_previousTime;
    in.previous = m_previous;
    in.diverged = m_diverged;
    for (int i = 0; i < kPendulumSlots; ++i)
        in.slots[static_cast<std::size_t>(i)] = m_slots[static_cast<std::size_t>(i)].internals();
    return in;
}

void PendulumSet::restoreTrace(PendulumTrace trace) {
    constexpr std::size_t n = PendulumTrace::kSamples;
    bool whole = trace.time.size() == n && trace.exactTheta.size() == n && trace.head < n && trace.size <= n;
    for (int i = 0; i < kPendulumSlots; ++i) {
        whole = whole && trace.theta[static_cast<std::size_t>(i)].size() == n &&
                trace.energyError[static_cast<std::size_t>(i)].size() == n;
    }
    if (!whole)
        throw std::invalid_argument("pendulum set: a trace must hold " + std::to_string(n) +
                                    " samples of each plot, its head and size within them");
    m_trace = std::move(trace);
}

void PendulumSet::restore(const Internals& in) {
    if (!std::isfinite(in.previousTime)) throw std::invalid_argument("pendulum set: previous time must be finite");
    for (const auto& s : in.previous) {
        if (!finiteState(s)) throw std::invalid_argument("pendulum set: previous state must be finite");
    }
    std::array<physics::Pendulum, kPendulumSlots> slots = m_slots;
    for (int i = 0; i < kPendulumSlots; ++i)
        slots[static_cast<std::size_t>(i)].setInternals(in.slots[static_cast<std::size_t>(i)]);
    m_slots = slots;
    m_released = in.released;
    m_previousTime = in.previousTime;
    m_previous = in.previous;
    m_diverged = in.diverged;
    m_trace = {};
    record();
}

float PendulumSet::postHeight() const { return static_cast<float>(m_def.length) + 1.2f; }

glm::vec3 PendulumSet::pivot(int i) const {
    const glm::vec3 foot(static_cast<float>(m_base.x) + 0.5f, static_cast<float>(m_base.y),
                         static_cast<float>(m_base.z) + 0.5f);
    return foot + glm::vec3(0.0f, postHeight(), 0.0f) + kArmDirection[static_cast<std::size_t>(i)] * kArmLength;
}

// Each pendulum swings in the vertical plane that contains its arm, so the four never cross.
glm::vec3 PendulumSet::swingAxis(int i) const { return kArmDirection[static_cast<std::size_t>(i)]; }

glm::vec3 PendulumSet::bobPosition(int i, double theta) const {
    const float l = static_cast<float>(m_def.length);
    return pivot(i) + swingAxis(i) * (l * static_cast<float>(std::sin(theta))) -
           glm::vec3(0.0f, l * static_cast<float>(std::cos(theta)), 0.0f);
}

} // namespace game
