// What the renderer culls a chunk's mesh with, all made from the padded chunk the mesh was made from:
// which of its faces see each other through its air (FaceLinks), where it is solid through (SolidColumns)
// and its solid blocks (ChunkOccupancy). Pure functions of a padded chunk whose blocks are not stale: they
// never read the world and know nothing of GL (the culling itself is render/chunk_visibility.cpp's).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "world/chunk.h"
#include "world/chunk_vertex.h"
#include "world/padded_chunk.h"

namespace world {

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

} // namespace world
