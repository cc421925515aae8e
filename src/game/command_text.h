// Panel edits as script words, so a recording (session/recording.h) can write them and a replay read them
// back bit for bit: `pendulum INDEX set release=60 length=1 gravity=9.81 step=1 methods=exact,euler,...`,
// `pendulum INDEX release`, `pendulum INDEX reset`, and `hair INDEX radius=0.3 colour=R,G,B ... method=dftl`.
// Numbers are written in their shortest exact form. A field left out keeps its default (PendulumSetDef{},
// HairBallDef{}), so a hand-written line may name only what it changes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "game/game_state.h"

namespace game {

// The words after the index.
std::vector<std::string> pendulumCommandWords(const PendulumCommand& command);
std::vector<std::string> hairCommandWords(const HairCommand& command);

// The command the words describe; throws std::invalid_argument naming the bad word (unknown field or op,
// a value that is not a number or out of its type's range). Whether the edit fits the game (room, limits)
// is decided when the tick applies it, as for a panel's edit.
PendulumCommand pendulumCommandFrom(std::uint64_t index, const std::vector<std::string>& words);
HairCommand hairCommandFrom(std::uint64_t index, const std::vector<std::string>& words);
// `hotbar SLOT ITEM`: SLOT 1 to 9 as the hotbar shows it, ITEM a block's name (not air), pendulum_set or
// hair_ball; throws std::invalid_argument naming what is wrong and what is allowed.
HotbarCommand hotbarCommandFrom(std::uint64_t slot, const std::string& item);

} // namespace game
