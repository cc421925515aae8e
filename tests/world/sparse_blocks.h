// A sparse test world for the collision and raycast tests: the listed blocks are stone, everything else air.
#pragma once
#include <cstdint>
#include <glm/vec3.hpp>
#include <set>
#include <tuple>

#include "core/rng.h"
#include "world/block.h"

namespace world_test {

struct Blocks {
    std::set<std::tuple<int, int, int>> solid;
    void add(glm::ivec3 p) { solid.insert({p.x, p.y, p.z}); }
    world::BlockType operator()(glm::ivec3 p) const {
        return solid.count({p.x, p.y, p.z}) ? world::BlockType::Stone : world::BlockType::Air;
    }

    // Adds `count` blocks drawn from `rng` (repeats allowed) in the cube of side `size` centred on the origin.
    void addRandom(core::Rng& rng, int count, std::uint32_t size) {
        const int half = static_cast<int>(size / 2);
        for (int i = 0; i < count; ++i) {
            add({static_cast<int>(rng.below(size)) - half, static_cast<int>(rng.below(size)) - half,
                 static_cast<int>(rng.below(size)) - half});
        }
    }
};

} // namespace world_test
