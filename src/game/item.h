// What a hotbar slot holds: a block, or a placeable lab object (a pendulum set or a hair ball).
// Placing either goes through the same aim-and-click path; only what gets created differs.
#pragma once
#include <optional>
#include <string_view>
#include <vector>

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
// Whether a slot can hold it: an object, or a block that exists and is not air.
bool isHoldable(const Item& item);
// The item of that name (itemName's inverse); nothing for an unknown name or "air".
std::optional<Item> itemFromName(std::string_view name);
// Everything a hotbar slot can hold, in the block picker's order: every block but air, in BlockType order, then
// the pendulum set and the hair ball.
std::vector<Item> everyItem();

} // namespace game
