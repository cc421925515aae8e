
#include <gtest/gtest.h>

#include "core/rng.h"
#include "sparse_blocks.h"
#include "world/collision.h"
#include "world/world.h"

namespace {

using world::Aabb;
using world::BlockType;
using world::kCollisionSkin;

using world_test::Blocks;

std::function<BlockType(glm::ivec3)> fn(const Blocks& b) {
    return [&b](glm::ivec3 p) { return b(p); };
}

Aabb playerAt(glm::vec3 feet) { return {feet - glm::vec3(0.3f, 0.0f, 0.3f), feet + glm::vec3(0.3f, 1.8f, 0.3f)}; }

TEST(Collision, FallingAtHugeSpeedStopsOnTop) {
    const world::World w(world::TerrainDef{1, world::TerrainKind::Flat});
    for (const float speed : {7.5f, 10.0f, 1000.0f, 1.0e6f}) {
        Aabb box = playerAt({0.5f, 40.0f, -7.25f});
        const auto r = world::moveAabb(w, box, {0.0f, -speed, 0.0f});
        EXPECT_TRUE(r.blocked.y) << speed;
        EXPECT_NEAR(box.min.y, 33.0f + kCollisionSkin, 1e-5f);
        EXPECT_NEAR(r.moved.y, 33.0f + kCollisionSkin - 40.0f, 1e-4f);
        EXPECT_FALSE(world::intersectsSolid(w, box));
        // Standing there, a further fall is blocked at once and moves nothing.
        const auto again = world::moveAabb(w, box, {0.0f, -1.0f, 0.0f});
        EXPECT_TRUE(again.blocked.y);
        EXPECT_EQ(again.moved.y, 0.0f);
    }
}

TEST(Collision, WalkingIntoWallAndSliding) {
    Blocks b;
    for (int y = 0; y < 3; ++y)
        for (int z = -5; z <= 5; ++z) b.add({5, y, z});
    Aabb box = playerAt({2.0f, 0.0f, 0.0f});
    const auto r = world::moveAabb(fn(b), box, {10.0f, 0.0f, 1.5f});
    EXPECT_TRUE(r.blocked.x);
    EXPECT_FALSE(r.blocked.z);
    EXPECT_NEAR(box.max.x, 5.0f - kCollisionSkin, 1e-5f);
    EXPECT_FLOAT_EQ(r.moved.z, 1.5f); // slides along the wall
    EXPECT_FLOAT_EQ(box.min.z, -0.3f + 1.5f);
    // Moving away from the wall is free.
    const auto back = world::moveAabb(fn(b), box, {-1.0f, 0.0f, 0.0f});
    EXPECT_FALSE(back.blocked.x);
    EXPECT_FLOAT_EQ(back.moved.x, -1.0f);
}

TEST(Collision, Corner) {
    Blocks b;
    for (int i = -5; i <= 5; ++i) {
        b.add({3, 0, i}); // wall at x = 3
        b.add({i, 0, 3}); // wall at z = 3
    }
    Aabb box{{0.0f, 0.1f, 0.0f}, {0.6f, 0.9f, 0.6f}};
    const auto r = world::moveAabb(fn(b), box, {5.0f, 0.0f, 5.0f});
    EXPECT_TRUE(r.blocked.x);
    EXPECT_TRUE(r.blocked.z);
    EXPECT_NEAR(box.max.x, 3.0f - kCollisionSkin, 1e-5f);
    EXPECT_NEAR(box.max.z, 3.0f - kCollisionSkin, 1e-5f);
    // Into the negative corner too.
    b.add({-3, 0, -1});
    b.add({-1, 0, -3});
    Aabb box2{{-0.5f, 0.1f, -0.5f}, {0.5f, 0.9f, 0.5f}};
    const auto r2 = world::moveAabb(fn(b), box2, {-4.0f, 0.0f, -4.0f});
    EXPECT_TRUE(r2.blocked.x);
    EXPECT_NEAR(box2.min.x, -2.0f + kCollisionSkin, 1e-5f);
    EXPECT_TRUE(r2.blocked.z);
    EXPECT_NEAR(box2.min.z, -2.0f + kCollisionSkin, 1e-5f);
}

TEST(Collision, OnlyEdgeOfCornerBlockStillBlocks) {
    // A box overlapping a wall block by only a sliver in z must still be stopped in x.
    Blocks b;
    b.add({3, 0, 0});
    Aabb box{{0.0f, 0.2f, 0.95f}, {0.5f, 0.8f, 1.5f}};
    const auto r = world::moveAabb(fn(b), box, {4.0f, 0.0f, 0.0f});
    EXPECT_TRUE(r.blocked.x);
    // Touching the block's face exactly in z does not count as overlapping.
    Aabb touching{{0.0f, 0.2f, 1.0f}, {0.5f, 0.8f, 1.5f}};
    EXPECT_FALSE(world::moveAabb(fn(b), touching, {4.0f, 0.0f, 0.0f}).blocked.x);
}

TEST(Collision, NoTunnellingThroughThinWall) {
    Blocks b;
    for (int i = -3; i <= 3; ++i)
        for (int j = -3; j <= 3; ++j) {
            b.add({10, i, j});
            b.add({-10, i, j});
            b.add({i, 10, j});
            b.add({i, -10, j});
            b.add({i, j, 10});
            b.add({i, j, -10});
        }
    for (int face = 0; face < 6; ++face) {
        glm::vec3 dir(0.0f);
        dir[face / 2] = face % 2 == 0 ? 1.0f : -1.0f;
        Aabb box{{-0.4f, -0.4f, -0.4f}, {0.4f, 0.4f, 0.4f}};
        const auto r = world::moveAabb(fn(b), box, dir * 1000.0f);
        EXPECT_TRUE(r.blocked[face / 2]) << face;
        const int a = face / 2;
        if (face % 2 == 0) {
            EXPECT_NEAR(box.max[a], 10.0f - kCollisionSkin, 1e-5f);
        } else {
            EXPECT_NEAR(box.min[a], -9.0f + kCollisionSkin, 1e-5f);
        }
    }
}

TEST(Collision, AxisOrderIsYThenXThenZ) {
    // A box resting on a floor moving down and sideways into a step: Y resolves first (blocked by
    // the floor), then X runs into the step.
    Blocks b;
    for (int x = -2; x <= 4; ++x) b.add({x, -1, 0});
    b.add({2, 0, 0});
    Aabb box{{0.2f, kCollisionSkin, 0.2f}, {0.8f, 1.0f, 0.8f}};
    const auto r = world::moveAabb(fn(b), box, {3.0f, -0.5f, 0.0f});
    EXPECT_TRUE(r.blocked.y);
    EXPECT_EQ(r.moved.y, 0.0f);
    EXPECT_TRUE(r.blocked.x);
    EXPECT_NEAR(box.max.x, 2.0f - kCollisionSkin, 1e-5f);
}

TEST(Collision, BoxInsideBlocksCanMoveOut) {
    Blocks b;
    b.add({0, 0, 0});
    Aabb box{{0.2f, 0.2f, 0.2f}, {0.8f, 0.8f, 0.8f}};
    EXPECT_TRUE(world::intersectsSolid(fn(b), box));
    const auto r = world::moveAabb(fn(b), box, {0.0f, 2.0f, 0.0f});
    EXPECT_FALSE(r.blocked.y);
    EXPECT_FALSE(world::intersectsSolid(fn(b), box));
}

// Random worlds and moves: a box that starts free stays free, and the volume swept along each axis
// holds no solid voxel (so nothing was tunnelled through).
TEST(Collision, RandomSweepsNeverPenetrate) {
    core::Rng rng(5);
    Blocks b;
    b.addRandom(rng, 1500, 24);
    const auto blockAt = fn(b);
    int blockedCount = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 c(rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(-12, 12));
        const glm::vec3 half(rng.uniform(0.1, 0.9), rng.uniform(0.1, 1.4), rng.uniform(0.1, 0.9));
        Aabb box{c - half, c + half};
        if (world::intersectsSolid(blockAt, box)) continue;
        const glm::vec3 delta(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20));
        const Aabb start = box;
        const auto r = world::moveAabb(blockAt, box, delta);
        ASSERT_FALSE(world::intersectsSolid(blockAt, box));
        // Replay the three axis moves and check each swept volume.
        Aabb cur = start;
        for (const int a : {1, 0, 2}) {
            Aabb swept = cur;
            swept.min[a] = std::min(cur.min[a], cur.min[a] + r.moved[a]);
            swept.max[a] = std::max(cur.max[a], cur.max[a] + r.moved[a]);
            ASSERT_FALSE(world::intersectsSolid(blockAt, swept)) << "tunnelled on axis " << a;
            EXPECT_LE(std::abs(r.moved[a]), std::abs(delta[a]) + 1e-5f);
            if (!r.blocked[a]) {
                EXPECT_FLOAT_EQ(r.moved[a], delta[a]);
            } else {
                ++blockedCount;
                // Stopped within the skin of a solid face: one skin further would overlap it.
                Aabb further = cur;
                const float extra = (r.moved[a] + (delta[a] > 0 ? 3 : -3) * kCollisionSkin);
                further.min[a] += extra;
                further.max[a] += extra;
                EXPECT_TRUE(world::intersectsSolid(blockAt, further)) << a;
            }
            cur.min[a] += r.moved[a];
            cur.max[a] += r.moved[a];
        }
    }
    EXPECT_GT(blockedCount, 200);
}

TEST(Collision, WorldAndFunctionAgree) {
    world::World w(world::TerrainDef{3});
    const auto blockAt = [&w](glm::ivec3 p) { return w.get(p); };
    core::Rng rng(8);
    for (int i = 0; i < 50; ++i) {
        const glm::vec3 feet(rng.uniform(-50, 50), rng.uniform(30, 110), rng.uniform(-50, 50));
        const glm::vec3 delta(rng.uniform(-5, 5), rng.uniform(-60, 5), rng.uniform(-5, 5));
        Aabb a = playerAt(feet), b = a;
        const auto ra = world::moveAabb(w, a, delta);
        const auto rb = world::moveAabb(blockAt, b, delta);
        EXPECT_EQ(ra.moved, rb.moved);
        EXPECT_EQ(ra.blocked, rb.blocked);
    }
    EXPECT_EQ(w.loadedChunkCount(), 0u);
}

TEST(Collision, AboveTheWorldIsOpen) {
    const world::World w(world::TerrainDef{1, world::TerrainKind::Flat});
    Aabb box = playerAt({0.5f, 200.0f, 0.5f});
    const auto r = world::moveAabb(w, box, {1.0e5f, 1.0e5f, -1.0e5f});
    EXPECT_FALSE(r.blocked.x || r.blocked.y || r.blocked.z);
    EXPECT_FLOAT_EQ(r.moved.y, 1.0e5f);
}

} // namespace
