// Compiled as part of the game layer (linking mc_game). It must NOT compile: session/ lies above game/, so
// its include root is not on game's path, and the compiler says the header does not exist.
#include "session/session.h"
int probe() { return 0; }
