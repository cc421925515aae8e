#include "world/mesh_worker.h"

#include "world/column_light.h"
#include "world/level_of_detail.h"

#include <algorithm>
#include <memory>
#include <utility>

namespace world {

void gatherPaddedFromTerrain(const TerrainDef& def, ChunkCoord coord, const std::vector<BlockEdit>& edits,
                             PaddedChunk& out) {
    const glm::ivec3 low = chunkOrigin(coord) - glm::ivec3(1);
    generateBox(def, low, glm::ivec3(PaddedChunk::kSize), out.blocks.untrackedData());
    for (const BlockEdit& e : edits) {
        const glm::ivec3 p = e.pos - low;
        if (p.x < 0 || p.y < 0 || p.z < 0 || p.x >= PaddedChunk::kSize || p.y >= PaddedChunk::kSize ||
            p.z >= PaddedChunk::kSize) {
            continue;
        }
        out.blocks.untrackedData()[PaddedChunk::index(p.x, p.y, p.z)] = e.block;
    }
    out.rebuildSolid();
}

MeshWorker::MeshWorker(TerrainDef def) : m_def(def), m_thread([this] { loop(); }) {}

MeshWorker::~MeshWorker() {
    {
        const std::lock_guard lock(m_mutex);
        m_stop = true;
        m_queue.clear();
    }
    m_wake.notify_all();
    m_thread.join();
}

void MeshWorker::submit(std::vector<MeshJob> jobs) {
    {
        const std::lock_guard lock(m_mutex);
        m_queue.clear();
        // Not again what is being meshed or is done and waits to be taken (takeResults): those chunks are still
        // wanted until their results are applied, and meshing one again may light its region again (on the
        // render thread, through takeRegion).
        const auto done = [&](const MeshJob& j) {
            return (m_running && m_running->sameWork(j)) ||
                   std::any_of(m_results.begin(), m_results.end(),
                               [&](const MeshResult& r) { return r.job.sameWork(j); });
        };
        for (MeshJob& j : jobs) {
            if (!done(j)) m_queue.push_back(std::move(j));
        }
    }
    m_wake.notify_one();
}

std::optional<MeshJob> MeshWorker::takeJob() {
    const std::lock_guard lock(m_mutex);
    if (m_queue.empty()) return std::nullopt;
    MeshJob j = std::move(m_queue.front());
    m_queue.pop_front();
    return j;
}

std::vector<MeshJob> MeshWorker::takeRegion() {
    const std::lock_guard lock(m_mutex);
    const auto inRegion = [](const MeshJob& j, ChunkCoord r) { return lightRegionOf(j.coord) == r; };
    const auto first = std::find_if(m_queue.begin(), m_queue.end(),
                                    [&](const MeshJob& j) { return !m_lastRegion || !inRegion(j, *m_lastRegion); });
    std::vector<MeshJob> out;
    if (first == m_queue.end()) return out;
    const ChunkCoord region = lightRegionOf(first->coord);
    std::deque<MeshJob> rest;
    for (MeshJob& j : m_queue) (inRegion(j, region) ? out.emplace_back(std::move(j)) : rest.emplace_back(std::move(j)));
    m_queue.swap(rest);
    return out;
}

MeshResult MeshWorker::run(const TerrainDef& def, MeshJob job) {
    // Two padded chunks of about 48 KB each, kept per thread rather than on its stack.
    thread_local const auto fine = std::make_unique<PaddedChunk>();
    thread_local const auto coarse = std::make_unique<PaddedChunk>();
    // The mesh grows in a buffer kept per thread and leaves in one allocation of its own size: a
    // vector grown from empty for each job copied itself four or five times as it doubled, into
    // fresh pages that the allocator handed back to the system when the result was freed.
    thread_local ChunkMesh scratch;
    gatherAndLight(def, job.coord, job.edits, *fine); // blocks and light from the light region's box
    MeshResult r;
    meshAtDetail(*fine, job.mode, job.cell, *coarse, scratch);
    r.mesh.vertices.assign(scratch.vertices.begin(), scratch.vertices.end());
    r.culling = cullingDataOf(*fine, job.cell);
    job.edits.clear();
    job.edits.shrink_to_fit();
    r.job = std::move(job);
    return r;
}

std::vector<MeshResult> MeshWorker::takeResults() {
    const std::lock_guard lock(m_mutex);
    return std::exchange(m_results, {});
}

void MeshWorker::waitIdle() {
    std::unique_lock lock(m_mutex);
    m_idle.wait(lock, [&] { return (m_held || m_queue.empty()) && !m_running; });
}

void MeshWorker::hold(bool held) {
    {
        const std::lock_guard lock(m_mutex);
        m_held = held;
    }
    m_wake.notify_all();
    m_idle.notify_all();
}

std::size_t MeshWorker::queued() const {
    const std::lock_guard lock(m_mutex);
    return m_queue.size();
}

void MeshWorker::loop() {
    std::unique_lock lock(m_mutex);
    for (;;) {
        m_wake.wait(lock, [&] { return m_stop || (!m_held && !m_queue.empty()); });
        if (m_stop) return;
        MeshJob job = std::move(m_queue.front());
        m_queue.pop_front();
        m_running = job;
        m_running->edits.clear();
        m_lastRegion = lightRegionOf(job.coord);
        lock.unlock();
        MeshResult r = run(m_def, std::move(job));
        lock.lock();
        m_results.push_back(std::move(r));
        m_running.reset();
        if (m_queue.empty()) m_idle.notify_all();
    }
}

} // namespace world
