// Block types and their static properties (name, atlas tiles, solidity, light).
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
    Lamp, // gives white block light (kMaxLight in each channel); saved worlds hold it from schema 5
    // Coloured lamps; saved worlds hold them from schema 7.
    RedLamp,
    GreenLamp,
    BlueLamp,
    WarmLamp,   // a warm white: red at full, green and blue a little and a little more below it
    OrangeLamp, // a mixed colour: red at full, green at about half, no blue
    Count
};
inline constexpr int kBlockTypeCount = static_cast<int>(BlockType::Count);

// Light levels, sunlight's and block light's alike: 0 (none) to kMaxLight (the open sky, a lamp).
inline constexpr int kMaxLight = 15;

// The block light a block gives, by colour channel (0..kMaxLight each): white gives all three alike.
struct LightColour {
    std::uint8_t red = 0, green = 0, blue = 0;
    constexpr int brightest() const { return red > green ? (red > blue ? red : blue) : (green > blue ? green : blue); }
    constexpr bool any() const { return (red | green | blue) != 0; }
    friend constexpr bool operator==(LightColour, LightColour) = default;
};

struct BlockInfo {
    std::string_view name;
    std::uint8_t tileTop;
    std::uint8_t tileSide;
    std::uint8_t tileBottom;
    bool solid;
    // How many levels light loses on entering this block, on top of the one it loses per block it spreads:
    // 0 for air, a little for leaves, kMaxLight (none gets in) for the rest. Sunlight falling straight down
    // through air keeps its level.
    std::uint8_t lightOpacity;
    LightColour emission; // the block light it gives
};

// Unknown values (including Count) map to the entry for Air rather than reading out of bounds.
const BlockInfo& blockInfo(BlockType type);
// Exact, case-sensitive match on BlockInfo::name; "air" is a valid name.
std::optional<BlockType> blockFromName(std::string_view name);

// Every non-air block is an opaque full cube; meshing and collision rely on this.
inline bool isSolid(BlockType t) { return t != BlockType::Air; }

} // namespace world
