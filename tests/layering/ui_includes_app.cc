// Compiled as part of the ui layer (linking mc_ui). It must NOT compile: app/ lies above ui/.
#include "app/frontend.h"
int probe() { return 0; }
