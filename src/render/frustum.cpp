#include "render/frustum.h"

#include <glm/geometric.hpp>

namespace render {

Frustum::Frustum(const glm::mat4& m) {
    // Rows of the matrix (GLM stores columns).
    const glm::vec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]);
    const glm::vec4 r1(m[0][1], m[1][1], m[2][1], m[3][1]);
    const glm::vec4 r2(m[0][2], m[1][2], m[2][2], m[3][2]);
    const glm::vec4 r3(m[0][3], m[1][3], m[2][3], m[3][3]);
    m_planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
    for (auto& p : m_planes) p /= glm::length(glm::vec3(p));
}

bool Frustum::intersectsBox(const glm::vec3& min, const glm::vec3& max) const {
    for (const auto& p : m_planes) {
        // The box corner farthest along the plane normal.
        const glm::vec3 v(p.x >= 0 ? max.x : min.x, p.y >= 0 ? max.y : min.y, p.z >= 0 ? max.z : min.z);
        if (glm::dot(glm::vec3(p), v) + p.w < 0.0f) return false;
    }
    return true;
}

} // namespace render
