#include "world/world.h"

#include "world/column_light.h"

#include <atomic>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <tuple>
#include <utility>

namespace world {

namespace {

bool inWorldY(ChunkCoord c) { return c.y >= 0 && c.y < kWorldHeightChunks; }

const Chunk& constantChunk(BlockType t) {
    static const Chunk stone = [] {
        Chunk c;
        c.fill(BlockType::Stone);
        return c;
    }();
    static const Chunk air;
    return t == BlockType::Stone ? stone : air;
}

// The part of a neighbour that borders a chunk, along one axis: d = -1 is its last layer, 0 the whole
// span, +1 its first layer. `padded` is where that part lands in the PaddedChunk.
struct Span {
    int padded, source, count;
};
constexpr Span spanFor(int d) {
    if (d < 0) return {0, kChunkSize - 1, 1};
    if (d == 0) return {1, 0, kChunkSize};
    return {kChunkSize + 1, 0, 1};
}

// Inverse of Chunk::index.
glm::ivec3 localOfIndex(int index) {
    return {index & (kChunkSize - 1), index >> (2 * kChunkShift), (index >> kChunkShift) & (kChunkSize - 1)};
}

} // namespace

namespace {
std::atomic<std::uint64_t> g_nextIdentity{1};
} // namespace

World::World(TerrainDef def) : m_def(def), m_identity(g_nextIdentity++) {}

BlockType World::get(glm::ivec3 pos) const {
    if (pos.y < 0) return BlockType::Stone;
    if (pos.y >= kWorldHeight) return BlockType::Air;
    const ChunkCoord c = chunkOf(pos);
    const glm::ivec3 l = localOf(pos);
    if (const auto it = m_chunks.find(c); it != m_chunks.end()) return it->second->get(l.x, l.y, l.z);
    if (const auto e = m_edits.find(c); e != m_edits.end()) {
        const auto f = e->second.find(static_cast<std::uint16_t>(Chunk::index(l.x, l.y, l.z)));
        if (f != e->second.end()) return f->second;
    }
    return terrainBlock(m_def, pos);
}

void World::set(glm::ivec3 pos, BlockType block) {
    if (pos.y < 0 || pos.y >= kWorldHeight) return;
    ++m_revision;
    const ChunkCoord c = chunkOf(pos);
    const glm::ivec3 l = localOf(pos);
    const auto index = static_cast<std::uint16_t>(Chunk::index(l.x, l.y, l.z));
    if (m_edits[c].insert_or_assign(index, block).second) ++m_editCount;
    if (const auto it = m_chunks.find(c); it != m_chunks.end()) it->second->set(l.x, l.y, l.z, block);
    bumpAround(pos);
}

void World::bumpAround(glm::ivec3 pos) {
    // A mesh reads the blocks and light of its padded voxels. The light changes at most kLightReach steps
    // up or sideways from the block, and sunlight falls down any distance: the chunks whose padded voxels
    // are that near sideways (kLightReach + 1 from their own blocks: kLightBorder, as their light box reaches),
    // from that high down to the bottom. This covers the chunks whose one-voxel border holds the block too.
    static_assert(kLightBorder == kLightReach + 1);
    const ChunkCoord low = chunkOf(pos - glm::ivec3(kLightBorder, 0, kLightBorder));
    const ChunkCoord high = chunkOf(pos + glm::ivec3(kLightBorder));
    for (int cy = 0; cy <= std::min(high.y, kWorldHeightChunks - 1); ++cy) {
        for (int cz = low.z; cz <= high.z; ++cz) {
            for (int cx = low.x; cx <= high.x; ++cx) ++m_revisions[{cx, cy, cz}];
        }
    }
}

void World::setEdits(const std::vector<BlockEdit>& edits) {
    const std::vector<BlockEdit> now = this->edits();
    // Both lists are sorted by position: one merge finds what to drop and what to set.
    std::size_t i = 0, j = 0;
    while (i < now.size() || j < edits.size()) {
        if (j == edits.size() || (i < now.size() && positionLess(now[i], edits[j]))) {
            const glm::ivec3 pos = now[i++].pos; // dropped: the terrain's block again
            const ChunkCoord c = chunkOf(pos);
            const glm::ivec3 l = localOf(pos);
            auto map = m_edits.find(c);
            map->second.erase(static_cast<std::uint16_t>(Chunk::index(l.x, l.y, l.z)));
            if (map->second.empty()) m_edits.erase(map);
            --m_editCount;
            ++m_revision;
            if (const auto it = m_chunks.find(c); it != m_chunks.end())
                it->second->set(l.x, l.y, l.z, terrainBlock(m_def, pos));
            bumpAround(pos);
        } else if (i == now.size() || positionLess(edits[j], now[i])) {
            set(edits[j].pos, edits[j].block);
            ++j;
        } else {
            if (now[i].block != edits[j].block) set(edits[j].pos, edits[j].block);
            ++i, ++j;
        }
    }
}

void World::buildChunk(ChunkCoord coord, Chunk& out) const {
    // Terrain, then edits, in one bulk write: the occupancy is rebuilt once.
    out.writeBlocks([&](BlockType* blocks) {
        generateBox(m_def, chunkOrigin(coord), glm::ivec3(kChunkSize), blocks);
        if (const auto e = m_edits.find(coord); e != m_edits.end()) {
            for (const auto& [index, block] : e->second) blocks[index] = block;
        }
    });
}

const Chunk& World::chunk(ChunkCoord coord) const {
    if (coord.y < 0) return constantChunk(BlockType::Stone);
    if (coord.y >= kWorldHeightChunks) return constantChunk(BlockType::Air);
    if (const auto it = m_chunks.find(coord); it != m_chunks.end()) return *it->second;
    auto fresh = std::make_unique<Chunk>();
    buildChunk(coord, *fresh);
    return *m_chunks.emplace(coord, std::move(fresh)).first->second;
}

const Chunk* World::loadedOrNull(ChunkCoord coord) const {
    if (!inWorldY(coord)) return &chunk(coord);
    const auto it = m_chunks.find(coord);
    return it == m_chunks.end() ? nullptr : it->second.get();
}

bool World::isLoaded(ChunkCoord coord) const { return m_chunks.find(coord) != m_chunks.end(); }

void World::unloadOutside(ChunkCoord center, int radiusXZ) const {
    std::erase_if(m_chunks, [&](const auto& entry) {
        const ChunkCoord& c = entry.first;
        return columnDistance(c, center) > radiusXZ;
    });
}

std::uint64_t World::chunkRevision(ChunkCoord coord) const {
    const auto it = m_revisions.find(coord);
    return it == m_revisions.end() ? 0 : it->second;
}

std::vector<BlockEdit> World::edits() const {
    std::vector<BlockEdit> out;
    out.reserve(m_editCount);
    for (const auto& [c, map] : m_edits) {
        const glm::ivec3 origin = chunkOrigin(c);
        for (const auto& [index, block] : map) {
            out.push_back({origin + localOfIndex(index), block});
        }
    }
    std::sort(out.begin(), out.end(), positionLess);
    return out;
}

void World::editsAround(ChunkCoord coord, std::vector<BlockEdit>& out) const {
    out.clear();
    if (m_editCount == 0) return;
    const LightBox box = lightBoxOf(coord);
    const ChunkCoord first = chunkOf(box.origin), last = chunkOf(box.origin + box.size - glm::ivec3(1));
    for (int cy = first.y; cy <= last.y; ++cy) {
        for (int cz = first.z; cz <= last.z; ++cz) {
            for (int cx = first.x; cx <= last.x; ++cx) {
                const ChunkCoord n{cx, cy, cz};
                const auto e = m_edits.find(n);
                if (e == m_edits.end()) continue;
                const glm::ivec3 origin = chunkOrigin(n);
                for (const auto& [index, block] : e->second) {
                    const glm::ivec3 p = origin + localOfIndex(index);
                    if (box.contains(p)) out.push_back({p, block});
                }
            }
        }
    }
}

void World::gatherPadded(ChunkCoord coord, PaddedChunk& out) const {
    const Chunk& self = chunk(coord);
    const glm::ivec3 origin = chunkOrigin(coord);

    // Loaded neighbours (and the chunk itself) are copied row by row, in the output's own order, and
    // their occupancy rows shifted into the padded 64-bit rows (x - 1 -> bit 0, x = 32 -> bit 33).
    std::memset(out.solid, 0, sizeof out.solid);
    bool missing[3][3][3] = {};
    bool anyMissing = false;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dx = -1; dx <= 1; ++dx) {
                const Chunk* src =
                    (dx | dy | dz) == 0 ? &self : loadedOrNull({coord.x + dx, coord.y + dy, coord.z + dz});
                if (!src) {
                    missing[dy + 1][dz + 1][dx + 1] = anyMissing = true;
                    continue;
                }
                const Span sx = spanFor(dx), sy = spanFor(dy), sz = spanFor(dz);
                for (int y = 0; y < sy.count; ++y) {
                    for (int z = 0; z < sz.count; ++z) {
                        BlockType* to =
                            out.blocks.untrackedData() + PaddedChunk::index(sx.padded, sy.padded + y, sz.padded + z);
                        const BlockType* from = src->data() + Chunk::index(sx.source, sy.source + y, sz.source + z);
                        const std::uint32_t row = src->solidRow(sy.source + y, sz.source + z);
                        std::uint64_t& bits = out.solid[sy.padded + y][sz.padded + z];
                        if (sx.count == kChunkSize) {
                            std::memcpy(to, from, kChunkSize); // a constant size compiles to a few moves
                            bits |= std::uint64_t{row} << 1;
                        } else {
                            *to = *from;
                            bits |= dx < 0 ? std::uint64_t{row >> 31} : std::uint64_t{row & 1u} << (kChunkSize + 1);
                        }
                    }
                }
            }
        }
    }
    if (!anyMissing) {
        out.blocks.stale = false;
        return;
    }

    // The others read exactly what get() would (terrain, then edits) without being loaded. Neighbours
    // above and below share their columns, so one box serves all of them: the column noise is the
    // expensive part of terrain.
    thread_local std::vector<BlockType> slab;
    for (int dz = -1; dz <= 1; ++dz) {
        for (int dx = -1; dx <= 1; ++dx) {
            int low = 2, high = -2;
            for (int dy = -1; dy <= 1; ++dy) {
                if (missing[dy + 1][dz + 1][dx + 1]) low = std::min(low, dy), high = std::max(high, dy);
            }
            if (low > high) continue;
            const Span sx = spanFor(dx), sz = spanFor(dz);
            const int y0 = spanFor(low).padded;
            const int y1 = spanFor(high).padded + spanFor(high).count; // exclusive
            const glm::ivec3 size(sx.count, y1 - y0, sz.count);
            slab.resize(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) *
                        static_cast<std::size_t>(size.z));
            generateBox(m_def, origin + glm::ivec3(sx.padded, y0, sz.padded) - 1, size, slab.data());
            for (int dy = low; dy <= high; ++dy) {
                if (!missing[dy + 1][dz + 1][dx + 1]) continue;
                const Span sy = spanFor(dy);
                for (int y = 0; y < sy.count; ++y) {
                    for (int z = 0; z < size.z; ++z) {
                        std::memcpy(out.blocks.untrackedData() +
                                        PaddedChunk::index(sx.padded, sy.padded + y, sz.padded + z),
                                    &slab[static_cast<std::size_t>(size.x) *
                                          static_cast<std::size_t>(z + size.z * (sy.padded + y - y0))],
                                    static_cast<std::size_t>(size.x));
                    }
                }
                const auto e = m_edits.find({coord.x + dx, coord.y + dy, coord.z + dz});
                if (e == m_edits.end()) continue;
                const glm::ivec3 lo(sx.source, sy.source, sz.source), count(sx.count, sy.count, sz.count);
                const glm::ivec3 to(sx.padded, sy.padded, sz.padded);
                for (const auto& [index, block] : e->second) {
                    const glm::ivec3 r = localOfIndex(index) - lo;
                    if (r.x < 0 || r.y < 0 || r.z < 0 || r.x >= count.x || r.y >= count.y || r.z >= count.z) continue;
                    out.set(to.x + r.x, to.y + r.y, to.z + r.z, block);
                }
            }
        }
    }
    out.rebuildSolid(); // the slabs came in as bytes; generating them cost far more than this
}

} // namespace world
