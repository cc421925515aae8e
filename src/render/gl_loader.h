// Loads OpenGL entry points for whichever context is current: a GLFW window (GLX) or OSMesa.
//
// Two traps, both verified on Debian 12 (GLEW 2.2, Mesa 22.3, glvnd):
// 1. Debian's GLEW is a GLX build. glewInit asks glXGetProcAddressARB for every entry point, which
//    knows nothing of OSMesa, so under an OSMesa context no GL 2.0+ function loads. gl_loader.cpp
//    defines glXGetProcAddressARB in the executable; it answers with OSMesaGetProcAddress while an
//    OSMesa context is current and forwards to the real GLX lookup otherwise.
// 2. GL 1.0/1.1 functions (glClear, glReadPixels, glTexImage2D...) are not loaded by GLEW at all: the
//    dynamic linker binds them to the first library exporting them. With both libGL (glvnd) and
//    libOSMesa loaded, one of the two contexts then draws nothing (checked: libGL first leaves an
//    OSMesa frame black). gl_loader.cpp therefore also defines those functions in the executable as
//    forwarders to pointers looked up from the current context, so both backends work in one binary
//    on any driver.
// glewInit returns a GLX error code when there is no X display even though every core entry point
// loaded; GLEW_VERSION_3_3 is the real check.
#pragma once
#include <string>

namespace render {

enum class GlBackend { Glx, OsMesa };

// Call with the context current. Returns an empty string on success, else what is missing.
std::string loadGl(GlBackend backend);

} // namespace render
