#include <memory>
#include <unordered_set>

#include <gtest/gtest.h>

#include "world/chunk.h"

namespace {

using world::ChunkCoord;
using world::kChunkSize;

TEST(Chunk, CoordinateHelpersRoundTrip) {
    for (int v = -100; v <= 100; ++v) {
        for (const glm::ivec3 p :
             {glm::ivec3(v, 0, 0), glm::ivec3(0, v, 0), glm::ivec3(0, 0, v), glm::ivec3(v, -v, 3 * v)}) {
            const ChunkCoord c = world::chunkOf(p);
            const glm::ivec3 l = world::localOf(p);
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(l[a], 0);
                EXPECT_LT(l[a], kChunkSize);
            }
            EXPECT_EQ(world::chunkOrigin(c) + l, p);
        }
    }
}

TEST(Chunk, NegativesUseFloorDivision) {
    EXPECT_EQ(world::chunkOf({-1, -1, -1}), (ChunkCoord{-1, -1, -1}));
    EXPECT_EQ(world::localOf({-1, -1, -1}), glm::ivec3(31, 31, 31));
    EXPECT_EQ(world::chunkOf({-32, -33, 31}), (ChunkCoord{-1, -2, 0}));
    EXPECT_EQ(world::localOf({-32, -33, 31}), glm::ivec3(0, 31, 31));
    EXPECT_EQ(world::chunkOf({32, 64, -64}), (ChunkCoord{1, 2, -2}));
    EXPECT_EQ(world::chunkOrigin({-2, 1, 3}), glm::ivec3(-64, 32, 96));
    EXPECT_EQ(world::chunkOf({2147483647, -2147483647 - 1, 0}), (ChunkCoord{67108863, -67108864, 0}));
}

TEST(Chunk, CoordOrderingAndHash) {
    EXPECT_LT((ChunkCoord{0, 0, 0}), (ChunkCoord{0, 0, 1}));
    EXPECT_LT((ChunkCoord{0, 5, 5}), (ChunkCoord{1, 0, 0}));
    EXPECT_EQ((ChunkCoord{1, 2, 3}), (ChunkCoord{1, 2, 3}));
    world::ChunkCoordHash h;
    EXPECT_EQ(h({1, 2, 3}), h({1, 2, 3}));
    std::unordered_set<std::size_t> seen;
    for (int x = -8; x < 8; ++x)
        for (int y = 0; y < 4; ++y)
            for (int z = -8; z < 8; ++z) seen.insert(h({x, y, z}));
    EXPECT_EQ(seen.size(), 16u * 4u * 16u);
}

TEST(Chunk, StorageLayoutAndAir) {
    world::Chunk c;
    EXPECT_TRUE(c.isAllAir());
    c.set(1, 2, 3, world::BlockType::Stone);
    EXPECT_FALSE(c.isAllAir());
    EXPECT_EQ(c.get(1, 2, 3), world::BlockType::Stone);
    EXPECT_EQ(c.data()[1 + kChunkSize * (3 + kChunkSize * 2)], world::BlockType::Stone);
    EXPECT_EQ(world::Chunk::index(31, 31, 31), world::kChunkVolume - 1);
    c.set(1, 2, 3, world::BlockType::Air);
    EXPECT_TRUE(c.isAllAir());
    c.set(31, 31, 31, world::BlockType::Leaves);
    EXPECT_FALSE(c.isAllAir());
    c.fill(world::BlockType::Dirt);
    EXPECT_EQ(c.get(0, 0, 0), world::BlockType::Dirt);
    EXPECT_EQ(c.get(31, 31, 31), world::BlockType::Dirt);
}

} // namespace

namespace {

// The occupancy rows against the bytes, block by block.
void expectRowsMatchBlocks(const world::Chunk& c) {
    for (int y = 0; y < kChunkSize; ++y)
        for (int z = 0; z < kChunkSize; ++z)
            for (int x = 0; x < kChunkSize; ++x)
                ASSERT_EQ((c.solidRow(y, z) >> x & 1u) != 0, world::isSolid(c.get(x, y, z)))
                    << x << ' ' << y << ' ' << z;
}

TEST(Chunk, OccupancyRowsFollowEveryWriter) {
    auto c = std::make_unique<world::Chunk>();
    for (int r = 0; r < kChunkSize * kChunkSize; ++r) ASSERT_EQ(c->solidRows()[r], 0u);
    c->fill(world::BlockType::Dirt);
    for (int r = 0; r < kChunkSize * kChunkSize; ++r) ASSERT_EQ(c->solidRows()[r], ~0u);
    c->set(0, 0, 0, world::BlockType::Air);
    c->set(31, 31, 31, world::BlockType::Air);
    c->set(31, 31, 31, world::BlockType::Sand); // back again
    c->set(17, 4, 9, world::BlockType::Air);
    expectRowsMatchBlocks(*c);
    EXPECT_EQ(c->solidRow(0, 0), ~1u);
    // Bulk writes rebuild the rows from the bytes.
    c->writeBlocks([](world::BlockType* b) {
        for (int i = 0; i < world::kChunkVolume; ++i)
            b[i] = (i * 7919) % 5 == 0 ? world::BlockType::Stone : world::BlockType::Air;
    });
    expectRowsMatchBlocks(*c);
    c->fill(world::BlockType::Air);
    EXPECT_TRUE(c->isAllAir());
    for (int r = 0; r < kChunkSize * kChunkSize; ++r) ASSERT_EQ(c->solidRows()[r], 0u);
}

TEST(Chunk, SolidMask32ReadsThirtyTwoBytes) {
    world::BlockType bytes[40] = {};
    bytes[0] = bytes[5] = bytes[31] = world::BlockType::Gravel;
    bytes[32] = world::BlockType::Stone; // past the end: not read into the mask
    EXPECT_EQ(world::solidMask32(bytes), (1u << 0) | (1u << 5) | (1u << 31));
}

} // namespace
