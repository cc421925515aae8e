#include <gtest/gtest.h>

#include <cmath>

#include "game/game_state.h"
#include "game/state_io.h"

namespace {

game::GameDef flatDef() {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.terrain.seed = 3;
    return def;
}

void settle(game::GameState& s, int ticks = 30) {
    for (int i = 0; i < ticks; ++i) game::tick(s, {}, 1.0f / 60.0f);
}

TEST(Game, SpawnsStandingOnTheGround) {
    game::GameState s(flatDef());
    EXPECT_FLOAT_EQ(s.player.position.y, 33.0f); // flat grass top is y = 32
    settle(s);
    EXPECT_TRUE(s.player.onGround);
    EXPECT_NEAR(s.player.position.y, 33.0f, 1e-3f);
}

TEST(Game, WalkingForwardFollowsYaw) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions a;
    a.lookAbsolute = glm::vec2(90.0f, 0.0f); // east, +X
    game::tick(s, a, 1.0f / 60.0f);
    const glm::vec3 start = s.player.position;
    input::Actions walk;
    walk.move = {0.0f, 1.0f};
    for (int i = 0; i < 120; ++i) game::tick(s, walk, 1.0f / 60.0f);
    const glm::vec3 d = s.player.position - start;
    EXPECT_GT(d.x, 7.0f); // ~4.3 m/s for 2 s, minus the ramp-up
    EXPECT_LT(d.x, 8.7f);
    EXPECT_NEAR(d.z, 0.0f, 1e-3f);
    EXPECT_NEAR(d.y, 0.0f, 1e-3f);
}

TEST(Game, JumpReachesTheHeightGravityAllows) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions jump;
    jump.jump = true;
    float top = s.player.position.y;
    game::tick(s, jump, 1.0f / 60.0f);
    for (int i = 0; i < 60; ++i) {
        game::tick(s, {}, 1.0f / 60.0f);
        top = std::max(top, s.player.position.y);
    }
    const game::PlayerDef def;
    const float ideal = def.jumpSpeed * def.jumpSpeed / (2.0f * def.gravity); // continuous apex
    EXPECT_NEAR(top - 33.0f, ideal, 0.1f); // semi-implicit Euler undershoots by about v*dt/2
    EXPECT_GT(top - 33.0f, 1.0f);          // clears a one-block step
    EXPECT_TRUE(s.player.onGround);
}

TEST(Game, FallingAtTerminalSpeedNeverTunnels) {
    game::GameState s(flatDef());
    input::Actions tp;
    tp.teleport = glm::vec3(0.5f, 120.0f, 0.5f);
    game::tick(s, tp, 1.0f / 60.0f);
    s.player.velocity.y = -1000.0f;                        // far beyond anything the game allows
    for (int i = 0; i < 10; ++i) game::tick(s, {}, 0.25f); // and huge steps
    EXPECT_NEAR(s.player.position.y, 33.0f, 1e-3f);
    EXPECT_TRUE(s.player.onGround);
}

TEST(Game, BreakAndPlaceOnTheTargetedFace) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions look;
    look.lookAbsolute = glm::vec2(0.0f, -60.0f); // north and down: hits the ground ahead
    game::tick(s, look, 1.0f / 60.0f);
    const auto hit = game::targetedBlock(s);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->block.y, 32);
    EXPECT_EQ(hit->normal, glm::ivec3(0, 1, 0));

    input::Actions place;
    place.selectSlot = 6; // brick
    place.place = true;
    game::tick(s, place, 1.0f / 60.0f);
    EXPECT_EQ(s.world.get(hit->block + glm::ivec3(0, 1, 0)), world::BlockType::Brick);

    input::Actions brk;
    brk.breakBlock = true;
    game::tick(s, brk, 1.0f / 60.0f);
    EXPECT_EQ(s.world.get(hit->block + glm::ivec3(0, 1, 0)), world::BlockType::Air);
    const auto edits = s.world.edits();
    ASSERT_EQ(edits.size(), 1u); // the latest value per position
    EXPECT_EQ(edits[0].block, world::BlockType::Air);
}

TEST(Game, NeverPlacesInsideThePlayer) {
    game::GameState s(flatDef());
    settle(s);
    // Looking straight down: the targeted face is the top of the block under the feet, and the new
    // block would be where the player stands.
    input::Actions a;
    a.lookAbsolute = glm::vec2(0.0f, -89.0f);
    game::tick(s, a, 1.0f / 60.0f);
    EXPECT_EQ(game::placeTargeted(s), game::EditResult::WouldOverlapPlayer);
    EXPECT_EQ(s.world.editCount(), 0u);
}

TEST(Game, BottomLayerIsUnbreakable) {
    game::GameDef def = flatDef();
    game::GameState s(def);
    input::Actions a;
    a.teleport = glm::vec3(0.5f, 1.0f, 0.5f);
    a.lookAbsolute = glm::vec2(0.0f, -89.0f);
    for (int y = 32; y >= 1; --y) s.world.set({0, y, 0}, world::BlockType::Air);
    game::tick(s, a, 1.0f / 60.0f);
    EXPECT_EQ(game::breakTargeted(s), game::EditResult::Unbreakable);
}

TEST(Game, PauseFreezesTheSimulation) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions p;
    p.togglePause = true;
    game::tick(s, p, 1.0f / 60.0f);
    ASSERT_TRUE(s.paused);
    const glm::vec3 before = s.player.position;
    input::Actions walk;
    walk.move = {0.0f, 1.0f};
    walk.place = true;
    for (int i = 0; i < 30; ++i) game::tick(s, walk, 1.0f / 60.0f);
    EXPECT_EQ(s.player.position, before);
    EXPECT_EQ(s.world.editCount(), 0u);
}

TEST(Game, SameActionsSameHashDifferentActionsDifferentHash) {
    auto run = [](bool turn) {
        game::GameState s(game::GameDef{});
        for (int i = 0; i < 200; ++i) {
            input::Actions a;
            a.move = {0.3f, 1.0f};
            a.yawDelta = turn ? 0.5f : 0.0f;
            a.jump = (i % 50) == 0;
            a.breakBlock = (i % 37) == 0;
            game::tick(s, a, 1.0f / 60.0f);
        }
        return game::stateHash(s);
    };
    EXPECT_EQ(run(true), run(true));
    EXPECT_NE(run(true), run(false));
}

TEST(Game, HashIgnoresWhichChunksAreLoaded) {
    game::GameState a(game::GameDef{}), b(game::GameDef{});
    for (int x = -2; x <= 2; ++x) b.world.chunk({x, 1, 0}); // a renderer would do this
    EXPECT_EQ(game::stateHash(a), game::stateHash(b));
}

TEST(Game, DumpHasTheContractFields) {
    game::GameState s(flatDef());
    s.world.set({1, 33, 1}, world::BlockType::Planks);
    const auto j = game::dumpState(s);
    EXPECT_EQ(j["tick"], 0);
    EXPECT_EQ(j["state_hash"].get<std::string>().size(), 16u);
    EXPECT_EQ(j["player"]["position"].size(), 3u);
    EXPECT_TRUE(j["player"].contains("yaw"));
    EXPECT_TRUE(j["player"].contains("pitch"));
    EXPECT_EQ(j["player"]["selected_block"], "grass");
    ASSERT_EQ(j["edits"].size(), 1u);
    EXPECT_EQ(j["edits"][0]["pos"], nlohmann::json::array({1, 33, 1}));
    EXPECT_EQ(j["edits"][0]["block"], "planks");
}

} // namespace
