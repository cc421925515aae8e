// Compiled as part of the platform layer (linking mc_platform, with its defines). It must NOT compile:
// render/ stands beside platform, not below it; the window runner in app joins the two.
#include "render/context.h"
int probe() { return 0; }
