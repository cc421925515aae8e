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

} // namespace game
