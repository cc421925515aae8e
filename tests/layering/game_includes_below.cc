// Compiled as part of the game layer (linking mc_game) with the no-GL defines: it MUST compile. It includes
// a header of every layer game may use, so the failing probes beside it fail for their include alone.
#include "core/hash.h"
#include "game/game_state.h"
#include "input/mapper.h"
#include "physics/pendulum.h"
#include "world/world.h"
int probe() { return 0; }
