// libFuzzer target: the world loader (save/world_store.h). Each input is written as the world file, opened
// read-only (createIfMissing = false) and loaded; a bad file must give save::WorldFileError and nothing
// else. What load() returns is then restored into a game state, as the game does on start, and stepped
// two ticks: a value the loader lets through must also be safe to simulate (a 1e30 m hair strand once
// passed the loader and overflowed a float-to-int conversion in the first tick).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "game/game_state.h"
#include "save/world_store.h"

namespace {

const std::filesystem::path& scratchDir() {
    static const std::filesystem::path dir = [] {
        const std::filesystem::path d =
            std::filesystem::temp_directory_path() / ("mc-fuzz-world-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path file = scratchDir() / "fuzz.mcworld";
    // A journal left by the previous input would be "rolled back" into this one; start clean.
    std::error_code ec;
    for (const char* suffix : {"", "-journal", "-wal", "-shm"}) std::filesystem::remove(file.string() + suffix, ec);
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) std::abort();
    }
    try {
        auto store = save::WorldStore::open(file, false);
        if (!store || store->isNew()) return 0;
        const save::Snapshot snapshot = store->load();
        game::GameState state = save::restore(snapshot);
        for (int i = 0; i < 2; ++i) game::tick(state, {}, 1.0 / 60.0);
    } catch (const save::WorldFileError&) {
        // The expected outcome for a file that is not a valid world.
    }
    return 0;
}
