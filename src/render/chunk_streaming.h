// Streaming of chunk meshes around the camera: which chunks in the view radius need a (new) mesh, nearest
// first; the worker thread's job queue and its results; the chunks meshed on this thread within the
// frame's time budget; what is dropped out of range; and the shortcut once everything in range is
// meshed. Separate from level of detail, culling and the GPU so that a change to when and where chunks
// are meshed (the budget, the queue, the order) lands in this one file. It decides and meshes; the
// meshes themselves live in ChunkUpload, which it hands each one to.
#pragma once
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "render/chunk_lod.h"
#include "render/chunk_upload.h"
#include "world/chunk.h"
#include "world/mesh_worker.h"
#include "world/mesher.h"
#include "world/world.h"

namespace render {

class ChunkStreaming {
public:
    using Clock = std::chrono::steady_clock;
    // Of ChunkStats, the fields this unit fills (ChunkStats says what each means).
    struct Stats {
        int meshes = 0, pending = 0;
        int meshedThisFrame = 0, meshedByWorker = 0, queued = 0;
        int stale = 0, completedLate = 0;
        bool settled = false;
    };
    // Frames a chunk may show a mesh older than its blocks and light (an edit changed them beyond the chunks
    // meshed on this thread at once) while it waits for the worker; then this thread meshes it.
    static constexpr int kLateFrames = 2;

    ChunkStreaming();

    // ChunkRenderer::update is begin, then meshInRange. begin: another world drops every mesh and
    // starts a worker for it; the meshes the worker finished since the last update are uploaded (if
    // their chunk has not changed since); meshes out of range are dropped, and the world's chunks
    // beyond them unloaded. lod: this update's camera chunk and level of detail.
    void begin(const world::World& world, const ChunkLod& lod, int radius, ChunkUpload& meshes);
    // Queues the chunks still needed for the worker, nearest first, and meshes from the front of the
    // same queue on this thread until budgetSeconds since start are spent (at least one chunk);
    // budgetSeconds <= 0 means everything in range, the worker's jobs included. Returns false when
    // that needs more chunks than one queue holds: update() must run again to queue the rest.
    bool meshInRange(const world::World& world, double budgetSeconds, Clock::time_point start, ChunkUpload& meshes);
    // The column distance from the camera's within which every chunk of the last update's disc has a
    // mesh of its current blocks (nothing pending there).
    int currentReach() const { return m_currentReach; }
    const Stats& stats() const { return m_stats; }
    // Tests: the worker starts no job while held (world::MeshWorker::hold), this world's worker and the next's.
    void holdWorker(bool held);
    void waitForWorker() { // tests: until the worker has run every job queued (its results wait for begin)
        if (m_worker) m_worker->waitIdle();
    }

    // A candidate: its key (its column's squared distance from the camera's times kHeights plus its squared height
    // difference from the camera's chunk, held under kHeights: the camera may fly far above the world) and its chunk.
    using Candidate = std::pair<int, world::ChunkCoord>;
    static constexpr int kHeights = 1 << 12;
    // The order chunks are meshed in: light region by light region (a region's columns one after another, so a
    // thread lights each region once while it keeps it), regions by their column nearest `centre`; within a
    // region, columns nearest first, and a column's chunks nearest the camera's height first. `scratch` holds the
    // keys (computed once a candidate, not once a comparison).
    using CandidateKey = std::pair<std::array<int, 8>, Candidate>;
    static void orderCandidates(world::ChunkCoord centre, std::vector<Candidate>& candidates,
                                std::vector<CandidateKey>& scratch);

private:
    // The steps of update(), in its order (m_lod: this update's camera chunk and detail).
    void startWorld(const world::World& world, ChunkUpload& meshes); // another world: everything cached is dropped
    void applyWorkerResults(const world::World& world, int radius, ChunkUpload& meshes);
    void uploadResult(world::MeshResult r, ChunkUpload& meshes); // its mesh and culling data, as its chunk's
    void pruneOutOfRange(int radius, ChunkUpload& meshes);
    // fills m_candidates; returns chunks in range
    int gatherCandidates(const world::World& world, int radius, const ChunkUpload& upload);
    // returns how many candidates it meshed
    std::size_t meshNearEdits(const world::World& world, ChunkUpload& upload);
    // Meshes here the candidates (from m_candidates[from]) that have shown an old mesh for kLateFrames.
    void completeLate(const world::World& world, std::size_t from, ChunkUpload& upload);
    void meshHere(const world::World& world, world::ChunkCoord c, const ChunkDetail& detail, std::uint64_t revision,
                  ChunkUpload& meshes);
    void queueJobs(const world::World& world, std::size_t from);
    void countPending(const world::World& world, int radius, int total, const ChunkUpload& upload);

    Stats m_stats;
    ChunkLod m_lod;   // this update's rings: the camera's chunk and --lod
    int m_radius = 1; // this update's
    std::unique_ptr<world::PaddedChunk> m_padded, m_coarse;
    world::ChunkMesh m_cpuMesh;
    std::vector<world::BlockEdit> m_edits; // meshHere's: the edits its chunk's light region's box holds
    std::vector<Candidate> m_candidates;
    std::vector<CandidateKey> m_keyed;           // orderCandidates' scratch
    std::unique_ptr<world::MeshWorker> m_worker; // for the world m_worldIdentity names
    bool m_holdWorker = false;
    std::vector<world::MeshJob> m_jobs;
    static constexpr std::size_t kMaxJobs = 512; // the worker's queue: more than a loading frame's work
    std::uint64_t m_worldIdentity = 0;
    // The camera's chunk column and the radius when meshes out of range were last dropped: only a move
    // to another column or a new radius can put any out of range, so the (cache-missing) walk over
    // every mesh is skipped otherwise.
    std::optional<std::tuple<int, int, int>> m_prunedAround;
    // What the last update saw when it left nothing pending: the camera's chunk column, radius, level
    // of detail on, the world's revision. While all four stay the same no chunk can need a (new) mesh
    // (neither the range nor the level of detail depends on the camera's height), so update() looks up
    // no chunk in range (thousands of hash look-ups a frame at radius 12).
    struct Settled {
        int x, z;
        int radius;
        bool levelOfDetail;
        std::uint64_t worldRevision;
        int total; // chunks in range
    };
    std::optional<Settled> m_settled;
    int m_currentReach = 0; // currentReach()
    long long m_frame = 0;  // updates so far
    // Chunks showing a mesh older than their blocks and light, and the update that first saw each so.
    std::unordered_map<world::ChunkCoord, long long, world::ChunkCoordHash> m_staleSince, m_stillStale;
};

} // namespace render
