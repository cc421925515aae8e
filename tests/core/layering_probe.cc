// Compiled by the layering test with the defines that src/CMakeLists.txt gives the no-GL layers.
// It must NOT compile: that is the proof that a stray GL include in core/world/physics/game/input fails.
#include <GL/glew.h>
int main() { return 0; }
