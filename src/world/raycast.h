// Voxel ray casting (Amanatides & Woo): the first solid block along a ray, for picking blocks.
// Reads blocks only through World::get or the given function, so it never loads chunks or changes
// anything; the same ray over the same blocks always gives the same hit.
#pragma once
#include <functional>
#include <optional>

#include <glm/vec3.hpp>

#include "world/block.h"

namespace world {

class World;

struct RayHit {
    glm::ivec3 block;
    glm::ivec3 normal; // outward normal of the face the ray entered through; zero if it started inside
    float distance;    // along the normalised direction
    BlockType type;
};

// `direction` need not be normalised; a zero or non-finite direction gives nullopt. An origin lying
// exactly on a block face belongs to the block the ray moves into, so a ray starting on the top face
// of the ground and pointing down hits that block at distance 0 through its top face, while one
// pointing up does not hit it at all.
std::optional<RayHit> raycast(const World& world, glm::vec3 origin, glm::vec3 direction, float maxDistance);
std::optional<RayHit> raycast(const std::function<BlockType(glm::ivec3)>& blockAt, glm::vec3 origin,
                              glm::vec3 direction, float maxDistance);

} // namespace world
