// What a hotbar slot holds: a block, or a placeable lab object (a pendulum set or a hair ball).
// Placing either goes through the same aim-and-click path; only what gets created differs.
#pragma once
#include <optional>
#include <string_view>

#include "world/block.h"

namespace game {

enum class ItemKind : unsigned char { Block, PendulumSet, HairBall, Count };

struct Item {
    ItemKind kind = ItemKind::Block;
    world::BlockType block = world::BlockType::Grass; // meaningful for ItemKind::Block

    static constexpr Item ofBlock(world::BlockType b) { return {ItemKind::Block, b}; }
    static constexpr Item pendulumSet() { return {ItemKind::PendulumSet, world::BlockType::Air}; }
    static constexpr Item hairBall() { return {ItemKind::HairBall, world::BlockType::Air}; }
    bool operator==(const Item&) const = default;
};

// "grass", "brick", ... for blocks; "pendulum_set", "hair_ball" for the objects.
std::string_view itemName(const Item& item);

} // namespace game
