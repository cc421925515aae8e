// View-frustum culling of axis-aligned boxes: six planes taken from a view-projection matrix
// (Gribb & Hartmann). Conservative: a box is culled only when it lies wholly outside one plane.
#pragma once
#include <array>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace render {

class Frustum {
public:
    explicit Frustum(const glm::mat4& viewProjection);
    bool intersectsBox(const glm::vec3& min, const glm::vec3& max) const;

private:
    std::array<glm::vec4, 6> m_planes;
};

} // namespace render
