// Not compiled: the layering check scans it as if it were in src/game/. A relative include that climbs out of
// its folder reaches any layer whatever the include roots (the compiler looks beside the including file
// first), so the check refuses it by reading the sources; this file proves that refusal fires.
#include "../session/paths.h"
int probe() { return 0; }
