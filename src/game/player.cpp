#include "game/player.h"

#include "game/space.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>
#include <vector>

namespace game {

glm::vec3 lookDirection(float yawDeg, float pitchDeg) {
    const float yaw = glm::radians(yawDeg);
    const float pitch = glm::radians(pitchDeg);
    return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

glm::vec3 eyePosition(const Player& p, const PlayerDef& def) {
    return p.position + glm::vec3(0.0f, def.eyeHeight, 0.0f);
}

world::Aabb playerBox(const glm::vec3& feet, const PlayerDef& def) {
    const float h = def.width * 0.5f;
    return {feet - glm::vec3(h, 0.0f, h), feet + glm::vec3(h, def.height, h)};
}

void applyLookAndSelection(Player& p, const input::Actions& a, const PlayerDef&) {
    // Actions come from outside (a mouse, a script): a non-finite value is ignored, and a huge one is
    // reduced to a turn before it is added, so the view stays finite whatever arrives.
    const auto finiteOr = [](float v, float fallback) { return std::isfinite(v) ? v : fallback; };
    if (a.lookAbsolute) {
        p.yaw = finiteOr(a.lookAbsolute->x, p.yaw);
        p.pitch = finiteOr(a.lookAbsolute->y, p.pitch);
    }
    p.yaw = std::fmod(std::fmod(p.yaw, 360.0f) + std::fmod(finiteOr(a.yawDelta, 0.0f), 360.0f), 360.0f);
    if (p.yaw < 0.0f) p.yaw += 360.0f;
    if (p.yaw >= 360.0f) p.yaw = 0.0f; // -1e-30 + 360 rounds to 360 (found by the game fuzzer)
    p.pitch = std::clamp(p.pitch + std::clamp(finiteOr(a.pitchDelta, 0.0f), -180.0f, 180.0f), -89.0f, 89.0f);

    if (a.selectSlot >= 0 && a.selectSlot < kHotbarSize) p.selectedSlot = a.selectSlot;
    if (a.selectDelta != 0) {
        const int s = (p.selectedSlot + a.selectDelta) % kHotbarSize;
        p.selectedSlot = s < 0 ? s + kHotbarSize : s;
    }
    if (a.toggleFly) {
        p.flying = !p.flying;
        p.velocity.y = 0.0f;
    }
    if (a.teleport) {
        p.position = clampToBorder(*a.teleport); // past the border lands on it
        p.velocity = glm::vec3(0.0f);
        p.onGround = false;
    }
}

namespace {
bool fits(const world::World& w, const glm::vec3& feet, const PlayerDef& def) {
    const world::Aabb box = playerBox(feet, def);
    // Cells the box overlaps (a face touching a cell is not overlapping it).
    const glm::ivec3 lo(glm::floor(box.min)), hi(glm::ceil(box.max) - 1.0f);
    for (int y = lo.y; y <= hi.y; ++y)
        for (int z = lo.z; z <= hi.z; ++z)
            for (int x = lo.x; x <= hi.x; ++x)
                if (world::isSolid(w.get({x, y, z}))) return false;
    return true;
}
} // namespace

bool liftOutOfBlocks(Player& p, const world::World& w, const PlayerDef& def) {
    if (fits(w, p.position, def)) return false;
    // Feet at every whole-block height of the world, nearest first, up first at equal distance.
    std::vector<float> heights;
    for (int y = 0; y <= world::kWorldHeight; ++y) heights.push_back(static_cast<float>(y));
    const float from = p.position.y;
    std::stable_sort(heights.begin(), heights.end(), [from](float a, float b) {
        const float da = std::abs(a - from), db = std::abs(b - from);
        return da != db ? da < db : a > b;
    });
    for (const float y : heights) {
        const glm::vec3 feet(p.position.x, y, p.position.z);
        if (fits(w, feet, def)) {
            p.position = feet;
            p.velocity = glm::vec3(0.0f);
            return true;
        }
    }
    return false; // a column solid from the bottom to the top of the world: nothing fits
}

void movePlayer(Player& p, const world::World& w, const input::Actions& a, float dt, const PlayerDef& def,
                std::span<const world::Aabb> obstacles) {
    // Wish velocity in the horizontal plane, relative to where the player faces.
    const float yaw = glm::radians(p.yaw);
    const glm::vec3 forward(std::sin(yaw), 0.0f, -std::cos(yaw));
    const glm::vec3 right(std::cos(yaw), 0.0f, std::sin(yaw));
    glm::vec2 move = a.move;
    if (glm::length(move) > 1.0f) move = glm::normalize(move);
    const float speed =
        p.flying ? (a.sprint ? def.flySprintSpeed : def.flySpeed) : (a.sprint ? def.sprintSpeed : def.walkSpeed);
    const glm::vec3 wish = (forward * move.y + right * move.x) * speed;

    // Exponential approach, exact for any dt, so the feel does not depend on the tick rate.
    const float response = (p.onGround || p.flying) ? def.groundResponse : def.airResponse;
    const float k = 1.0f - std::exp(-response * dt);
    p.velocity.x += (wish.x - p.velocity.x) * k;
    p.velocity.z += (wish.z - p.velocity.z) * k;

    if (p.flying) {
        const float vertical = (a.jump ? 1.0f : 0.0f) - (a.descend ? 1.0f : 0.0f);
        p.velocity.y += (vertical * speed - p.velocity.y) * k;
    } else {
        if (a.jump && p.onGround) p.velocity.y = def.jumpSpeed;
        p.velocity.y = std::max(p.velocity.y - def.gravity * dt, -def.terminalSpeed);
    }

    world::Aabb box = playerBox(p.position, def);
    const glm::vec3 delta = p.velocity * dt;
    const world::SweepResult r = world::moveAabb(w, box, delta, obstacles);
    const glm::vec3 moved((box.min.x + box.max.x) * 0.5f, box.min.y, (box.min.z + box.max.z) * 0.5f);
    p.position = clampToBorder(moved);
    const glm::bvec3 atBorder = glm::notEqual(p.position, moved);
    p.onGround = r.blocked.y && delta.y <= 0.0f;
    if (r.blocked.x || atBorder.x) p.velocity.x = 0.0f;
    if (r.blocked.y || atBorder.y) p.velocity.y = 0.0f;
    if (r.blocked.z || atBorder.z) p.velocity.z = 0.0f;
}

} // namespace game
