// What a chunk mesh is made of: the six face directions and the 8-byte vertex, four to a quad, that the
// mesher writes and the renderer uploads byte for byte. The layout is the contract between the two: it
// knows nothing of GL, and a change to it must be made in shaders/chunk.vert, which unpacks it, as well.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "world/block.h"

namespace world {

// Face directions, as stored in ChunkVertex::face.
enum Face : std::uint8_t { kFacePosX, kFaceNegX, kFacePosY, kFaceNegY, kFacePosZ, kFaceNegZ, kFaceCount };
inline constexpr int kFaceNormals[kFaceCount][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};

// x, y, z: corner, chunk-local 0..32. u, v: texture coordinates in blocks, so the tile repeats across a
// merged quad; on side faces v = 0 at the top edge and grows downward and u grows to the right as seen
// from outside; on top and bottom faces u runs along x and v along z.
// face: the direction in the low three bits, and in the high four the sunlight's shortfall at the corner
// (kMaxLight minus its level). ao: the occlusion in the low two bits (3 open .. 0 fully occluded), and the
// block light at the corner in the high four. Both light fields are 0 under the open sky, so a vertex
// there holds the plain fields: faceOf(v) == v.face, aoOf(v) == v.ao.
struct ChunkVertex {
    std::uint8_t x, y, z, face, u, v, tile, ao;
};
static_assert(sizeof(ChunkVertex) == 8);
inline int faceOf(const ChunkVertex& v) { return v.face & 7; }
inline int aoOf(const ChunkVertex& v) { return v.ao & 3; }
inline int sunlightOf(const ChunkVertex& v) { return kMaxLight - (v.face >> 4); }
inline int blockLightOf(const ChunkVertex& v) { return v.ao >> 4; }

// An allocator whose default-inserted elements are left uninitialised: resizing a VertexList up costs
// nothing, so the mesher grows a mesh ahead and writes quads in place (every element it keeps is
// written first). Otherwise std::allocator.
template <typename T>
struct UninitialisedAllocator : std::allocator<T> {
    UninitialisedAllocator() = default;
    template <typename U>
    explicit UninitialisedAllocator(const UninitialisedAllocator<U>&) {}
    template <typename U>
    void construct(U* p) {
        ::new (static_cast<void*>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};
using VertexList = std::vector<ChunkVertex, UninitialisedAllocator<ChunkVertex>>;

// Four vertices per quad; triangles (0, 1, 2) and (0, 2, 3) are counter-clockwise seen from outside,
// and the split diagonal is chosen so occlusion interpolates without the anisotropy artefact.
struct ChunkMesh {
    VertexList vertices;
    std::size_t quadCount() const { return vertices.size() / 4; }
};

} // namespace world
