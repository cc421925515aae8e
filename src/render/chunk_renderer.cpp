#include "render/chunk_renderer.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <climits>
#include <cmath>
#include <glm/common.hpp>
#include <glm/matrix.hpp>
#include <glm/vector_relational.hpp>
#include <limits>
#include <optional>

namespace render {

ChunkRenderer::ChunkRenderer(const std::filesystem::path& dataDir)
    : m_upload(dataDir), m_padded(std::make_unique<world::PaddedChunk>()),
      m_coarse(std::make_unique<world::PaddedChunk>()) {}

ChunkRenderer::~ChunkRenderer() = default;

void ChunkRenderer::startWorld(const world::World& world) {
    m_upload.releaseAll();
    m_worker.reset(); // joins; its results were for the old world
    m_worker = std::make_unique<world::MeshWorker>(world.terrain());
    m_worldIdentity = world.identity();
    m_prunedAround.reset();
    m_settled.reset();
}

// What the worker finished, if it still is what its chunk should show.
void ChunkRenderer::applyWorkerResults(const world::World& world, int radius) {
    for (world::MeshResult& r : m_worker->takeResults()) {
        const world::ChunkCoord c = r.job.coord;
        const Detail detail{r.job.mode, r.job.cell};
        if (world::columnDistance(c, m_lod.center()) > radius + 1 || r.job.revision != world.chunkRevision(c) ||
            detail != m_lod.detailHere(c)) {
            continue; // stale: the chunk changed, or the camera moved it to another level of detail
        }
        GpuMesh& mesh = m_upload.entry(c);
        if (mesh.vao != 0 && mesh.revision == r.job.revision && mesh.detail == detail) continue; // have it
        m_upload.upload(mesh, r.mesh);
        mesh.culling = std::move(r.culling);
        mesh.revision = r.job.revision;
        mesh.detail = detail;
        ++m_stats.meshedThisFrame;
        ++m_stats.meshedByWorker;
    }
}

// Drops what is out of range (with a margin, so walking back and forth over a border does not thrash).
// Meshes are only ever added in range, so nothing can have left it unless the centre or radius moved.
void ChunkRenderer::pruneOutOfRange(int radius) {
    if (m_prunedAround == std::tuple(m_lod.center().x, m_lod.center().z, radius)) return;
    m_upload.releaseIf([&](world::ChunkCoord c) { return world::columnDistance(c, m_lod.center()) > radius + 1; });
    m_prunedAround = std::tuple(m_lod.center().x, m_lod.center().z, radius);
}

// Chunks in a disc around the camera that need a (new) mesh, nearest first.
int ChunkRenderer::gatherCandidates(const world::World& world, int radius) {
    m_candidates.clear();
    const ChunkUpload::Meshes& meshes = m_upload.meshes();
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
                const int dy = y - m_lod.center().y;
                m_candidates.emplace_back(dx * dx + dz * dz + dy * dy, c);
            }
        }
    }
    std::sort(m_candidates.begin(), m_candidates.end(), [](const auto& a, const auto& b) {
        return a.first < b.first || (a.first == b.first && a.second < b.second);
    });
    return total;
}

// The chunks within kNearReach columns of the camera's whose blocks changed since their mesh (an edit) are
// meshed again on this thread in this frame, not queued: the edit shows at once, and the near occluders,
// which need those meshes current, stay on (given to the worker, the chunk of a block just broken was drawn
// as it was, without them, for a frame). Chunks with no mesh yet (loading) or a mesh of another detail
// (after a long jump) take their turn in the queue. They are moved to the front of m_candidates.
std::size_t ChunkRenderer::meshNearEdits(const world::World& world) {
    const ChunkUpload::Meshes& meshes = m_upload.meshes();
    const auto nearEnd = std::stable_partition(m_candidates.begin(), m_candidates.end(), [&](const auto& item) {
        if (world::columnDistance(item.second, m_lod.center()) > ChunkVisibility::kNearReach) return false;
        const auto it = meshes.find(item.second);
        return it != meshes.end() && it->second.detail == m_lod.detailHere(item.second);
    });
    const auto nearCount = static_cast<std::size_t>(nearEnd - m_candidates.begin());
    for (std::size_t i = 0; i < nearCount; ++i) {
        const world::ChunkCoord c = m_candidates[i].second;
        meshHere(world, c, m_lod.detailHere(c), world.chunkRevision(c));
    }
    return nearCount;
}

void ChunkRenderer::meshHere(const world::World& world, world::ChunkCoord c, const Detail& detail,
                             std::uint64_t revision) {
    world.gatherPadded(c, *m_padded);
    world::meshAtDetail(*m_padded, detail.mode, detail.cell, *m_coarse, m_cpuMesh);
    GpuMesh& mesh = m_upload.entry(c);
    m_upload.upload(mesh, m_cpuMesh);
    mesh.culling = world::cullingDataOf(*m_padded, detail.cell);
    mesh.revision = revision;
    mesh.detail = detail;
    ++m_stats.meshedThisFrame;
}

// The worker's queue: the nearest chunks still needed from m_candidates[from], each with the edits it can
// see. The queue is replaced every frame, so it only needs to hold more than a frame of the worker's work.
void ChunkRenderer::queueJobs(const world::World& world, std::size_t from) {
    m_jobs.resize(std::min(m_candidates.size() - from, kMaxJobs));
    for (std::size_t i = 0; i < m_jobs.size(); ++i) {
        const world::ChunkCoord c = m_candidates[from + i].second;
        const Detail detail = m_lod.detailHere(c);
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

void ChunkRenderer::countPending(const world::World& world, int radius, int total) {
    const ChunkUpload::Meshes& meshes = m_upload.meshes();
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

void ChunkRenderer::update(const world::World& world, const glm::vec3& camera, int radius, double budgetSeconds,
                           bool levelOfDetail) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    m_lod = ChunkLod(cameraChunk(camera), levelOfDetail);
    radius = std::max(radius, 1);
    m_radius = radius;
    if (world.identity() != m_worldIdentity || !m_worker) startWorld(world); // nothing cached belongs to it
    m_stats.meshedThisFrame = 0;
    m_stats.meshedByWorker = 0;
    m_stats.queued = 0;
    applyWorkerResults(world, radius);
    pruneOutOfRange(radius);
    world.unloadOutside(m_lod.center(), radius + 2);
    m_visibility.noteAirAround(world, camera);

    const auto finishStats = [&] {
        m_stats.loaded = static_cast<int>(world.loadedChunkCount());
        m_stats.meshMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    };
    if (m_settled && m_settled->x == m_lod.center().x && m_settled->z == m_lod.center().z &&
        m_settled->radius == radius && m_settled->levelOfDetail == levelOfDetail &&
        m_settled->worldRevision == world.revision()) {
        m_stats.settled = true;
        m_stats.pending = 0;
        m_currentReach = INT_MAX;
        m_stats.meshes = m_settled->total;
        finishStats();
        return;
    }
    m_settled.reset();
    m_stats.settled = false;

    const int total = gatherCandidates(world, radius);
    const std::size_t nearCount = meshNearEdits(world);
    queueJobs(world, nearCount);

    // This thread takes from the front of the queue: the nearest chunks are meshed in this frame. It
    // reads the world's loaded chunks, which is faster than the worker's generating from the terrain.
    const bool everything = budgetSeconds <= 0.0;
    for (;;) {
        if (!everything && m_stats.meshedThisFrame > 0 &&
            std::chrono::duration<double>(Clock::now() - start).count() > budgetSeconds) {
            break;
        }
        std::optional<world::MeshJob> job = m_worker->takeJob();
        if (!job) {
            if (!everything || m_candidates.size() - nearCount <= kMaxJobs) break;
            // Meshing everything with more candidates than one queue holds: queue the rest.
            m_worker->waitIdle();
            applyWorkerResults(world, radius);
            return update(world, camera, radius, budgetSeconds, levelOfDetail);
        }
        meshHere(world, job->coord, Detail{job->mode, job->cell}, job->revision);
    }
    if (everything) { // the frame must show everything in range: wait for what the worker has in hand
        m_worker->waitIdle();
        applyWorkerResults(world, radius);
    }
    countPending(world, radius, total);
    finishStats();
}

void ChunkRenderer::draw(const glm::mat4& viewProjection, const glm::vec3& camera, glm::ivec2 viewport,
                         GLuint atlasArray, const ChunkLighting& light, bool occlusionCulling) {
    m_visibility.cull({viewProjection, camera, light.fogEnd, m_radius, occlusionCulling}, m_currentReach, m_upload);
    m_upload.useShader(viewProjection, viewport, atlasArray, light);
    m_upload.uploadPartIndices(m_visibility.partIndices());
    m_stats.drawn = 0;
    m_stats.triangles = 0;
    m_visibility.forEachDraw([&](world::ChunkCoord c, const GpuMesh& mesh, const ChunkVisibility::PartDraw& part) {
        const glm::vec3 offset = glm::vec3(world::chunkOrigin(c)) - camera;
        m_upload.bindChunk(mesh, offset);
        if (part.count >= 0) {
            if (part.count > 0) m_stats.triangles += m_upload.drawPart(part.first, part.count);
        } else {
            visibleRanges(mesh, offset, [&](int from, int to) { m_stats.triangles += m_upload.drawQuads(from, to); });
        }
        ++m_stats.drawn;
    });
    m_upload.endDraw();
    const ChunkVisibility::Stats& v = m_visibility.stats();
    m_stats.hidden = v.hidden;
    m_stats.occluded = v.occluded;
    m_stats.occluders = v.occluders;
    m_stats.nearPixels = v.nearPixels;
    m_stats.hiddenColumns = v.hiddenColumns;
    m_stats.hiddenQuads = v.hiddenQuads;
}

} // namespace render
