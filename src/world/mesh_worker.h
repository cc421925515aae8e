// Chunk meshes built off the render thread: one worker thread takes jobs (nearest first), cuts the
// padded chunk and its light out of its light region's box, built from the terrain and a snapshot of the
// edits around it (gatherAndLight), and meshes it.
// A job carries everything it needs (the terrain definition, the edits, the level of detail), so the
// worker never reads the World, which is not thread-safe: the simulation cannot see it at all. The
// caller applies results at a point of its choosing (the renderer: the start of a frame), and may run
// queued jobs itself (takeJob, then run) so that the chunks it needs now are meshed in this frame.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "world/chunk.h"
#include "world/culling_data.h"
#include "world/mesher.h"
#include "world/terrain.h"
#include "world/world.h"

namespace world {

struct MeshJob {
    ChunkCoord coord;
    std::uint64_t revision = 0; // World::chunkRevision when the job was made
    MeshMode mode = MeshMode::GreedyStrips;
    int cell = 1;                 // level of detail: 1, 2 or 4 blocks per cell (coarsenPadded)
    std::vector<BlockEdit> edits; // every edit in the light region's box (World::editsAround)
    bool sameWork(const MeshJob& o) const {
        return coord == o.coord && revision == o.revision && mode == o.mode && cell == o.cell;
    }
};

struct MeshResult {
    MeshJob job; // its edits emptied
    ChunkMesh mesh;
    CullingData culling;
};

// The padded chunk of `coord` from the terrain alone plus `edits` (positions in world blocks; those
// outside the padded box are ignored): the same blocks World::gatherPadded gives.
void gatherPaddedFromTerrain(const TerrainDef& def, ChunkCoord coord, const std::vector<BlockEdit>& edits,
                             PaddedChunk& out);

class MeshWorker {
public:
    explicit MeshWorker(TerrainDef def);
    ~MeshWorker(); // finishes the job in hand, drops the queue, joins
    MeshWorker(const MeshWorker&) = delete;
    MeshWorker& operator=(const MeshWorker&) = delete;

    const TerrainDef& terrain() const { return m_def; }
    // Replaces the queue with `jobs` (in the order given: nearest first), leaving out the one the
    // worker is running if it is the same work.
    void submit(std::vector<MeshJob> jobs);
    // The next queued job, taken off the queue, for the caller to run itself.
    std::optional<MeshJob> takeJob();
    // Every queued job of the first light region (world::lightRegionOf) in the queue that the worker is not
    // lighting (the region of the job it runs, or else of the last it ran), taken off the queue, in queue order:
    // a caller that runs them lights that region once, and the worker never lights it too. Empty when every
    // queued job is in the worker's region (the worker goes on with them).
    std::vector<MeshJob> takeRegion();
    // Builds one job's mesh on the calling thread (what the worker does with each job).
    static MeshResult run(const TerrainDef& def, MeshJob job);
    // Finished results, oldest first; empties the list.
    std::vector<MeshResult> takeResults();
    // Blocks until the queue is empty (or the worker is held) and no job is running.
    void waitIdle();
    // While held the worker starts no job (the one in hand is finished): the caller meshes everything itself.
    // For tests that need chunks to stay queued until the render thread completes them late.
    void hold(bool held);
    std::size_t queued() const;

private:
    void loop();

    const TerrainDef m_def;
    mutable std::mutex m_mutex;
    std::condition_variable m_wake, m_idle;
    std::deque<MeshJob> m_queue;
    std::optional<MeshJob> m_running;       // what the worker is meshing (edits emptied)
    std::optional<ChunkCoord> m_lastRegion; // the light region of the job the worker ran or runs last
    std::vector<MeshResult> m_results;
    bool m_stop = false;
    bool m_held = false;
    std::thread m_thread; // last: started once everything above exists
};

} // namespace world
