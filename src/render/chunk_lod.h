// Level of detail for chunk meshes: the rings of chunk columns around the camera's chunk, the disc a view
// radius covers and the cell size and mesh mode a chunk is meshed at by its ring. Separate from the
// streaming (which decides when a chunk is meshed) so that a change to the rings, and so to the quads a
// frame draws and the time a chunk takes to mesh, lands in this one file. Pure arithmetic: no GL, no
// world access.
#pragma once
#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "world/chunk.h"
#include "world/mesher.h"

namespace render {

// The chunks a view radius covers: a disc of chunk columns around the camera's (dx, dz in chunks).
// update() meshes these and draw() draws only these, so the picture does not depend on which meshes a
// renderer still holds from an earlier, larger radius or position (it keeps one chunk more, so that
// walking to and fro over a border does not mesh the same chunks again and again).
inline bool inDisc(int dx, int dz, int radius) { return dx * dx + dz * dz <= (radius + 1) * (radius + 1) - 1; }
inline world::ChunkCoord cameraChunk(const glm::vec3& camera) { return world::chunkOf(glm::ivec3(glm::floor(camera))); }

// How a chunk is meshed, by its distance from the camera's chunk (Chebyshev, in chunks): with
// ambient occlusion (GreedyStrips) up to kDetailRadius; unlit beyond (occlusion is about a pixel
// wide there and merging by tile alone cuts a terrain chunk's quads from 2,466 to 1,389 and the
// frame's triangles by 31%, docs/ENGINE.md); with levelOfDetail, from cells of 2 blocks beyond
// kCoarseRadius and of 4 blocks beyond kCoarserRadius (world::coarsenPadded: a third and a tenth
// of the unlit quads).
struct ChunkDetail {
    world::MeshMode mode = world::MeshMode::GreedyStrips;
    int cell = 1; // blocks per cell edge: 1, 2 or 4
    bool operator==(const ChunkDetail&) const = default;
};

// The rings of one update: the camera's chunk and whether level of detail is on (--lod).
class ChunkLod {
public:
    static constexpr int kDetailRadius = 3;
    static constexpr int kCoarseRadius = 4;
    static constexpr int kCoarserRadius = 8;
    static ChunkDetail detailAt(world::ChunkCoord c, world::ChunkCoord center, bool levelOfDetail);

    ChunkLod() = default;
    ChunkLod(world::ChunkCoord center, bool levelOfDetail) : m_center(center), m_levelOfDetail(levelOfDetail) {}
    world::ChunkCoord center() const { return m_center; }
    bool levelOfDetail() const { return m_levelOfDetail; }
    // The detail chunk c is meshed at in this update.
    ChunkDetail detailHere(world::ChunkCoord c) const { return detailAt(c, m_center, m_levelOfDetail); }

private:
    world::ChunkCoord m_center{}; // the camera's chunk in the update
    bool m_levelOfDetail = true;  // the update's --lod
};

} // namespace render
