// Observing a game state from outside: the determinism hash and the JSON state dump used by headless
// runs, tests and acceptance checks. Read-only: nothing here changes the state.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "game/game_state.h"

namespace game {

// Hash of the whole simulation state: everything a later tick depends on (docs/WORLDS.md, "The state hash",
// owns the list). Loaded-chunk caches are derived data and excluded, so the hash does not depend on what
// happened to be drawn; the settings (hair detail and budget) are not state, but what they change is.
// asPutDown: hash the state as if a carried hair ball were put down where it is, which is the state a
// save of it loads as (save::takeSnapshot), without building that state.
std::uint64_t stateHash(const GameState& state, bool asPutDown = false);
std::string hashToHex(std::uint64_t hash);

nlohmann::json dumpState(const GameState& state);

} // namespace game
