#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/rng.h"
#include "sparse_blocks.h"
#include "world/raycast.h"
#include "world/world.h"

namespace {

using world::BlockType;

using world_test::Blocks; // the listed blocks are stone, everything else air

TEST(Raycast, DownOntoFlatGround) {
    const world::World w(world::TerrainDef{1, world::TerrainKind::Flat});
    const auto hit = world::raycast(w, {0.5f, 40.5f, 0.5f}, {0.0f, -1.0f, 0.0f}, 100.0f);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->block, glm::ivec3(0, 32, 0));
    EXPECT_EQ(hit->normal, glm::ivec3(0, 1, 0));
    EXPECT_FLOAT_EQ(hit->distance, 7.5f);
    EXPECT_EQ(hit->type, BlockType::Grass);
    EXPECT_EQ(w.loadedChunkCount(), 0u); // reading never loads
}

TEST(Raycast, AxisAlignedInEveryDirection) {
    for (int face = 0; face < 6; ++face) {
        const glm::ivec3 n(face / 2 == 0 ? 1 : 0, face / 2 == 1 ? 1 : 0, face / 2 == 2 ? 1 : 0);
        const glm::ivec3 dir = face % 2 == 0 ? n : -n;
        Blocks b;
        const glm::ivec3 target = glm::ivec3(2, -3, 4) + dir * 6;
        b.add(target);
        const glm::vec3 origin = glm::vec3(2.5f, -2.5f, 4.5f);
        const auto hit = world::raycast(b, origin, glm::vec3(dir) * 3.0f, 20.0f); // not normalised
        ASSERT_TRUE(hit) << face;
        EXPECT_EQ(hit->block, target);
        EXPECT_EQ(hit->normal, -dir);
        EXPECT_FLOAT_EQ(hit->distance, 5.5f);
    }
}

TEST(Raycast, NegativeCoordinates) {
    Blocks b;
    b.add({-5, -3, -7});
    const auto hit = world::raycast(b, {-0.5f, -2.5f, -6.5f}, {-1.0f, 0.0f, 0.0f}, 10.0f);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->block, glm::ivec3(-5, -3, -7));
    EXPECT_EQ(hit->normal, glm::ivec3(1, 0, 0));
    EXPECT_FLOAT_EQ(hit->distance, 3.5f);
}

TEST(Raycast, MaxDistance) {
    Blocks b;
    b.add({5, 0, 0});
    EXPECT_FALSE(world::raycast(b, {0.5f, 0.5f, 0.5f}, {1, 0, 0}, 4.4f));
    const auto hit = world::raycast(b, {0.5f, 0.5f, 0.5f}, {1, 0, 0}, 4.5f); // reaching the face exactly counts
    ASSERT_TRUE(hit);
    EXPECT_FLOAT_EQ(hit->distance, 4.5f);
    EXPECT_FALSE(world::raycast(b, {0.5f, 0.5f, 0.5f}, {-1, 0, 0}, 1000.0f));
}

TEST(Raycast, OriginInsideSolid) {
    Blocks b;
    b.add({0, 0, 0});
    const auto hit = world::raycast(b, {0.3f, 0.6f, 0.2f}, {1, 1, 0}, 5.0f);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->block, glm::ivec3(0));
    EXPECT_EQ(hit->normal, glm::ivec3(0));
    EXPECT_EQ(hit->distance, 0.0f);
}

TEST(Raycast, OriginOnBlockFace) {
    const world::World w(world::TerrainDef{1, world::TerrainKind::Flat});
    // Standing exactly on the grass top: looking down enters the grass through its top at once...
    auto hit = world::raycast(w, {3.25f, 33.0f, -2.5f}, {0.3f, -1.0f, 0.1f}, 5.0f);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->block, glm::ivec3(3, 32, -3));
    EXPECT_EQ(hit->normal, glm::ivec3(0, 1, 0));
    EXPECT_EQ(hit->distance, 0.0f);
    // ...looking up moves away from it.
    EXPECT_FALSE(world::raycast(w, {3.25f, 33.0f, -2.5f}, {0.3f, 1.0f, 0.1f}, 5.0f));
    // On a vertical face of a block, moving into it and away from it.
    Blocks b;
    b.add({-1, 0, 0});
    hit = world::raycast(b, {0.0f, 0.5f, 0.5f}, {-1, 0, 0}, 5.0f);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->block, glm::ivec3(-1, 0, 0));
    EXPECT_EQ(hit->normal, glm::ivec3(1, 0, 0));
    EXPECT_FALSE(world::raycast(b, {0.0f, 0.5f, 0.5f}, {1, 0, 0}, 5.0f));
    // Starting on a lattice line and corner, moving diagonally.
    b.add({3, 3, 0});
    hit = world::raycast(b, {0.0f, 0.0f, 0.5f}, {1, 1, 0}, 10.0f);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->block, glm::ivec3(3, 3, 0));
    EXPECT_NEAR(hit->distance, 3.0f * std::sqrt(2.0f), 1e-4f);
}

TEST(Raycast, DegenerateInput) {
    Blocks b;
    b.add({0, 0, 0});
    EXPECT_FALSE(world::raycast(b, {0.5f, 0.5f, 0.5f}, {0, 0, 0}, 10.0f));
    EXPECT_FALSE(world::raycast(b, {0.5f, 0.5f, 0.5f}, {NAN, 0, 0}, 10.0f));
    EXPECT_FALSE(world::raycast(b, {2.5f, 0.5f, 0.5f}, {-1, 0, 0}, -1.0f));
    EXPECT_FALSE(world::raycast(std::function<BlockType(glm::ivec3)>{}, {0.5f, 0.5f, 0.5f}, {1, 0, 0}, 10.0f));
}

// On random rays: the hit point lies on the reported face of the hit block, and fine sampling along
// the ray finds no solid block before it.
TEST(Raycast, RandomRaysAgreeWithSampling) {
    core::Rng rng(99);
    Blocks b;
    b.addRandom(rng, 400, 20);
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 o(rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10));
        const glm::vec3 d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        if (glm::length(d) < 0.1f) continue;
        const auto hit = world::raycast(b, o, d, 30.0f);
        const glm::vec3 dn = glm::normalize(d);
        const float end = hit ? hit->distance : 30.0f;
        for (float t = 0.0f; t < end - 1e-3f; t += 1e-3f) {
            const glm::vec3 p = o + dn * t;
            ASSERT_EQ(b(glm::ivec3(glm::floor(p))), BlockType::Air) << "ray skipped a block at t=" << t;
        }
        if (!hit) continue;
        ++hits;
        if (hit->normal == glm::ivec3(0)) {
            EXPECT_EQ(hit->distance, 0.0f);
            EXPECT_EQ(glm::ivec3(glm::floor(o)), hit->block);
            continue;
        }
        const glm::vec3 p = o + dn * hit->distance;
        for (int a = 0; a < 3; ++a) {
            if (hit->normal[a] != 0) {
                EXPECT_NEAR(p[a], static_cast<float>(hit->block[a] + (hit->normal[a] > 0 ? 1 : 0)), 1e-3f);
                EXPECT_LT(dn[a] * static_cast<float>(hit->normal[a]), 0.0f); // entered against the normal
            } else {
                EXPECT_GE(p[a], static_cast<float>(hit->block[a]) - 1e-3f);
                EXPECT_LE(p[a], static_cast<float>(hit->block[a] + 1) + 1e-3f);
            }
        }
        EXPECT_EQ(b(hit->block), BlockType::Stone);
    }
    EXPECT_GT(hits, 100);
}

} // namespace
