#include "game/game_state.h"

#include <algorithm>

namespace game {

GameState::GameState(const GameDef& d) : def(d), world(d.terrain) {
    player = spawnPlayer(world, def.player);
    previousPlayer = player;
}

Player spawnPlayer(const world::World& w, const PlayerDef& def) {
    Player p;
    const int x = 0, z = 0;
    int y = world::surfaceHeight(w.terrain(), x, z) + 1;
    // Trees or edits may stand on the surface: climb until the whole body is in air.
    while (y < world::kWorldHeightChunks * world::kChunkSize - 2 &&
           (world::isSolid(w.get({x, y, z})) || world::isSolid(w.get({x, y + 1, z})))) {
        ++y;
    }
    p.position = glm::vec3(x + 0.5f, static_cast<float>(y), z + 0.5f);
    p.yaw = 35.0f;
    p.pitch = -12.0f;
    p.onGround = true;
    (void)def;
    return p;
}

std::optional<world::RayHit> targetedBlock(const GameState& s) {
    const Player& p = s.player;
    return world::raycast(s.world, eyePosition(p, s.def.player), lookDirection(p.yaw, p.pitch),
                          s.def.player.reach);
}

EditResult breakTargeted(GameState& s) {
    const auto hit = targetedBlock(s);
    if (!hit) return EditResult::NothingTargeted;
    if (hit->block.y <= 0) return EditResult::Unbreakable; // the bottom layer keeps the world closed
    s.world.set(hit->block, world::BlockType::Air);
    return EditResult::Done;
}

EditResult placeTargeted(GameState& s) {
    const auto hit = targetedBlock(s);
    if (!hit || hit->normal == glm::ivec3(0)) return EditResult::NothingTargeted;
    const glm::ivec3 pos = hit->block + hit->normal;
    if (pos.y < 0 || pos.y >= world::kWorldHeightChunks * world::kChunkSize) return EditResult::OutOfWorld;
    // Never inside the player: compare the block's cube with the body, shrunk by a hair so that
    // standing flush against a face still allows placing there.
    const world::Aabb body = playerBox(s.player.position, s.def.player);
    const glm::vec3 lo(pos), hi = lo + glm::vec3(1.0f);
    constexpr float kSkin = 1e-3f;
    const bool overlaps = body.min.x + kSkin < hi.x && body.max.x - kSkin > lo.x && body.min.y + kSkin < hi.y &&
                          body.max.y - kSkin > lo.y && body.min.z + kSkin < hi.z && body.max.z - kSkin > lo.z;
    if (overlaps) return EditResult::WouldOverlapPlayer;
    s.world.set(pos, s.player.selectedBlock());
    return EditResult::Done;
}

void tick(GameState& s, const input::Actions& a, float dt) {
    ++s.tick;
    s.previousPlayer = s.player;
    if (a.togglePause) s.paused = !s.paused;
    if (s.paused) return;

    applyLookAndSelection(s.player, a, s.def.player);
    if (a.teleport) s.previousPlayer = s.player; // a jump cut, not a glide across the map
    if (a.pickBlock) {
        if (const auto hit = targetedBlock(s)) {
            Player& p = s.player;
            const auto it = std::find(p.hotbar.begin(), p.hotbar.end(), hit->type);
            if (it != p.hotbar.end()) {
                p.selectedSlot = static_cast<int>(it - p.hotbar.begin());
            } else {
                p.hotbar[static_cast<std::size_t>(p.selectedSlot)] = hit->type;
            }
        }
    }
    // Edits use the view of this tick and the position before moving: what the player saw when clicking.
    if (a.breakBlock) breakTargeted(s);
    if (a.place) placeTargeted(s);
    movePlayer(s.player, s.world, a, dt, s.def.player);
}

} // namespace game
