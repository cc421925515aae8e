// The light meshes are lit by (world/column_light.h): equal whether a thread repairs a kept column or relights
// it from scratch, equal to a box far wider than the light box, equal whichever thread meshes and in which
// order; and every chunk whose mesh input changes with an edit gets a new revision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <thread>
#include <tuple>
#include <vector>

#include "world/column_light.h"
#include "world/light.h"
#include "world/light_level.h"
#include "world/mesh_worker.h"

namespace {

using world::BlockEdit;
using world::BlockType;
using world::ChunkCoord;
using world::PaddedLight;

constexpr world::TerrainDef kTerrain{6};

// Chunk column (column.x, column.z) lit over a box `margin` blocks wider on every side, every height, filled from
// the World block by block: no cache, no light box, no light region.
std::unique_ptr<world::LightField> widelyLit(const world::World& w, int margin, ChunkCoord column = {0, 0, 0}) {
    const glm::ivec3 o = world::chunkOrigin({column.x, 0, column.z}) - glm::ivec3(margin, 0, margin);
    const glm::ivec3 size(world::kChunkSize + 2 * margin, world::kWorldHeight, world::kChunkSize + 2 * margin);
    auto f = std::make_unique<world::LightField>(o, size);
    const ChunkCoord low = world::chunkOf(o), high = world::chunkOf(o + size - glm::ivec3(1));
    for (int cz = low.z; cz <= high.z; ++cz) // load them: get() is then fast
        for (int cx = low.x; cx <= high.x; ++cx)
            for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) w.chunk({cx, cy, cz});
    f->fillAndRelight([&](world::LightField& field, std::vector<BlockType>& blocks) {
        for (std::size_t i = 0; i < blocks.size(); ++i) blocks[i] = w.get(field.position(i));
    });
    return f;
}

// The padded light of chunk `c` of column (0, 0), read from a field lit by widelyLit().
std::unique_ptr<PaddedLight> paddedFrom(const world::LightField& f, ChunkCoord c) {
    auto out = std::make_unique<PaddedLight>();
    const glm::ivec3 low = world::chunkOrigin(c) - glm::ivec3(1);
    for (int y = 0; y < PaddedLight::kSize; ++y)
        for (int z = 0; z < PaddedLight::kSize; ++z)
            for (int x = 0; x < PaddedLight::kSize; ++x) {
                const glm::ivec3 p = low + glm::ivec3(x, y, z);
                const bool inside = p.y >= 0 && p.y < world::kWorldHeight;
                const int sun = p.y < 0 ? 0 : inside ? f.level(world::LightChannel::Sun, p) : world::kMaxLight;
                const auto colour = [&](world::LightChannel c) { return inside ? f.level(c, p) : 0; };
                out->level[static_cast<std::size_t>(world::PaddedChunk::index(x, y, z))] =
                    world::LightLevel::of(sun, colour(world::LightChannel::Red), colour(world::LightChannel::Green),
                                          colour(world::LightChannel::Blue))
                        .bits;
            }
    out->rebuildShade();
    return out;
}

std::unique_ptr<PaddedLight> lit(const world::World& w, ChunkCoord c) {
    std::vector<BlockEdit> edits;
    w.editsAround(c, edits);
    auto out = std::make_unique<PaddedLight>();
    world::lightPadded(w.terrain(), c, edits, *out);
    return out;
}

bool equal(const PaddedLight& a, const PaddedLight& b) {
    return a.level == b.level && std::memcmp(a.shade, b.shade, sizeof a.shade) == 0;
}

// Random edits in and around columns (0, 0) to (columns - 1, columns - 1) near the surface: lamps of every colour,
// leaves, stone and holes, across chunk borders and in the neighbouring columns' margin. Returns how many of the
// edits placed a coloured lamp (a test of colour asserts some did).
int editAtRandom(world::World& w, std::mt19937& rng, int count, int columns = 1) {
    std::uniform_int_distribution<int> xz(-20, columns * world::kChunkSize + 19), dy(-6, 4), kind(0, 8);
    int colourLamps = 0;
    for (int i = 0; i < count; ++i) {
        const int x = xz(rng), z = xz(rng);
        const glm::ivec3 p(x, world::surfaceHeight(w.terrain(), x, z) + dy(rng), z);
        const BlockType types[] = {BlockType::Lamp,    BlockType::Leaves,     BlockType::Stone,
                                   BlockType::Air,     BlockType::Air,        BlockType::Planks,
                                   BlockType::RedLamp, BlockType::OrangeLamp, BlockType::BlueLamp};
        const BlockType t = types[kind(rng)];
        w.set(p, t);
        colourLamps += t == BlockType::RedLamp || t == BlockType::OrangeLamp || t == BlockType::BlueLamp;
    }
    return colourLamps;
}

TEST(ColumnLight, RepairedRelitAndWidelyLitAgreeAfterRandomEdits) {
    world::World w(kTerrain);
    world::clearColumnLight();
    std::mt19937 rng(37);
    int shaded = 0, lampLit = 0, changedByEdits = 0, colourLamps = 0;
    std::vector<std::unique_ptr<PaddedLight>> before(world::kWorldHeightChunks);
    for (int round = 0; round < 4; ++round) {
        colourLamps += editAtRandom(w, rng, round == 0 ? 0 : 16);
        const auto wide = widelyLit(w, 40);
        // Every chunk of the column from the kept column, brought up to date edit by edit (after the first
        // round), then every chunk again from a column lit from scratch.
        std::vector<std::unique_ptr<PaddedLight>> repaired, relit;
        const world::ColumnLightStats start = world::columnLightStats();
        for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) repaired.push_back(lit(w, {0, cy, 0}));
        const world::ColumnLightStats kept = world::columnLightStats();
        world::clearColumnLight();
        for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) relit.push_back(lit(w, {0, cy, 0}));
        if (round > 0) {
            // Precondition: the first request repaired the kept column, the other three reused it.
            EXPECT_EQ(kept.repaired - start.repaired, 1) << round;
            EXPECT_EQ(kept.relit - start.relit, 0) << round;
            EXPECT_EQ(kept.reused - start.reused, 3) << round;
        }
        for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
            const auto k = static_cast<std::size_t>(cy);
            EXPECT_TRUE(equal(*repaired[k], *relit[k])) << "round " << round << " chunk y " << cy;
            EXPECT_TRUE(equal(*relit[k], *paddedFrom(*wide, {0, cy, 0}))) << "round " << round << " chunk y " << cy;
            for (std::size_t v = 0; v < relit[k]->level.size(); ++v) {
                const std::uint16_t l = relit[k]->level[v];
                shaded += world::LightLevel{l}.sun() < world::kMaxLight;
                lampLit += world::LightLevel{l}.block() > 0;
                if (before[k]) changedByEdits += l != before[k]->level[v];
            }
            before[k] = std::move(relit[k]);
        }
    }
    // Preconditions: the scenes have shade and lamp light, so a field of open sky would not pass, and the edits
    // changed the light the repaired columns were compared on (measured: 219,504 shaded voxels, 558 lamp-lit, 236
    // changed by the edits; about a tenth of each asked).
    std::printf("voxels in the shade %d, lit by lamps %d, changed by the edits %d\n", shaded, lampLit, changedByEdits);
    EXPECT_GT(shaded, 20000);
    EXPECT_GT(lampLit, 50);
    EXPECT_GT(changedByEdits, 20);
    EXPECT_GT(colourLamps, 0); // precondition: coloured lamps among the edits
}

// Columns are lit a light region at a time (world::kLightRegion square): every column of a region, the ones at its
// far sides too, is lit as by a box 40 blocks wider around that column alone, after random edits and lamps within
// 20 blocks of the region on every side. Mutation caught: a light box one border short on the far side
// (kLightRegion * kChunkSize + kLightBorder + 2 wide).
TEST(ColumnLight, EveryColumnOfALightRegionIsLitAsAloneInAWideBox) {
    ASSERT_GE(world::kLightRegion, 2) << "with one column a region, this is RepairedRelitAndWidelyLitAgree...";
    world::World w(kTerrain);
    world::clearColumnLight();
    std::mt19937 rng(41);
    EXPECT_GT(editAtRandom(w, rng, 160, world::kLightRegion), 0); // precondition: coloured lamps among the edits
    int columns = 0, lampLit = 0;
    for (int cz = 0; cz < world::kLightRegion; ++cz) {
        for (int cx = 0; cx < world::kLightRegion; ++cx) {
            ASSERT_EQ(world::lightRegionOf({cx, 0, cz}), (ChunkCoord{0, 0, 0})); // precondition: one region
            const auto wide = widelyLit(w, 40, {cx, 0, cz});
            for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
                const auto l = lit(w, {cx, cy, cz});
                EXPECT_TRUE(equal(*l, *paddedFrom(*wide, {cx, cy, cz})))
                    << "column " << cx << ", " << cz << " y " << cy;
                for (const std::uint16_t v : l->level) lampLit += world::LightLevel{v}.block() > 0;
            }
            ++columns;
        }
    }
    // Precondition: the lamps light the region's columns (measured: see the printed count).
    std::printf("columns %d, voxels lit by lamps %d\n", columns, lampLit);
    EXPECT_GT(lampLit, 200);
}

// Every column's light box holds the column and kLightBorder around it, on both sides of the origin, and
// columns share a box exactly when they share a region. Mutation caught: regions by truncating division (columns
// -1 and 0 in one region, whose box then misses column -1's far side).
TEST(ColumnLight, EveryColumnLiesInItsRegionsBoxWithItsBorder) {
    for (int cz = -5; cz <= 5; ++cz) {
        for (int cx = -5; cx <= 5; ++cx) {
            const world::LightBox box = world::lightBoxOf({cx, 3, cz});
            const glm::ivec3 low =
                world::chunkOrigin({cx, 0, cz}) - glm::ivec3(world::kLightBorder, 0, world::kLightBorder);
            const glm::ivec3 high =
                low + glm::ivec3(world::kChunkSize + 2 * world::kLightBorder - 1, world::kWorldHeight - 1,
                                 world::kChunkSize + 2 * world::kLightBorder - 1);
            EXPECT_TRUE(box.contains(low) && box.contains(high)) << "column " << cx << ", " << cz;
            const world::LightBox right = world::lightBoxOf({cx + 1, 0, cz});
            const bool sameRegion = world::lightRegionOf({cx, 0, cz}) == world::lightRegionOf({cx + 1, 0, cz});
            EXPECT_EQ(sameRegion, right.origin == box.origin) << "column " << cx << ", " << cz;
        }
    }
}

// An edit changes the light of at most the 2 x 2 light regions around it (light reaches 14 blocks, a region is
// 64 wide), and a thread keeps 4 regions (column_light.cpp), so a thread that meshes every chunk an edit bumps
// repairs its kept regions and relights none. A lamp one block inside the corner of four regions, the surface
// chunks of the 4 x 4 columns around it: first lit with no edit (four relights), then with the lamp (four repairs,
// no relight), each equal to the light of a fresh thread. Mutation caught: three regions kept (relights).
TEST(ColumnLight, AnEditAtFourRegionsCornerRepairsEachKeptRegion) {
    const int corner = world::kLightRegion * world::kChunkSize; // x and z where regions 0 and 1 meet
    const int ground = world::surfaceHeight(kTerrain, corner, corner);
    const std::vector<BlockEdit> none, lamp{{{corner, ground + 1, corner}, BlockType::Lamp}};
    std::vector<ChunkCoord> chunks;
    for (int cz = 0; cz < 2 * world::kLightRegion; ++cz)
        for (int cx = 0; cx < 2 * world::kLightRegion; ++cx)
            chunks.push_back(world::chunkOf({cx * 32, ground, cz * 32}));
    ASSERT_EQ(world::lightRegionOf(chunks.front()).x, 0); // precondition: the chunks span regions 0 and 1 each way
    ASSERT_EQ(world::lightRegionOf(chunks.back()).x, 1);
    std::vector<std::unique_ptr<PaddedLight>> repaired;
    std::thread([&] {
        world::clearColumnLight();
        for (const ChunkCoord c : chunks) world::lightPadded(kTerrain, c, none, *std::make_unique<PaddedLight>());
        const world::ColumnLightStats before = world::columnLightStats();
        EXPECT_EQ(before.relit, 4);
        for (const ChunkCoord c : chunks) {
            repaired.push_back(std::make_unique<PaddedLight>());
            world::lightPadded(kTerrain, c, lamp, *repaired.back());
        }
        const world::ColumnLightStats after = world::columnLightStats();
        EXPECT_EQ(after.relit - before.relit, 0);
        EXPECT_EQ(after.repaired - before.repaired, 4);
    }).join();
    std::thread([&] {
        for (std::size_t k = 0; k < chunks.size(); ++k) {
            world::clearColumnLight();
            PaddedLight fresh;
            world::lightPadded(kTerrain, chunks[k], lamp, fresh);
            EXPECT_TRUE(equal(fresh, *repaired[k])) << "chunk " << k;
        }
    }).join();
    // Precondition: the lamp's light does reach a chunk of each region.
    int lampLit = 0;
    for (const auto& r : repaired)
        lampLit += std::any_of(r->level.begin(), r->level.end(),
                               [](std::uint16_t l) { return world::LightLevel{l}.block() > 0; });
    EXPECT_GE(lampLit, 4);
}

// A kept column asked for fewer edits than it was lit with (another world of the same terrain, on the same thread)
// puts the terrain's blocks back where the edits went: equal to a column lit from scratch. Mutation caught: edits
// gone left as they were (repair() skipping them).
TEST(ColumnLight, EditsGoneFromAKeptColumnGiveTheTerrainBack) {
    world::World w(kTerrain);
    std::mt19937 rng(21);
    editAtRandom(w, rng, 30);
    std::vector<BlockEdit> all;
    w.editsAround({0, 0, 0}, all);
    ASSERT_GT(all.size(), 10u); // precondition: edits to take away
    const std::vector<BlockEdit> half(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2));
    int changedChunks = 0;
    for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
        const ChunkCoord c{0, cy, 0};
        auto repaired = std::make_unique<PaddedLight>(), fresh = std::make_unique<PaddedLight>();
        world::clearColumnLight();
        world::lightPadded(w.terrain(), c, all, *repaired);
        world::lightPadded(w.terrain(), c, half, *repaired);
        EXPECT_EQ(world::columnLightStats().repaired, 1) << cy; // precondition: the kept column was repaired
        world::clearColumnLight();
        world::lightPadded(w.terrain(), c, half, *fresh);
        EXPECT_TRUE(equal(*repaired, *fresh)) << cy;
        changedChunks += !equal(*lit(w, c), *fresh); // what the edits taken away changed here
    }
    EXPECT_GT(changedChunks, 0); // precondition: the edits taken away changed the light somewhere
}

// The mesh worker cuts a chunk's blocks out of its column's light box with its light (gatherAndLight): the same
// bytes and solid rows as generating the padded chunk from the terrain and the edits, and the same light, for every
// chunk of a column, the world's bottom (stone below) and top (air above) included. Mutation caught: the layer
// under the world filled with air.
TEST(ColumnLight, BlocksCutFromTheLightBoxAreTheTerrainsAndTheEdits) {
    world::World w(kTerrain);
    std::mt19937 rng(3);
    editAtRandom(w, rng, 40);
    auto cut = std::make_unique<world::PaddedChunk>(), generated = std::make_unique<world::PaddedChunk>();
    for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
        const ChunkCoord c{0, cy, 0};
        std::vector<BlockEdit> edits;
        w.editsAround(c, edits);
        ASSERT_FALSE(edits.empty()); // precondition: edits in the box
        world::gatherAndLight(w.terrain(), c, edits, *cut);
        world::gatherPaddedFromTerrain(w.terrain(), c, edits, *generated);
        world::lightPadded(w.terrain(), c, edits, generated->light);
        ASSERT_FALSE(cut->blocks.stale);
        EXPECT_EQ(std::memcmp(cut->blocks.data(), generated->blocks.data(), world::PaddedChunk::kVolume), 0) << cy;
        EXPECT_EQ(std::memcmp(cut->solid, generated->solid, sizeof cut->solid), 0) << cy;
        EXPECT_TRUE(equal(cut->light, generated->light)) << cy;
    }
}

// Meshes from the worker thread, in two different orders, with its kept columns cold and then warm (repaired
// after edits), equal meshes built on this thread with nothing kept.
TEST(ColumnLight, MeshesAreEqualWhicheverThreadAndOrderLightsThem) {
    world::World w(kTerrain);
    std::mt19937 rng(5);
    editAtRandom(w, rng, 20);
    std::vector<world::MeshJob> jobs;
    const auto makeJobs = [&] {
        jobs.clear();
        for (int cz = -1; cz <= 1; ++cz)
            for (int cx = -1; cx <= 1; ++cx)
                for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
                    world::MeshJob j;
                    j.coord = {cx, cy, cz};
                    j.revision = w.chunkRevision(j.coord);
                    w.editsAround(j.coord, j.edits);
                    jobs.push_back(std::move(j));
                }
    };
    const auto reference = [&](const world::MeshJob& job) {
        world::MeshResult r;
        std::thread([&] { r = world::MeshWorker::run(w.terrain(), job); }).join(); // a thread with nothing kept
        return r.mesh;
    };
    world::MeshWorker worker(w.terrain());
    for (int pass = 0; pass < 2; ++pass) {
        makeJobs();
        std::map<std::tuple<int, int, int>, world::ChunkMesh> expected;
        for (const world::MeshJob& j : jobs) expected[{j.coord.x, j.coord.y, j.coord.z}] = reference(j);
        if (pass == 1) std::reverse(jobs.begin(), jobs.end());
        worker.submit(jobs);
        worker.waitIdle();
        std::vector<world::MeshResult> results = worker.takeResults();
        ASSERT_EQ(results.size(), jobs.size());
        int shadedVertices = 0;
        for (const world::MeshResult& r : results) {
            const world::ChunkMesh& want = expected.at({r.job.coord.x, r.job.coord.y, r.job.coord.z});
            ASSERT_EQ(r.mesh.vertices.size(), want.vertices.size());
            // Byte for byte (an empty mesh's data() may be null: nothing to compare).
            EXPECT_TRUE(want.vertices.empty() || std::memcmp(r.mesh.vertices.data(), want.vertices.data(),
                                                             want.vertices.size() * sizeof(world::ChunkVertex)) == 0);
            for (const world::ChunkVertex& v : r.mesh.vertices)
                shadedVertices += world::sunlightOf(v) < world::kMaxLight;
        }
        EXPECT_GT(shadedVertices, 100); // precondition: light that a mesh without it would miss
        editAtRandom(w, rng, 10);       // the worker's kept columns are repaired in the next pass
    }
}

// Every chunk whose mesh input (padded blocks or padded light) changes with an edit gets a new revision, checked
// against the blocks and light themselves before and after each edit. Edits stay in column (0, 0), so only
// columns -1..1 can change (light reaches 14 blocks sideways; column 2 begins 32 blocks away). Mutation caught:
// the one-voxel reach of the mesh before light (World.RevisionsOfEditedAndBorderingChunks holds the exact reach).
TEST(ColumnLight, AnEditBumpsEveryChunkWhoseMeshChanges) {
    world::World w(kTerrain);
    std::mt19937 rng(11);
    using Key = std::tuple<int, int, int>;
    const auto snapshot = [&] {
        std::map<Key, std::pair<std::vector<std::uint8_t>, std::uint64_t>> out;
        auto padded = std::make_unique<world::PaddedChunk>();
        for (int cz = -1; cz <= 1; ++cz)
            for (int cx = -1; cx <= 1; ++cx)
                for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) {
                    const ChunkCoord c{cx, cy, cz};
                    std::vector<BlockEdit> edits;
                    w.editsAround(c, edits);
                    world::gatherPaddedFromTerrain(w.terrain(), c, edits, *padded);
                    world::lightPadded(w.terrain(), c, edits, padded->light);
                    constexpr std::size_t kLightBytes = sizeof(padded->light.level); // every channel's word
                    std::vector<std::uint8_t> bytes(world::PaddedChunk::kVolume + kLightBytes);
                    std::memcpy(bytes.data(), padded->blocks.data(), world::PaddedChunk::kVolume);
                    std::memcpy(bytes.data() + world::PaddedChunk::kVolume, padded->light.level.data(), kLightBytes);
                    out[{cx, cy, cz}] = {std::move(bytes), w.chunkRevision(c)};
                }
        return out;
    };
    std::uniform_int_distribution<int> xz(0, 31), dy(-5, 3), kind(0, 4);
    int changedChunks = 0, bumped = 0, changedByLight = 0, greenLamps = 0;
    auto before = snapshot();
    for (int i = 0; i < 24; ++i) {
        const int x = xz(rng), z = xz(rng);
        const BlockType types[] = {BlockType::Lamp, BlockType::Stone, BlockType::Air, BlockType::Leaves,
                                   BlockType::GreenLamp};
        const glm::ivec3 at(x, world::surfaceHeight(w.terrain(), x, z) + dy(rng), z);
        const BlockType t = types[kind(rng)];
        greenLamps += t == BlockType::GreenLamp;
        w.set(at, t);
        auto after = snapshot();
        for (const auto& [key, now] : after) {
            const auto& was = before.at(key);
            const bool changed = now.first != was.first, newRevision = now.second != was.second;
            changedChunks += changed;
            bumped += newRevision;
            // A chunk whose padded box does not hold the edit changed through its light alone.
            const glm::ivec3 low = world::chunkOrigin({std::get<0>(key), std::get<1>(key), std::get<2>(key)}) - 1;
            const glm::ivec3 d = at - low;
            const bool holds = d.x >= 0 && d.y >= 0 && d.z >= 0 && d.x < world::PaddedChunk::kSize &&
                               d.y < world::PaddedChunk::kSize && d.z < world::PaddedChunk::kSize;
            changedByLight += changed && !holds;
            EXPECT_TRUE(!changed || newRevision) << "edit " << i << ": chunk " << std::get<0>(key) << ","
                                                 << std::get<1>(key) << "," << std::get<2>(key) << " changed";
        }
        before = std::move(after);
    }
    // Precondition: chunks that changed through light alone, which the one-voxel rule before light would miss.
    EXPECT_GT(changedByLight, 0);
    EXPECT_GT(greenLamps, 0);   // precondition: a coloured lamp among the edits
    EXPECT_LE(bumped, 24 * 16); // at most four columns of four chunks an edit
    std::printf("chunks changed %d (through light alone %d), bumped %d, over 24 edits\n", changedChunks, changedByLight,
                bumped);
}

} // namespace

// --frame-stats' light figures (world::lightCost): while counting is off nothing is counted; then every chunk of two
// columns of one region asked for counts two columns, one region, one relight and the CPU of it; an edit counts one
// repair and no new column; the light on an object in a region this thread does not keep counts a relight for
// objects. Process-wide and cumulative, so the test reads differences, from a thread whose kept regions are cleared.
// Mutations caught: counting chunks instead of columns (8 columns), counting while off, a relight for objects
// counted as the meshes'.
TEST(ColumnLight, TheLightCostCountsColumnsRelightsAndRepairsOnce) {
    world::clearColumnLight();
    const world::TerrainDef def{1234}; // a terrain no other test of this process lights
    PaddedLight out;
    std::vector<BlockEdit> edits;
    world::countLightCost(false);
    const world::LightCost off = world::lightCost();
    world::lightPadded(def, {4, 0, 4}, edits, out);
    const world::LightCost stillOff = world::lightCost();
    EXPECT_EQ(stillOff.relit, off.relit);
    EXPECT_EQ(stillOff.columns, off.columns);
    EXPECT_EQ(stillOff.cpuSeconds, off.cpuSeconds);

    world::countLightCost(true);
    world::clearColumnLight();
    const world::LightCost before = world::lightCost();
    for (int cx = 0; cx < 2; ++cx) {
        for (int cy = 0; cy < world::kWorldHeightChunks; ++cy) world::lightPadded(def, {cx, cy, 0}, edits, out);
    }
    ASSERT_EQ(world::lightRegionOf({0, 0, 0}), world::lightRegionOf({1, 0, 0})); // precondition: one region
    const world::LightCost lit = world::lightCost();
    EXPECT_EQ(lit.columns - before.columns, 2);
    EXPECT_EQ(lit.regions - before.regions, 1);
    EXPECT_EQ(lit.relit - before.relit, 1);
    EXPECT_EQ(lit.repaired - before.repaired, 0);
    EXPECT_GT(lit.cpuSeconds, before.cpuSeconds);
    edits.push_back({{5, 70, 5}, BlockType::Lamp});
    world::lightPadded(def, {0, 2, 0}, edits, out);
    const world::LightCost edited = world::lightCost();
    EXPECT_EQ(edited.columns, lit.columns);
    EXPECT_EQ(edited.regions, lit.regions);
    EXPECT_EQ(edited.relit, lit.relit);
    EXPECT_EQ(edited.repaired - lit.repaired, 1);
    EXPECT_GT(edited.cpuSeconds, lit.cpuSeconds);

    const world::World w(def);
    world::lightAt(w, {300, 70, 300}); // a region this thread has not lit
    const world::LightCost objects = world::lightCost();
    EXPECT_EQ(objects.relit - edited.relit, 1);
    EXPECT_EQ(objects.relitForObjects - edited.relitForObjects, 1);
    EXPECT_EQ(objects.columns, edited.columns); // the light on objects meshes no column
    world::countLightCost(false);
}
