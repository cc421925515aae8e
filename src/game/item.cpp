#include "game/item.h"

namespace game {

std::string_view itemName(const Item& item) {
    switch (item.kind) {
    case ItemKind::Block:
        return world::blockInfo(item.block).name;
    case ItemKind::PendulumSet:
        return "pendulum_set";
    case ItemKind::HairBall:
        return "hair_ball";
    case ItemKind::Count:
        break;
    }
    return "unknown";
}

bool isHoldable(const Item& item) {
    if (item.kind == ItemKind::PendulumSet || item.kind == ItemKind::HairBall) return true;
    return item.kind == ItemKind::Block && item.block != world::BlockType::Air &&
           static_cast<int>(item.block) < world::kBlockTypeCount;
}

std::optional<Item> itemFromName(std::string_view name) {
    if (name == "pendulum_set") return Item::pendulumSet();
    if (name == "hair_ball") return Item::hairBall();
    const auto b = world::blockFromName(name);
    if (!b || *b == world::BlockType::Air) return std::nullopt;
    return Item::ofBlock(*b);
}

std::vector<Item> everyItem() {
    std::vector<Item> items;
    for (int t = 1; t < world::kBlockTypeCount; ++t) items.push_back(Item::ofBlock(static_cast<world::BlockType>(t)));
    items.push_back(Item::pendulumSet());
    items.push_back(Item::hairBall());
    return items;
}

} // namespace game
