// What the hair of all balls may cost in one tick, and how that cost is shared. Two parts:
//  - a broadphase: each ball collides its hair only with the balls its hair can reach (sort and sweep
//    along x), instead of with every other ball, which grew with the square of the count;
//  - a budget in node passes per tick (settings: hair budget): every awake ball asks for its level of
//    detail (game::activeStrandsFor), and when the sum is over the budget the strands are shared out by
//    weight: near and in front of the player first, far and behind last. Sleeping balls cost nothing
//    and keep what they have (changing it would wake them).
// Deterministic: it reads only the state, so the same state gives the same shares.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "physics/hair.h"

namespace game {

struct GameState;
class HairBall;

// A node pass: one node through one constraint projection (physics::hairProjectionsPerNode) of one substep.
// Each projection makes two passes (the length constraint with the ball's own sphere, and the blocks) and one
// more per neighbouring ball. A default ball (512 strands of 12 nodes, dftl: 1 projection, 1 substep at a
// 60 Hz tick) alone costs 512 x 11 x 1 x 1 x 2 = 11,264 node passes a tick.
// The default budget is measured, not guessed: see docs/HAIR.md (the ballsTick table under "Hair balls in the game").
inline constexpr std::int64_t kDefaultHairBudget = 1'000'000;

struct HairNeighbours {
    std::vector<std::uint32_t> offsets; // ball i's neighbours are colliders[offsets[i] .. offsets[i + 1])
    std::vector<physics::SphereCollider> colliders;
    std::vector<std::uint32_t> index; // the ball each collider belongs to, ascending within a ball's range
};
// For every ball, the other balls whose sphere its hair can touch (centre distance < radius + strand
// length + the other's radius), in ascending index order.
void findHairNeighbours(const std::vector<HairBall>& balls, HairNeighbours& out);

// Node passes of one ball with `strands` active strands and `neighbours` balls in reach, for a tick of
// tickSeconds (which sets the substeps: physics::hairSubstepsFor).
std::int64_t hairCost(const HairBall& ball, int strands, std::size_t neighbours, double tickSeconds = 1.0 / 60.0);

// Active strands per ball for this tick, within `budget` node passes for the awake balls.
// eye, forward: the player's eye and unit view direction (behind the player weighs less).
std::vector<int> shareHairBudget(const GameState& state, const HairNeighbours& neighbours, const glm::vec3& eye,
                                 const glm::vec3& forward, std::int64_t budget, double tickSeconds = 1.0 / 60.0);

} // namespace game
