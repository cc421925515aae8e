// Block types and their static properties (name, atlas tiles, solidity).
// This is a pure lookup table: it never touches chunks, the world or any rendering API. The tile
// indices refer to the 16x16 atlas described in assets/README.md.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

namespace world {

enum class BlockType : std::uint8_t {
    Air,
    Grass,
    Dirt,
    Stone,
    Sand,
    Log,
    Leaves,
    Planks,
    Brick,
    Cobblestone,
    Snow,
    Gravel,
    Count
};
inline constexpr int kBlockTypeCount = static_cast<int>(BlockType::Count);

struct BlockInfo {
    std::string_view name;
    std::uint8_t tileTop;
    std::uint8_t tileSide;
    std::uint8_t tileBottom;
    bool solid;
};

// Unknown values (including Count) map to the entry for Air rather than reading out of bounds.
const BlockInfo& blockInfo(BlockType type);
// Exact, case-sensitive match on BlockInfo::name; "air" is a valid name.
std::optional<BlockType> blockFromName(std::string_view name);

// Every non-air block is an opaque full cube; meshing and collision rely on this.
inline bool isSolid(BlockType t) { return t != BlockType::Air; }

} // namespace world
