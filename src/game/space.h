// What occupies space in the game, and the tests the game makes before it places or moves anything:
// solid blocks, the player's body, hair balls (their spheres) and pendulum sets (the post and the
// region each bob can swing through). One rule for every object: nothing is put where another thing
// already is. Also the world border, inside which every position the game holds stays (positions are
// floats; see kWorldBorder). Pure queries: nothing here changes the state.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "world/collision.h"

namespace world {
class World;
}

namespace game {

struct GameState;
class PendulumSet;

// Every position the game holds (player, hair balls, pendulum sets) stays within |x|, |z| <= kWorldBorder
// and kWorldFloor <= y <= kWorldCeiling. Positions are 32-bit floats: within 8192 m one float step is at
// most 2^-10 m (about 1 mm), so a walking player's step of 72 mm a tick is resolved to 0.7% and a hair
// segment of 41 mm to 1.2%, and the terrain's noise is evaluated at distinct points for every block.
// Far beyond (the issue found floating slabs near 1e9 m) none of that holds. A teleport past the border
// lands on it; walking stops at it like at a wall.
inline constexpr float kWorldBorder = 8192.0f; // m, in x and z
inline constexpr float kWorldFloor = 0.0f;     // m: below is the unbreakable bottom layer and stone
inline constexpr float kWorldCeiling = 384.0f; // m: the world is 128 blocks tall; room to fly above it

bool insideBorder(const glm::vec3& p);
glm::vec3 clampToBorder(const glm::vec3& p);

// The boxes a pendulum set occupies: its post (with the cross of arms) and, per slot, the region its bob
// sweeps when it swings all the way round (a method past its stability limit goes over the top).
std::array<world::Aabb, 5> pendulumSetBoxes(const PendulumSet& set);

bool boxesOverlap(const world::Aabb& a, const world::Aabb& b); // positive volume; touching faces do not count
bool sphereOverlapsBox(const glm::vec3& centre, float radius, const world::Aabb& box);
bool sphereOverlapsSolid(const world::World& world, const glm::vec3& centre, float radius);

// What to leave out of a test: the object being moved or edited.
struct Ignore {
    std::optional<std::size_t> ball, set;
};

// Can a hair ball's sphere be at `centre`: no solid block, not the player's body, no other ball's sphere,
// no pendulum set's boxes.
bool ballSpaceFree(const GameState& state, const glm::vec3& centre, float radius, Ignore ignore = {});
// Can these boxes (a pendulum set's) be there: no solid block, not the player, no ball, no other set.
bool setSpaceFree(const GameState& state, const std::array<world::Aabb, 5>& boxes, Ignore ignore = {});
// Is the unit cube at `block` free of hair balls' spheres and pendulum sets' boxes (the player is checked
// by the caller, which allows standing flush against a face).
bool blockSpaceFreeOfObjects(const GameState& state, const glm::ivec3& block);

// The placement rule as an invariant: what a placement and the panels check before an object appears, moves or
// grows, held by every object of a state (the player aside: collision keeps it out). A set stands on a solid
// block, and its boxes meet no block and no other set's boxes; a ball's sphere meets no block, no other ball and
// no set's boxes. "" when all hold, else the first that does not, naming the objects by index.
std::string placementProblem(const GameState& state);

// Where a carried ball goes: along the view ray from the eye, as far as `wanted` (m) without entering a
// block, a set, another ball or the player's body on the way (a sweep in small steps from the eye, so a
// ball never passes through a wall to a free spot behind it). nullopt when even the nearest spot that
// clears the player's body is taken: the ball then stays where it is.
std::optional<glm::vec3> carrySpot(const GameState& state, std::size_t ball, float wanted);

// The boxes the player's body collides with besides blocks: every hair ball that is not carried (the cube
// around its sphere) and every pendulum set's boxes. A bob never swings through the camera because the
// body never enters a set's swing region.
std::vector<world::Aabb> playerObstacles(const GameState& state);

} // namespace game
