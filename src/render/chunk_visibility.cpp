// Which chunks and quads a frame draws: the walk, the occluders and the draw-time culling
// (chunk_visibility.h says why this is a unit of its own).
#include "render/chunk_visibility.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vector_relational.hpp>
#include <limits>

#include "render/chunk_lod.h"

namespace render {

// Which blocks around the camera are air: occlusion culling needs the near plane in air.
void ChunkVisibility::noteAirAround(const world::World& world, const glm::vec3& camera) {
    m_updateCamera = camera;
    m_airAround = 0;
    const glm::ivec3 cameraBlock(glm::floor(camera));
    for (int i = 0; i < 27; ++i) {
        const glm::ivec3 b = cameraBlock + glm::ivec3(i % 3 - 1, i / 3 % 3 - 1, i / 9 - 1);
        if (!world::isSolid(world.get(b))) m_airAround |= 1u << i;
    }
}

void ChunkVisibility::cull(const ChunkView& view, int currentReach, const ChunkUpload& meshes) {
    const Frustum frustum(view.viewProjection);
    const bool nearInAir = view.occlusionCulling && nearPlaneInAir(view.viewProjection, view.camera);
    if (view.occlusionCulling) markVisible(frustum, view.camera, nearInAir, view.radius, meshes);
    m_stats.nearPixels = 0;
    const bool occluding =
        nearInAir && occlude(view.viewProjection, view.camera, view.fogEnd, view.radius, currentReach);
    m_stats.hidden = 0;
    m_stats.occluded = 0;
    m_stats.hiddenColumns = 0;
    m_stats.hiddenQuads = 0;
    m_stats.occluders = occluding ? m_occlusion.occluders() : 0;
    chooseChunks(frustum, view, occluding, meshes);
    writePartIndices(view.camera, occluding);
}

std::size_t ChunkVisibility::gridCell(world::ChunkCoord c) const {
    const std::size_t side = 2 * static_cast<std::size_t>(m_gridReach) + 1;
    return (static_cast<std::size_t>(c.y) * side + static_cast<std::size_t>(c.z - m_gridAt.second + m_gridReach)) *
               side +
           static_cast<std::size_t>(c.x - m_gridAt.first + m_gridReach);
}

bool ChunkVisibility::nearPlaneInAir(const glm::mat4& viewProjection, const glm::vec3& camera) const {
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

void ChunkVisibility::markVisible(const Frustum& frustum, const glm::vec3& camera, bool nearInAir, int radius,
                                  const ChunkUpload& meshes) {
    ++m_frame;
    const world::ChunkCoord start = cameraChunk(camera);
    const auto inFrustum = [&](world::ChunkCoord c) {
        const glm::vec3 low = glm::vec3(world::chunkOrigin(c)) - camera;
        return frustum.intersectsBox(low, low + glm::vec3(static_cast<float>(world::kChunkSize)));
    };
    // Outside the world's height, or looking from inside a block (the rays start in rock and can reach
    // faces behind it, through no air): no walk.
    if (start.y < 0 || start.y >= world::kWorldHeightChunks || !nearInAir) {
        for (const auto& [c, mesh] : meshes.meshes()) mesh.seenInFrame = m_frame;
        return;
    }
    const auto step = [](world::ChunkCoord c, int face) {
        return world::ChunkCoord{c.x + world::kFaceNormals[face][0], c.y + world::kFaceNormals[face][1],
                                 c.z + world::kFaceNormals[face][2]};
    };
    const auto opposite = [](int face) { return face ^ 1; }; // +X -X, +Y -Y, +Z -Z pairs
    // The walk stays within the chunks kept around the camera: columns within `reach` = radius + 1
    // (Chebyshev, in chunks), a box side x side x kWorldHeightChunks. Its meshes and the faces each
    // chunk was entered by live in flat arrays over that box rather than in hash maps; the meshes'
    // array is rebuilt only when a mesh is uploaded or released, the camera enters another column or
    // the radius changes.
    const int reach = radius + 1, side = 2 * reach + 1;
    const auto inBox = [&](world::ChunkCoord c) {
        return c.y >= 0 && c.y < world::kWorldHeightChunks && world::columnDistance(c, start) <= reach;
    };
    const std::size_t cells =
        static_cast<std::size_t>(side) * static_cast<std::size_t>(side) * world::kWorldHeightChunks;
    const std::pair<int, int> gridAt(start.x, start.z);
    if (m_gridVersion != meshes.version() || m_gridReach != reach || m_gridAt != gridAt) {
        m_gridVersion = meshes.version();
        m_gridReach = reach;
        m_gridAt = gridAt;
        m_grid.assign(cells, nullptr);
        for (const auto& [c, mesh] : meshes.meshes()) {
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

bool ChunkVisibility::occlude(const glm::mat4& viewProjection, const glm::vec3& camera, float fogEnd, int radius,
                              int currentReach) {
    // Called only with the near plane in air (draw).
    const world::ChunkCoord start = cameraChunk(camera);
    if (start.y < 0 || start.y >= world::kWorldHeightChunks) return false; // markVisible built no grid
    // Every chunk a ray from the camera to an occluder passes through lies in the square of columns
    // around the camera's that holds the occluder (the square is convex): those must all be drawn.
    int reach = std::min(kOccluderReach, currentReach);
    const float kChunk = static_cast<float>(world::kChunkSize);
    while (reach >= 0 && (2 * reach * reach > (radius + 1) * (radius + 1) - 1 || // draw()'s disc
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

ChunkVisibility::HiddenColumns ChunkVisibility::hiddenColumns(const GpuMesh& mesh, const glm::vec3& offset) const {
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

void ChunkVisibility::chooseChunks(const Frustum& frustum, const ChunkView& view, bool occluding,
                                   const ChunkUpload& meshes) {
    const glm::vec3& camera = view.camera;
    const world::ChunkCoord center = cameraChunk(camera);
    // Visible chunks, nearest first, so that the depth test rejects hidden fragments before shading.
    if (m_drawableVersion != meshes.version()) { // meshes were uploaded or released since the last frame
        m_drawable.clear();
        for (const auto& entry : meshes.meshes()) {
            if (entry.second.quads > 0) m_drawable.emplace_back(entry.first, &entry);
        }
        m_drawableVersion = meshes.version();
    }
    m_drawList.clear();
    m_partDraws.clear();
    for (const auto& [c, entry] : m_drawable) {
        if (!inDisc(c.x - center.x, c.z - center.z, view.radius)) continue;
        const glm::vec3 offset = glm::vec3(world::chunkOrigin(c)) - camera;
        const glm::vec3 centre = offset + glm::vec3(0.5f * world::kChunkSize);
        if (glm::length(glm::vec2(centre.x, centre.z)) > view.fogEnd + 0.71f * world::kChunkSize) continue;
        if (!frustum.intersectsBox(offset, offset + glm::vec3(static_cast<float>(world::kChunkSize)))) continue;
        if (view.occlusionCulling && entry->second.seenInFrame != m_frame) {
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
}

// With occluders, each quad that can face the camera (visibleRanges) in a column in view is tested on its
// own, and a chunk with some quads hidden (by their columns or one by one) has its other quads written
// out as indices.
void ChunkVisibility::writePartIndices(const glm::vec3& camera, bool occluding) {
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
}

} // namespace render
