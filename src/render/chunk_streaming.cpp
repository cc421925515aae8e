// Streaming of chunk meshes around the camera: the worker's queue, the frame's meshing budget, pruning
// (chunk_streaming.h says why this is a unit of its own).
#include "render/chunk_streaming.h"

#include <algorithm>
#include <climits>

#include "world/column_light.h"
#include "world/level_of_detail.h"

#include "render/chunk_visibility.h" // kNearReach: the near occluders need those meshes current

namespace render {

ChunkStreaming::ChunkStreaming()
    : m_padded(std::make_unique<world::PaddedChunk>()), m_coarse(std::make_unique<world::PaddedChunk>()) {}

void ChunkStreaming::begin(const world::World& world, const ChunkLod& lod, int radius, ChunkUpload& meshes) {
    m_lod = lod;
    m_radius = radius;
    if (world.identity() != m_worldIdentity || !m_worker) startWorld(world, meshes); // nothing cached belongs to it
    ++m_frame;
    m_stats.meshedThisFrame = 0;
    m_stats.meshedByWorker = 0;
    m_stats.queued = 0;
    m_stats.stale = 0;
    m_stats.completedLate = 0;
    applyWorkerResults(world, radius, meshes);
    pruneOutOfRange(radius, meshes);
    world.unloadOutside(m_lod.center(), radius + 2);
}

bool ChunkStreaming::meshInRange(const world::World& world, double budgetSeconds, Clock::time_point start,
                                 ChunkUpload& meshes) {
    if (m_settled && m_settled->x == m_lod.center().x && m_settled->z == m_lod.center().z &&
        m_settled->radius == m_radius && m_settled->levelOfDetail == m_lod.levelOfDetail() &&
        m_settled->worldRevision == world.revision()) {
        m_stats.settled = true;
        m_stats.pending = 0;
        m_currentReach = INT_MAX;
        m_stats.meshes = m_settled->total;
        m_staleSince.clear();
        return true;
    }
    m_settled.reset();
    m_stats.settled = false;

    const int total = gatherCandidates(world, m_radius, meshes);
    const std::size_t nearCount = meshNearEdits(world, meshes);
    completeLate(world, nearCount, meshes);
    queueJobs(world, nearCount);

    // This thread takes from the front of the queue: the nearest chunks are meshed in this frame, as the
    // worker meshes them (MeshWorker::run: blocks and light cut from the light region's box, which has to be
    // built for the light anyway; the World's chunks are not loaded for it).
    const bool everything = budgetSeconds <= 0.0;
    for (;;) {
        if (!everything && m_stats.meshedThisFrame > 0 &&
            std::chrono::duration<double>(Clock::now() - start).count() > budgetSeconds) {
            break;
        }
        // A light region at a time, never the one the worker is lighting: the two threads do not both light
        // one (each region's jobs are together in the queue, gatherCandidates' order).
        std::vector<world::MeshJob> jobs = m_worker->takeRegion();
        if (jobs.empty()) {
            if (!everything || m_candidates.size() - nearCount <= kMaxJobs) break;
            // Meshing everything with more candidates than one queue holds: queue the rest.
            m_worker->waitIdle();
            applyWorkerResults(world, m_radius, meshes);
            return false;
        }
        for (world::MeshJob& job : jobs) {
            uploadResult(world::MeshWorker::run(world.terrain(), std::move(job)), meshes);
            ++m_stats.meshedThisFrame;
        }
    }
    if (everything) { // the frame must show everything in range: wait for what the worker has in hand
        m_worker->waitIdle();
        applyWorkerResults(world, m_radius, meshes);
    }
    countPending(world, m_radius, total, meshes);
    return true;
}

void ChunkStreaming::holdWorker(bool held) {
    m_holdWorker = held;
    if (m_worker) m_worker->hold(held);
}

void ChunkStreaming::startWorld(const world::World& world, ChunkUpload& meshes) {
    meshes.releaseAll();
    m_worker.reset(); // joins; its results were for the old world
    m_worker = std::make_unique<world::MeshWorker>(world.terrain());
    m_worker->hold(m_holdWorker);
    m_worldIdentity = world.identity();
    m_prunedAround.reset();
    m_settled.reset();
}

// What the worker finished, if it still is what its chunk should show.
void ChunkStreaming::applyWorkerResults(const world::World& world, int radius, ChunkUpload& meshes) {
    for (world::MeshResult& r : m_worker->takeResults()) {
        const world::ChunkCoord c = r.job.coord;
        const ChunkDetail detail{r.job.mode, r.job.cell};
        if (world::columnDistance(c, m_lod.center()) > radius + 1 || r.job.revision != world.chunkRevision(c) ||
            detail != m_lod.detailHere(c)) {
            continue; // stale: the chunk changed, or the camera moved it to another level of detail
        }
        const GpuMesh& have = meshes.entry(c);
        if (have.vao != 0 && have.revision == r.job.revision && have.detail == detail) continue; // have it
        uploadResult(std::move(r), meshes);
        ++m_stats.meshedThisFrame;
        ++m_stats.meshedByWorker;
    }
}

void ChunkStreaming::uploadResult(world::MeshResult r, ChunkUpload& meshes) {
    GpuMesh& mesh = meshes.entry(r.job.coord);
    meshes.upload(mesh, r.mesh);
    mesh.culling = std::move(r.culling);
    mesh.revision = r.job.revision;
    mesh.detail = ChunkDetail{r.job.mode, r.job.cell};
}

// Drops what is out of range (with a margin, so walking back and forth over a border does not thrash).
// Meshes are only ever added in range, so nothing can have left it unless the centre or radius moved.
void ChunkStreaming::pruneOutOfRange(int radius, ChunkUpload& meshes) {
    if (m_prunedAround == std::tuple(m_lod.center().x, m_lod.center().z, radius)) return;
    meshes.releaseIf([&](world::ChunkCoord c) { return world::columnDistance(c, m_lod.center()) > radius + 1; });
    m_prunedAround = std::tuple(m_lod.center().x, m_lod.center().z, radius);
}

void ChunkStreaming::orderCandidates(world::ChunkCoord centre, std::vector<Candidate>& candidates,
                                     std::vector<CandidateKey>& scratch) {
    // Each key is computed once: the sort compares about log2(n) times a candidate, and at radius 32 (17,000
    // candidates, ordered again for every queue of kMaxJobs while a view streams in) computing the keys in the
    // comparisons was a tenth of the CPU.
    const auto nearest = [](int camera, int first) {
        return std::clamp(camera, first, first + world::kLightRegion - 1) - camera;
    };
    scratch.clear();
    for (const Candidate& item : candidates) {
        const world::ChunkCoord r = world::lightRegionOf(item.second);
        const int rx = nearest(centre.x, r.x * world::kLightRegion), rz = nearest(centre.z, r.z * world::kLightRegion);
        scratch.push_back({{rx * rx + rz * rz, r.x, r.z, item.first / kHeights, item.second.x, item.second.z,
                            item.first % kHeights, item.second.y},
                           item});
    }
    std::sort(scratch.begin(), scratch.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < scratch.size(); ++i) candidates[i] = scratch[i].second;
}

// Chunks in a disc around the camera that need a (new) mesh, nearest first.
int ChunkStreaming::gatherCandidates(const world::World& world, int radius, const ChunkUpload& upload) {
    m_candidates.clear();
    const ChunkUpload::Meshes& meshes = upload.meshes();
    int total = 0;
    for (int dz = -radius; dz <= radius; ++dz) {
        for (int dx = -radius; dx <= radius; ++dx) {
            if (!inDisc(dx, dz, radius)) continue;
            for (int y = 0; y < world::kWorldHeightChunks; ++y) {
                const world::ChunkCoord c{m_lod.center().x + dx, y, m_lod.center().z + dz};
                ++total;
                const auto it = meshes.find(c);
                if (it != meshes.end() && it->second.revision == world.chunkRevision(c) &&
                    it->second.detail == m_lod.detailHere(c)) {
                    continue;
                }
                // A column's chunks one after another, nearest height first (the sort below): its light region's
                // light is computed once for all of them (world/column_light.h).
                const int dy = y - m_lod.center().y;
                m_candidates.emplace_back((dx * dx + dz * dz) * kHeights + std::min(dy * dy, kHeights - 1), c);
            }
        }
    }
    orderCandidates(m_lod.center(), m_candidates, m_keyed);
    return total;
}

// The chunks within kNearReach columns of the camera's whose blocks changed since their mesh (an edit) are
// meshed again on this thread in this frame, not queued: the edit shows at once, and the near occluders,
// which need those meshes current, stay on (given to the worker, the chunk of a block just broken was drawn
// as it was, without them, for a frame). Chunks with no mesh yet (loading) or a mesh of another detail
// (after a long jump) take their turn in the queue. They are moved to the front of m_candidates.
std::size_t ChunkStreaming::meshNearEdits(const world::World& world, ChunkUpload& upload) {
    const ChunkUpload::Meshes& meshes = upload.meshes();
    const auto nearEnd = std::stable_partition(m_candidates.begin(), m_candidates.end(), [&](const auto& item) {
        if (world::columnDistance(item.second, m_lod.center()) > ChunkVisibility::kNearReach) return false;
        const auto it = meshes.find(item.second);
        return it != meshes.end() && it->second.detail == m_lod.detailHere(item.second);
    });
    const auto nearCount = static_cast<std::size_t>(nearEnd - m_candidates.begin());
    for (std::size_t i = 0; i < nearCount; ++i) {
        const world::ChunkCoord c = m_candidates[i].second;
        meshHere(world, c, m_lod.detailHere(c), world.chunkRevision(c), upload);
    }
    return nearCount;
}

void ChunkStreaming::completeLate(const world::World& world, std::size_t from, ChunkUpload& upload) {
    const ChunkUpload::Meshes& meshes = upload.meshes();
    m_stillStale.clear();
    for (std::size_t i = from; i < m_candidates.size(); ++i) {
        const world::ChunkCoord c = m_candidates[i].second;
        const auto it = meshes.find(c);
        if (it == meshes.end() || it->second.detail != m_lod.detailHere(c)) continue; // not shown yet: loading
        const auto seen = m_staleSince.find(c);
        const long long since = seen == m_staleSince.end() ? m_frame : seen->second;
        if (m_frame - since >= kLateFrames) {
            meshHere(world, c, m_lod.detailHere(c), world.chunkRevision(c), upload);
            ++m_stats.completedLate;
            m_candidates[i].first = -1; // done: not queued below
            continue;
        }
        m_stillStale.emplace(c, since);
    }
    m_staleSince.swap(m_stillStale);
    if (m_stats.completedLate > 0) {
        m_candidates.erase(std::remove_if(m_candidates.begin() + static_cast<std::ptrdiff_t>(from), m_candidates.end(),
                                          [](const auto& item) { return item.first < 0; }),
                           m_candidates.end());
    }
    m_stats.stale = static_cast<int>(m_staleSince.size());
}

void ChunkStreaming::meshHere(const world::World& world, world::ChunkCoord c, const ChunkDetail& detail,
                              std::uint64_t revision, ChunkUpload& meshes) {
    world.gatherPadded(c, *m_padded);
    world.editsAround(c, m_edits);
    world::lightPadded(world.terrain(), c, m_edits, m_padded->light);
    world::meshAtDetail(*m_padded, detail.mode, detail.cell, *m_coarse, m_cpuMesh);
    GpuMesh& mesh = meshes.entry(c);
    meshes.upload(mesh, m_cpuMesh);
    mesh.culling = world::cullingDataOf(*m_padded, detail.cell);
    mesh.revision = revision;
    mesh.detail = detail;
    ++m_stats.meshedThisFrame;
}

// The worker's queue: the nearest chunks still needed from m_candidates[from], each with the edits it can
// see. The queue is replaced every frame, so it must hold more than a frame of the worker's work: a frame while a
// view loads at 1280x720 takes about 30 ms on llvmpipe, more than 128 jobs (many of them air) keep it busy.
void ChunkStreaming::queueJobs(const world::World& world, std::size_t from) {
    m_jobs.resize(std::min(m_candidates.size() - from, kMaxJobs));
    for (std::size_t i = 0; i < m_jobs.size(); ++i) {
        const world::ChunkCoord c = m_candidates[from + i].second;
        const ChunkDetail detail = m_lod.detailHere(c);
        world::MeshJob& j = m_jobs[i];
        j.coord = c;
        j.revision = world.chunkRevision(c);
        j.mode = detail.mode;
        j.cell = detail.cell;
        world.editsAround(c, j.edits);
    }
    m_stats.queued = static_cast<int>(m_jobs.size());
    m_worker->submit(std::move(m_jobs));
    m_jobs.clear();
}

void ChunkStreaming::countPending(const world::World& world, int radius, int total, const ChunkUpload& upload) {
    const ChunkUpload::Meshes& meshes = upload.meshes();
    int pending = 0;
    m_currentReach = INT_MAX;
    for (const auto& [dist, c] : m_candidates) {
        const auto it = meshes.find(c);
        if (it == meshes.end() || it->second.revision != world.chunkRevision(c) ||
            it->second.detail != m_lod.detailHere(c)) {
            ++pending;
            m_currentReach = std::min(m_currentReach, world::columnDistance(c, m_lod.center()) - 1);
        }
    }
    m_stats.pending = pending;
    m_stats.meshes = total - pending;
    if (pending == 0)
        m_settled = Settled{m_lod.center().x, m_lod.center().z, radius, m_lod.levelOfDetail(), world.revision(), total};
}

} // namespace render
