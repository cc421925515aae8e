// The player: a walking or flying AABB with a view direction and a hotbar.
// Movement constants live here so the game, the renderer (eye height) and tests agree on them.
// Player movement never reads anything but the world's blocks: no GL, no input devices.
#pragma once
#include <array>
#include <glm/vec3.hpp>
#include <span>

#include "game/item.h"
#include "input/actions.h"
#include "world/block.h"
#include "world/collision.h"
#include "world/world.h"

namespace game {

inline constexpr int kHotbarSize = 9;

struct PlayerDef {
    float width = 0.6f;       // AABB width and depth (m)
    float height = 1.8f;      // AABB height (m)
    float eyeHeight = 1.62f;  // eye above the feet (m)
    float walkSpeed = 4.3f;   // m/s
    float sprintSpeed = 5.6f; // m/s
    float flySpeed = 10.0f;   // m/s, horizontal and vertical
    float flySprintSpeed = 20.0f;
    float gravity = 28.0f;        // m/s^2: with jumpSpeed this gives a jump of about 1.25 blocks
    float jumpSpeed = 8.4f;       // m/s
    float terminalSpeed = 60.0f;  // m/s, the fastest fall
    float groundResponse = 20.0f; // 1/s: how fast horizontal velocity follows the stick on the ground
    float airResponse = 4.0f;     // 1/s: the same in the air (some control, not full)
    float reach = 6.0f;           // m, from the eye, for placing and breaking
};

struct Player {
    glm::vec3 position{0.0f}; // centre of the feet (m)
    glm::vec3 velocity{0.0f}; // m/s
    float yaw = 0.0f;         // degrees; 0 looks north (-Z), 90 east (+X)
    float pitch = 0.0f;       // degrees; + looks up, within +-89
    bool onGround = false;
    bool flying = false;
    int selectedSlot = 0;
    std::array<Item, kHotbarSize> hotbar{Item::ofBlock(world::BlockType::Grass),
                                         Item::ofBlock(world::BlockType::Dirt),
                                         Item::ofBlock(world::BlockType::Stone),
                                         Item::ofBlock(world::BlockType::Cobblestone),
                                         Item::ofBlock(world::BlockType::Planks),
                                         Item::ofBlock(world::BlockType::Lamp),
                                         Item::ofBlock(world::BlockType::Brick),
                                         Item::hairBall(),
                                         Item::pendulumSet()};

    const Item& selectedItem() const { return hotbar[static_cast<std::size_t>(selectedSlot)]; }
};

glm::vec3 lookDirection(float yawDeg, float pitchDeg);
glm::vec3 eyePosition(const Player&, const PlayerDef& def = {});
world::Aabb playerBox(const glm::vec3& feet, const PlayerDef& def = {});

// A body inside solid blocks (a teleport into stone, a world edited by hand) is moved to the nearest height
// in its column where it fits: feet at a whole block, trying one block up, then one down, then two up, and
// so on (up first at equal distance). Returns whether it moved; a body that fits stays exactly where it is.
bool liftOutOfBlocks(Player& player, const world::World& world, const PlayerDef& def = {});

// View and hotbar changes from one tick's actions (no movement).
void applyLookAndSelection(Player&, const input::Actions&, const PlayerDef& def = {});
// One tick of movement: velocity from intent, gravity, and a collision-resolved move against the blocks and
// `obstacles` (objects in the world, see game/space.h), stopping at the world border like at a wall.
void movePlayer(Player&, const world::World&, const input::Actions&, float dt, const PlayerDef& def = {},
                std::span<const world::Aabb> obstacles = {});

} // namespace game
