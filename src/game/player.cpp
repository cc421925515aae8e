#include "game/player.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

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
    if (a.lookAbsolute) {
        p.yaw = a.lookAbsolute->x;
        p.pitch = a.lookAbsolute->y;
    }
    p.yaw = std::fmod(p.yaw + a.yawDelta, 360.0f);
    if (p.yaw < 0.0f) p.yaw += 360.0f;
    p.pitch = std::clamp(p.pitch + a.pitchDelta, -89.0f, 89.0f);

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
        p.position = *a.teleport;
        p.velocity = glm::vec3(0.0f);
        p.onGround = false;
    }
}

void movePlayer(Player& p, const world::World& w, const input::Actions& a, float dt, const PlayerDef& def) {
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
    const world::SweepResult r = world::moveAabb(w, box, delta);
    p.position = glm::vec3((box.min.x + box.max.x) * 0.5f, box.min.y, (box.min.z + box.max.z) * 0.5f);
    p.onGround = r.blocked.y && delta.y <= 0.0f;
    if (r.blocked.x) p.velocity.x = 0.0f;
    if (r.blocked.y) p.velocity.y = 0.0f;
    if (r.blocked.z) p.velocity.z = 0.0f;
}

} // namespace game
