// A flat world without the demo objects: the plain ground the game tests place things on, and the way a
// player places an object on it from the hotbar.
#pragma once
#include <glm/vec2.hpp>
#include <string>

#include "game/game_state.h"
#include "game/item.h"
#include "input/actions.h"

inline game::GameDef flatNoDemo() {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    return def;
}

// Looks along yaw 0 at `pitchDegrees` (negative: down), selects hotbar `slot`, then places its item: one tick
// each. Returns the name of the item that was selected when it placed.
inline std::string placeFromHotbar(game::GameState& s, float pitchDegrees, int slot, double dt) {
    input::Actions aim;
    aim.lookAbsolute = glm::vec2(0.0f, pitchDegrees);
    aim.selectSlot = slot;
    game::tick(s, aim, dt);
    std::string item(game::itemName(s.player.selectedItem()));
    input::Actions place;
    place.place = true;
    game::tick(s, place, dt);
    return item;
}
