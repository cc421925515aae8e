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

// Which blocks around the camera are air: occlusion culling needs the near plane in air.
void ChunkRenderer::noteAirAround(const world::World& world, const glm::vec3& camera) {
    m_updateCamera = camera;
    m_airAround = 0;
    const glm::ivec3 cameraBlock(glm::floor(camera));
    for (int i = 0; i < 27; ++i) {
        const glm::ivec3 b = cameraBlock + glm::ivec3(i % 3 - 1, i / 3 % 3 - 1, i / 9 - 1);
        if (!world::isSolid(world.get(b))) m_airAround |= 1u << i;
    }
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
        if (world::columnDistance(item.second, m_lod.center()) > kNearReach) return false;
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
    noteAirAround(world, camera);

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

std::size_t ChunkRenderer::gridCell(world::ChunkCoord c) const {
    const std::size_t side = 2 * static_cast<std::size_t>(m_gridReach) + 1;
    return (static_cast<std::size_t>(c.y) * side + static_cast<std::size_t>(c.z - m_gridAt.second + m_gridReach)) *
               side +
           static_cast<std::size_t>(c.x - m_gridAt.first + m_gridReach);
}

bool ChunkRenderer::nearPlaneInAir(const glm::mat4& viewProjection, const glm::vec3& camera) const {
    if (camera != m_updateCamera) return false; // update() looked at the blocks around another place
    const glm::mat4 inverse = glm::inverse(viewProjection);
    glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
    for (int i = 0; i < 4; ++i) {
        const glm::vec4 p = inverse * glm::vec4((i & 1) != 0 ? 1.0f : -1.0f, (i & 2) != 0 ? 1.0f : -1.0f, -1.0f, 1.0f);
        if (!(std::abs(p.w) > 0.0f)) return false;
        const glm::vec3 corner = camera + glm::vec3(p) / p.w;
        low = glm::min(low, corner);
        high = glm::max(high, corner);
    }
    // The near rectangle and the camera (the rays' common start) in air.
    low = glm::min(low, camera);
    high = glm::max(high, camera);
    const glm::ivec3 cameraBlock(glm::floor(camera)), from(glm::floor(low)), to(glm::floor(high));
    if (glm::any(glm::lessThan(from, cameraBlock - 1)) || glm::any(glm::greaterThan(to, cameraBlock + 1))) {
        return false; // a near plane wider than the blocks update() looked at
    }
    for (int y = from.y; y <= to.y; ++y)
        for (int z = from.z; z <= to.z; ++z)
            for (int x = from.x; x <= to.x; ++x) {
                const glm::ivec3 d = glm::ivec3(x, y, z) - cameraBlock + 1;
                if ((m_airAround >> (d.x + 3 * d.y + 9 * d.z) & 1u) == 0) return false;
            }
    return true;
}

void ChunkRenderer::markVisible(const Frustum& frustum, const glm::vec3& camera, bool nearInAir) {
    ++m_frame;
    const world::ChunkCoord start = cameraChunk(camera);
    const auto inFrustum = [&](world::ChunkCoord c) {
        const glm::vec3 low = glm::vec3(world::chunkOrigin(c)) - camera;
        return frustum.intersectsBox(low, low + glm::vec3(static_cast<float>(world::kChunkSize)));
    };
    // Outside the world's height, or looking from inside a block (the rays start in rock and can reach
    // faces behind it, through no air): no walk.
    if (start.y < 0 || start.y >= world::kWorldHeightChunks || !nearInAir) {
        for (const auto& [c, mesh] : m_upload.meshes()) mesh.seenInFrame = m_frame;
        return;
    }
    const auto step = [](world::ChunkCoord c, int face) {
        return world::ChunkCoord{c.x + world::kFaceNormals[face][0], c.y + world::kFaceNormals[face][1],
                                 c.z + world::kFaceNormals[face][2]};
    };
    const auto opposite = [](int face) { return face ^ 1; }; // +X -X, +Y -Y, +Z -Z pairs
    // The walk stays within the chunks kept around the camera: columns within `reach` = m_radius + 1
    // (Chebyshev, in chunks), a box side x side x kWorldHeightChunks. Its meshes and the faces each
    // chunk was entered by live in flat arrays over that box rather than in hash maps; the meshes'
    // array is rebuilt only when a mesh is uploaded or released, the camera enters another column or
    // the radius changes.
    const int reach = m_radius + 1, side = 2 * reach + 1;
    const auto inBox = [&](world::ChunkCoord c) {
        return c.y >= 0 && c.y < world::kWorldHeightChunks && world::columnDistance(c, start) <= reach;
    };
    const std::size_t cells =
        static_cast<std::size_t>(side) * static_cast<std::size_t>(side) * world::kWorldHeightChunks;
    const std::pair<int, int> gridAt(start.x, start.z);
    if (m_gridVersion != m_upload.version() || m_gridReach != reach || m_gridAt != gridAt) {
        m_gridVersion = m_upload.version();
        m_gridReach = reach;
        m_gridAt = gridAt;
        m_grid.assign(cells, nullptr);
        for (const auto& [c, mesh] : m_upload.meshes()) {
            if (inBox(c)) m_grid[gridCell(c)] = &mesh;
        }
    }
    m_walk.clear();
    m_entered.assign(cells, 0);
    if (const GpuMesh* own = m_grid[gridCell(start)]) own->seenInFrame = m_frame;
    for (int f = 0; f < world::kFaceCount; ++f) { // the camera's own chunk: every way out
        const world::ChunkCoord n = step(start, f);
        if (!inBox(n) || !inFrustum(n)) continue;
        m_entered[gridCell(n)] |= static_cast<std::uint8_t>(1u << opposite(f));
        m_walk.push_back({n, opposite(f)});
    }
    for (std::size_t i = 0; i < m_walk.size(); ++i) {
        const Step s = m_walk[i];
        const GpuMesh* mesh = m_grid[gridCell(s.c)];
        if (mesh != nullptr) mesh->seenInFrame = m_frame;
        const world::FaceLinks links = mesh != nullptr ? mesh->culling.links : world::FaceLinks::all();
        // A line of sight never turns back along an axis: away from the camera's chunk only.
        const int away[3] = {s.c.x - start.x, s.c.y - start.y, s.c.z - start.z};
        for (int f = 0; f < world::kFaceCount; ++f) {
            if (f == s.entry || !links.joins(s.entry, f)) continue;
            const int axis = f / 2, sign = world::kFaceNormals[f][axis];
            if (away[axis] * sign < 0) continue;
            const world::ChunkCoord n = step(s.c, f);
            if (!inBox(n)) continue;
            std::uint8_t& in = m_entered[gridCell(n)];
            if ((in >> opposite(f) & 1u) != 0 || !inFrustum(n)) continue;
            in |= static_cast<std::uint8_t>(1u << opposite(f));
            m_walk.push_back({n, opposite(f)});
        }
    }
}

namespace {
// The highest run of set bits in a column's layers (bit y of word y / 32): [low, high) in blocks, or
// an empty run when no bit is set.
template <std::size_t N>
std::pair<int, int> topRun(const std::array<std::uint32_t, N>& layers) {
    int top = -1;
    for (int w = static_cast<int>(N) - 1; w >= 0 && top < 0; --w) {
        const std::uint32_t word = layers[static_cast<std::size_t>(w)];
        if (word != 0) top = w * 32 + 31 - std::countl_zero(word);
    }
    if (top < 0) return {0, 0};
    int y = top; // the run's lowest block so far is y + 1 .. top; extend it downward a word at a time
    while (y >= 0) {
        const int bit = y % 32;
        const std::uint32_t below = layers[static_cast<std::size_t>(y / 32)] << (31 - bit); // bit y at the top
        const int ones = std::countl_one(below);
        y -= ones;
        if (ones <= bit) break;
    }
    return {y + 1, top + 1};
}
} // namespace

bool ChunkRenderer::occlude(const glm::mat4& viewProjection, const glm::vec3& camera, float fogEnd) {
    // Called only with the near plane in air (draw).
    const world::ChunkCoord start = cameraChunk(camera);
    if (start.y < 0 || start.y >= world::kWorldHeightChunks) return false; // markVisible built no grid
    // Every chunk a ray from the camera to an occluder passes through lies in the square of columns
    // around the camera's that holds the occluder (the square is convex): those must all be drawn.
    int reach = std::min(kOccluderReach, m_currentReach);
    const float kChunk = static_cast<float>(world::kChunkSize);
    while (reach >= 0 && (2 * reach * reach > (m_radius + 1) * (m_radius + 1) - 1 || // draw()'s disc
                          std::sqrt(2.0f) * (static_cast<float>(reach) + 0.5f) * kChunk >
                              fogEnd + 0.71f * kChunk)) { // draw()'s fog test, the camera anywhere in its chunk
        --reach;
    }
    if (reach < 0) return false;

    // The solid layers of each column of 8 x 8 blocks over the square, the world's height in one mask.
    constexpr int kCell = world::SolidColumns::kCell, kCells = world::SolidColumns::kCells;
    const int side = 2 * reach + 1, cells = side * kCells;
    m_columnLayers.assign(static_cast<std::size_t>(cells) * static_cast<std::size_t>(cells), {});
    const auto column = [&](int gx, int gz) {
        return static_cast<std::size_t>(gz) * static_cast<std::size_t>(cells) + static_cast<std::size_t>(gx);
    };
    for (int dz = -reach; dz <= reach; ++dz) {
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int y = 0; y < world::kWorldHeightChunks; ++y) {
                const GpuMesh* mesh = m_grid[gridCell({start.x + dx, y, start.z + dz})];
                if (mesh == nullptr) return false; // not meshed: nothing drawn for it yet
                for (int cz = 0; cz < kCells; ++cz) {
                    for (int cx = 0; cx < kCells; ++cx) {
                        const int gx = (dx + reach) * kCells + cx, gz = (dz + reach) * kCells + cz;
                        m_columnLayers[column(gx, gz)][static_cast<std::size_t>(y)] = mesh->culling.solid.at(cx, cz);
                    }
                }
            }
        }
    }
    // Occluders: the top of each column's highest solid run, and of the run solid in all four columns
    // of each 2 x 2 window. A pixel counts only where one silhouette covers it wholly, so neighbouring
    // columns alone would leave their seams open; the windows, overlapping by a column, cover each seam
    // up to the lower of the two heights.
    m_occlusion.clear(viewProjection);
    const glm::vec3 origin = glm::vec3(world::chunkOrigin({start.x - reach, 0, start.z - reach})) - camera;
    const auto add = [&](int gx, int gz, int size, std::pair<int, int> run) {
        if (run.first >= run.second) return;
        run.first = std::max(run.first, run.second - kOccluderDepth);
        const glm::vec3 low = origin + glm::vec3(static_cast<float>(gx * kCell), static_cast<float>(run.first),
                                                 static_cast<float>(gz * kCell));
        m_occlusion.addOccluder(low, low + glm::vec3(static_cast<float>(size * kCell),
                                                     static_cast<float>(run.second - run.first),
                                                     static_cast<float>(size * kCell)));
    };
    for (int gz = 0; gz < cells; ++gz) {
        for (int gx = 0; gx < cells; ++gx) {
            const auto& own = m_columnLayers[column(gx, gz)];
            add(gx, gz, 1, topRun(own));
            if (gx + 1 == cells || gz + 1 == cells) continue;
            auto window = own;
            for (const std::size_t o : {std::size_t{1}, column(0, 1), column(1, 1)}) {
                const auto& other = m_columnLayers[column(gx, gz) + o];
                for (std::size_t y = 0; y < window.size(); ++y) window[y] &= other[y];
            }
            add(gx, gz, 2, topRun(window));
        }
    }
    // Near occluders, block by block: the blocks each mesh within kNearReach was made from, so exactly
    // what is drawn there (every face between their air and a solid block).
    if (reach >= kNearReach) {
        constexpr int kSize = world::kChunkSize, kSide = 2 * kNearReach + 1;
        m_nearGrid.reset({kSide * kSize, world::kWorldHeightChunks * kSize, kSide * kSize},
                         glm::vec3(world::chunkOrigin({start.x - kNearReach, 0, start.z - kNearReach})) - camera);
        for (int dz = -kNearReach; dz <= kNearReach; ++dz) {
            for (int dx = -kNearReach; dx <= kNearReach; ++dx) {
                for (int y = 0; y < world::kWorldHeightChunks; ++y) {
                    const GpuMesh* mesh = m_grid[gridCell({start.x + dx, y, start.z + dz})];
                    if (mesh->culling.occupancy == nullptr) return true; // not meshed block by block
                    for (int by = 0; by < kSize; ++by) {
                        for (int bz = 0; bz < kSize; ++bz) {
                            m_nearGrid.row(y * kSize + by, (dz + kNearReach) * kSize + bz)[dx + kNearReach] =
                                mesh->culling.occupancy
                                    ->rows[static_cast<std::size_t>(by) * kSize + static_cast<std::size_t>(bz)];
                        }
                    }
                }
            }
        }
        m_stats.nearPixels = m_occlusion.addSolidBlocks(m_nearGrid, kNearDepth);
    }
    return true;
}

ChunkRenderer::HiddenColumns ChunkRenderer::hiddenColumns(const GpuMesh& mesh, const glm::vec3& offset) const {
    constexpr int kCell = world::SolidColumns::kCell, kCells = world::SolidColumns::kCells;
    HiddenColumns h;
    for (int cz = 0; cz < kCells; ++cz) {
        for (int cx = 0; cx < kCells; ++cx) {
            const GpuMesh::Span& span = mesh.spans[world::SolidColumns::index(cx, cz)];
            if (span.low > span.high) continue; // no quad there
            const auto bit = static_cast<std::uint16_t>(1u << world::SolidColumns::index(cx, cz));
            h.withQuads = static_cast<std::uint16_t>(h.withQuads | bit);
            const glm::vec3 low = offset + glm::vec3(static_cast<float>(cx * kCell), static_cast<float>(span.low),
                                                     static_cast<float>(cz * kCell));
            const glm::vec3 high = low + glm::vec3(static_cast<float>(kCell), static_cast<float>(span.high - span.low),
                                                   static_cast<float>(kCell));
            if (m_occlusion.hides(low, high)) h.hidden = static_cast<std::uint16_t>(h.hidden | bit);
        }
    }
    return h;
}

void ChunkRenderer::draw(const glm::mat4& viewProjection, const glm::vec3& camera, glm::ivec2 viewport,
                         GLuint atlasArray, const ChunkLighting& light, bool occlusionCulling) {
    const Frustum frustum(viewProjection);
    const bool nearInAir = occlusionCulling && nearPlaneInAir(viewProjection, camera);
    if (occlusionCulling) markVisible(frustum, camera, nearInAir);
    m_stats.nearPixels = 0;
    const bool occluding = nearInAir && occlude(viewProjection, camera, light.fogEnd);
    m_upload.useShader(viewProjection, viewport, atlasArray, light);

    const world::ChunkCoord center = cameraChunk(camera);
    m_stats.drawn = 0;
    m_stats.hidden = 0;
    m_stats.occluded = 0;
    m_stats.hiddenColumns = 0;
    m_stats.hiddenQuads = 0;
    m_stats.occluders = occluding ? m_occlusion.occluders() : 0;
    m_stats.triangles = 0;
    // Visible chunks, nearest first, so that the depth test rejects hidden fragments before shading.
    if (m_drawableVersion != m_upload.version()) { // meshes were uploaded or released since the last frame
        m_drawable.clear();
        for (const auto& entry : m_upload.meshes()) {
            if (entry.second.quads > 0) m_drawable.emplace_back(entry.first, &entry);
        }
        m_drawableVersion = m_upload.version();
    }
    m_drawList.clear();
    m_partDraws.clear();
    for (const auto& [c, entry] : m_drawable) {
        if (!inDisc(c.x - center.x, c.z - center.z, m_radius)) continue;
        const glm::vec3 offset = glm::vec3(world::chunkOrigin(c)) - camera;
        const glm::vec3 centre = offset + glm::vec3(0.5f * world::kChunkSize);
        if (glm::length(glm::vec2(centre.x, centre.z)) > light.fogEnd + 0.71f * world::kChunkSize) continue;
        if (!frustum.intersectsBox(offset, offset + glm::vec3(static_cast<float>(world::kChunkSize)))) continue;
        if (occlusionCulling && entry->second.seenInFrame != m_frame) {
            ++m_stats.hidden;
            continue;
        }
        const GpuMesh& mesh = entry->second;
        const HiddenColumns h = occluding ? hiddenColumns(mesh, offset) : HiddenColumns{};
        if (occluding && h.hidden == h.withQuads) {
            ++m_stats.hidden;
            ++m_stats.occluded;
            continue;
        }
        m_drawList.emplace_back(glm::dot(centre, centre), entry);
        m_partDraws.push_back({h.hidden, 0, -1}); // in step with m_drawList
    }
    // Nearest first; the order is kept as indices, so that m_partDraws stays in step with m_drawList.
    m_drawOrder.resize(m_drawList.size());
    for (std::size_t i = 0; i < m_drawOrder.size(); ++i) m_drawOrder[i] = i;
    std::sort(m_drawOrder.begin(), m_drawOrder.end(), [&](std::size_t i, std::size_t j) {
        const auto& a = m_drawList[i];
        const auto& b = m_drawList[j];
        return a.first < b.first || (a.first == b.first && a.second->first < b.second->first);
    });
    // A face can be seen only from the side its normal points to: of each direction, the planes on the
    // camera's side (all of them, or none, for a chunk the camera is not level with). With occluders,
    // each quad of those ranges in a column in view is tested on its own, and a chunk with some quads
    // hidden (by their columns or one by one) has its other quads written out as indices.
    const auto visibleRanges = [&](const GpuMesh& mesh, const glm::vec3& offset, auto&& range) {
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
    };
    m_partIndices.clear();
    for (const std::size_t i : m_drawOrder) {
        if (!occluding) break; // nothing is known hidden: every chunk is drawn whole
        PartDraw& part = m_partDraws[i];
        const GpuMesh& mesh = m_drawList[i].second->second;
        const glm::vec3 offset = glm::vec3(world::chunkOrigin(m_drawList[i].second->first)) - camera;
        m_stats.hiddenColumns += std::popcount(part.hidden);
        part.first = m_partIndices.size();
        const auto shown = static_cast<std::uint16_t>(~part.hidden);
        bool left = part.hidden != 0; // whether a quad of the visible ranges was left out
        visibleRanges(mesh, offset, [&](int from, int to) {
            for (int q = from; q < to; ++q) {
                const auto k = static_cast<std::size_t>(q);
                if ((mesh.quadColumns[k] & shown) == 0) continue; // hidden wherever it is
                const GpuMesh::QuadBox& box = mesh.quadBoxes[k];
                if (m_occlusion.hidesBounds(offset + glm::vec3(box.low[0], box.low[1], box.low[2]),
                                            offset + glm::vec3(box.high[0], box.high[1], box.high[2]))) {
                    ++m_stats.hiddenQuads;
                    left = true;
                    continue;
                }
                const auto b = static_cast<std::uint32_t>(q) * 4;
                m_partIndices.insert(m_partIndices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
            }
        });
        if (left) {
            part.count = static_cast<long long>(m_partIndices.size() - part.first);
        } else { // all drawn: from the shared index buffer, as without occluders
            m_partIndices.resize(part.first);
        }
    }
    m_upload.uploadPartIndices(m_partIndices);
    for (const std::size_t i : m_drawOrder) {
        const world::ChunkCoord& c = m_drawList[i].second->first;
        const GpuMesh& mesh = m_drawList[i].second->second;
        const PartDraw& part = m_partDraws[i];
        const glm::vec3 offset = glm::vec3(world::chunkOrigin(c)) - camera;
        m_upload.bindChunk(mesh, offset);
        if (part.count >= 0) {
            if (part.count > 0) m_stats.triangles += m_upload.drawPart(part.first, part.count);
        } else {
            visibleRanges(mesh, offset, [&](int from, int to) { m_stats.triangles += m_upload.drawQuads(from, to); });
        }
        ++m_stats.drawn;
    }
    m_upload.endDraw();
}

} // namespace render
