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
}};
static_assert(kBlocks.size() == static_cast<std::size_t>(BlockType::Count));
static_assert(kBlocks[static_cast<std::size_t>(BlockType::Gravel)].tileTop == 13);
static_assert(kBlocks[static_cast<std::size_t>(BlockType::Lamp)].emission ==
              LightColour{kMaxLight, kMaxLight, kMaxLight});
// The greedy mesher keys a face by its tile in four bits (world/mesher.cpp, meshSlice).
static_assert([] {
    for (const BlockInfo& b : kBlocks) {
        if (b.tileTop > 15 || b.tileSide > 15 || b.tileBottom > 15) return false;
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
