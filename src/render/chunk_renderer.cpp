#include "render/chunk_renderer.h"

#include <algorithm>
#include <chrono>

namespace render {

ChunkRenderer::ChunkRenderer(const std::filesystem::path& dataDir) : m_upload(dataDir) {}

ChunkRenderer::~ChunkRenderer() = default;

void ChunkRenderer::update(const world::World& world, const glm::vec3& camera, int radius, double budgetSeconds,
                           bool levelOfDetail) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    radius = std::max(radius, 1);
    m_radius = radius;
    m_streaming.begin(world, ChunkLod(cameraChunk(camera), levelOfDetail), radius, m_upload);
    m_visibility.noteAirAround(world, camera);
    if (!m_streaming.meshInRange(world, budgetSeconds, start, m_upload)) {
        return update(world, camera, radius, budgetSeconds, levelOfDetail); // queues the chunks left over
    }
    const ChunkStreaming::Stats& s = m_streaming.stats();
    m_stats.meshes = s.meshes;
    m_stats.pending = s.pending;
    m_stats.meshedThisFrame = s.meshedThisFrame;
    m_stats.meshedByWorker = s.meshedByWorker;
    m_stats.queued = s.queued;
    m_stats.stale = s.stale;
    m_stats.completedLate = s.completedLate;
    m_stats.settled = s.settled;
    m_stats.loaded = static_cast<int>(world.loadedChunkCount());
    m_stats.meshMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void ChunkRenderer::draw(const glm::mat4& viewProjection, const glm::vec3& camera, glm::ivec2 viewport,
                         GLuint atlasArray, const ChunkLighting& light, bool occlusionCulling) {
    m_visibility.cull({viewProjection, camera, light.fogEnd, m_radius, occlusionCulling}, m_streaming.currentReach(),
                      m_upload);
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
