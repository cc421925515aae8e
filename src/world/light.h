// Sunlight and block light over a box of blocks, kept up to date edit by edit. Block light has three colour
// channels (red, green, blue); each of the four channels has 16 levels (0..kMaxLight) and keeps the same rule
// (the light is its least solution over the sources below, which lit from nothing but those sources is its only
// one):
//   level(v) = max(emission(v), max over the six neighbours n of level(n) - cost(n -> v)), at least 0,
//   cost(n -> v) = 1 + lightOpacity(v), except sunlight at kMaxLight going straight down into a block of
//   opacity 0, which keeps its level (cost 0).
// Sunlight's emission is the sky above the box: the layer under the box's top gets kMaxLight from above as if
// the sky were a block of sunlight there. A colour channel's emission is that channel of the block's
// BlockInfo::emission (the lamps). Outside the box's sides and bottom nothing is lit and nothing passes.
//
// setBlock() changes one block and repairs sunlight, then the three colour channels together, by breadth-first
// passes that touch only what the change can reach: a removal pass clears every voxel's channels whose light may
// have come through the changed one (levels below the one that was lost, and sunlight's columns under a lost full
// level), then an adding pass spreads light back in from the edge of what was cleared, from emitters inside it
// and from the changed voxel. The colour channels share their passes: a voxel is queued once for all three, and
// each step works on the three at once (docs/LIGHT.md). tests/world/test_light.cpp holds every channel to a
// brute-force relaxation from scratch after random edits.
//
// world/column_light.h lights chunk columns with it for the mesher.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "world/block.h"

namespace world {

enum class LightChannel { Sun, Red, Green, Blue };
inline constexpr LightChannel kLightChannels[] = {LightChannel::Sun, LightChannel::Red, LightChannel::Green,
                                                  LightChannel::Blue};

class LightField {
public:
    // All air, fully sunlit. size: blocks along x, y, z (each at least 1).
    LightField(glm::ivec3 origin, glm::ivec3 size);

    glm::ivec3 origin() const { return m_origin; }
    glm::ivec3 size() const { return m_size; }
    bool contains(glm::ivec3 p) const;

    BlockType block(glm::ivec3 p) const { return contains(p) ? m_blocks[index(p)] : BlockType::Air; }
    int level(LightChannel c, glm::ivec3 p) const;

    // Sets many blocks without repairing the light, then relights the whole box from scratch (fill a region,
    // then call this once).
    template <class Fill>
    void fillAndRelight(Fill&& fill) {
        fill(*this, m_blocks);
        relightAll();
    }
    // Moves the box to `origin`, its size kept: its blocks and light are then stale until fillAndRelight.
    void moveTo(glm::ivec3 origin) { m_origin = origin; }
    // Changes one block (inside the box) and repairs every channel. Returns how many voxels the passes visited.
    std::size_t setBlock(glm::ivec3 p, BlockType t);
    // Every channel from scratch; returns the voxels the spreading visited (the open sky is filled without).
    std::size_t relightAll();

    // Every channel of every voxel (LightLevel::bits, world/light_level.h), in index() order.
    const std::uint16_t* packedLevels() const { return m_light.data(); }
    // Every block, in index() order.
    const BlockType* blocks() const { return m_blocks.data(); }

    // Of a position inside the box (contains(p)); position() is its inverse.
    std::size_t index(glm::ivec3 p) const {
        const glm::ivec3 l = p - m_origin;
        const auto at = [](int v) { return static_cast<std::size_t>(v); };
        return at(l.x) + at(m_size.x) * (at(l.z) + at(m_size.z) * at(l.y));
    }
    glm::ivec3 position(std::size_t i) const;

private:
    int get(LightChannel c, std::size_t i) const;

    glm::ivec3 m_origin, m_size;
    std::vector<BlockType> m_blocks;
    std::vector<std::uint16_t> m_light; // LightLevel::bits of each voxel
};

} // namespace world
