#include "game/hair_ball.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>
#include <stdexcept>
#include <string>

namespace game {

void validateHairBallDef(const HairBallDef& def) {
    // Written so that NaN fails every check: each comparison with it is false.
    const auto require = [](bool ok, float v, const char* what, const char* range) {
        if (ok) return;
        char b[160];
        std::snprintf(b, sizeof b, "hair ball: %s must be in %s, got %g", what, range, static_cast<double>(v));
        throw std::invalid_argument(b);
    };
    require(def.radius > 0.0f && def.radius <= kMaxHairBallRadius, def.radius, "radius", "(0, 2] m");
    const float length = def.hair.strandLength;
    require(length > 0.0f && length <= kMaxHairStrandLength, length, "strand length", "(0, 4] m");
    require(std::abs(def.spinRate) <= kMaxHairSpinRate, def.spinRate, "spin rate", "[-60, 60] rad/s");
    require(std::abs(def.hair.gravity) <= kMaxHairGravity, def.hair.gravity, "gravity", "[-1000, 1000] m/s^2");
    for (int c = 0; c < 3; ++c)
        require(def.colour[c] >= 0.0f && def.colour[c] <= 1.0f, def.colour[c], "colour", "[0, 1]");
    if (def.hair.iterations < 1 || def.hair.iterations > kMaxHairIterations)
        throw std::invalid_argument("hair ball: iterations must be in 1..100, got " +
                                    std::to_string(def.hair.iterations));
    if (def.hair.substeps < 1 || def.hair.substeps > kMaxHairSubsteps)
        throw std::invalid_argument("hair ball: substeps must be in 1..16, got " + std::to_string(def.hair.substeps));
    physics::validateHairParams(def.hair);
}

std::uint64_t newBallSerial() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

HairBall::HairBall(const glm::vec3& centre, const HairBallDef& def)
    : m_def(def), m_centre(centre), m_previousCentre(centre), m_serial(newBallSerial()) {
    validateHairBallDef(m_def);
    m_solver = std::make_unique<physics::HairSolver>(m_def.hair, m_def.radius, pose());
}

HairBall::HairBall(const HairBallImage& image) : HairBall(image, newBallSerial(), 0) {}

HairBall::HairBall(const HairBallImage& image, std::uint64_t serial, std::uint64_t generation)
    : m_def(image.def), m_centre(image.centre), m_previousCentre(image.previousCentre), m_spin(image.spin),
      m_stats(image.stats), m_serial(serial), m_generation(generation) {
    validateHairBallDef(m_def);
    m_solver = std::make_unique<physics::HairSolver>(m_def.hair, m_def.radius, pose());
    m_solver->restore(image.hair);
}

HairBall::HairBall(HairBall&&) noexcept = default;
HairBall& HairBall::operator=(HairBall&&) noexcept = default;
HairBall::~HairBall() = default;

physics::HostPose HairBall::pose() const {
    physics::HostPose p;
    p.centre = m_centre;
    p.orientation = glm::angleAxis(m_spin, glm::vec3(0.0f, 1.0f, 0.0f));
    return p;
}

void HairBall::setDef(const HairBallDef& def) {
    validateHairBallDef(def);
    ++m_generation;
    m_def = def;
    m_solver = std::make_unique<physics::HairSolver>(m_def.hair, m_def.radius, pose());
}

void HairBall::setSpin(float radians) {
    ++m_generation;
    m_spin = radians;
    m_solver = std::make_unique<physics::HairSolver>(m_def.hair, m_def.radius, pose());
}

void HairBall::tick(double dt, int hairSteps, double hairLag, const world::World& world,
                    std::span<const physics::SphereCollider> others, int activeStrands) {
    if (m_def.spinRate != 0.0f) {
        ++m_generation;
        m_spin = std::fmod(m_spin + m_def.spinRate * static_cast<float>(dt), 6.28318530718f);
        m_solver->wake();
    }
    if (hairSteps <= 0) return; // the hair clock's next substep ends in a later tick
    // The solid blocks the hair can reach this step: a box around the ball, hair length included.
    const float reach = m_def.radius + m_def.hair.strandLength + 1.0f;
    const glm::ivec3 lo(glm::floor(m_centre - glm::vec3(reach)));
    const glm::ivec3 hi(glm::floor(m_centre + glm::vec3(reach)));
    m_voxels.origin = lo;
    m_voxels.size = hi - lo + glm::ivec3(1);
    m_voxels.solid.resize(static_cast<std::size_t>(m_voxels.size.x) * m_voxels.size.y * m_voxels.size.z);
    std::size_t i = 0;
    bool anySolid = false;
    for (int z = lo.z; z <= hi.z; ++z) {
        for (int y = lo.y; y <= hi.y; ++y) {
            for (int x = lo.x; x <= hi.x; ++x) {
                const bool solid = world::isSolid(world.get({x, y, z}));
                m_voxels.solid[i++] = solid ? 1 : 0;
                anySolid = anySolid || solid;
            }
        }
    }
    const int wasActive = m_solver->activeStrands();
    m_solver->setActiveStrands(activeStrands);
    const bool wasAsleep = m_solver->sleeping();
    // A ball in open air skips the block pass (scalar, the costliest per node); a block appearing in reach
    // changes what the solver is given, which wakes a sleeping ball.
    physics::HostPose at = pose();
    if (hairLag > 0.0 && dt > 0.0) {
        // The hair's substep ended hairLag before the tick did: the host as it was then (at 60 Hz and at rates
        // whose ticks fall on the clock, hairLag is 0 and this is the tick's own pose, bit for bit).
        const auto back = static_cast<float>(std::min(hairLag / dt, 1.0));
        at.centre = m_centre + (m_previousCentre - m_centre) * back;
        at.orientation =
            glm::angleAxis(m_spin - m_def.spinRate * static_cast<float>(hairLag), glm::vec3(0.0f, 1.0f, 0.0f));
    }
    const physics::HairStepStats stats = m_solver->step(at, static_cast<float>(hairSteps * physics::kHairClockSeconds),
                                                        others, anySolid ? &m_voxels : nullptr, 1);
    // A sleeping solver does no work and reports zeros; the hair is as the last awake step left it, so its
    // figures (segment error, penetration) stay those of that step.
    if (!(wasAsleep && m_solver->sleeping())) m_stats = stats;
    // A solver that slept through the step returned at once, leaving its state as it was and reporting no substeps
    // (physics/hair.cpp); one that woke, stepped and fell asleep again in the same step (a sleep delay of 0) did
    // substeps. The strand count is the one thing set on it before.
    if (!(wasAsleep && m_solver->sleeping()) || stats.substeps > 0 || m_solver->activeStrands() != wasActive)
        ++m_generation;
}

} // namespace game
