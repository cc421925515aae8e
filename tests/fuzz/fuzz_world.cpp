// libFuzzer target: the world loader (save/world_store.h). Each input is a world file's bytes, validated and
// loaded from memory (WorldStore::openImage: the same checks as a file, without writing one, so that thousands
// of inputs run a second); a bad file must give save::WorldFileError and nothing else. What load() returns is
// then restored into a game state, as the game does on start, and stepped two ticks with the game's invariants
// checked: a value the loader lets through must also be safe to simulate (a 1e30 m hair strand once passed
// the loader and overflowed a float-to-int conversion in the first tick).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>

#include "game/game_state.h"
#include "save/world_store.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        auto store = save::WorldStore::openImage(std::span(data, size), "fuzz.mcworld");
        if (store->isNew()) return 0;
        game::GameState state = save::restore(store->load());
        for (int i = 0; i < 2; ++i) {
            game::tick(state, {}, 1.0 / 60.0);
            if (const std::string why = game::checkInvariants(state); !why.empty()) {
                std::fprintf(stderr, "fuzz_world: a loaded world broke an invariant: %s\n", why.c_str());
                std::abort();
            }
        }
    } catch (const save::WorldFileError&) {
        // The expected outcome for a file that is not a valid world.
    }
    return 0;
}
