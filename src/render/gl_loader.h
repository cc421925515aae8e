// Loads OpenGL entry points for whichever context is current: a GLFW window (GLX), OSMesa or EGL.
//
// Two traps, both verified on Debian 12 (GLEW 2.2, Mesa 22.3, glvnd):
// 1. Debian's GLEW is a GLX build. glewInit asks glXGetProcAddressARB for every entry point, which
//    knows nothing of OSMesa or EGL, so under such a context no GL 2.0+ function loads. gl_loader.cpp
//    defines glXGetProcAddressARB in the executable; it answers with the off-screen backend's lookup
//    (OSMesaGetProcAddress, eglGetProcAddress) while one is in use and forwards to the real GLX lookup
//    otherwise.
// 2. GL 1.0/1.1 functions (glClear, glReadPixels, glTexImage2D...) are not loaded by GLEW at all: the
//    dynamic linker binds them to the first library exporting them. With both libGL (glvnd) and
//    libOSMesa loaded, one of the two contexts then draws nothing (checked: libGL first leaves an
//    OSMesa frame black). gl_loader.cpp therefore also defines those functions in the executable as
//    forwarders to pointers looked up from the current context, so both backends work in one binary
//    on any driver.
// 3. glewInit ends in glxewInit, which looks up glXGetCurrentDisplay and queries that display; under an EGL
//    context eglGetProcAddress hands out glvnd's GLX function, which answers from EGL's thread state and
//    crashes. The lookup therefore finds no glX* function while an off-screen backend is in use.
// glewInit returns a GLX error code when there is no X display even though every core entry point
// loaded; GLEW_VERSION_3_3 is the real check.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

namespace render {

enum class GlBackend { Glx, OsMesa, Egl };
using ProcFn = void (*)();
using ProcLookup = std::function<ProcFn(const char*)>;

// Call with the context current. For OsMesa and Egl, `lookup` is the backend's own GetProcAddress (both are
// loaded with dlopen, render/offscreen.cpp); the GLX lookup is the real one. Returns an empty string on
// success, else what is missing.
std::string loadGl(GlBackend backend, ProcLookup lookup = {});

// Draw calls issued since the process started, for the frame statistics (which take differences).
// glDrawArrays and glDrawElements count themselves in their forwarders; draws through entry points
// GLEW loads (Dear ImGui's glDrawElementsBaseVertex) are added by their caller with countDrawCalls.
// Render thread only.
std::uint64_t drawCallsIssued();
void countDrawCalls(std::uint64_t n);

} // namespace render
