// CPU meshing of one chunk into plain vertex arrays: greedy (the default) or one quad per face.
// Input is the chunk plus a one-voxel border taken from its neighbours, so faces against neighbouring
// chunks are culled and ambient occlusion is seamless across chunk borders.
// Pure function of its input: it never reads the world, never allocates beyond growing the output
// vector, and knows nothing of GL (uploading the vertices is the renderer's business).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "world/block.h"
#include "world/chunk.h"

namespace world {

// The padded block bytes. Reading is free; any non-const access (operator[], data(), begin(), end(),
// fill()) marks the occupancy rows stale, so bytes written behind PaddedChunk::set's back can never be
// meshed with old solidity: meshChunk then derives the rows from the bytes itself (about 3 us).
struct PaddedBlocks : std::array<BlockType, (kChunkSize + 2) * (kChunkSize + 2) * (kChunkSize + 2)> {
    using Base = std::array<BlockType, (kChunkSize + 2) * (kChunkSize + 2) * (kChunkSize + 2)>;
    const BlockType* data() const { return Base::data(); }
    BlockType* data() { return stale = true, Base::data(); }
    const_reference operator[](size_type i) const { return Base::operator[](i); }
    reference operator[](size_type i) { return stale = true, Base::operator[](i); }
    const_iterator begin() const { return Base::begin(); }
    iterator begin() { return stale = true, Base::begin(); }
    const_iterator end() const { return Base::end(); }
    iterator end() { return stale = true, Base::end(); }
    void fill(BlockType t) { stale = true, Base::fill(t); }
    // For writers that keep PaddedChunk::solid in step themselves (set(), World::gatherPadded).
    BlockType* untrackedData() { return Base::data(); }

    bool stale = false;
};

// Light levels packed in a byte: sunlight in the high four bits, block light in the low four (world/light.h).
inline constexpr std::uint8_t kOpenSkyLight = kMaxLight << 4; // full sunlight, no block light

// The light of the padded voxels, for smooth lighting: what a chunk's faces are lit by. Starts as open sky
// everywhere, which meshes exactly as a chunk without light did.
struct PaddedLight {
    static constexpr int kSize = kChunkSize + 2;
    static constexpr int kVolume = kSize * kSize * kSize;
    PaddedLight() { fillOpenSky(); }
    void fillOpenSky();
    // Recomputes `shade` from `level`; call after writing `level`.
    void rebuildShade();

    std::array<std::uint8_t, kVolume> level; // sunlight << 4 | block light, in PaddedChunk::index order
    // Bit x of shade[y][z] is set where level differs from kOpenSkyLight. A face whose 3x3 neighbourhood
    // on the air side has no such bit is lit as under the open sky at every corner, and merges as before.
    std::uint64_t shade[kSize][kSize];
};

struct PaddedChunk {
    static constexpr int kSize = kChunkSize + 2;
    static constexpr int kVolume = kSize * kSize * kSize;
    // Padded coordinates 0..33; the chunk's own block (x, y, z) is at (x + 1, y + 1, z + 1).
    // Same order as Chunk: x fastest, then z, then y.
    static constexpr int index(int x, int y, int z) { return x + kSize * (z + kSize * y); }
    BlockType get(int x, int y, int z) const { return blocks[static_cast<std::size_t>(index(x, y, z))]; }
    void set(int x, int y, int z, BlockType t) {
        blocks.untrackedData()[index(x, y, z)] = t;
        std::uint64_t& row = solid[y][z];
        row = (row & ~(std::uint64_t{1} << x)) | std::uint64_t{isSolid(t)} << x;
    }
    bool solidAt(int x, int y, int z) const { return (solid[y][z] >> x & 1u) != 0; }
    // Recomputes `solid` from `blocks` and clears blocks.stale.
    void rebuildSolid();

    // Unless blocks.stale: bit x of solid[y][z] is set exactly when blocks[index(x, y, z)] is solid,
    // and bits 34..63 are clear. The mesher reads solidity only from these 64-bit rows (culling,
    // merging and ambient occlusion) and block bytes only for the tiles of visible faces.
    PaddedBlocks blocks{};               // all Air
    std::uint64_t solid[kSize][kSize]{}; // all clear
    PaddedLight light;                   // all open sky
};
static_assert(sizeof(PaddedBlocks::Base) == PaddedChunk::kVolume);

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
// there reads as before light: faceOf(v) == v.face, aoOf(v) == v.ao.
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

// Greedy merges coplanar faces with the same tile and the same uniform occlusion into rectangles, so
// a merged quad renders exactly like the faces it replaces. GreedyStrips merges further: faces whose
// occlusion changes along one axis of the face only (a floor along a wall) merge along the other axis,
// with the same tile and corners, into strips one face wide; the occlusion of such a strip is linear
// across it and constant along it, so every point is shaded as the faces shade themselves (and either
// diagonal splits it alike). What the renderer draws near the camera. GreedyFlat leaves occlusion out
// and lights each face flat by the voxel on its air side, so that faces merge by tile and that one light:
// the level of detail for distant chunks, where occlusion is about a pixel wide and the triangle count is
// what costs. Culled emits one quad
// per visible face and is the reference for tests and benchmarks.
enum class MeshMode { Greedy, GreedyFlat, Culled, GreedyStrips };

// Clears `out` first and reuses its capacity.
void meshChunk(const PaddedChunk& in, ChunkMesh& out, MeshMode mode = MeshMode::GreedyStrips);

// Level of detail for distant chunks: `out` is `fine` with the chunk's inside rebuilt from cells of
// factor^3 blocks (factor 2 or 4). A cell is solid when any of its blocks is, and then wholly of the
// type of its highest solid block (grass stays on top); the one-block border stays fine. Meshed as
// usual, a coarse chunk needs far fewer quads, and it leaves no gap at any seam: it covers at least
// every solid block of `fine`, and its border faces are culled only against solid fine neighbours,
// which every level of detail also covers. `fine.blocks` must not be stale.
void coarsenPadded(const PaddedChunk& fine, int factor, PaddedChunk& out);

// Which faces of a chunk see each other through it: bit g of to[f] is set when some air block on face
// f (the chunk's own blocks, faces in Face order) is joined to an air block on face g by air blocks of
// the chunk, stepping across block faces. Symmetric; a face with no air reaches nothing. The renderer's
// occlusion culling walks chunks through these links (docs/ENGINE.md). Where a face holds separate air
// pockets the links of all of them are merged, which only ever joins more: safe for culling.
struct FaceLinks {
    std::uint8_t to[kFaceCount] = {};
    bool joins(int f, int g) const { return (to[f] >> g & 1u) != 0; }
    static FaceLinks all(); // every face joined to every face (an all-air chunk, or one not known yet)
};
FaceLinks faceLinks(const PaddedChunk& in); // in.blocks must not be stale

// Where a chunk is solid through and through, for the renderer's occlusion test (docs/ENGINE.md,
// "Occluders"): the chunk's own blocks in columns of kCell x kCell blocks; bit y of
// layers[cz * kCells + cx] is set when every block of column (cx, cz) at height y is solid. Every ray
// from air into such a layer crosses a face some mesh draws, at any level of detail (coarsenPadded covers
// every solid block), so the layers can stand for terrain in front of what they hide.
struct SolidColumns {
    static constexpr int kCell = 8;
    static constexpr int kCells = kChunkSize / kCell;
    std::array<std::uint32_t, kCells * kCells> layers{};
    static constexpr std::size_t index(int cx, int cz) {
        return static_cast<std::size_t>(cz) * kCells + static_cast<std::size_t>(cx);
    }
    std::uint32_t at(int cx, int cz) const { return layers[index(cx, cz)]; }
};
static_assert(kChunkSize == 32, "SolidColumns keeps a chunk's layers in 32-bit masks");
SolidColumns solidColumns(const PaddedChunk& in); // in.blocks must not be stale

// A chunk's solid blocks, as a mesh was made from them: bit x of rows[y * kChunkSize + z] is set when
// block (x, y, z) is solid. The renderer casts rays through those of the chunks around the camera for
// near occluders (docs/ENGINE.md, "Occluders"), which must be exactly the blocks the drawn meshes show.
struct ChunkOccupancy {
    std::array<std::uint32_t, kChunkSize * kChunkSize> rows{};
};
ChunkOccupancy occupancyOf(const PaddedChunk& in); // in.blocks must not be stale

// What the renderer culls a chunk's mesh with, all of the fine chunk whatever the mesh's level of
// detail: its face links, its solid columns and, for a mesh of cell 1 only, its occupancy. Made from
// the padded chunk the mesh was made from, by the render thread and the mesh worker alike.
struct CullingData {
    FaceLinks links = FaceLinks::all(); // all: not known yet
    SolidColumns solid;
    std::shared_ptr<const ChunkOccupancy> occupancy;
};
CullingData cullingDataOf(const PaddedChunk& fine, int cell); // fine.blocks must not be stale

// The mesh of `fine` at a level of detail: cell 1 meshes it as it is, 2 or 4 coarsens it into
// `scratch` first. What both the render thread and the mesh worker build.
void meshAtDetail(const PaddedChunk& fine, MeshMode mode, int cell, PaddedChunk& scratch, ChunkMesh& out);

// A mesh's quads ordered by face direction and, within a direction, by the plane they lie in (their
// chunk-local coordinate along the face's normal, 0..32), nearest first to a camera on the side the
// faces look to (descending planes for a positive face, ascending for a negative one), so that the
// depth test rejects what a nearer plane of the same chunk hides before it is shaded. A face is seen
// from the front only from the side its normal points to, so of a chunk whose extent holds the camera
// along an axis a renderer draws only the planes on the camera's side, leaving out before the vertex
// stage what back-face culling would discard after it.
struct PlaneOrder {
    static constexpr int kPlanes = kChunkSize + 1;
    // Slot of plane p within face f's quads: nearest first, as above.
    static constexpr int slotOf(int face, int plane) { return face % 2 == 0 ? kPlanes - 1 - plane : plane; }
    // Quads of face f in slot k: [start[f * kPlanes + k], start[f * kPlanes + k + 1]).
    std::array<int, kFaceCount * kPlanes + 1> start{};
    // start[face * kPlanes + slot]; slot kPlanes is the next face's first (or the end).
    int at(int face, int slot) const {
        return start[static_cast<std::size_t>(face) * kPlanes + static_cast<std::size_t>(slot)];
    }
    // Quads [first, last) of face f that can face a camera at coordinate t along the face's axis,
    // relative to the chunk's origin: planes p < t for a positive face, p > t for a negative one, and
    // at most the plane through the camera besides (seen edge-on, so back-face culling drops it).
    struct Range {
        int first = 0, last = 0;
    };
    Range visible(int face, float t) const;
};
// Writes mesh's quads to `sorted` (resized to fit) in plane order, stably, and returns the order.
PlaneOrder sortByPlane(const ChunkMesh& mesh, std::vector<ChunkVertex>& sorted);

} // namespace world
