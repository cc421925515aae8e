// Observing a game state from outside: the determinism hash and the JSON state dump used by headless
// runs, tests and acceptance checks. Read-only: nothing here changes the state.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "game/game_state.h"

namespace game {

// Hash of the whole simulation state (tick, world seed and edits, player, pause, pendulum sets, hair
// balls' parameters, solver included, and poses). Loaded-chunk caches are derived data and excluded, so the hash does
// not depend on what happened to be drawn. Hair strands are excluded too: they are rebuilt when a
// saved world loads, so a loaded world hashes like the one saved; the dump gives each ball's strands
// their own `hair_hash`, bit for bit, for determinism checks.
// asPutDown: hash the state as if a carried hair ball were put down where it is, which is the state a
// save of it loads as (save::takeSnapshot), without building that state.
std::uint64_t stateHash(const GameState& state, bool asPutDown = false);
std::string hashToHex(std::uint64_t hash);

nlohmann::json dumpState(const GameState& state);

} // namespace game
