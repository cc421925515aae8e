#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "core/rng.h"
#include "world/column_light.h"
#include "world/culling_data.h"
#include "world/level_of_detail.h"
#include "world/light_level.h"
#include "world/mesher.h"
#include "world/plane_order.h"
#include "world/terrain.h"
#include "world/world.h"

namespace {

using world::BlockType;
using world::ChunkMesh;
using world::ChunkVertex;
using world::MeshMode;
using world::PaddedChunk;

constexpr int kN = world::kChunkSize;

std::unique_ptr<PaddedChunk> emptyPadded() { return std::make_unique<PaddedChunk>(); }

// Sets a block by chunk-local coordinates (-1..32, the border included).
void put(PaddedChunk& p, int x, int y, int z, BlockType t) { p.set(x + 1, y + 1, z + 1, t); }

ChunkMesh mesh(const PaddedChunk& p, MeshMode mode) {
    ChunkMesh m;
    world::meshChunk(p, m, mode);
    EXPECT_EQ(m.vertices.size() % 4, 0u);
    return m;
}

glm::ivec3 pos(const ChunkVertex& v) { return {world::xOf(v), world::yOf(v), world::zOf(v)}; }
glm::ivec3 normalOf(int face) {
    return {world::kFaceNormals[face][0], world::kFaceNormals[face][1], world::kFaceNormals[face][2]};
}
int normalAxis(int face) { return face / 2; }

// One unit face: direction and the chunk-local solid block it belongs to.
using FaceKey = std::tuple<int, int, int, int>;
struct UnitFace {
    int tile;
    std::map<std::tuple<int, int, int>, int> cornerAo;    // corner position -> ao
    std::map<std::tuple<int, int, int>, int> cornerLight; // corner position -> lightWordOf()
};

// A vertex's smooth light as one number: its light word.
int lightWordOf(const ChunkVertex& v) { return world::lightOf(v).bits; }

struct Rect {
    int face;
    glm::ivec3 lo, hi; // corner extents; equal on the normal axis
    int tile;
    std::array<int, 4> ao;
};

Rect rectOf(const ChunkVertex* q) {
    Rect r{world::faceOf(q[0]),
           pos(q[0]),
           pos(q[0]),
           q[0].tile,
           {world::aoOf(q[0]), world::aoOf(q[1]), world::aoOf(q[2]), world::aoOf(q[3])}};
    for (int k = 1; k < 4; ++k) {
        EXPECT_EQ(world::faceOf(q[k]), r.face);
        EXPECT_EQ(q[k].tile, q[0].tile);
        r.lo = glm::min(r.lo, pos(q[k]));
        r.hi = glm::max(r.hi, pos(q[k]));
    }
    return r;
}

// The unit faces a quad covers, each with the block it belongs to.
template <typename F>
void forEachUnitFace(const Rect& r, F&& f) {
    const int a = normalAxis(r.face);
    const bool positive = r.face % 2 == 0;
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (int i = r.lo[u]; i < r.hi[u]; ++i) {
        for (int j = r.lo[v]; j < r.hi[v]; ++j) {
            glm::ivec3 block;
            block[a] = r.lo[a] - (positive ? 1 : 0);
            block[u] = i;
            block[v] = j;
            f(block);
        }
    }
}

std::map<FaceKey, UnitFace> unitFacesOfCulled(const ChunkMesh& m) {
    std::map<FaceKey, UnitFace> out;
    for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
        const ChunkVertex* q = &m.vertices[i];
        const Rect r = rectOf(q);
        int count = 0;
        forEachUnitFace(r, [&](glm::ivec3 b) {
            ++count;
            UnitFace uf{r.tile, {}, {}};
            for (int k = 0; k < 4; ++k) {
                uf.cornerAo[{world::xOf(q[k]), world::yOf(q[k]), world::zOf(q[k])}] = world::aoOf(q[k]);
                uf.cornerLight[{world::xOf(q[k]), world::yOf(q[k]), world::zOf(q[k])}] = lightWordOf(q[k]);
            }
            EXPECT_TRUE(out.emplace(FaceKey{r.face, b.x, b.y, b.z}, uf).second) << "face emitted twice";
        });
        EXPECT_EQ(count, 1);
    }
    return out;
}

// The unit faces a merged mesh covers, checked against the culled mesh's (`reference`).
struct Coverage {
    std::map<FaceKey, UnitFace> reference;
    std::map<FaceKey, int> covered;

    // Counts unit face `b` of quad `q` (rect `r`) and expects it in the reference with the same tile; a quad of one
    // face (`single`) must carry that face's own corner occlusion and light. A merged quad must have one light at
    // every corner, the light of every corner of the faces it covers. Returns the reference face for a merged
    // quad's own shading checks; null for a single face, or when the face is missing (a failure naming `what`).
    const UnitFace* visit(const Rect& r, const ChunkVertex* q, glm::ivec3 b, bool single, const char* what) {
        const FaceKey key{r.face, b.x, b.y, b.z};
        ++covered[key];
        const auto it = reference.find(key);
        if (it == reference.end()) {
            ADD_FAILURE() << what << " face not in culled mesh";
            return nullptr;
        }
        EXPECT_EQ(it->second.tile, r.tile);
        if (!single) {
            for (int k = 1; k < 4; ++k)
                EXPECT_EQ(lightWordOf(q[k]), lightWordOf(q[0])) << "merged quad with uneven light";
            for (const auto& [corner, light] : it->second.cornerLight) EXPECT_EQ(light, lightWordOf(q[0]));
            return &it->second;
        }
        for (int k = 0; k < 4; ++k) {
            EXPECT_EQ(it->second.cornerAo.at({world::xOf(q[k]), world::yOf(q[k]), world::zOf(q[k])}),
                      world::aoOf(q[k]));
            EXPECT_EQ(it->second.cornerLight.at({world::xOf(q[k]), world::yOf(q[k]), world::zOf(q[k])}),
                      lightWordOf(q[k]));
        }
        return nullptr;
    }

    // Expects every reference face covered, each exactly once.
    void expectEachCoveredOnce() const {
        EXPECT_EQ(covered.size(), reference.size());
        for (const auto& [key, n] : covered) EXPECT_EQ(n, 1) << "unit face covered twice";
    }
};

// Greedy and culled meshes must cover exactly the same unit faces with the same tiles, and shade
// them alike: a merged quad has four equal occlusion values matching every face it replaces.
void expectSameCoverage(const PaddedChunk& p) {
    const ChunkMesh culled = mesh(p, MeshMode::Culled);
    const ChunkMesh greedy = mesh(p, MeshMode::Greedy);
    Coverage coverage{unitFacesOfCulled(culled), {}};
    for (std::size_t i = 0; i < greedy.vertices.size(); i += 4) {
        const ChunkVertex* q = &greedy.vertices[i];
        const Rect r = rectOf(q);
        int count = 0;
        forEachUnitFace(r, [&](glm::ivec3) { ++count; });
        ASSERT_GE(count, 1);
        forEachUnitFace(r, [&](glm::ivec3 b) {
            const UnitFace* face = coverage.visit(r, q, b, count == 1, "greedy");
            if (!face) return;
            for (int k = 1; k < 4; ++k)
                EXPECT_EQ(world::aoOf(q[k]), world::aoOf(q[0])) << "merged quad, uneven occlusion";
            for (const auto& [corner, ao] : face->cornerAo) EXPECT_EQ(ao, world::aoOf(q[0]));
        });
    }
    coverage.expectEachCoveredOnce();
    EXPECT_LE(greedy.quadCount(), culled.quadCount());
}

// Properties of every quad: counter-clockwise from outside, AO diagonal rule, texture coordinates.
void expectWellFormed(const ChunkMesh& m) {
    for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
        const ChunkVertex* q = &m.vertices[i];
        const int face = world::faceOf(q[0]);
        ASSERT_LT(face, 6);
        const glm::ivec3 e1 = pos(q[1]) - pos(q[0]), e2 = pos(q[2]) - pos(q[0]);
        const glm::ivec3 cross(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
        const glm::ivec3 n = normalOf(face);
        EXPECT_GT(cross.x * n.x + cross.y * n.y + cross.z * n.z, 0) << "face " << face;
        EXPECT_EQ(cross.x * n.x + cross.y * n.y + cross.z * n.z,
                  std::abs(cross.x) + std::abs(cross.y) + std::abs(cross.z));
        // Second triangle too.
        const glm::ivec3 f1 = pos(q[2]) - pos(q[0]), f2 = pos(q[3]) - pos(q[0]);
        const glm::ivec3 cross2(f1.y * f2.z - f1.z * f2.y, f1.z * f2.x - f1.x * f2.z, f1.x * f2.y - f1.y * f2.x);
        EXPECT_GT(cross2.x * n.x + cross2.y * n.y + cross2.z * n.z, 0);
        EXPECT_GE(world::aoOf(q[0]) + world::aoOf(q[2]), world::aoOf(q[1]) + world::aoOf(q[3]));
        for (int k = 0; k < 4; ++k) {
            EXPECT_EQ(world::faceOf(q[k]), face);
            EXPECT_LE(world::xOf(q[k]), kN);
            EXPECT_LE(world::yOf(q[k]), kN);
            EXPECT_LE(world::zOf(q[k]), kN);
        }
        const Rect r = rectOf(q);
        for (int k = 0; k < 4; ++k) {
            const ChunkVertex& v = q[k];
            if (normalAxis(face) == 1) { // top and bottom: u along x, v along z
                EXPECT_EQ(world::uOf(v), world::xOf(v) - r.lo.x);
                EXPECT_EQ(world::vOf(v), world::zOf(v) - r.lo.z);
            } else { // sides: v = 0 on the top edge, growing downward; u spans the horizontal extent
                EXPECT_EQ(world::vOf(v), r.hi.y - world::yOf(v));
                const int h = normalAxis(face) == 0 ? 2 : 0; // horizontal axis in the face
                const int width = r.hi[h] - r.lo[h];
                EXPECT_TRUE(world::uOf(v) == pos(v)[h] - r.lo[h] || world::uOf(v) == r.hi[h] - pos(v)[h]);
                EXPECT_LE(world::uOf(v), width);
            }
        }
    }
}

TEST(Mesher, EmptyChunkHasNoQuads) {
    auto p = emptyPadded();
    EXPECT_EQ(mesh(*p, MeshMode::Greedy).quadCount(), 0u);
    EXPECT_EQ(mesh(*p, MeshMode::Culled).quadCount(), 0u);
    // Solid border only: the faces belong to the neighbours.
    for (int y = 0; y < PaddedChunk::kSize; ++y)
        for (int z = 0; z < PaddedChunk::kSize; ++z)
            for (int x = 0; x < PaddedChunk::kSize; ++x)
                if (x == 0 || y == 0 || z == 0 || x == 33 || y == 33 || z == 33) p->set(x, y, z, BlockType::Stone);
    EXPECT_EQ(mesh(*p, MeshMode::Greedy).quadCount(), 0u);
    EXPECT_EQ(mesh(*p, MeshMode::Culled).quadCount(), 0u);
}

TEST(Mesher, SingleBlockHasSixQuads) {
    for (const glm::ivec3 at :
         {glm::ivec3(10, 10, 10), glm::ivec3(0, 0, 0), glm::ivec3(31, 31, 31), glm::ivec3(0, 31, 5)}) {
        auto p = emptyPadded();
        put(*p, at.x, at.y, at.z, BlockType::Grass);
        for (const MeshMode mode : {MeshMode::Greedy, MeshMode::Culled}) {
            const ChunkMesh m = mesh(*p, mode);
            ASSERT_EQ(m.quadCount(), 6u);
            expectWellFormed(m);
            std::array<int, 6> perFace{};
            for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
                const ChunkVertex& v = m.vertices[i];
                ++perFace[v.face];
                const int expectedTile = v.face == world::kFacePosY ? 0 : v.face == world::kFaceNegY ? 2 : 1;
                EXPECT_EQ(v.tile, expectedTile);
                for (int k = 0; k < 4; ++k) EXPECT_EQ(m.vertices[i + static_cast<std::size_t>(k)].ao, 3);
            }
            for (const int n : perFace) EXPECT_EQ(n, 1);
        }
    }
}

TEST(Mesher, BarMergesGreedily) {
    auto p = emptyPadded();
    put(*p, 4, 7, 9, BlockType::Stone);
    put(*p, 5, 7, 9, BlockType::Stone);
    EXPECT_EQ(mesh(*p, MeshMode::Greedy).quadCount(), 6u);
    EXPECT_EQ(mesh(*p, MeshMode::Culled).quadCount(), 10u);
    expectSameCoverage(*p);
    // Different tiles do not merge: a stone and a dirt block side by side.
    put(*p, 5, 7, 9, BlockType::Dirt);
    EXPECT_EQ(mesh(*p, MeshMode::Greedy).quadCount(), 10u);
    expectSameCoverage(*p);
}

TEST(Mesher, TallColumnTextureRunsDownward) {
    auto p = emptyPadded();
    for (int y = 3; y < 6; ++y) put(*p, 8, y, 8, BlockType::Brick);
    const ChunkMesh m = mesh(*p, MeshMode::Greedy);
    ASSERT_EQ(m.quadCount(), 6u);
    expectWellFormed(m);
    for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
        if (normalAxis(m.vertices[i].face) == 1) continue;
        for (int k = 0; k < 4; ++k) {
            const ChunkVertex& v = m.vertices[i + static_cast<std::size_t>(k)];
            EXPECT_EQ(world::vOf(v), world::yOf(v) == 6 ? 0 : 3);
        }
    }
}

TEST(Mesher, FullChunk) {
    auto p = emptyPadded();
    for (int y = 0; y < kN; ++y)
        for (int z = 0; z < kN; ++z)
            for (int x = 0; x < kN; ++x) put(*p, x, y, z, BlockType::Stone);
    const ChunkMesh greedy = mesh(*p, MeshMode::Greedy);
    EXPECT_EQ(greedy.quadCount(), 6u);
    EXPECT_EQ(mesh(*p, MeshMode::Culled).quadCount(), 6u * kN * kN);
    expectWellFormed(greedy);
    for (std::size_t i = 0; i < greedy.vertices.size(); i += 4) {
        const Rect r = rectOf(&greedy.vertices[i]);
        const int a = normalAxis(r.face);
        EXPECT_EQ(r.lo[a], r.face % 2 == 0 ? kN : 0);
        for (int axis = 0; axis < 3; ++axis) {
            if (axis != a) {
                EXPECT_EQ(r.hi[axis] - r.lo[axis], kN);
            }
        }
    }
    expectSameCoverage(*p);
}

TEST(Mesher, NoFacesAgainstSolidNeighbours) {
    auto p = emptyPadded();
    for (int y = 0; y < kN; ++y)
        for (int z = 0; z < kN; ++z)
            for (int x = 0; x < kN; ++x) put(*p, x, y, z, BlockType::Dirt);
    // Solid neighbour on -X and +Y only: those two sides have no faces. The slabs stop short of the
    // edges so that the other sides stay fully lit and merge into one quad each.
    for (int y = 0; y < kN; ++y)
        for (int z = 0; z < kN; ++z) put(*p, -1, y, z, BlockType::Stone);
    for (int z = 0; z < kN; ++z)
        for (int x = 0; x < kN; ++x) put(*p, x, kN, z, BlockType::Stone);
    for (const MeshMode mode : {MeshMode::Greedy, MeshMode::Culled}) {
        const ChunkMesh m = mesh(*p, mode);
        for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
            EXPECT_NE(m.vertices[i].face, world::kFaceNegX);
            EXPECT_NE(m.vertices[i].face, world::kFacePosY);
        }
        EXPECT_EQ(m.quadCount(), mode == MeshMode::Culled ? 4u * kN * kN : 4u);
    }
    expectSameCoverage(*p);
}

TEST(Mesher, CheckerboardWorstCase) {
    auto p = emptyPadded();
    for (int y = 0; y < kN; ++y)
        for (int z = 0; z < kN; ++z)
            for (int x = 0; x < kN; ++x)
                if ((x + y + z) % 2 == 0) put(*p, x, y, z, BlockType::Cobblestone);
    const ChunkMesh greedy = mesh(*p, MeshMode::Greedy), culled = mesh(*p, MeshMode::Culled);
    EXPECT_EQ(culled.quadCount(), 6u * 16384u);
    EXPECT_EQ(greedy.quadCount(), 6u * 16384u);
    expectWellFormed(greedy);
    expectSameCoverage(*p);
}

// An L of two blocks standing around one corner of a floor block's top face.
TEST(Mesher, AmbientOcclusionOnLCorner) {
    auto p = emptyPadded();
    put(*p, 4, 4, 4, BlockType::Planks); // floor block
    put(*p, 5, 5, 4, BlockType::Planks); // +x of the space above it
    put(*p, 4, 5, 5, BlockType::Planks); // +z of the space above it
    for (const MeshMode mode : {MeshMode::Greedy, MeshMode::Culled}) {
        const ChunkMesh m = mesh(*p, mode);
        expectWellFormed(m);
        bool foundTop = false, foundSide = false;
        for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
            const ChunkVertex* q = &m.vertices[i];
            const Rect r = rectOf(q);
            if (r.face == world::kFacePosY && r.lo == glm::ivec3(4, 5, 4) && r.hi == glm::ivec3(5, 5, 5)) {
                foundTop = true;
                std::map<std::pair<int, int>, int> ao;
                for (int k = 0; k < 4; ++k) ao[{world::xOf(q[k]), world::zOf(q[k])}] = q[k].ao;
                EXPECT_EQ(ao.at({5, 5}), 0); // both sides solid
                EXPECT_EQ(ao.at({5, 4}), 2); // one side
                EXPECT_EQ(ao.at({4, 5}), 2);
                EXPECT_EQ(ao.at({4, 4}), 3); // open
                // The split diagonal joins the two equal corners, so the dark corner stays in one triangle.
                EXPECT_EQ(q[0].ao, 2);
                EXPECT_EQ(q[2].ao, 2);
            }
            // The floor block's +X face has the L's +x block right above its air side.
            if (r.face == world::kFacePosX && r.lo == glm::ivec3(5, 4, 4) && r.hi == glm::ivec3(5, 5, 5)) {
                foundSide = true;
                for (int k = 0; k < 4; ++k) EXPECT_EQ(q[k].ao, world::yOf(q[k]) == 5 ? 2 : 3);
            }
        }
        EXPECT_TRUE(foundTop);
        EXPECT_TRUE(foundSide);
    }
}

TEST(Mesher, UniformOcclusionStillMerges) {
    // A trench one block wide: the floor faces all have occlusion 1 on every corner and merge.
    auto p = emptyPadded();
    for (int z = 0; z < 10; ++z) put(*p, 5, 0, z, BlockType::Stone);
    for (int z = -1; z <= 10; ++z) { // the walls run one past each end, so the end faces are alike
        put(*p, 4, 1, z, BlockType::Stone);
        put(*p, 6, 1, z, BlockType::Stone);
    }
    const ChunkMesh m = mesh(*p, MeshMode::Greedy);
    int floorQuads = 0;
    for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
        const Rect r = rectOf(&m.vertices[i]);
        if (r.face == world::kFacePosY && r.lo.y == 1) {
            ++floorQuads;
            EXPECT_EQ(r.hi.z - r.lo.z, 10);
            for (int k = 0; k < 4; ++k) EXPECT_EQ(m.vertices[i + static_cast<std::size_t>(k)].ao, 1);
        }
    }
    EXPECT_EQ(floorQuads, 1);
    expectSameCoverage(*p);
}

TEST(Mesher, WindingForEveryDirectionOnRandomChunks) {
    core::Rng rng(7);
    auto p = emptyPadded();
    for (auto& b : p->blocks) b = rng.below(3) == 0 ? static_cast<BlockType>(1 + rng.below(11)) : BlockType::Air;
    for (const MeshMode mode : {MeshMode::Greedy, MeshMode::Culled}) {
        const ChunkMesh m = mesh(*p, mode);
        std::array<int, 6> perFace{};
        for (std::size_t i = 0; i < m.vertices.size(); i += 4) ++perFace[world::faceOf(m.vertices[i])];
        for (const int n : perFace) EXPECT_GT(n, 0);
        expectWellFormed(m);
    }
}

TEST(Mesher, GreedyCoversCulledOnRandomChunks) {
    core::Rng rng(2024);
    for (int round = 0; round < 8; ++round) {
        auto p = emptyPadded();
        const int types = 1 + static_cast<int>(rng.below(3));
        const std::uint32_t density = 2 + rng.below(6); // 1 in density is solid, or its complement
        const bool dense = rng.below(2) == 0;
        for (auto& b : p->blocks) {
            const bool solid = (rng.below(density) == 0) != dense;
            b = solid ? static_cast<BlockType>(1 + rng.below(static_cast<std::uint32_t>(types))) : BlockType::Air;
        }
        expectSameCoverage(*p);
        expectWellFormed(mesh(*p, MeshMode::Greedy));
    }
}

TEST(Mesher, GreedyCoversCulledOnTerrain) {
    const world::TerrainDef def{1};
    for (const world::ChunkCoord coord :
         {world::ChunkCoord{0, 1, 0}, world::ChunkCoord{5, 2, -7}, world::ChunkCoord{-3, 1, 2}}) {
        auto p = emptyPadded();
        std::vector<BlockType> box(PaddedChunk::kVolume);
        world::generateBox(def, world::chunkOrigin(coord) - glm::ivec3(1), glm::ivec3(PaddedChunk::kSize), box.data());
        std::copy(box.begin(), box.end(), p->blocks.begin());
        expectSameCoverage(*p);
        const ChunkMesh greedy = mesh(*p, MeshMode::Greedy);
        expectWellFormed(greedy);
    }
}

// The distant level of detail: the same faces and tiles as the culled mesh, every corner fully lit, and
// never more quads than the occlusion-aware greedy mesh (faces merge by tile alone).
TEST(Mesher, GreedyFlatCoversCulledWithFewerQuads) {
    const world::TerrainDef def{1};
    for (const world::ChunkCoord coord : {world::ChunkCoord{0, 1, 0}, world::ChunkCoord{5, 2, -7}}) {
        auto p = emptyPadded();
        std::vector<BlockType> box(PaddedChunk::kVolume);
        world::generateBox(def, world::chunkOrigin(coord) - glm::ivec3(1), glm::ivec3(PaddedChunk::kSize), box.data());
        std::copy(box.begin(), box.end(), p->blocks.begin());
        const ChunkMesh culled = mesh(*p, MeshMode::Culled);
        const ChunkMesh unlit = mesh(*p, MeshMode::GreedyFlat);
        const auto reference = unitFacesOfCulled(culled);
        std::map<FaceKey, int> covered;
        for (std::size_t i = 0; i < unlit.vertices.size(); i += 4) {
            const ChunkVertex* q = &unlit.vertices[i];
            for (int k = 0; k < 4; ++k) ASSERT_EQ(q[k].ao, 3);
            const Rect r = rectOf(q);
            forEachUnitFace(r, [&](glm::ivec3 b) {
                const FaceKey key{r.face, b.x, b.y, b.z};
                ++covered[key];
                const auto it = reference.find(key);
                ASSERT_NE(it, reference.end());
                EXPECT_EQ(it->second.tile, r.tile);
            });
        }
        EXPECT_EQ(covered.size(), reference.size());
        for (const auto& [key, n] : covered) EXPECT_EQ(n, 1) << "unit face covered twice";
        expectWellFormed(unlit);
        EXPECT_LE(unlit.quadCount(), mesh(*p, MeshMode::Greedy).quadCount());
    }
}

// GreedyStrips against the culled mesh: the same unit faces and tiles, and the same shade at every
// point. A quad of one face carries that face's corners; a larger quad's occlusion must be affine over
// it (a0 + a2 == a1 + a3, so either diagonal interpolates it alike, as one face's own two triangles
// do), and equal at every corner of every face it covers to that face's own occlusion there. Returns
// the quads that are neither one face nor uniform: the strips.
int expectSameShading(const PaddedChunk& p) {
    const ChunkMesh culled = mesh(p, MeshMode::Culled);
    const ChunkMesh strips = mesh(p, MeshMode::GreedyStrips);
    Coverage coverage{unitFacesOfCulled(culled), {}};
    int stripQuads = 0;
    for (std::size_t i = 0; i < strips.vertices.size(); i += 4) {
        const ChunkVertex* q = &strips.vertices[i];
        const Rect r = rectOf(q);
        const int a = normalAxis(r.face), u = (a + 1) % 3, v = (a + 2) % 3;
        const int w = r.hi[u] - r.lo[u], h = r.hi[v] - r.lo[v];
        EXPECT_GE(w, 1);
        EXPECT_GE(h, 1);
        const int ao[4] = {world::aoOf(q[0]), world::aoOf(q[1]), world::aoOf(q[2]), world::aoOf(q[3])};
        if (w * h > 1) {
            EXPECT_EQ(ao[0] + ao[2], ao[1] + ao[3]) << "merged quad whose occlusion is not affine";
            if (ao[0] != ao[1] || ao[0] != ao[2] || ao[0] != ao[3]) ++stripQuads;
        }
        // The quad's occlusion at a corner (i, j) in the face's plane, times w * h, from its corners.
        std::map<std::pair<int, int>, int> at;
        for (int k = 0; k < 4; ++k) at[{pos(q[k])[u], pos(q[k])[v]}] = ao[k];
        const int a00 = at.at({r.lo[u], r.lo[v]}), a10 = at.at({r.hi[u], r.lo[v]});
        const int a01 = at.at({r.lo[u], r.hi[v]});
        const auto scaledShade = [&](int i, int j) {
            return a00 * w * h + (a10 - a00) * (i - r.lo[u]) * h + (a01 - a00) * (j - r.lo[v]) * w;
        };
        forEachUnitFace(r, [&](glm::ivec3 b) {
            // A quad of one face is the face itself, whatever its occlusion.
            const UnitFace* face = coverage.visit(r, q, b, w * h == 1, "merged");
            if (!face) return;
            for (const auto& [corner, ao] : face->cornerAo) {
                const int c[3] = {std::get<0>(corner), std::get<1>(corner), std::get<2>(corner)};
                EXPECT_EQ(scaledShade(c[u], c[v]), ao * w * h) << "shade differs at a corner of a covered face";
            }
        });
    }
    coverage.expectEachCoveredOnce();
    EXPECT_LE(strips.quadCount(), mesh(p, MeshMode::Greedy).quadCount());
    expectWellFormed(strips);
    return stripQuads;
}

// A floor along a wall: its faces darken towards the wall and not along it, so Greedy keeps one quad
// per face and GreedyStrips one strip for the row (the faces further out are fully lit and merge anyway).
TEST(Mesher, FloorAlongAWallMergesIntoOneStrip) {
    auto p = emptyPadded();
    for (int x = 2; x < 12; ++x) {
        for (int z = 2; z < 8; ++z) put(*p, x, 0, z, BlockType::Stone); // the floor
    }
    for (int x = 0; x < 14; ++x) put(*p, x, 1, 1, BlockType::Brick); // a wall along x, past both ends
    const auto floorRow = [](const ChunkMesh& m) {
        std::vector<Rect> row; // +Y quads of the floor touching the wall (z from 2 to 3)
        for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
            const Rect r = rectOf(&m.vertices[i]);
            if (r.face == world::kFacePosY && r.lo.y == 1 && r.lo.z == 2) row.push_back(r);
        }
        return row;
    };
    const std::vector<Rect> greedy = floorRow(mesh(*p, MeshMode::Greedy));
    EXPECT_EQ(greedy.size(), 10u);
    const std::vector<Rect> strip = floorRow(mesh(*p, MeshMode::GreedyStrips));
    ASSERT_EQ(strip.size(), 1u);
    EXPECT_EQ(strip[0].lo, glm::ivec3(2, 1, 2));
    EXPECT_EQ(strip[0].hi, glm::ivec3(12, 1, 3));
    std::array<int, 4> sorted = strip[0].ao;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, (std::array<int, 4>{1, 1, 3, 3})); // dark at the wall, open away from it
    // Strips: this floor row; the wall's side facing the floor and its bottom, both beside the floor
    // along x 2..11; and the floor's side under the wall.
    EXPECT_EQ(expectSameShading(*p), 4);
}

TEST(Mesher, StripsShadeLikeTheFacesTheyReplace) {
    core::Rng rng(2031);
    int strips = 0;
    for (int round = 0; round < 8; ++round) {
        auto p = emptyPadded();
        const std::uint32_t density = 2 + rng.below(6);
        const bool dense = rng.below(2) == 0;
        for (auto& b : p->blocks) {
            const bool solid = (rng.below(density) == 0) != dense;
            b = solid ? static_cast<BlockType>(1 + rng.below(2)) : BlockType::Air;
        }
        strips += expectSameShading(*p);
    }
    for (const world::ChunkCoord coord :
         {world::ChunkCoord{0, 1, 0}, world::ChunkCoord{5, 2, -7}, world::ChunkCoord{-3, 1, 2}}) {
        auto p = emptyPadded();
        std::vector<BlockType> box(PaddedChunk::kVolume);
        world::generateBox(world::TerrainDef{1}, world::chunkOrigin(coord) - glm::ivec3(1),
                           glm::ivec3(PaddedChunk::kSize), box.data());
        std::copy(box.begin(), box.end(), p->blocks.begin());
        const int terrainStrips = expectSameShading(*p);
        EXPECT_GT(terrainStrips, 0); // precondition: the terrain has strips to check
        EXPECT_LT(mesh(*p, MeshMode::GreedyStrips).quadCount(), mesh(*p, MeshMode::Greedy).quadCount());
        strips += terrainStrips;
    }
    EXPECT_GT(strips, 0);
}

TEST(Mesher, ReusesOutputAndClearsIt) {
    auto p = emptyPadded();
    put(*p, 1, 1, 1, BlockType::Sand);
    ChunkMesh m;
    m.vertices.resize(1000);
    world::meshChunk(*p, m);
    EXPECT_EQ(m.quadCount(), 6u);
    EXPECT_GE(m.vertices.capacity(), 1000u);
}

} // namespace

namespace {

std::string withThousands(std::size_t n) {
    const std::string digits = std::to_string(n);
    std::string s;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) s.push_back(',');
        s.push_back(digits[i]);
    }
    return s;
}

// The text of docs/ENGINE.md, which the next two tests hold to what the mesher makes; empty if missing.
std::string engineDoc() {
    std::ifstream in(std::string(MC_TEST_DATA) + "/../docs/ENGINE.md");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// docs/ENGINE.md quotes the quads of the benchmark's terrain chunk (tests/bench/bench_mesher.cpp): they
// must be what this mesher makes of that chunk.
TEST(Mesher, TheDocsQuoteTheTerrainChunksQuadCounts) {
    const world::World w(world::TerrainDef{1});
    const int h = world::surfaceHeight(w.terrain(), 16, 16);
    auto p = std::make_unique<PaddedChunk>();
    w.gatherPadded(world::chunkOf({16, h, 16}), *p);
    const std::string text = engineDoc();
    ASSERT_FALSE(text.empty()) << "docs/ENGINE.md not found beside tests/";
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    const std::pair<const char*, MeshMode> rows[] = {
        {"| typical terrain chunk (seed 1), greedy with ambient occlusion |", MeshMode::Greedy},
        {"| same chunk, greedy with occlusion and strips ", MeshMode::GreedyStrips},
        {"| same chunk, greedy lit flat ", MeshMode::GreedyFlat},
        {"| same chunk, face culling alone ", MeshMode::Culled},
    };
    for (const auto& row : rows) {
        const char* start = row.first; // clang 14 cannot capture a structured binding in a lambda
        const MeshMode mode = row.second;
        const auto it =
            std::find_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(start, 0) == 0; });
        ASSERT_NE(it, lines.end()) << "no row starting '" << start << "' in docs/ENGINE.md";
        std::string quads = "| "; // built piecewise: GCC 12 misreports "literal" + std::string (-Wrestrict)
        quads += withThousands(mesh(*p, mode).quadCount());
        quads += " |";
        ASSERT_GT(mesh(*p, mode).quadCount(), 0u);
        EXPECT_TRUE(it->size() >= quads.size() && it->compare(it->size() - quads.size(), quads.size(), quads) == 0)
            << *it << "\nshould end with " << quads;
    }
}

// docs/ENGINE.md ("Strips") quotes how the visible faces of the surface chunks around the spawn (seed 1,
// 7 x 7 columns, three chunks deep) split by occlusion, and the quads each mode makes of them. A face's
// corners, in order around it: one value; equal along one axis (a0 == a1 and a2 == a3, or a1 == a2
// and a3 == a0: what strips merge); or changing along both.
TEST(Mesher, TheDocsQuoteTheFaceCensus) {
    const world::World w(world::TerrainDef{1});
    auto p = std::make_unique<PaddedChunk>();
    std::size_t faces = 0, uniform = 0, oneAxis = 0, both = 0, leavesBoth = 0, chunks = 0;
    std::size_t greedy = 0, strips = 0, flatQuads = 0;
    const int leaves = world::blockInfo(BlockType::Leaves).tileSide;
    for (int cx = -3; cx <= 3; ++cx) {
        for (int cz = -3; cz <= 3; ++cz) {
            const int h = world::surfaceHeight(w.terrain(), cx * kN + 16, cz * kN + 16);
            for (int dy = -1; dy <= 1; ++dy) {
                world::ChunkCoord c = world::chunkOf({cx * kN + 16, h, cz * kN + 16});
                c.y += dy;
                w.gatherPadded(c, *p);
                ++chunks;
                greedy += mesh(*p, MeshMode::Greedy).quadCount();
                strips += mesh(*p, MeshMode::GreedyStrips).quadCount();
                flatQuads += mesh(*p, MeshMode::GreedyFlat).quadCount();
                const ChunkMesh culled = mesh(*p, MeshMode::Culled);
                for (std::size_t i = 0; i < culled.vertices.size(); i += 4) {
                    const ChunkVertex* v = &culled.vertices[i];
                    ++faces;
                    if (v[0].ao == v[1].ao && v[1].ao == v[2].ao && v[2].ao == v[3].ao) {
                        ++uniform;
                    } else if ((v[0].ao == v[1].ao && v[2].ao == v[3].ao) ||
                               (v[1].ao == v[2].ao && v[3].ao == v[0].ao)) {
                        ++oneAxis;
                    } else {
                        ++both;
                        leavesBoth += v[0].tile == leaves ? 1 : 0;
                    }
                }
            }
        }
    }
    ASSERT_EQ(chunks, 147u);
    ASSERT_GT(faces, 0u); // precondition: the chunks were gathered with their terrain
    const auto percent = [](std::size_t part, std::size_t whole) {
        return std::to_string((200 * part + whole) / (2 * whole)) + "%"; // rounded to the nearest
    };
    std::printf("census: %zu faces, %s one value, %s one axis, %s both (leaves %s of those); quads %zu / %zu / %zu\n",
                faces, percent(uniform, faces).c_str(), percent(oneAxis, faces).c_str(), percent(both, faces).c_str(),
                percent(leavesBoth, both).c_str(), greedy, strips, flatQuads);
    const std::string text = engineDoc();
    ASSERT_FALSE(text.empty()) << "docs/ENGINE.md not found beside tests/";
    // The paragraph is wrapped: compare with runs of whitespace made single spaces.
    std::string flat;
    for (const char ch : text) {
        const bool space = ch == ' ' || ch == '\n';
        if (!(space && !flat.empty() && flat.back() == ' ')) flat.push_back(space ? ' ' : ch);
    }
    const std::string quotes[] = {
        "Of the " + withThousands(faces) + " visible faces of the 147 surface chunks",
        percent(uniform, faces) + " have one occlusion value, " + percent(oneAxis, faces) + " change along one axis",
        "and " + percent(both, faces) + " along both",
        "leaves are " + percent(leavesBoth, both) + " of those",
        "from " + withThousands(greedy) + " quads to " + withThousands(strips) + " (flat: " + withThousands(flatQuads) +
            ")",
    };
    for (const std::string& q : quotes)
        EXPECT_NE(flat.find(q), std::string::npos) << "docs/ENGINE.md should say: " << q;
}

} // namespace

namespace {

std::unique_ptr<PaddedChunk> terrainPadded(std::uint64_t seed, world::ChunkCoord coord) {
    const world::World w(world::TerrainDef{seed});
    auto p = std::make_unique<PaddedChunk>();
    w.gatherPadded(coord, *p);
    return p;
}

// The level of detail: each cell filled from its bottom up to its highest solid layer and air above (so the
// ground keeps its height), of one type: its highest lamp's, or else that of the first solid block in its
// highest solid layer (grass stays on top); the border untouched; the solid rows in step with the bytes.
// Computed here cell by cell from the fine blocks, on a terrain chunk with lamps put in: one alone, one under a
// higher block of its cell, one in the border (which no cell holds). Mutations caught: cells solid to their
// top (the old rule), a lamp losing to a higher block, a border lamp taken into a cell.
TEST(Mesher, CoarseCellsKeepTheGroundsHeightAndShowTheirLamps) {
    const world::World w(world::TerrainDef{3});
    const int h = world::surfaceHeight(w.terrain(), 40, 8);
    const auto fine = terrainPadded(3, world::chunkOf({40, h, 8}));
    // Lamps at the surface: one in place of a column's top block, one with a block added over it in its cell,
    // and one in the border.
    const auto topOf = [&](int x, int z) {
        for (int y = PaddedChunk::kSize - 2; y >= 1; --y)
            if (world::isSolid(fine->get(x, y, z))) return y;
        return 0;
    };
    const int yA = topOf(5, 5), yB = topOf(10, 21) | 1; // odd: yB and yB + 1 share a 2-cell and a 4-cell
    ASSERT_TRUE(yA >= 1 && yB >= 1 && yB + 1 <= kN) << "precondition: the chunk holds the surface there";
    fine->set(5, yA, 5, BlockType::Lamp);
    fine->set(10, yB, 21, BlockType::Lamp);
    fine->set(9, yB + 1, 21, BlockType::Stone); // higher, and first in its layer
    fine->set(0, yA, 6, BlockType::Lamp);       // the border
    int solidCells = 0, airCells = 0, lampCells = 0, loweredCells = 0;
    for (const int f : {2, 4}) {
        auto coarse = std::make_unique<PaddedChunk>();
        world::coarsenPadded(*fine, f, *coarse);
        ASSERT_FALSE(coarse->blocks.stale);
        for (int y = 0; y < PaddedChunk::kSize; ++y)
            for (int z = 0; z < PaddedChunk::kSize; ++z)
                for (int x = 0; x < PaddedChunk::kSize; ++x) {
                    ASSERT_EQ(coarse->solidAt(x, y, z), world::isSolid(coarse->get(x, y, z)));
                    const bool border = x == 0 || y == 0 || z == 0 || x == PaddedChunk::kSize - 1 ||
                                        y == PaddedChunk::kSize - 1 || z == PaddedChunk::kSize - 1;
                    if (border) {
                        ASSERT_EQ(coarse->get(x, y, z), fine->get(x, y, z)) << "border changed";
                    }
                }
        for (int cy = 1; cy <= kN; cy += f)
            for (int cz = 1; cz <= kN; cz += f)
                for (int cx = 1; cx <= kN; cx += f) {
                    int top = 0;
                    BlockType first = BlockType::Air, lamp = BlockType::Air;
                    for (int y = cy + f - 1; y >= cy; --y) // from the top layer down, z then x in a layer
                        for (int z = cz; z < cz + f; ++z)
                            for (int x = cx; x < cx + f; ++x) {
                                const BlockType b = fine->get(x, y, z);
                                if (!world::isSolid(b)) continue;
                                if (top == 0) top = y, first = b;
                                if (b == BlockType::Lamp && lamp == BlockType::Air) lamp = b;
                            }
                    const BlockType type = lamp != BlockType::Air ? lamp : first;
                    (type == BlockType::Air ? airCells : solidCells) += 1;
                    lampCells += type == BlockType::Lamp;
                    loweredCells += top != 0 && top < cy + f - 1;
                    for (int y = cy; y < cy + f; ++y)
                        for (int z = cz; z < cz + f; ++z)
                            for (int x = cx; x < cx + f; ++x)
                                ASSERT_EQ(coarse->get(x, y, z), y <= top ? type : BlockType::Air)
                                    << f << " at " << x << "," << y << "," << z;
                }
        expectSameCoverage(*coarse); // an ordinary chunk to the mesher
    }
    // Preconditions: the chunk holds the surface, both solid and air, cells whose top is below theirs, and both
    // lamps at both levels (the border one is in no cell).
    EXPECT_GT(solidCells, 0);
    EXPECT_GT(airCells, 0);
    EXPECT_GT(loweredCells, 0);
    EXPECT_EQ(lampCells, 4);
}

// What the level of detail is for: fewer quads on the game's terrain, the more so the coarser.
TEST(Mesher, CoarseChunksNeedFewerQuads) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        const world::World w(world::TerrainDef{seed});
        const int h = world::surfaceHeight(w.terrain(), 16, 16);
        const auto fine = terrainPadded(seed, world::chunkOf({16, h, 16}));
        auto coarse2 = std::make_unique<PaddedChunk>(), coarse4 = std::make_unique<PaddedChunk>();
        world::coarsenPadded(*fine, 2, *coarse2);
        world::coarsenPadded(*fine, 4, *coarse4);
        const std::size_t q1 = mesh(*fine, MeshMode::GreedyFlat).quadCount();
        const std::size_t q2 = mesh(*coarse2, MeshMode::GreedyFlat).quadCount();
        const std::size_t q4 = mesh(*coarse4, MeshMode::GreedyFlat).quadCount();
        ASSERT_GT(q1, 100u) << "precondition: a surface chunk";
        EXPECT_LT(q2, q1) << seed;
        EXPECT_LT(q4, q2) << seed;
        std::printf("seed %llu: unlit quads %zu, 2x %zu, 4x %zu\n", static_cast<unsigned long long>(seed), q1, q2, q4);
    }
}

// Plane order: the same quads, by face then plane (nearest first to a camera in front), with the
// starts right.
// Light over a padded chunk much as propagation leaves it: the open sky down to a random height and sunlight
// falling off a level a block below it, block light falling off from three lamps (white, red, and a blue-green
// whose channels differ), and random levels, each channel its own, at one voxel in twenty; the shade rows rebuilt.
void lightAtRandom(PaddedChunk& p, core::Rng& rng) {
    const int skyFrom = 8 + static_cast<int>(rng.below(20));
    glm::ivec3 lamps[3];
    const glm::ivec3 colours[3] = {glm::ivec3(15, 15, 15), glm::ivec3(15, 0, 0), glm::ivec3(0, 9, 15)};
    for (glm::ivec3& l : lamps) {
        l = glm::ivec3(static_cast<int>(rng.below(34)), static_cast<int>(rng.below(34)),
                       static_cast<int>(rng.below(34)));
    }
    for (int y = 0; y < PaddedChunk::kSize; ++y)
        for (int z = 0; z < PaddedChunk::kSize; ++z)
            for (int x = 0; x < PaddedChunk::kSize; ++x) {
                int sun = std::max(0, world::kMaxLight - std::max(0, skyFrom - y));
                glm::ivec3 block(0);
                for (int i = 0; i < 3; ++i) {
                    const glm::ivec3 d = glm::abs(glm::ivec3(x, y, z) - lamps[i]);
                    block = glm::max(block, colours[i] - glm::ivec3(d.x + d.y + d.z));
                }
                if (rng.below(20) == 0) {
                    sun = static_cast<int>(rng.below(16));
                    for (int c = 0; c < 3; ++c) block[c] = static_cast<int>(rng.below(16));
                }
                p.light.level[static_cast<std::size_t>(PaddedChunk::index(x, y, z))] =
                    world::LightLevel::of(sun, block.r, block.g, block.b).bits;
            }
    p.light.rebuildShade();
}

// Counts of a mesh's vertices in the shade, lit by lamps, of quads whose corners' light differs, and of quads
// of more than one face lit otherwise than by the open sky.
struct LightCensus {
    int shaded = 0, lampLit = 0, unevenQuads = 0, mergedInTheShade = 0;
};
LightCensus censusOf(const ChunkMesh& m) {
    LightCensus c;
    for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
        const ChunkVertex* q = &m.vertices[i];
        bool uneven = false;
        for (int k = 0; k < 4; ++k) {
            c.shaded += world::sunlightOf(q[k]) < world::kMaxLight;
            c.lampLit += world::lightOf(q[k]).block() > 0;
            uneven |= lightWordOf(q[k]) != lightWordOf(q[0]);
        }
        c.unevenQuads += uneven;
        const Rect r = rectOf(q);
        const glm::ivec3 extent = r.hi - r.lo;
        const int faces = std::max(extent.x, 1) * std::max(extent.y, 1) * std::max(extent.z, 1);
        c.mergedInTheShade += faces > 1 && lightWordOf(q[0]) != world::kOpenSkyLight;
    }
    return c;
}

// Smooth light, against the culled mesh's face-by-face light (written voxel by voxel, sharing nothing with the
// greedy mesher's): every face has the same light at every corner, merged quads only over faces of one light.
TEST(Mesher, SmoothLightMatchesTheFaceByFaceReference) {
    core::Rng rng(37);
    for (int round = 0; round < 6; ++round) {
        auto p = emptyPadded();
        const std::uint32_t density = 2 + rng.below(5);
        for (auto& b : p->blocks)
            b = rng.below(density) == 0 ? static_cast<BlockType>(1 + rng.below(3)) : BlockType::Air;
        lightAtRandom(*p, rng);
        const LightCensus c = censusOf(mesh(*p, MeshMode::Culled));
        // Precondition: shade, lamp light and faces whose light varies, so that light left out would show, and
        // faces merged in the shade, so that merging across light would too.
        ASSERT_GT(c.shaded, 0);
        ASSERT_GT(c.lampLit, 0);
        ASSERT_GT(c.unevenQuads, 0);
        ASSERT_GT(censusOf(mesh(*p, MeshMode::Greedy)).mergedInTheShade, 0);
        expectSameCoverage(*p);
        expectSameShading(*p);
        expectWellFormed(mesh(*p, MeshMode::Greedy));
    }
}

// The same on the game's terrain with lamps and a roof, lit by world::lightPadded.
TEST(Mesher, LitTerrainMatchesTheFaceByFaceReference) {
    world::World w(world::TerrainDef{3});
    const int h = world::surfaceHeight(w.terrain(), 16, 16);
    for (const glm::ivec3 at : {glm::ivec3(10, h + 1, 10), glm::ivec3(20, h + 2, 25), glm::ivec3(3, h - 2, 30)}) {
        w.set(at, BlockType::Lamp);
    }
    w.set({16, h + 4, 16}, BlockType::Planks); // a roof
    const world::ChunkCoord c = world::chunkOf({16, h, 16});
    auto p = emptyPadded();
    w.gatherPadded(c, *p);
    const ChunkMesh unlit = mesh(*p, MeshMode::Greedy);
    std::vector<world::BlockEdit> edits;
    w.editsAround(c, edits);
    world::lightPadded(w.terrain(), c, edits, p->light);
    const LightCensus census = censusOf(mesh(*p, MeshMode::Culled));
    ASSERT_GT(census.shaded, 0);
    ASSERT_GT(census.lampLit, 0);
    expectSameCoverage(*p);
    expectSameShading(*p);
    const ChunkMesh lit = mesh(*p, MeshMode::Greedy);
    std::printf("terrain chunk, greedy with occlusion: %zu quads unlit, %zu lit\n", unlit.quadCount(), lit.quadCount());
    EXPECT_GE(lit.quadCount(), unlit.quadCount());
}

// The level of detail (GreedyFlat) is lit flat: each face by the light of the voxel on its air side, and a
// quad only over faces of one light.
TEST(Mesher, DistantDetailIsLitFlatByTheVoxelInFrontOfEachFace) {
    core::Rng rng(8);
    for (int round = 0; round < 4; ++round) {
        auto p = emptyPadded();
        for (auto& b : p->blocks) b = rng.below(4) == 0 ? static_cast<BlockType>(1 + rng.below(3)) : BlockType::Air;
        lightAtRandom(*p, rng);
        const ChunkMesh m = mesh(*p, MeshMode::GreedyFlat);
        int notOpenSky = 0;
        for (std::size_t i = 0; i < m.vertices.size(); i += 4) {
            const ChunkVertex* q = &m.vertices[i];
            const Rect r = rectOf(q);
            for (int k = 0; k < 4; ++k) {
                ASSERT_EQ(world::aoOf(q[k]), 3);
                ASSERT_EQ(lightWordOf(q[k]), lightWordOf(q[0]));
            }
            notOpenSky += lightWordOf(q[0]) != world::kOpenSkyLight;
            forEachUnitFace(r, [&](glm::ivec3 b) {
                const glm::ivec3 front = b + normalOf(r.face) + glm::ivec3(1); // padded
                EXPECT_EQ(p->light.level[static_cast<std::size_t>(PaddedChunk::index(front.x, front.y, front.z))],
                          lightWordOf(q[0]));
            });
        }
        EXPECT_GT(notOpenSky, 0); // precondition
    }
}

TEST(PlaneOrder, SortsEveryQuadByFaceThenPlane) {
    const world::World w(world::TerrainDef{1});
    const int h = world::surfaceHeight(w.terrain(), 16, 16);
    const ChunkMesh m = mesh(*terrainPadded(1, world::chunkOf({16, h, 16})), MeshMode::Greedy);
    ASSERT_GT(m.quadCount(), 100u) << "precondition: a surface chunk";
    std::vector<ChunkVertex> sorted;
    const world::PlaneOrder order = world::sortByPlane(m, sorted);
    ASSERT_EQ(sorted.size(), m.vertices.size());
    EXPECT_EQ(order.start.front(), 0);
    EXPECT_EQ(order.start.back(), static_cast<int>(m.quadCount()));
    using Quad = std::array<std::uint64_t, 4>;
    const auto quads = [](const auto& v) { // the mesh's VertexList or the sorted std::vector
        std::vector<Quad> q(v.size() / 4);
        for (std::size_t i = 0; i < q.size(); ++i)
            for (std::size_t k = 0; k < 4; ++k) std::memcpy(&q[i][k], &v[i * 4 + k], sizeof(ChunkVertex));
        return q;
    };
    std::vector<Quad> before = quads(m.vertices), after = quads(sorted);
    std::sort(before.begin(), before.end());
    std::sort(after.begin(), after.end());
    EXPECT_EQ(before, after) << "not the same quads";
    constexpr int kPlanes = world::PlaneOrder::kPlanes;
    int planesUsed = 0;
    for (int f = 0; f < world::kFaceCount; ++f)
        for (int p = 0; p < kPlanes; ++p) {
            const int from = order.at(f, p);
            const int to = order.at(f, p + 1);
            ASSERT_LE(from, to);
            planesUsed += to > from ? 1 : 0;
            for (int q = from; q < to; ++q)
                for (int k = 0; k < 4; ++k) {
                    const ChunkVertex& v = sorted[static_cast<std::size_t>(q) * 4 + static_cast<std::size_t>(k)];
                    ASSERT_EQ(v.face, f);
                    ASSERT_EQ(world::PlaneOrder::slotOf(f, f / 2 == 0   ? world::xOf(v)
                                                           : f / 2 == 1 ? world::yOf(v)
                                                                        : world::zOf(v)),
                              p);
                }
        }
    EXPECT_GT(planesUsed, 20); // the terrain's faces lie in many planes
}

// What a camera at coordinate t can see of a face direction: every quad whose front faces it is in the
// range, and every quad in the range faces it or lies in the plane through it (edge-on).
TEST(PlaneOrder, VisibleRangeHoldsExactlyTheQuadsThatCanFaceTheCamera) {
    const world::World w(world::TerrainDef{2});
    const int h = world::surfaceHeight(w.terrain(), 16, 16);
    const ChunkMesh m = mesh(*terrainPadded(2, world::chunkOf({16, h, 16})), MeshMode::Greedy);
    std::vector<ChunkVertex> sorted;
    const world::PlaneOrder order = world::sortByPlane(m, sorted);
    int cut = 0; // cameras level with the chunk that leave some but not all of a direction out
    for (const float t : {-1e9f, -40.0f, -0.5f, 0.0f, 0.25f, 1.0f, 7.5f, 16.0f, 16.001f, 31.9f, 32.0f, 33.0f, 1e9f}) {
        for (int f = 0; f < world::kFaceCount; ++f) {
            const world::PlaneOrder::Range r = order.visible(f, t);
            const bool positive = f % 2 == 0;
            int all = 0, drawn = 0;
            for (int q = order.at(f, 0); q < order.at(f + 1, 0); ++q) {
                const ChunkVertex& v = sorted[static_cast<std::size_t>(q) * 4];
                const float plane = f / 2 == 0 ? world::xOf(v) : f / 2 == 1 ? world::yOf(v) : world::zOf(v);
                const bool facing = positive ? plane < t : plane > t;
                const bool inRange = q >= r.first && q < r.last;
                ++all;
                drawn += inRange ? 1 : 0;
                if (facing) {
                    EXPECT_TRUE(inRange) << "face " << f << " plane " << plane << " camera at " << t;
                }
                if (inRange && !facing) {
                    EXPECT_EQ(plane, t) << "a quad facing away drawn, face " << f << " camera at " << t;
                }
            }
            cut += drawn > 0 && drawn < all ? 1 : 0;
        }
    }
    EXPECT_GT(cut, 10); // precondition of the point: most directions are cut for a camera inside
}

TEST(Mesher, CoarsenRefusesBadInput) {
    auto fine = emptyPadded(), out = emptyPadded();
    EXPECT_THROW(world::coarsenPadded(*fine, 3, *out), std::invalid_argument);
    fine->blocks[0] = BlockType::Stone; // stale rows
    EXPECT_THROW(world::coarsenPadded(*fine, 2, *out), std::invalid_argument);
}

} // namespace

namespace {

using world::FaceLinks;

// A chunk of stone with air carved in boxes (chunk-local, inclusive bounds), its solid rows in step.
std::unique_ptr<PaddedChunk> stoneWith(std::initializer_list<std::pair<glm::ivec3, glm::ivec3>> airBoxes) {
    auto p = emptyPadded();
    for (int y = 0; y < kN; ++y)
        for (int z = 0; z < kN; ++z)
            for (int x = 0; x < kN; ++x) p->set(x + 1, y + 1, z + 1, BlockType::Stone);
    for (const auto& [lo, hi] : airBoxes)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int z = lo.z; z <= hi.z; ++z)
                for (int x = lo.x; x <= hi.x; ++x) p->set(x + 1, y + 1, z + 1, BlockType::Air);
    return p;
}

std::uint8_t bits(std::initializer_list<int> faces) {
    std::uint8_t m = 0;
    for (const int f : faces) m |= static_cast<std::uint8_t>(1u << f);
    return m;
}

TEST(FaceLinks, AllAirJoinsEverythingAndAllSolidNothing) {
    auto air = emptyPadded();
    const FaceLinks a = world::faceLinks(*air);
    for (int f = 0; f < world::kFaceCount; ++f) EXPECT_EQ(a.to[f], 0x3F) << f;
    const FaceLinks s = world::faceLinks(*stoneWith({}));
    for (int f = 0; f < world::kFaceCount; ++f) EXPECT_EQ(s.to[f], 0) << f;
}

// A winding tunnel from -X to +Y (down the x axis, a turn, up a shaft) joins exactly those two faces;
// a sealed room touches no face; a pocket on +Z alone joins only +Z to itself.
TEST(FaceLinks, FollowsTunnelsAndNothingElse) {
    const auto p = stoneWith({
        {{0, 3, 3}, {20, 3, 3}},     // tunnel from x = 0 (the -X face) to x = 20
        {{20, 3, 3}, {20, 3, 17}},   // turns along z
        {{20, 3, 17}, {20, 31, 17}}, // and up a shaft to y = 31 (the +Y face)
        {{8, 10, 8}, {12, 14, 12}},  // a sealed room
        {{5, 20, 29}, {6, 21, 31}},  // a pocket open to +Z only
    });
    const FaceLinks l = world::faceLinks(*p);
    EXPECT_EQ(l.to[world::kFaceNegX], bits({world::kFaceNegX, world::kFacePosY}));
    EXPECT_EQ(l.to[world::kFacePosY], bits({world::kFaceNegX, world::kFacePosY}));
    EXPECT_EQ(l.to[world::kFacePosZ], bits({world::kFacePosZ}));
    EXPECT_EQ(l.to[world::kFacePosX], 0);
    EXPECT_EQ(l.to[world::kFaceNegY], 0);
    EXPECT_EQ(l.to[world::kFaceNegZ], 0);
    EXPECT_TRUE(l.joins(world::kFaceNegX, world::kFacePosY));
    EXPECT_FALSE(l.joins(world::kFaceNegX, world::kFacePosX));
}

// Air touching diagonally (across an edge, not a face) does not join.
TEST(FaceLinks, EdgeContactIsNoPassage) {
    const auto p = stoneWith({
        {{0, 5, 5}, {10, 5, 5}},  // from -X to x = 10
        {{11, 6, 5}, {31, 6, 5}}, // from x = 11, one block up: touches the first only along an edge
    });
    const FaceLinks l = world::faceLinks(*p);
    EXPECT_EQ(l.to[world::kFaceNegX], bits({world::kFaceNegX}));
    EXPECT_EQ(l.to[world::kFacePosX], bits({world::kFacePosX}));
}

// On the game's terrain, a surface chunk's open air joins its sides and top, and links are symmetric.
TEST(FaceLinks, SurfaceChunkAirJoinsSidesAndTop) {
    const auto p = terrainPadded(1, world::chunkOf({16, world::surfaceHeight(world::TerrainDef{1}, 16, 16), 16}));
    const FaceLinks l = world::faceLinks(*p);
    EXPECT_TRUE(l.joins(world::kFacePosY, world::kFacePosX));
    EXPECT_TRUE(l.joins(world::kFacePosY, world::kFaceNegZ));
    for (int f = 0; f < world::kFaceCount; ++f)
        for (int g = 0; g < world::kFaceCount; ++g) EXPECT_EQ(l.joins(f, g), l.joins(g, f)) << f << ' ' << g;
}

// A column's layer counts as solid only when all 64 of its blocks are; the padding (the neighbours'
// blocks) never counts.
TEST(SolidColumns, ALayerIsSolidOnlyWhenEveryBlockOfTheColumnIs) {
    const auto p = stoneWith({
        {{3, 5, 3}, {3, 5, 3}},       // one air block: column (0, 0), layer 5
        {{8, 0, 0}, {15, 31, 7}},     // column (1, 0) all air
        {{31, 30, 31}, {31, 31, 31}}, // the corner block of column (3, 3), layers 30 and 31
    });
    const world::SolidColumns c = world::solidColumns(*p);
    EXPECT_EQ(c.at(0, 0), ~(1u << 5));
    EXPECT_EQ(c.at(1, 0), 0u);
    EXPECT_EQ(c.at(3, 3), ~(3u << 30));
    EXPECT_EQ(c.at(2, 1), ~0u);
    auto onlyPadding = emptyPadded(); // solid all round the chunk, air inside
    for (int y = 0; y < PaddedChunk::kSize; ++y)
        for (int z = 0; z < PaddedChunk::kSize; ++z)
            for (int x = 0; x < PaddedChunk::kSize; ++x) {
                const bool inside = x > 0 && x <= kN && y > 0 && y <= kN && z > 0 && z <= kN;
                if (!inside) onlyPadding->set(x, y, z, BlockType::Stone);
            }
    for (const std::uint32_t layers : world::solidColumns(*onlyPadding).layers) EXPECT_EQ(layers, 0u);
}

// On the game's terrain (surface chunks of three seeds, where columns end at different heights), the
// masks equal a block-by-block count.
TEST(SolidColumns, MatchBlockByBlockOnTerrain) {
    int solidLayers = 0, openLayers = 0;
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        const auto p =
            terrainPadded(seed, world::chunkOf({40, world::surfaceHeight(world::TerrainDef{seed}, 40, 40), 40}));
        const world::SolidColumns c = world::solidColumns(*p);
        for (int cz = 0; cz < world::SolidColumns::kCells; ++cz)
            for (int cx = 0; cx < world::SolidColumns::kCells; ++cx)
                for (int y = 0; y < kN; ++y) {
                    bool all = true;
                    for (int z = cz * 8; z < cz * 8 + 8; ++z)
                        for (int x = cx * 8; x < cx * 8 + 8; ++x)
                            all = all && world::isSolid(p->get(x + 1, y + 1, z + 1));
                    EXPECT_EQ((c.at(cx, cz) >> y & 1u) != 0, all) << seed << ' ' << cx << ' ' << cz << ' ' << y;
                    ++(all ? solidLayers : openLayers);
                }
    }
    EXPECT_GT(solidLayers, 0) << "precondition: the chunks hold solid columns";
    EXPECT_GT(openLayers, 0) << "precondition: and open ones";
}

} // namespace
