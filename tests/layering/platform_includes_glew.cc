// Compiled as part of the platform layer (linking mc_platform, with the defines src/CMakeLists.txt gives it).
// It must NOT compile: the platform opens a GL context but draws nothing, so GLEW stops with its own
// "#error gl.h included before glew.h".
#include <GL/glew.h>
int probe() { return 0; }
