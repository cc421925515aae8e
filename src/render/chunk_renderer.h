// Chunk meshes on the GPU: streams chunks around the camera (generate on the CPU, mesh greedily, upload),
// nearest first within a per-frame time budget so walking never hitches, remeshes chunks whose revision
// changed after an edit, frees what falls out of range, and draws what the frustum can see.
// Reads the world only through its logically-const interface: it never changes the simulation.
// ChunkRenderer is the orchestration; each part is a unit of its own: render/chunk_streaming.h (what is
// meshed when, the worker and the budget), render/chunk_lod.h (at which detail), render/chunk_upload.h
// (GPU buffers, the shader and the draw calls) and render/chunk_visibility.h (what a frame draws).
#pragma once
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/chunk_lod.h"
#include "render/chunk_streaming.h"
#include "render/chunk_upload.h"
#include "render/chunk_visibility.h"
#include "render/gl.h"
#include "world/chunk.h"
#include "world/world.h"

namespace render {

struct ChunkStats {
    int loaded = 0;     // chunks in the world's cache
    int meshes = 0;     // chunks with an up-to-date mesh in range
    int pending = 0;    // chunks in range still waiting for a mesh
    int drawn = 0;      // chunks drawn in the last frame (after frustum and occlusion culling)
    int hidden = 0;     // chunks with something to draw, in the frustum, that occlusion culling left out
    int occluded = 0;   // of those, the ones the walk reached that the occlusion buffer found behind terrain
    int occluders = 0;  // solid boxes drawn into the occlusion buffer (0: it was not used this frame)
    int nearPixels = 0; // of the occlusion buffer's pixels, those the blocks around the camera covered
    // Of the chunks drawn, the columns of 8 x 8 blocks the occluders hid, whose quads were left out
    // (those of a quad that reaches into another column only where that column is hidden too).
    int hiddenColumns = 0;
    int hiddenQuads = 0; // of the quads left in the columns in view, those the occluders hid one by one
    long long triangles = 0;
    int meshedThisFrame = 0; // meshes uploaded in the last update: built on this thread or by the worker
    int meshedByWorker = 0;  // of which the worker built
    int queued = 0;          // jobs queued in the last update, nearest first (this thread takes from the front)
    // Chunks in range showing a mesh older than their blocks and light after the last update (waiting for the
    // worker after an edit), and those meshed on this thread in it because they had waited kLateFrames.
    int stale = 0, completedLate = 0;
    double meshMs = 0.0;  // this thread's time in the last update: applying results, generating, meshing
    bool settled = false; // the last update skipped the scan: nothing in range could need a mesh
};

class ChunkRenderer {
public:
    explicit ChunkRenderer(const std::filesystem::path& dataDir);
    ~ChunkRenderer();
    ChunkRenderer(const ChunkRenderer&) = delete;
    ChunkRenderer& operator=(const ChunkRenderer&) = delete;

    // Brings the meshes within radiusChunks of the camera up to date, nearest first. First the meshes
    // the worker thread finished since the last call are uploaded (if their chunk has not changed
    // since); then the chunks still needed are queued for the worker, and this thread meshes from the
    // front of the same queue until budgetSeconds of CPU time is spent (at least one chunk per call).
    // budgetSeconds <= 0 means everything in range, the worker's jobs included, before returning.
    // With levelOfDetail, distant chunks are meshed from coarser cells (render/chunk_lod.h).
    void update(const world::World& world, const glm::vec3& camera, int radiusChunks, double budgetSeconds,
                bool levelOfDetail = true);

    // viewProjection must be built around the camera (translation removed): drawing is camera-relative.
    // With occlusionCulling, only chunks the camera can see into through the air of the chunks between
    // are drawn (ChunkVisibility::markVisible), and of those only the ones not hidden behind nearer solid
    // terrain (ChunkVisibility::occlude).
    // viewport: the size in pixels of what viewProjection maps the view onto (the chunk shader seals the
    // gaps between quads by a share of a pixel).
    void draw(const glm::mat4& viewProjection, const glm::vec3& camera, glm::ivec2 viewport, GLuint atlasArray,
              const ChunkLighting&, bool occlusionCulling = true);
    const ChunkStats& stats() const { return m_stats; }
    void holdWorker(bool held) { m_streaming.holdWorker(held); } // tests: ChunkStreaming::holdWorker
    void waitForWorker() { m_streaming.waitForWorker(); }        // tests: ChunkStreaming::waitForWorker

private:
    ChunkUpload m_upload;         // the meshes on the GPU, the chunk shader, the draw calls
    ChunkStreaming m_streaming;   // what is meshed when: the worker's queue, the budget, pruning
    ChunkVisibility m_visibility; // which chunks and quads a frame draws
    ChunkStats m_stats;
    int m_radius = 1; // of the last update: draw() draws its disc, the walk keeps within m_radius + 1
};

} // namespace render
