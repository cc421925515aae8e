// A flat world without the demo objects: the plain ground the game tests place things on.
#pragma once
#include "game/game_state.h"

inline game::GameDef flatNoDemo() {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    return def;
}
