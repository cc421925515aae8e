#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "world/world.h"

namespace {

using world::BlockType;
using world::ChunkCoord;
using world::World;

TEST(World, GetSetAndWorldBounds) {
    World w;
    const glm::ivec3 p(3, 70, -5);
    w.set(p, BlockType::Brick);
    EXPECT_EQ(w.get(p), BlockType::Brick);
    EXPECT_EQ(w.get({0, -1, 0}), BlockType::Stone);
    EXPECT_EQ(w.get({0, -1000, 0}), BlockType::Stone);
    EXPECT_EQ(w.get({0, 128, 0}), BlockType::Air);
    w.set({0, -1, 0}, BlockType::Air);
    w.set({0, 128, 0}, BlockType::Stone);
    EXPECT_EQ(w.get({0, -1, 0}), BlockType::Stone);
    EXPECT_EQ(w.get({0, 128, 0}), BlockType::Air);
    EXPECT_EQ(w.editCount(), 1u);
    EXPECT_EQ(w.loadedChunkCount(), 0u); // neither get nor set loads
}

TEST(World, EditsAreSortedLatestValueAndKeepNoOps) {
    World w(world::TerrainDef{3, world::TerrainKind::Flat});
    w.set({5, 40, 1}, BlockType::Stone);
    w.set({-5, 40, 1}, BlockType::Planks);
    w.set({5, 2, 9}, BlockType::Air);
    w.set({5, 2, -9}, BlockType::Sand);
    w.set({5, 40, 1}, BlockType::Brick); // overwrites
    w.set({0, 32, 0}, BlockType::Grass); // equals the terrain, still recorded
    const auto e = w.edits();
    ASSERT_EQ(e.size(), 5u);
    EXPECT_EQ(w.editCount(), 5u);
    for (std::size_t i = 1; i < e.size(); ++i) {
        EXPECT_LT(std::tie(e[i - 1].pos.x, e[i - 1].pos.y, e[i - 1].pos.z),
                  std::tie(e[i].pos.x, e[i].pos.y, e[i].pos.z));
    }
    EXPECT_EQ(e[0].pos, glm::ivec3(-5, 40, 1));
    EXPECT_EQ(e[1].pos, glm::ivec3(0, 32, 0));
    EXPECT_EQ(e[1].block, BlockType::Grass);
    EXPECT_EQ(e[2].pos, glm::ivec3(5, 2, -9));
    EXPECT_EQ(e[3].pos, glm::ivec3(5, 2, 9));
    EXPECT_EQ(e[4].pos, glm::ivec3(5, 40, 1));
    EXPECT_EQ(e[4].block, BlockType::Brick);
}

TEST(World, EditsApplyToLoadedAndLaterLoadedChunks) {
    World w;
    const glm::ivec3 a(-40, 90, 17), b(10, 3, 10);
    w.set(a, BlockType::Cobblestone); // before loading
    const world::Chunk& ca = w.chunk(world::chunkOf(a));
    const glm::ivec3 la = world::localOf(a);
    EXPECT_EQ(ca.get(la.x, la.y, la.z), BlockType::Cobblestone);
    const world::Chunk& cb = w.chunk(world::chunkOf(b));
    w.set(b, BlockType::Air); // after loading
    const glm::ivec3 lb = world::localOf(b);
    EXPECT_EQ(cb.get(lb.x, lb.y, lb.z), BlockType::Air);
    EXPECT_EQ(w.get(b), BlockType::Air);
    // Unload and reload: the edits come back.
    w.unloadOutside({1000, 0, 1000}, 0);
    EXPECT_EQ(w.loadedChunkCount(), 0u);
    EXPECT_EQ(w.get(a), BlockType::Cobblestone);
    EXPECT_EQ(w.get(b), BlockType::Air);
    EXPECT_EQ(w.chunk(world::chunkOf(b)).get(lb.x, lb.y, lb.z), BlockType::Air);
}

TEST(World, UnloadedReadsMatchLoaded) {
    World unloaded(world::TerrainDef{11}), loaded(world::TerrainDef{11});
    for (World* w : {&unloaded, &loaded}) {
        w->set({31, 60, 0}, BlockType::Brick);
        w->set({32, 61, -1}, BlockType::Air);
    }
    for (int cy = 0; cy < world::kWorldHeightChunks; ++cy)
        for (int cz = -1; cz <= 0; ++cz)
            for (int cx = 0; cx <= 1; ++cx) loaded.chunk({cx, cy, cz});
    for (int y = 0; y < world::kWorldHeight; y += 3)
        for (int z = -32; z < 32; z += 5)
            for (int x = 0; x < 64; x += 3)
                ASSERT_EQ(unloaded.get({x, y, z}), loaded.get({x, y, z})) << x << ' ' << y << ' ' << z;
    EXPECT_EQ(unloaded.loadedChunkCount(), 0u);
    EXPECT_EQ(loaded.get({31, 60, 0}), BlockType::Brick);
    EXPECT_EQ(unloaded.get({32, 61, -1}), BlockType::Air);
}

TEST(World, RevisionsOfEditedAndBorderingChunks) {
    World w;
    const auto revisions = [&](ChunkCoord around) {
        std::map<ChunkCoord, std::uint64_t> r;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
                for (int dx = -1; dx <= 1; ++dx) {
                    const ChunkCoord c{around.x + dx, around.y + dy, around.z + dz};
                    r[c] = w.chunkRevision(c);
                }
        return r;
    };
    const ChunkCoord c{2, 1, -3};
    const glm::ivec3 o = world::chunkOrigin(c);
    const auto changed = [&](glm::ivec3 local) {
        const auto before = revisions(c);
        const std::uint64_t worldBefore = w.revision();
        w.set(o + local, BlockType::Planks);
        const auto after = revisions(c);
        EXPECT_GT(w.revision(), worldBefore); // any chunk revision that moves, moves the world's
        std::set<std::tuple<int, int, int>> out;
        for (const auto& [k, v] : after) {
            EXPECT_GE(v, before.at(k));
            if (v != before.at(k)) out.insert({k.x - c.x, k.y - c.y, k.z - c.z});
        }
        return out;
    };
    // Light changes at most 14 steps sideways or up from an edit, and a mesh reads one voxel around its
    // chunk: the chunks bumped are those within 15 blocks sideways, up to 15 blocks higher, and every chunk
    // below. (ColumnLight.AnEditBumpsEveryChunkWhoseMeshChanges holds this to the blocks and light.)
    using S = std::set<std::tuple<int, int, int>>;
    const auto box = [](std::initializer_list<int> xs, std::initializer_list<int> ys, std::initializer_list<int> zs) {
        S out;
        for (int y : ys)
            for (int z : zs)
                for (int x : xs) out.insert({x, y, z});
        return out;
    };
    EXPECT_EQ(w.chunkRevision(c), 0u);
    EXPECT_EQ(changed({16, 5, 16}), box({0}, {-1, 0}, {0}));       // 16 from every side
    EXPECT_EQ(changed({15, 5, 16}), box({0}, {-1, 0}, {0}));       // 15 steps from the padding to the west
    EXPECT_EQ(changed({14, 5, 16}), box({-1, 0}, {-1, 0}, {0}));   // 14 steps from it
    EXPECT_EQ(changed({5, 5, 5}), box({-1, 0}, {-1, 0}, {-1, 0})); // near two sides
    EXPECT_EQ(changed({0, 5, 5}), box({-1, 0}, {-1, 0}, {-1, 0})); // on the border
    EXPECT_EQ(changed({16, 16, 16}), box({0}, {-1, 0}, {0}));      // 15 steps below the next chunk's padding
    EXPECT_EQ(changed({16, 17, 16}), box({0}, {-1, 0, 1}, {0}));   // 14 steps below it
    EXPECT_EQ(changed({31, 5, 0}), box({0, 1}, {-1, 0}, {-1, 0}));
    EXPECT_EQ(changed({0, 31, 31}), box({-1, 0}, {-1, 0, 1}, {0, 1}));
    // Revisions do not depend on loading.
    const std::uint64_t r = w.chunkRevision(c), worldR = w.revision();
    EXPECT_GT(r, 0u);
    w.chunk(c);
    w.unloadOutside({100, 0, 100}, 1);
    EXPECT_FALSE(w.isLoaded(c));
    EXPECT_EQ(w.chunkRevision(c), r);
    w.chunk(c);
    EXPECT_EQ(w.chunkRevision(c), r);
    EXPECT_EQ(w.revision(), worldR);
    w.set({0, world::kWorldHeight, 0}, BlockType::Stone); // above the world: ignored, no revision moves
    EXPECT_EQ(w.revision(), worldR);
    // Neighbours outside the world's height are never meshed and get no revision.
    w.set({0, 0, 0}, BlockType::Stone);
    EXPECT_EQ(w.chunkRevision({0, -1, 0}), 0u);
    EXPECT_GT(w.chunkRevision({-1, 0, -1}), 0u);
}

TEST(World, LoadingAndUnloading) {
    World w;
    EXPECT_FALSE(w.isLoaded({0, 0, 0}));
    w.chunk({0, 0, 0});
    w.chunk({3, 1, 0});
    w.chunk({-2, 2, 2});
    w.chunk({0, -1, 0}); // below the world: shared stone, never cached
    w.chunk({0, 4, 0});
    EXPECT_EQ(w.loadedChunkCount(), 3u);
    EXPECT_EQ(w.chunk({0, -1, 0}).get(1, 2, 3), BlockType::Stone);
    EXPECT_TRUE(w.chunk({0, 9, 0}).isAllAir());
    w.unloadOutside({0, 0, 0}, 2);
    EXPECT_TRUE(w.isLoaded({0, 0, 0}));
    EXPECT_FALSE(w.isLoaded({3, 1, 0}));
    EXPECT_TRUE(w.isLoaded({-2, 2, 2}));
    EXPECT_EQ(w.loadedChunkCount(), 2u);
}

// Loads none (pattern 0), every other (1) or all (2) of the chunk's 3x3x3 neighbourhood into the cache.
void loadNeighbours(const World& w, ChunkCoord c, int pattern) {
    if (pattern == 0) return;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
            for (int dx = -1; dx <= 1; ++dx)
                if (pattern == 2 || (dx + dy + dz) % 2 == 0) w.chunk({c.x + dx, c.y + dy, c.z + dz});
}

// gatherPadded must equal get() on every padded voxel, whether neighbours are loaded or not.
TEST(World, GatherPaddedMatchesGet) {
    for (const int loadPattern : {0, 1, 2}) {
        World w(world::TerrainDef{1});
        const ChunkCoord c{0, 1, -1};
        const glm::ivec3 o = world::chunkOrigin(c);
        // Edits on every kind of border: faces, edges, corners, inside and in neighbours.
        w.set(o + glm::ivec3(-1, 5, 5), BlockType::Brick);
        w.set(o + glm::ivec3(32, 32, 32), BlockType::Brick);
        w.set(o + glm::ivec3(-1, -1, -1), BlockType::Planks);
        w.set(o + glm::ivec3(0, 0, 0), BlockType::Air);
        w.set(o + glm::ivec3(16, 32, 3), BlockType::Snow);
        w.set(o + glm::ivec3(16, 33, 3), BlockType::Snow); // not in the border
        loadNeighbours(w, c, loadPattern);
        auto padded = std::make_unique<world::PaddedChunk>();
        padded->blocks.fill(BlockType::Gravel); // everything must be overwritten
        w.gatherPadded(c, *padded);
        EXPECT_TRUE(w.isLoaded(c));
        for (int y = 0; y < world::PaddedChunk::kSize; ++y)
            for (int z = 0; z < world::PaddedChunk::kSize; ++z)
                for (int x = 0; x < world::PaddedChunk::kSize; ++x)
                    ASSERT_EQ(padded->get(x, y, z), w.get(o + glm::ivec3(x - 1, y - 1, z - 1)))
                        << loadPattern << ": " << x << ' ' << y << ' ' << z;
    }
}

// The padded occupancy rows come from the chunks' own rows (loaded neighbours) or from the bytes
// (neighbours generated as slabs); either way they must say what the bytes say, and nothing stale.
TEST(World, GatherPaddedSolidRowsMatchTheBlocks) {
    for (int loadPattern = 0; loadPattern < 3; ++loadPattern) {
        World w(world::TerrainDef{4});
        const ChunkCoord c = world::chunkOf({5, world::surfaceHeight(w.terrain(), 5, 5), 5});
        const glm::ivec3 o = world::chunkOrigin(c);
        w.set(o + glm::ivec3(-1, 5, 5), BlockType::Brick);
        w.set(o + glm::ivec3(32, 7, 0), BlockType::Brick);
        w.set(o + glm::ivec3(3, 32, 32), BlockType::Brick);
        w.set(o + glm::ivec3(4, 4, 4), BlockType::Air);
        loadNeighbours(w, c, loadPattern);
        auto padded = std::make_unique<world::PaddedChunk>();
        for (auto& row : padded->solid) std::fill(std::begin(row), std::end(row), ~std::uint64_t{0});
        w.gatherPadded(c, *padded);
        EXPECT_FALSE(padded->blocks.stale);
        for (int y = 0; y < world::PaddedChunk::kSize; ++y)
            for (int z = 0; z < world::PaddedChunk::kSize; ++z) {
                ASSERT_EQ(padded->solid[y][z] >> world::PaddedChunk::kSize, 0u) << "bits past the row";
                for (int x = 0; x < world::PaddedChunk::kSize; ++x)
                    ASSERT_EQ(padded->solidAt(x, y, z), world::isSolid(padded->get(x, y, z)))
                        << loadPattern << ": " << x << ' ' << y << ' ' << z;
            }
        // The mesh from the kept rows equals the mesh from the bytes alone.
        const world::PaddedChunk& gathered = *padded; // const: reading must not mark the rows stale
        auto bytesOnly = std::make_unique<world::PaddedChunk>();
        std::copy(gathered.blocks.begin(), gathered.blocks.end(), bytesOnly->blocks.begin());
        ASSERT_FALSE(gathered.blocks.stale);
        ASSERT_TRUE(bytesOnly->blocks.stale);
        for (const world::MeshMode mode :
             {world::MeshMode::Greedy, world::MeshMode::GreedyStrips, world::MeshMode::GreedyFlat}) {
            world::ChunkMesh fromRows, fromBytes;
            world::meshChunk(gathered, fromRows, mode);
            world::meshChunk(*bytesOnly, fromBytes, mode);
            ASSERT_GT(fromRows.quadCount(), 0u);
            ASSERT_EQ(fromRows.vertices.size(), fromBytes.vertices.size());
            EXPECT_EQ(std::memcmp(fromRows.vertices.data(), fromBytes.vertices.data(),
                                  fromRows.vertices.size() * sizeof(world::ChunkVertex)),
                      0);
        }
    }
}

// Writing the bytes directly marks the rows stale (and the mesher then reads the bytes); set() and
// rebuildSolid() keep them in step.
TEST(World, PaddedChunkTracksDirectWrites) {
    auto p = std::make_unique<world::PaddedChunk>();
    EXPECT_FALSE(p->blocks.stale);
    p->set(3, 4, 5, BlockType::Stone);
    EXPECT_FALSE(p->blocks.stale);
    EXPECT_TRUE(p->solidAt(3, 4, 5));
    p->blocks[world::PaddedChunk::index(6, 6, 6)] = BlockType::Dirt;
    EXPECT_TRUE(p->blocks.stale);
    EXPECT_FALSE(p->solidAt(6, 6, 6));
    p->rebuildSolid();
    EXPECT_FALSE(p->blocks.stale);
    EXPECT_TRUE(p->solidAt(6, 6, 6));
    EXPECT_TRUE(p->solidAt(3, 4, 5));
    const world::PaddedChunk& view = *p;
    EXPECT_EQ(view.blocks[world::PaddedChunk::index(6, 6, 6)], BlockType::Dirt); // reading marks nothing
    EXPECT_FALSE(p->blocks.stale);
}

TEST(World, GatherPaddedAtWorldBottomAndTop) {
    World w(world::TerrainDef{2, world::TerrainKind::Flat});
    auto padded = std::make_unique<world::PaddedChunk>();
    w.gatherPadded({0, 0, 0}, *padded);
    EXPECT_EQ(padded->get(10, 0, 10), BlockType::Stone);
    w.gatherPadded({0, 3, 0}, *padded);
    EXPECT_EQ(padded->get(10, 33, 10), BlockType::Air);
}

} // namespace
