// Where the programs find shaders/ and assets/: $MINECRAPPY_DATA if set (then only there), else beside the executable
// (the build copies them there), else its parent, else the source tree it was built from.
#pragma once
#include <filesystem>

namespace render {

// Throws RenderError naming the places searched when none holds shaders/chunk.vert.
std::filesystem::path dataDir();

} // namespace render
