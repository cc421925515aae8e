// The whole simulation state of a game and the one function that advances it by a tick.
// Everything that the state hash covers lives here; derived caches (loaded chunks, meshes) do not count.
// Nothing here reads a clock, a device or GL: the same state and actions give the same next state.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "game/day_clock.h"
#include "game/hair_ball.h"
#include "game/hair_budget.h"
#include "game/pendulum_set.h"
#include "game/player.h"
#include "input/actions.h"
#include "world/raycast.h"
#include "world/terrain.h"
#include "world/world.h"

namespace game {

struct GameDef {
    world::TerrainDef terrain{};
    PlayerDef player{};
    bool demoObjects = true; // a new world gets a pendulum set in view of the spawn point
    float hairDetail = 1.0f; // share of each hair ball's strands simulated up close (settings: 0.25, 0.5, 1)
    std::int64_t hairBudget = kDefaultHairBudget; // node passes of hair a tick, all balls (game/hair_budget.h)
    // The ball the hotbar places, and the demo balls' shape (the fuzzers use small ones); each demo ball then
    // takes its own solver with that solver's iterations and substeps (physics::hairMethodDefaults).
    HairBallDef ballDef{};
    DayClock day{}; // the clock a new world starts with (its hour from --time-of-day, the rest from the settings)
};

struct GameState {
    explicit GameState(const GameDef& def);

    GameDef def;
    std::uint64_t tick = 0;
    world::World world;
    Player player;
    Player previousPlayer; // the player one tick ago, for drawing between ticks
    bool paused = false;
    DayClock day; // advanced by every tick that is not paused
    std::vector<PendulumSet> pendulumSets;
    std::vector<HairBall> hairBalls;
    std::optional<std::size_t> carriedBall; // index into hairBalls while the player carries one
    // The length of the last tick (s), for drawing the hair between its clock's substeps
    // (physics::hairClockAlpha); set by tick(), not saved (0 until the first tick: drawn as stepped).
    double tickSeconds = 0.0;
};
// The alpha to draw the hair with in a frame `alpha` of the way from the last tick to this one.
float hairDrawAlpha(const GameState& state, float alpha);

struct HairCommand {
    std::size_t ball = 0;
    HairBallDef def{};
};

// Changes made through a panel, applied at the start of the next tick like any other input, so that
// they are part of the deterministic history.
struct PendulumCommand {
    enum class Op { SetDef, Release, Reset };
    std::size_t set = 0;
    Op op = Op::Release;
    PendulumSetDef def{};
};

// The block picker's choice (or a script's `hotbar SLOT ITEM` line): `item` into hotbar slot `slot` (0-based).
struct HotbarCommand {
    int slot = 0;
    Item item{};
};

// What the player's view ray meets first within reach: a block or a lab object.
struct Target {
    enum class Kind { None, Block, PendulumSet, HairBall };
    Kind kind = Kind::None;
    float distance = 0.0f;
    world::RayHit block{}; // Kind::Block
    std::size_t index = 0; // Kind::PendulumSet / HairBall: index into pendulumSets / hairBalls
};
Target targetOf(const GameState& state);

// Where a new player stands in this world: on the ground near the origin, facing the demo view.
Player spawnPlayer(const world::World& w, const PlayerDef& def = {});

// Advances the state by one tick of dt seconds. While paused only the pause toggle is honoured.
struct TickCommands {
    std::vector<PendulumCommand> pendulum;
    std::vector<HairCommand> hair;
    std::optional<double> timeOfDay;   // hours (parseHours): set even while paused, before the tick moves the clock on
    std::vector<HotbarCommand> hotbar; // applied even while paused (the picker is a page of the pause menu)
};
void tick(GameState& state, const input::Actions& actions, double dt, const TickCommands& commands = {});
// Hair balls farther than these distances from the player simulate a half and a quarter of their
// strands (level of detail); deterministic, since it depends only on the state.
inline constexpr float kHairDetailNear = 16.0f, kHairDetailFar = 32.0f; // m
int activeStrandsFor(const HairBall& ball, const glm::vec3& viewer, float detail = 1.0f);

// The invariants every reachable state keeps (game/space.h, docs): every number finite, every position
// inside the world border, pitch within +-89 degrees, indices valid, every object where a placement could have
// put it (game::placementProblem).
// Returns the first violation, empty when there is none. The game checks it after every tick in debug
// and sanitizer builds (MINECRAPPY_CHECK_INVARIANTS) and aborts on a violation; the fuzzers call it too.
std::string checkInvariants(const GameState& state);

// Result of a place/break attempt, for tests and feedback.
enum class EditResult { Done, NothingTargeted, WouldOverlapPlayer, OutOfWorld, Unbreakable, Occupied };
EditResult breakTargeted(GameState& state);
EditResult placeTargeted(GameState& state);

} // namespace game
