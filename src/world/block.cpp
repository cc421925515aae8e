#include "world/block.h"

#include <array>

namespace world {

namespace {

// Order must follow BlockType; the static_assert below catches a forgotten entry.
constexpr std::array<BlockInfo, kBlockTypeCount> kBlocks{{
    {"air", 0, 0, 0, false},
    {"grass", 0, 1, 2, true},
    {"dirt", 2, 2, 2, true},
    {"stone", 3, 3, 3, true},
    {"sand", 4, 4, 4, true},
    {"log", 6, 5, 6, true},
    {"leaves", 7, 7, 7, true},
    {"planks", 8, 8, 8, true},
    {"brick", 9, 9, 9, true},
    {"cobblestone", 10, 10, 10, true},
    {"snow", 11, 12, 2, true},
    {"gravel", 13, 13, 13, true},
}};
static_assert(kBlocks.size() == static_cast<std::size_t>(BlockType::Count));
static_assert(kBlocks[static_cast<std::size_t>(BlockType::Gravel)].tileTop == 13);

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
