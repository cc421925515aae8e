#include "world/raycast.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "world/world.h"

namespace world {

namespace {

// Rays longer than this are cut short: the loop must end even in an empty world.
constexpr double kMaxRayLength = 1.0e6;

template <typename BlockAt>
std::optional<RayHit> castRay(BlockAt&& blockAt, glm::vec3 origin, glm::vec3 direction, float maxDistance) {
    // Doubles inside: tMax accumulates over many steps, and floats would drift over long rays.
    const double o[3] = {origin.x, origin.y, origin.z};
    double d[3] = {direction.x, direction.y, direction.z};
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
    constexpr double kMaxCoordinate = 1 << 30; // block indices must fit an int
    for (const double c : o) {
        if (!(std::abs(c) < kMaxCoordinate)) return std::nullopt;
    }
    if (!(maxDistance >= 0.0f)) return std::nullopt;
    const double limit = std::min(static_cast<double>(maxDistance), kMaxRayLength);
    for (double& c : d) c /= length;

    constexpr double kInf = std::numeric_limits<double>::infinity();
    glm::ivec3 cell;
    int step[3];
    double tMax[3], tDelta[3];
    int entryAxis = -1; // an axis whose face the ray enters the start cell through at t = 0
    for (int a = 0; a < 3; ++a) {
        const double f = std::floor(o[a]);
        cell[a] = static_cast<int>(f);
        const bool onFace = o[a] == f;
        if (d[a] > 0.0) {
            step[a] = 1;
            tDelta[a] = 1.0 / d[a];
            tMax[a] = (f + 1.0 - o[a]) / d[a];
        } else if (d[a] < 0.0) {
            step[a] = -1;
            tDelta[a] = -1.0 / d[a];
            // On a face and moving down the axis: the ray is already leaving cell f for f - 1.
            if (onFace) cell[a] -= 1;
            tMax[a] = onFace ? tDelta[a] : (o[a] - f) / -d[a];
        } else {
            step[a] = 0;
            tDelta[a] = kInf;
            tMax[a] = kInf;
        }
        if (onFace && step[a] != 0 && (entryAxis < 0 || std::abs(d[a]) > std::abs(d[entryAxis]))) entryAxis = a;
    }

    BlockType type = blockAt(cell);
    if (isSolid(type)) {
        glm::ivec3 normal(0);
        if (entryAxis >= 0) normal[entryAxis] = -step[entryAxis];
        return RayHit{cell, normal, 0.0f, type};
    }
    for (;;) {
        int axis = 0;
        if (tMax[1] < tMax[axis]) axis = 1;
        if (tMax[2] < tMax[axis]) axis = 2;
        const double t = tMax[axis];
        if (t > limit) return std::nullopt;
        cell[axis] += step[axis];
        tMax[axis] += tDelta[axis];
        type = blockAt(cell);
        if (isSolid(type)) {
            glm::ivec3 normal(0);
            normal[axis] = -step[axis];
            return RayHit{cell, normal, static_cast<float>(t), type};
        }
    }
}

} // namespace

std::optional<RayHit> raycast(const World& world, glm::vec3 origin, glm::vec3 direction, float maxDistance) {
    return castRay([&](glm::ivec3 p) { return world.get(p); }, origin, direction, maxDistance);
}

std::optional<RayHit> raycast(const std::function<BlockType(glm::ivec3)>& blockAt, glm::vec3 origin,
                              glm::vec3 direction, float maxDistance) {
    if (!blockAt) return std::nullopt;
    return castRay(blockAt, origin, direction, maxDistance);
}

} // namespace world
