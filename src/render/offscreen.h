// Off-screen OpenGL for headless runs and the render tests, through either of two backends, both loaded at
// run time (dlopen) so that one binary works on a system that has only one of them:
// - OSMesa (libOSMesa.so.8): Mesa's software renderer drawing into memory. Mesa removed it in 25.1, so
//   current Fedora, Arch and Ubuntu releases ship none; Debian 12 has it (libosmesa6).
// - EGL (libEGL.so.1, with Mesa's EGL_MESA_platform_surfaceless): an OpenGL 3.3 core context on a pbuffer,
//   no display needed; Mesa picks llvmpipe when there is no GPU.
// `auto` takes OSMesa when it loads and works, else EGL. The two draw the same pictures within the render
// tests' tolerance (tests/render run on both).
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "render/context.h"

namespace render {

enum class OffscreenBackend { Auto, OsMesa, Egl };

std::optional<OffscreenBackend> offscreenBackendFromName(std::string_view name); // "auto", "osmesa", "egl"
std::string_view offscreenBackendName(OffscreenBackend backend);

// A current off-screen context of width x height (1..16384 each). Throws RenderError: for a named backend,
// why it cannot be used; for Auto, why neither can, and what to install.
std::unique_ptr<RenderContext> makeOffscreenContext(OffscreenBackend backend, int width, int height);
// The backend of the context made last ("osmesa" or "egl"), for messages and the state dump.
std::string_view currentOffscreenBackend();

} // namespace render
