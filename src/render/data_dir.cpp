#include "render/data_dir.h"

#include <cstdlib>
#include <string>
#include <vector>

#include "render/context.h"

namespace render {

std::filesystem::path dataDir() {
    namespace fs = std::filesystem;
    std::vector<fs::path> candidates;
    std::error_code ec;
    if (const char* env = std::getenv("MINECRAPPY_DATA"); env && *env) {
        // An explicit choice is the only place looked at: silently using another copy would hide it.
        if (fs::exists(fs::path(env) / "shaders" / "chunk.vert", ec)) return env;
        throw RenderError(std::string("cannot find shaders/chunk.vert in MINECRAPPY_DATA=") + env);
    }
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        candidates.push_back(exe.parent_path());
        candidates.push_back(exe.parent_path().parent_path());
    }
    candidates.emplace_back(MC_SOURCE_DIR);
    std::string searched;
    for (const auto& c : candidates) {
        if (fs::exists(c / "shaders" / "chunk.vert", ec)) return c;
        searched += (searched.empty() ? "" : ", ") + c.string();
    }
    throw RenderError("cannot find shaders/chunk.vert (searched " + searched + "); set MINECRAPPY_DATA");
}

} // namespace render
