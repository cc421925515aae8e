// The whole simulation state of a game and the one function that advances it by a tick.
// Everything that the state hash covers lives here; derived caches (loaded chunks, meshes) do not count.
// Nothing here reads a clock, a device or GL: the same state and actions give the same next state.
#pragma once
#include <cstdint>
#include <optional>

#include "game/player.h"
#include "input/actions.h"
#include "world/raycast.h"
#include "world/terrain.h"
#include "world/world.h"

namespace game {

struct GameDef {
    world::TerrainDef terrain{};
    PlayerDef player{};
};

struct GameState {
    explicit GameState(const GameDef& def);

    GameDef def;
    std::uint64_t tick = 0;
    world::World world;
    Player player;
    Player previousPlayer; // the player one tick ago, for drawing between ticks
    bool paused = false;
};

// Where a new player stands in this world: on the ground near the origin, facing the demo view.
Player spawnPlayer(const world::World& w, const PlayerDef& def = {});

// Advances the state by one tick of dt seconds. While paused only the pause toggle is honoured.
void tick(GameState& state, const input::Actions& actions, float dt);

// The block the player is looking at, within reach.
std::optional<world::RayHit> targetedBlock(const GameState& state);

// Result of a place/break attempt, for tests and feedback.
enum class EditResult { Done, NothingTargeted, WouldOverlapPlayer, OutOfWorld, Unbreakable };
EditResult breakTargeted(GameState& state);
EditResult placeTargeted(GameState& state);

} // namespace game
