#include "game/hair_ball.h"

#include <cmath>
#include <glm/gtc/quaternion.hpp>

namespace game {

HairBall::HairBall(const glm::vec3& centre, const HairBallDef& def)
    : m_def(def), m_centre(centre), m_previousCentre(centre) {
    m_solver = std::make_unique<physics::HairSolver>(m_def.hair, m_def.radius, pose());
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
    m_def = def;
    m_solver = std::make_unique<physics::HairSolver>(m_def.hair, m_def.radius, pose());
}

void HairBall::setSpin(float radians) {
    m_spin = radians;
    m_solver = std::make_unique<physics::HairSolver>(m_def.hair, m_def.radius, pose());
}

void HairBall::tick(double dt, const world::World& world, std::span<const physics::SphereCollider> others,
                    int activeStrands) {
    m_previousCentre = m_centre;
    if (m_def.spinRate != 0.0f) {
        m_spin = std::fmod(m_spin + m_def.spinRate * static_cast<float>(dt), 6.28318530718f);
        m_solver->wake();
    }
    // The solid blocks the hair can reach this step: a box around the ball, hair length included.
    const float reach = m_def.radius + m_def.hair.strandLength + 1.0f;
    const glm::ivec3 lo(glm::floor(m_centre - glm::vec3(reach)));
    const glm::ivec3 hi(glm::floor(m_centre + glm::vec3(reach)));
    m_voxels.origin = lo;
    m_voxels.size = hi - lo + glm::ivec3(1);
    m_voxels.solid.resize(static_cast<std::size_t>(m_voxels.size.x) * m_voxels.size.y * m_voxels.size.z);
    std::size_t i = 0;
    for (int z = lo.z; z <= hi.z; ++z) {
        for (int y = lo.y; y <= hi.y; ++y) {
            for (int x = lo.x; x <= hi.x; ++x) m_voxels.solid[i++] = world::isSolid(world.get({x, y, z})) ? 1 : 0;
        }
    }
    m_solver->setActiveStrands(activeStrands);
    m_stats = m_solver->step(pose(), static_cast<float>(dt), others, &m_voxels, 1);
}

} // namespace game
