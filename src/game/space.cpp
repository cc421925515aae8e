#include "game/space.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "game/game_state.h"
#include "world/world.h"

namespace game {

bool insideBorder(const glm::vec3& p) {
    return std::abs(p.x) <= kWorldBorder && std::abs(p.z) <= kWorldBorder && p.y >= kWorldFloor && p.y <= kWorldCeiling;
}

glm::vec3 clampToBorder(const glm::vec3& p) {
    // NaN would pass std::clamp unchanged; the game never holds one (see checkInvariants), but a position
    // that came from outside is made safe here whatever it is.
    const auto c = [](float v, float lo, float hi) { return std::isnan(v) ? 0.0f : std::clamp(v, lo, hi); };
    return {c(p.x, -kWorldBorder, kWorldBorder), c(p.y, kWorldFloor, kWorldCeiling),
            c(p.z, -kWorldBorder, kWorldBorder)};
}

std::array<world::Aabb, 5> pendulumSetBoxes(const PendulumSet& set) {
    std::array<world::Aabb, 5> boxes{};
    const glm::vec3 foot = glm::vec3(set.base()) + glm::vec3(0.5f, 0.0f, 0.5f);
    const float top = set.postHeight();
    constexpr float kPost = 0.15f; // half-width of the post, as the target test uses
    boxes[0] = {foot - glm::vec3(kPost, 0.0f, kPost), foot + glm::vec3(kPost, top + 0.1f, kPost)};
    const float reach = static_cast<float>(set.def().length) + PendulumSet::kBobRadius;
    for (int i = 0; i < kPendulumSlots; ++i) {
        const glm::vec3 pivot = set.pivot(i), along = set.swingAxis(i);
        const glm::vec3 across(std::abs(along.z), 0.0f, std::abs(along.x)); // horizontal, perpendicular
        const glm::vec3 half =
            glm::abs(along) * reach + across * PendulumSet::kBobRadius + glm::vec3(0.0f, reach, 0.0f);
        boxes[static_cast<std::size_t>(i) + 1] = {pivot - half, pivot + half};
    }
    return boxes;
}

bool boxesOverlap(const world::Aabb& a, const world::Aabb& b) {
    for (int k = 0; k < 3; ++k) {
        if (!(a.min[k] < b.max[k] && a.max[k] > b.min[k])) return false;
    }
    return true;
}

bool sphereOverlapsBox(const glm::vec3& centre, float radius, const world::Aabb& box) {
    const glm::vec3 nearest = glm::clamp(centre, box.min, box.max);
    const glm::vec3 d = centre - nearest;
    return glm::dot(d, d) < radius * radius;
}

bool sphereOverlapsSolid(const world::World& world, const glm::vec3& centre, float radius) {
    // The scan covers the sphere's box of blocks: a sphere larger than any the game holds (found by the game
    // fuzzer: a typed radius of 1e30 scanned for ever) or a position beyond the border counts as blocked.
    if (!(radius >= 0.0f && radius <= kMaxHairBallRadius) || !insideBorder(centre)) return true;
    const glm::ivec3 lo(glm::floor(centre - glm::vec3(radius)));
    const glm::ivec3 hi(glm::floor(centre + glm::vec3(radius)));
    for (int y = lo.y; y <= hi.y; ++y) {
        for (int z = lo.z; z <= hi.z; ++z) {
            for (int x = lo.x; x <= hi.x; ++x) {
                if (!world::isSolid(world.get({x, y, z}))) continue;
                const glm::vec3 b(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
                if (sphereOverlapsBox(centre, radius, {b, b + glm::vec3(1.0f)})) return true;
            }
        }
    }
    return false;
}

namespace {

world::Aabb ballBox(const HairBall& ball) {
    const glm::vec3 r(ball.def().radius);
    return {ball.centre() - r, ball.centre() + r};
}

bool overlapsAnySet(const GameState& s, const auto& overlaps, std::optional<std::size_t> ignore) {
    for (std::size_t i = 0; i < s.pendulumSets.size(); ++i) {
        if (ignore && *ignore == i) continue;
        for (const world::Aabb& b : pendulumSetBoxes(s.pendulumSets[i])) {
            if (overlaps(b)) return true;
        }
    }
    return false;
}

} // namespace

bool ballSpaceFree(const GameState& s, const glm::vec3& centre, float radius, Ignore ignore) {
    if (!insideBorder(centre)) return false;
    if (sphereOverlapsSolid(s.world, centre, radius)) return false;
    if (sphereOverlapsBox(centre, radius, playerBox(s.player.position, s.def.player))) return false;
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        if (ignore.ball && *ignore.ball == i) continue;
        const HairBall& other = s.hairBalls[i];
        const float apart = radius + other.def().radius;
        const glm::vec3 d = other.centre() - centre;
        if (glm::dot(d, d) < apart * apart) return false;
    }
    return !overlapsAnySet(
        s, [&](const world::Aabb& b) { return sphereOverlapsBox(centre, radius, b); }, ignore.set);
}

bool setSpaceFree(const GameState& s, const std::array<world::Aabb, 5>& boxes, Ignore ignore) {
    const world::Aabb body = playerBox(s.player.position, s.def.player);
    for (const world::Aabb& box : boxes) {
        if (!insideBorder(box.min) || !insideBorder(box.max)) return false;
        if (world::intersectsSolid(s.world, box) || boxesOverlap(box, body)) return false;
        for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
            if (ignore.ball && *ignore.ball == i) continue;
            if (sphereOverlapsBox(s.hairBalls[i].centre(), s.hairBalls[i].def().radius, box)) return false;
        }
        if (overlapsAnySet(
                s, [&](const world::Aabb& b) { return boxesOverlap(box, b); }, ignore.set))
            return false;
    }
    return true;
}

bool blockSpaceFreeOfObjects(const GameState& s, const glm::ivec3& block) {
    const glm::vec3 lo(block);
    const world::Aabb cube{lo, lo + glm::vec3(1.0f)};
    for (const HairBall& ball : s.hairBalls) {
        if (sphereOverlapsBox(ball.centre(), ball.def().radius, cube)) return false;
    }
    return !overlapsAnySet(
        s, [&](const world::Aabb& b) { return boxesOverlap(cube, b); }, std::nullopt);
}

std::string placementProblem(const GameState& s) {
    std::vector<std::array<world::Aabb, 5>> sets;
    sets.reserve(s.pendulumSets.size());
    for (std::size_t i = 0; i < s.pendulumSets.size(); ++i) {
        const PendulumSet& set = s.pendulumSets[i];
        const std::string name = "pendulum set " + std::to_string(i);
        if (!world::isSolid(s.world.get(set.base() - glm::ivec3(0, 1, 0)))) return name + " stands over air";
        sets.push_back(pendulumSetBoxes(set));
        for (const world::Aabb& box : sets.back()) {
            if (world::intersectsSolid(s.world, box)) return name + " overlaps blocks";
            for (std::size_t j = 0; j < i; ++j) {
                for (const world::Aabb& other : sets[j])
                    if (boxesOverlap(box, other)) return name + " overlaps pendulum set " + std::to_string(j);
            }
        }
    }
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        const HairBall& ball = s.hairBalls[i];
        const float r = ball.def().radius;
        const std::string name = "hair ball " + std::to_string(i);
        if (sphereOverlapsSolid(s.world, ball.centre(), r)) return name + " is inside blocks";
        for (std::size_t j = 0; j < i; ++j) {
            const HairBall& other = s.hairBalls[j];
            const float apart = r + other.def().radius;
            const glm::vec3 d = other.centre() - ball.centre();
            if (glm::dot(d, d) < apart * apart) return name + " overlaps hair ball " + std::to_string(j);
        }
        for (std::size_t j = 0; j < sets.size(); ++j) {
            for (const world::Aabb& box : sets[j])
                if (sphereOverlapsBox(ball.centre(), r, box))
                    return name + " overlaps pendulum set " + std::to_string(j);
        }
    }
    return {};
}

std::optional<glm::vec3> carrySpot(const GameState& s, std::size_t ball, float wanted) {
    const HairBall& b = s.hairBalls[ball];
    const float r = b.def().radius;
    const glm::vec3 eye = eyePosition(s.player, s.def.player);
    const glm::vec3 dir = lookDirection(s.player.yaw, s.player.pitch);
    // Small steps: thinner than anything the ball could pass (blocks are 1 m, a set's swing region is
    // 0.24 m across), so the sweep cannot step over an obstacle.
    constexpr float kStep = 0.05f;
    const Ignore self{ball, std::nullopt};
    std::optional<glm::vec3> spot;
    bool clearOfBody = false;
    for (float d = 0.0f; d <= wanted + 0.5f * kStep; d += kStep) {
        const glm::vec3 at = eye + dir * std::min(d, wanted);
        if (!clearOfBody) {
            // Inside or touching the player's body: not a spot yet, but not a wall either.
            if (sphereOverlapsBox(at, r, playerBox(s.player.position, s.def.player))) {
                if (sphereOverlapsSolid(s.world, at, r)) return std::nullopt;
                continue;
            }
            clearOfBody = true;
        }
        if (!ballSpaceFree(s, at, r, self)) break;
        spot = at;
    }
    return spot;
}

std::vector<world::Aabb> playerObstacles(const GameState& s) {
    std::vector<world::Aabb> boxes;
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        if (s.carriedBall && *s.carriedBall == i) continue;
        boxes.push_back(ballBox(s.hairBalls[i]));
    }
    for (const PendulumSet& set : s.pendulumSets) {
        const auto b = pendulumSetBoxes(set);
        boxes.insert(boxes.end(), b.begin(), b.end());
    }
    return boxes;
}

} // namespace game
