#include <algorithm>
#include <cstdlib>
#include <map>
#include <thread>
#include <vector>

#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include "world/block.h"
#include "world/terrain.h"

namespace {

using world::BlockType;
using world::Chunk;
using world::ChunkCoord;
using world::kChunkSize;
using world::TerrainDef;
using world::TerrainKind;

TEST(Terrain, Names) {
    EXPECT_EQ(world::terrainFromName("default"), TerrainKind::Default);
    EXPECT_EQ(world::terrainFromName("flat"), TerrainKind::Flat);
    EXPECT_FALSE(world::terrainFromName("Flat").has_value());
    EXPECT_FALSE(world::terrainFromName("").has_value());
    for (const auto k : {TerrainKind::Default, TerrainKind::Flat})
        EXPECT_EQ(world::terrainFromName(world::terrainName(k)), k);
}

TEST(Terrain, FlatLayout) {
    const TerrainDef def{7, TerrainKind::Flat};
    Chunk c;
    for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
        world::generateChunk(def, {-3, cy, 5}, c);
        for (int y = 0; y < kChunkSize; ++y) {
            const int wy = cy * kChunkSize + y;
            const BlockType expected = wy <= 28   ? BlockType::Stone
                                       : wy <= 31 ? BlockType::Dirt
                                       : wy == 32 ? BlockType::Grass
                                                  : BlockType::Air;
            for (int z = 0; z < kChunkSize; z += 7)
                for (int x = 0; x < kChunkSize; x += 5) ASSERT_EQ(c.get(x, y, z), expected) << wy;
        }
    }
    EXPECT_EQ(world::surfaceHeight(def, 12345, -999), 32);
    EXPECT_EQ(world::terrainBlock(def, {5, 32, 5}), BlockType::Grass);
    EXPECT_EQ(world::terrainBlock(def, {5, -1, 5}), BlockType::Stone);
    EXPECT_EQ(world::terrainBlock(def, {5, 128, 5}), BlockType::Air);
}

TEST(Terrain, DeterministicAndSeedDependent) {
    Chunk a, b, c;
    const ChunkCoord coord{3, 1, -2};
    world::generateChunk(TerrainDef{42}, coord, a);
    world::generateChunk(TerrainDef{42}, coord, b);
    world::generateChunk(TerrainDef{43}, coord, c);
    EXPECT_TRUE(std::equal(a.data(), a.data() + world::kChunkVolume, b.data()));
    EXPECT_FALSE(std::equal(a.data(), a.data() + world::kChunkVolume, c.data()));
    // Seeds that agree in their low 8 bits must still differ (stb_perlin's own seed keeps only those).
    int differing = 0;
    for (int x = 0; x < 64; ++x)
        differing += world::surfaceHeight(TerrainDef{1}, x * 9, 0) != world::surfaceHeight(TerrainDef{257}, x * 9, 0);
    EXPECT_GT(differing, 32);
}

// The property that makes the world seamless: a chunk is exactly the pointwise terrain, whichever
// chunks were generated before and in whichever order. Chosen chunks include tree crowns.
TEST(Terrain, ChunkEqualsPointwiseTerrain) {
    const TerrainDef def{1};
    for (const ChunkCoord coord :
         {ChunkCoord{0, 1, 0}, ChunkCoord{-1, 1, 0}, ChunkCoord{-1, 1, -1}, ChunkCoord{2, 2, -3}}) {
        Chunk c;
        world::generateChunk(def, coord, c);
        const glm::ivec3 origin = world::chunkOrigin(coord);
        for (int y = 0; y < kChunkSize; ++y)
            for (int z = 0; z < kChunkSize; ++z)
                for (int x = 0; x < kChunkSize; ++x)
                    ASSERT_EQ(c.get(x, y, z), world::terrainBlock(def, origin + glm::ivec3(x, y, z)))
                        << x << ' ' << y << ' ' << z;
    }
}

// Terrain keeps the columns of its last few footprints per thread (the chunks of one column of the
// world share them). Whatever is kept, a box must be exactly what a thread with no footprint kept computes:
// boxes at every height of one footprint, under two seeds, as flat terrain and again, each against a
// fresh thread. (Tiles are kept for all threads: TilesSharedByThreadsGiveEveryColumnItsOwnTerrain.)
TEST(Terrain, KeptColumnsGiveWhatAFreshThreadComputes) {
    const glm::ivec3 origin(-17, 0, 40), size(34, 34, 34);
    const auto box = [&](const TerrainDef& def, int y) {
        std::vector<BlockType> out(static_cast<std::size_t>(size.x * size.y * size.z));
        world::generateBox(def, origin + glm::ivec3(0, y, 0), size, out.data());
        return out;
    };
    const auto fresh = [&](const TerrainDef& def, int y) {
        std::vector<BlockType> out;
        std::thread([&] { out = box(def, y); }).join();
        return out;
    };
    const TerrainDef defs[] = {TerrainDef{5}, TerrainDef{6}, TerrainDef{5, world::TerrainKind::Flat}, TerrainDef{5}};
    // Precondition: the seeds and kinds give different blocks here, so a kept footprint taken for the
    // wrong terrain would show.
    EXPECT_NE(fresh(defs[0], 15), fresh(defs[1], 15));
    EXPECT_NE(fresh(defs[0], 15), fresh(defs[2], 15));
    for (const TerrainDef& def : defs) {
        for (int y = -1; y < world::kWorldHeight; y += 32) { // later boxes (all of the last seed's) find them kept
            EXPECT_EQ(box(def, y), fresh(def, y)) << def.seed << ' ' << y;
        }
    }
    // The same origin with another size is another footprint; and after more footprints than are
    // kept, the first is computed again, the same.
    const auto sized = [&](glm::ivec3 boxSize) {
        std::vector<BlockType> out(static_cast<std::size_t>(boxSize.x * boxSize.y * boxSize.z));
        world::generateBox(defs[0], origin, boxSize, out.data());
        return out;
    };
    const std::vector<BlockType> wide = sized({34, 34, 34});
    for (const glm::ivec3 other : {glm::ivec3(32, 34, 34), glm::ivec3(34, 34, 32), glm::ivec3(40, 34, 34)}) {
        const std::vector<BlockType> part = sized(other);
        int differing = 0;
        for (int y = 0; y < 34; ++y)
            for (int z = 0; z < std::min(other.z, 34); ++z)
                for (int x = 0; x < std::min(other.x, 34); ++x) {
                    const int inPart = x + other.x * (z + other.z * y), inWide = x + 34 * (z + 34 * y);
                    differing += part[static_cast<std::size_t>(inPart)] != wide[static_cast<std::size_t>(inWide)];
                }
        EXPECT_EQ(differing, 0) << other.x << 'x' << other.z;
    }
    std::vector<BlockType> scratch(static_cast<std::size_t>(size.x * size.y * size.z));
    for (int i = 0; i < 70; ++i)
        world::generateBox(defs[0], origin + glm::ivec3(34 * (i + 1), 0, 0), size, scratch.data());
    EXPECT_EQ(box(defs[0], -1), fresh(defs[0], -1)) << "after the kept footprints were all replaced";
}

// Tiles of columns are kept for all threads together (terrain.cpp), 1,024 of them in sets by a hash of their
// place. Two threads at once generate the chunk columns of a 40 x 40 tile area (more tiles than are kept, so tiles
// are replaced and sets are shared), in opposite orders, and at two columns of each tile every block from 6 under
// the surface to 8 above it is checked against terrainBlock, which computes its own column (no tile). Mutation
// caught: a kept tile matched by its x alone (another tile's columns served).
TEST(Terrain, TilesSharedByThreadsGiveEveryColumnItsOwnTerrain) {
    const TerrainDef def{7};
    constexpr int kTiles = 40, kSize = world::kChunkSize;
    const auto check = [&](bool forward, int& wrong, int& checked) {
        std::vector<BlockType> box(static_cast<std::size_t>(kSize * world::kWorldHeight * kSize));
        for (int k = 0; k < kTiles * kTiles; ++k) {
            const int i = forward ? k : kTiles * kTiles - 1 - k;
            const glm::ivec3 o((i % kTiles - kTiles / 2) * kSize, 0, (i / kTiles - kTiles / 2) * kSize);
            world::generateBox(def, o, {kSize, world::kWorldHeight, kSize}, box.data());
            for (int s = 0; s < 2; ++s) {
                const int x = (i * 7 + s * 13) % kSize, z = (i * 11 + s * 5) % kSize;
                const int h = world::surfaceHeight(def, o.x + x, o.z + z);
                for (int y = std::max(h - 6, 0); y <= std::min(h + 8, world::kWorldHeight - 1); ++y) {
                    const auto at = [](int v) { return static_cast<std::size_t>(v); };
                    const BlockType b = box[at(x) + at(kSize) * (at(z) + at(kSize) * at(y))];
                    wrong += b != world::terrainBlock(def, o + glm::ivec3(x, y, z));
                    ++checked;
                }
            }
        }
    };
    int wrongA = 0, wrongB = 0, checkedA = 0, checkedB = 0;
    std::thread a([&] { check(true, wrongA, checkedA); }), b([&] { check(false, wrongB, checkedB); });
    a.join();
    b.join();
    EXPECT_GE(checkedA, kTiles * kTiles * 2 * 12); // precondition: the columns were checked
    EXPECT_EQ(checkedA, checkedB);
    EXPECT_EQ(wrongA, 0);
    EXPECT_EQ(wrongB, 0);
}

TEST(Terrain, BoxStraddlingChunksMatchesChunks) {
    const TerrainDef def{99};
    const glm::ivec3 origin(-20, 40, -7), size(45, 30, 40);
    std::vector<BlockType> box(static_cast<std::size_t>(size.x * size.y * size.z));
    world::generateBox(def, origin, size, box.data());
    // Generate the covering chunks in two different orders; both must agree with the box.
    for (const bool reversed : {false, true}) {
        std::vector<ChunkCoord> coords;
        const ChunkCoord lo = world::chunkOf(origin), hi = world::chunkOf(origin + size - 1);
        for (int cy = lo.y; cy <= hi.y; ++cy)
            for (int cz = lo.z; cz <= hi.z; ++cz)
                for (int cx = lo.x; cx <= hi.x; ++cx) coords.push_back({cx, cy, cz});
        if (reversed) std::reverse(coords.begin(), coords.end());
        for (const ChunkCoord c : coords) {
            Chunk chunk;
            world::generateChunk(def, c, chunk);
            const glm::ivec3 co = world::chunkOrigin(c);
            for (int y = 0; y < kChunkSize; ++y)
                for (int z = 0; z < kChunkSize; ++z)
                    for (int x = 0; x < kChunkSize; ++x) {
                        const glm::ivec3 r = co + glm::ivec3(x, y, z) - origin;
                        if (r.x < 0 || r.y < 0 || r.z < 0 || r.x >= size.x || r.y >= size.y || r.z >= size.z) continue;
                        ASSERT_EQ(chunk.get(x, y, z),
                                  box[static_cast<std::size_t>(r.x + size.x * (r.z + size.z * r.y))]);
                    }
        }
    }
}

// Scans a region chunk by chunk and returns the blocks in one array, index x + n*(z + n*y).
struct Region {
    glm::ivec3 origin;
    int n; // chunks per side in x and z
    std::vector<BlockType> blocks;
    int side() const { return n * kChunkSize; }
    std::size_t index(int x, int y, int z) const {
        const auto s = static_cast<std::size_t>(side());
        return static_cast<std::size_t>(x) + s * (static_cast<std::size_t>(z) + s * static_cast<std::size_t>(y));
    }
    BlockType get(int x, int y, int z) const { return blocks[index(x, y, z)]; }
};
Region generateRegion(const TerrainDef& def, ChunkCoord first, int n) {
    Region r{world::chunkOrigin({first.x, 0, first.z}), n, {}};
    r.blocks.resize(r.index(0, world::kWorldHeight, 0));
    Chunk c;
    for (int cy = 0; cy < world::kWorldHeightChunks; ++cy)
        for (int cz = 0; cz < n; ++cz)
            for (int cx = 0; cx < n; ++cx) {
                world::generateChunk(def, {first.x + cx, cy, first.z + cz}, c);
                for (int y = 0; y < kChunkSize; ++y)
                    for (int z = 0; z < kChunkSize; ++z)
                        for (int x = 0; x < kChunkSize; ++x) {
                            const int gx = cx * kChunkSize + x, gy = cy * kChunkSize + y, gz = cz * kChunkSize + z;
                            r.blocks[r.index(gx, gy, gz)] = c.get(x, y, z);
                        }
            }
    return r;
}

TEST(Terrain, SurfaceLayersAndTrees) {
    const TerrainDef def{1};
    const Region r = generateRegion(def, {-2, 0, -2}, 4);
    const int side = r.side();
    int trees = 0, crossingBorder = 0;
    std::vector<glm::ivec2> trunks;
    for (int z = 0; z < side; ++z) {
        for (int x = 0; x < side; ++x) {
            const int wx = r.origin.x + x, wz = r.origin.z + z;
            const int h = world::surfaceHeight(def, wx, wz);
            ASSERT_GE(h, 1);
            ASSERT_LT(h + 8, world::kWorldHeight);
            const BlockType top = r.get(x, h, z);
            ASSERT_TRUE(world::isSolid(top));
            ASSERT_NE(top, BlockType::Log);
            ASSERT_NE(top, BlockType::Leaves);
            // Above the surface only trees (or air).
            for (int y = h + 1; y < world::kWorldHeight; ++y) {
                const BlockType b = r.get(x, y, z);
                ASSERT_TRUE(b == BlockType::Air || b == BlockType::Log || b == BlockType::Leaves) << y;
            }
            if (top == BlockType::Sand) {
                EXPECT_LT(h, 34);
            }
            if (top == BlockType::Snow) {
                EXPECT_GE(h, 80);
            }
            if (h < 34) {
                EXPECT_EQ(top, BlockType::Sand);
            }
            // Stone lies under at most a few layers of soil, and the bottom is stone.
            EXPECT_EQ(r.get(x, h - 5, z), BlockType::Stone);
            EXPECT_EQ(r.get(x, 0, z), BlockType::Stone);
            if (top == BlockType::Grass) {
                EXPECT_EQ(r.get(x, h - 1, z), BlockType::Dirt);
                EXPECT_EQ(r.get(x, h - 3, z), BlockType::Dirt);
            }
            if (r.get(x, h + 1, z) == BlockType::Log) {
                ++trees;
                EXPECT_EQ(top, BlockType::Grass);
                int trunk = 0;
                while (r.get(x, h + 1 + trunk, z) == BlockType::Log) ++trunk;
                EXPECT_GE(trunk, 4);
                EXPECT_LE(trunk, 6);
                EXPECT_EQ(r.get(x, h + trunk + 1, z), BlockType::Leaves);
                trunks.push_back({x, z});
                const int lx = (wx % kChunkSize + kChunkSize) % kChunkSize,
                          lz = (wz % kChunkSize + kChunkSize) % kChunkSize;
                if (lx < 2 || lx > 29 || lz < 2 || lz > 29) ++crossingBorder;
            }
        }
    }
    EXPECT_GT(trees, 20);
    EXPECT_GT(crossingBorder, 3); // the region does exercise crowns split between chunks
    // Trunks never touch, not even diagonally.
    for (std::size_t i = 0; i < trunks.size(); ++i)
        for (std::size_t j = i + 1; j < trunks.size(); ++j)
            EXPECT_GE(std::max(std::abs(trunks[i].x - trunks[j].x), std::abs(trunks[i].y - trunks[j].y)), 2);
    // Every log column, the trunk, stands on the column's surface (no floating logs).
    for (int y = 1; y < world::kWorldHeight; ++y)
        for (int z = 0; z < side; ++z)
            for (int x = 0; x < side; ++x)
                if (r.get(x, y, z) == BlockType::Log) {
                    const BlockType below = r.get(x, y - 1, z);
                    ASSERT_TRUE(below == BlockType::Log || below == BlockType::Grass);
                }
}

TEST(Terrain, HeightsSpanHillsWithVariety) {
    const TerrainDef def{1};
    int lo = 1000, hi = -1000;
    std::map<BlockType, int> tops; // columns topped by each block
    for (int z = -3000; z < 3000; z += 37) {
        for (int x = -3000; x < 3000; x += 41) {
            const int h = world::surfaceHeight(def, x, z);
            lo = std::min(lo, h);
            hi = std::max(hi, h);
            ++tops[world::terrainBlock(def, {x, h, z})];
        }
    }
    for (const auto& [top, columns] : tops) {
        const bool expected =
            top == BlockType::Sand || top == BlockType::Snow || top == BlockType::Gravel || top == BlockType::Grass;
        EXPECT_TRUE(expected) << "unexpected top block " << world::blockInfo(top).name << " on " << columns
                              << " columns";
    }
    EXPECT_LT(lo, 30);
    EXPECT_GT(hi, 90);
    EXPECT_GT(tops[BlockType::Sand], 0);
    EXPECT_GT(tops[BlockType::Snow], 0);
    EXPECT_GT(tops[BlockType::Gravel], 0);
    EXPECT_GT(tops[BlockType::Grass], tops[BlockType::Sand] + tops[BlockType::Snow] + tops[BlockType::Gravel]);
}

TEST(Terrain, OutsideWorldHeight) {
    const TerrainDef def{5};
    std::vector<BlockType> box(8);
    world::generateBox(def, {0, -1, 0}, {2, 2, 2}, box.data()); // y -1 and 0
    for (int i = 0; i < 4; ++i) EXPECT_EQ(box[static_cast<std::size_t>(i)], BlockType::Stone);
    world::generateBox(def, {0, 127, 0}, {2, 2, 2}, box.data()); // y 127 and 128
    for (int i = 4; i < 8; ++i) EXPECT_EQ(box[static_cast<std::size_t>(i)], BlockType::Air);
}

} // namespace
