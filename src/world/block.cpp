#include "world/block.h"

#include <array>

namespace world {

namespace {

// Order must follow BlockType; the static_assert below catches a forgotten entry.
constexpr std::array<BlockInfo, kBlockTypeCount> kBlocks{{
    {"air", 0, 0, 0, false, 0, {}},
    {"grass", 0, 1, 2, true, kMaxLight, {}},
    {"dirt", 2, 2, 2, true, kMaxLight, {}},
    {"stone", 3, 3, 3, true, kMaxLight, {}},
    {"sand", 4, 4, 4, true, kMaxLight, {}},
    {"log", 6, 5, 6, true, kMaxLight, {}},
    {"leaves", 7, 7, 7, true, 2, {}},
    {"planks", 8, 8, 8, true, kMaxLight, {}},
    {"brick", 9, 9, 9, true, kMaxLight, {}},
    {"cobblestone", 10, 10, 10, true, kMaxLight, {}},
    {"snow", 11, 12, 2, true, kMaxLight, {}},
    {"gravel", 13, 13, 13, true, kMaxLight, {}},
    {"lamp", 14, 14, 14, true, kMaxLight, {kMaxLight, kMaxLight, kMaxLight}},
    {"red_lamp", 15, 15, 15, true, kMaxLight, {kMaxLight, 0, 0}},
    {"green_lamp", 16, 16, 16, true, kMaxLight, {0, kMaxLight, 0}},
    {"blue_lamp", 17, 17, 17, true, kMaxLight, {0, 0, kMaxLight}},
    {"warm_lamp", 18, 18, 18, true, kMaxLight, {kMaxLight, 14, 12}},
    {"orange_lamp", 19, 19, 19, true, kMaxLight, {kMaxLight, 8, 0}},
}};
static_assert(kBlocks.size() == static_cast<std::size_t>(BlockType::Count));
static_assert(kBlocks[static_cast<std::size_t>(BlockType::Gravel)].tileTop == 13);
static_assert(kBlocks[static_cast<std::size_t>(BlockType::Lamp)].emission ==
              LightColour{kMaxLight, kMaxLight, kMaxLight});
// The chunk shader marks the tiles of blocks that give light in a 32-bit mask (uEmissiveTiles,
// render/chunk_upload.cpp); the greedy mesher keys a face by its tile in a byte.
static_assert([] {
    for (const BlockInfo& b : kBlocks) {
        if (b.emission.any() && (b.tileTop > 31 || b.tileSide > 31 || b.tileBottom > 31)) return false;
    }
    return true;
}());

} // namespace

const BlockInfo& blockInfo(BlockType type) {
    const auto i = static_cast<std::size_t>(type);
    return i < kBlocks.size() ? kBlocks[i] : kBlocks[0];
}

std::optional<BlockType> blockFromName(std::string_view name) {
    for (std::size_t i = 0; i < kBlocks.size(); ++i) {
        if (kBlocks[i].name == name) return static_cast<BlockType>(i);
    }
    return std::nullopt;
}

} // namespace world
