// libFuzzer target: the whole game state. See game_fuzz.h: bytes become a script of any commands with extreme
// values and panel edits; the game runs it with its invariants checked after every tick, then saves and
// reloads it from memory and must get the same state hash.
#include <cstddef>
#include <cstdint>

#include "game_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    gamefuzz::runOne(data, size);
    return 0;
}
