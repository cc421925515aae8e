// Compiled as part of the render layer (linking mc_render). It must NOT compile: platform/ stands beside
// render, not below it, so its include root is not on render's path and render never sees the window.
#include "platform/glfw_window.h"
int probe() { return 0; }
