// The one way the render layer includes OpenGL: GLEW for every entry point, 3.3 core.
#pragma once
#include <GL/glew.h>
