// Compiled as part of the game layer (linking mc_game, with the defines src/CMakeLists.txt gives the no-GL
// layers). It must NOT compile, and for the right reason: GLEW's own "#error gl.h included before glew.h".
#include <GL/glew.h>
int probe() { return 0; }
