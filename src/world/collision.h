// Axis-aligned boxes against the voxel grid: sweeping a moving box and testing overlap.
// Sweeps are exact for any displacement: every voxel layer the box would cross is examined, so
// nothing tunnels, however fast. Reads blocks only through World::get or the given function, so
// results never depend on which chunks are loaded; it never changes the world.
#pragma once
#include <functional>
#include <span>

#include <glm/vec3.hpp>

#include "world/block.h"

namespace world {

class World;

struct Aabb {
    glm::vec3 min, max;
};

struct SweepResult {
    glm::vec3 moved;    // displacement actually applied
    glm::bvec3 blocked; // per axis: a solid face stopped the motion
};

// Gap left between a stopped box and the face it ran into (blocks), so that it does not count as
// overlapping that face afterwards.
inline constexpr float kCollisionSkin = 1e-4f;

// Moves `box` by `delta`, one axis at a time in the order Y, X, Z, stopping each axis at the nearest
// solid face. Voxels the box already overlaps are ignored, so a box stuck inside blocks can move out.
// Cost grows with |delta| times the box's cross-section in voxels.
// obstacles: boxes that block like solid voxels (objects the game places); one the box already overlaps is
// ignored, like a voxel.
SweepResult moveAabb(const World& world, Aabb& box, glm::vec3 delta, std::span<const Aabb> obstacles = {});
SweepResult moveAabb(const std::function<BlockType(glm::ivec3)>& blockAt, Aabb& box, glm::vec3 delta);

// True if any solid voxel overlaps the box with positive volume (touching faces do not count).
bool intersectsSolid(const World& world, const Aabb& box);
bool intersectsSolid(const std::function<BlockType(glm::ivec3)>& blockAt, const Aabb& box);

} // namespace world
