// Which chunks, and which of their quads, a frame draws: the frustum, the disc and the fog; the
// occlusion walk through the chunks' air; the occluders (solid columns and the blocks around the
// camera) drawn into a CPU depth buffer (render/occlusion_buffer.h), and the chunks, columns and quads
// they hide; and the faces that can face the camera. Separate from streaming and upload so that a change
// to the culling, the frame's triangles and the CPU time spent on them, lands in this one file. It only
// reads the meshes (render/chunk_upload.h) and issues no GL call: ChunkRenderer::draw draws its list.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <utility>
#include <vector>

#include "render/chunk_upload.h"
#include "render/frustum.h"
#include "render/occlusion_buffer.h"
#include "world/chunk.h"
#include "world/chunk_vertex.h"
#include "world/culling_data.h"
#include "world/plane_order.h"
#include "world/world.h"

namespace render {

// A face can be seen only from the side its normal points to: of each direction, the planes on the
// camera's side (all of them, or none, for a chunk the camera is not level with). Calls range(from, to)
// for each run of the mesh's quads (in drawing order) that can face the camera; offset is the chunk's
// origin relative to the camera.
template <class Range>
void visibleRanges(const GpuMesh& mesh, const glm::vec3& offset, Range&& range) {
    int first = 0, last = 0; // a run of quads not drawn yet: neighbouring ranges are merged into one
    for (int f = 0; f < world::kFaceCount; ++f) {
        const world::PlaneOrder::Range r = mesh.order.visible(f, -offset[f / 2]);
        if (r.first == r.last) continue;
        if (r.first != last) {
            if (last > first) range(first, last);
            first = r.first;
        }
        last = r.last;
    }
    if (last > first) range(first, last);
}

// What one frame is culled for.
struct ChunkView {
    glm::mat4 viewProjection; // built around the camera (translation removed)
    glm::vec3 camera;
    float fogEnd;          // blocks: nothing beyond is drawn
    int radius;            // the last update's: its disc is drawn, the walk keeps within radius + 1
    bool occlusionCulling; // the walk and the occluders (--occlusion-culling)
};

class ChunkVisibility {
public:
    // Of ChunkStats, the fields this unit fills (ChunkStats says what each means).
    struct Stats {
        int hidden = 0, occluded = 0, occluders = 0, nearPixels = 0, hiddenColumns = 0, hiddenQuads = 0;
    };
    // Per chunk to draw: its columns hidden, and where its indices start in partIndices() and how many
    // there are (count -1: no quad hidden, drawn from the shared index buffer).
    struct PartDraw {
        std::uint16_t hidden = 0;
        std::size_t first = 0;
        long long count = -1;
    };

    // Occluders come from the chunk columns within kOccluderReach of the camera's (Chebyshev), each
    // the top kOccluderDepth blocks of a column's highest solid run: a slab's farthest corner is nearer
    // than a whole hill's, and lower down the terrain in front covers the screen (docs/ENGINE.md
    // measures both choices).
    static constexpr int kOccluderReach = 2;
    static constexpr int kOccluderDepth = 8;
    // And block by block from the chunks within kNearReach of the camera's (the meshes' occupancy),
    // by rays out to kNearDepth blocks of view depth: trees, walls and the hill in front, which no
    // column of 8 x 8 blocks is solid through.
    static constexpr int kNearReach = 1;
    static constexpr float kNearDepth = 32.0f;

    // In update(): which blocks around the camera are air (occlusion culling needs the near plane in air).
    void noteAirAround(const world::World& world, const glm::vec3& camera);
    // In draw(): chooses the chunks to draw, nearest first, and which of their quads (forEachDraw,
    // partIndices). currentReach: the column distance from the camera's within which every chunk of the
    // last update's disc has a mesh of its current blocks (ChunkStreaming::currentReach).
    void cull(const ChunkView& view, int currentReach, const ChunkUpload& meshes);
    // The last cull's chunks, nearest first: f(coord, mesh, part) for each.
    template <class F>
    void forEachDraw(F&& f) const {
        for (const std::size_t i : m_drawOrder)
            f(m_drawList[i].second->first, m_drawList[i].second->second, m_partDraws[i]);
    }
    // The last cull's indices of the chunks with some quads hidden (their other quads, in drawing order).
    const std::vector<std::uint32_t>& partIndices() const { return m_partIndices; }
    const Stats& stats() const { return m_stats; }

private:
    // Whether the camera and the near plane lie in air, by the blocks around the camera update() saw.
    // Occlusion culling needs it: from inside a block, rays pass through rock to faces behind it.
    bool nearPlaneInAir(const glm::mat4& viewProjection, const glm::vec3& camera) const;
    std::size_t gridCell(world::ChunkCoord c) const;
    // Occlusion culling: walks from the camera's chunk through chunk faces, entering a chunk by one face
    // and leaving by another only if its air joins the two (FaceLinks), never turning back along an
    // axis, and only into chunks the frustum touches. Every chunk a line of sight from the camera
    // passes through is reached this way, so nothing visible is left out. Chunks without a mesh yet
    // count as open. Marks the chunks reached with m_frame; every chunk unless nearInAir.
    void markVisible(const Frustum& frustum, const glm::vec3& camera, bool nearInAir, int radius,
                     const ChunkUpload& meshes);
    // Fills m_occlusion with the solid columns of the chunks around the camera (SolidColumns) and the
    // solid blocks of those next to it (ChunkOccupancy), when that is safe this frame; returns whether
    // it did. Needs markVisible's grid and the near plane in
    // air. Safe means: every ray from the near plane to an occluder crosses a face that this frame
    // draws, so every chunk between is meshed as its blocks are now and drawn (in the disc, the fog
    // and up to date). docs/ENGINE.md, "Occluders".
    bool occlude(const glm::mat4& viewProjection, const glm::vec3& camera, float fogEnd, int radius, int currentReach);
    // The columns of the mesh's quads (GpuMesh::spans) that the occluders hide, bit
    // SolidColumns::index(cx, cz) each, and the columns with quads; offset is the chunk's origin
    // relative to the camera. The whole chunk is hidden when the two are equal.
    struct HiddenColumns {
        std::uint16_t hidden = 0, withQuads = 0;
    };
    HiddenColumns hiddenColumns(const GpuMesh& mesh, const glm::vec3& offset) const;
    // The steps of cull() after the walk and the occluders: the chunks to draw, nearest first; then the
    // indices of the quads of those with some hidden.
    void chooseChunks(const Frustum& frustum, const ChunkView& view, bool occluding, const ChunkUpload& meshes);
    void writePartIndices(const glm::vec3& camera, bool occluding);

    Stats m_stats;
    std::uint64_t m_frame = 0;
    std::vector<std::pair<float, const std::pair<const world::ChunkCoord, GpuMesh>*>> m_drawList;
    std::vector<PartDraw> m_partDraws;    // per entry of m_drawList
    std::vector<std::size_t> m_drawOrder; // m_drawList's entries, nearest first
    std::vector<std::uint32_t> m_partIndices;
    // The meshes with quads and their chunks, in a flat list rebuilt only when one is uploaded or
    // released: the draw list is chosen from it each frame, reading a mesh only for chunks in the disc,
    // the fog and the frustum.
    std::vector<std::pair<world::ChunkCoord, const std::pair<const world::ChunkCoord, GpuMesh>*>> m_drawable;
    std::uint64_t m_drawableVersion = 0; // ChunkUpload::version() when m_drawable was built
    // markVisible's meshes by position in the box of chunks around the camera (nullptr: none), at
    // gridCell(c) for a chunk within m_gridReach columns of m_gridAt and in the world's height.
    std::vector<const GpuMesh*> m_grid;
    std::pair<int, int> m_gridAt{0, 0}; // the camera's chunk column when m_grid was built
    int m_gridReach = -1;
    std::uint64_t m_gridVersion = 0; // ChunkUpload::version() when m_grid was built
    struct Step {
        world::ChunkCoord c;
        int entry; // the face it was entered by
    };
    std::vector<Step> m_walk;
    std::vector<std::uint8_t> m_entered; // faces entered by, per chunk of the walk's box (markVisible)

    SolidGrid m_nearGrid; // occlude()'s scratch
    OcclusionBuffer m_occlusion;
    std::vector<std::array<std::uint32_t, world::kWorldHeightChunks>> m_columnLayers; // occlude()'s scratch
    // From the last update: the camera it was given, and which of the 3 x 3 x 3 blocks around the
    // camera's are air (bit dx + 3 dy + 9 dz for the camera's block plus (dx, dy, dz) - 1).
    glm::vec3 m_updateCamera{0.0f};
    std::uint32_t m_airAround = 0;
};

} // namespace render
