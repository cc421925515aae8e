// Compiled as part of the physics layer (linking mc_physics). It must NOT compile: game/ lies above physics/.
#include "game/game_state.h"
int probe() { return 0; }
