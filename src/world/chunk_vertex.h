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
#include "world/light_level.h"

namespace world {

// Face directions, as stored in ChunkVertex::face.
enum Face : std::uint8_t { kFacePosX, kFaceNegX, kFacePosY, kFaceNegY, kFacePosZ, kFaceNegZ, kFaceCount };
inline constexpr int kFaceNormals[kFaceCount][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};

// x, y, z: corner, chunk-local 0..32, in the low six bits. u, v: texture coordinates in blocks (0..32, the
// low six bits), so the tile repeats across a merged quad; on side faces v = 0 at the top edge and grows
// downward and u grows to the right as seen from outside; on top and bottom faces u runs along x and v along z.
// face: the direction in the low three bits, and in the high four the sunlight's shortfall at the corner
// (kMaxLight minus its level). ao: the occlusion in the low two bits (3 open .. 0 fully occluded), and the
// block light's red channel at the corner in the high four. The green channel's four bits are the top two bits
// of x (its low two) and of y (its high two); blue's those of z and u. Every light field is 0 under the open
// sky, so a vertex there holds the plain fields. Read the fields through the functions below.
struct ChunkVertex {
    std::uint8_t x, y, z, face, u, v, tile, ao;
};
static_assert(sizeof(ChunkVertex) == 8);
inline constexpr std::uint8_t kVertexFieldBits = 63; // of x, y, z, u and v: the rest is light
inline int xOf(const ChunkVertex& v) { return v.x & kVertexFieldBits; }
inline int yOf(const ChunkVertex& v) { return v.y & kVertexFieldBits; }
inline int zOf(const ChunkVertex& v) { return v.z & kVertexFieldBits; }
inline int uOf(const ChunkVertex& v) { return v.u & kVertexFieldBits; }
inline int vOf(const ChunkVertex& v) { return v.v & kVertexFieldBits; }
inline int faceOf(const ChunkVertex& v) { return v.face & 7; }
inline int aoOf(const ChunkVertex& v) { return v.ao & 3; }
inline int sunlightOf(const ChunkVertex& v) { return kMaxLight - (v.face >> 4); }
inline int redLightOf(const ChunkVertex& v) { return v.ao >> 4; }
inline int greenLightOf(const ChunkVertex& v) { return v.x >> 6 | (v.y >> 6) << 2; }
inline int blueLightOf(const ChunkVertex& v) { return v.z >> 6 | (v.u >> 6) << 2; }
// The corner's light as the light field holds it.
inline LightLevel lightOf(const ChunkVertex& v) {
    return LightLevel::of(sunlightOf(v), redLightOf(v), greenLightOf(v), blueLightOf(v));
}

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
