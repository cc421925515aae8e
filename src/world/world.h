// The block world: terrain plus the player's edits, with a cache of generated chunks.
// Simulation state is (TerrainDef, edits) and nothing else. Loaded chunks are a cache derived from
// it (hence mutable behind const methods): reading a block never depends on what happens to be
// loaded, and loading or unloading never changes what any block reads.
// Not thread-safe: const methods may fill or trim the cache. No rendering API lives here.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "world/block.h"
#include "world/chunk.h"
#include "world/mesher.h"
#include "world/terrain.h"

namespace world {

struct BlockEdit {
    glm::ivec3 pos;
    BlockType block;
    bool operator==(const BlockEdit& o) const { return pos == o.pos && block == o.block; }
};
// Edits by position: x, then y, then z (the order of World::edits()).
inline bool positionLess(const BlockEdit& a, const BlockEdit& b) {
    return std::tie(a.pos.x, a.pos.y, a.pos.z) < std::tie(b.pos.x, b.pos.y, b.pos.z);
}

class World {
public:
    explicit World(TerrainDef def = {});

    const TerrainDef& terrain() const { return m_def; }
    // A number no other World in this process has: lets caches derived from a world (meshes on the
    // GPU) notice that they now look at a different one, even at the same address.
    std::uint64_t identity() const { return m_identity; }

    // Any position. Below y = 0 reads Stone, from kWorldHeight up reads Air. Uses a loaded chunk if
    // present, else edits and terrain, without loading anything.
    BlockType get(glm::ivec3 pos) const;
    // Ignored outside the world's y range. Records the edit (even if it equals the terrain), updates
    // a loaded chunk, and bumps the revision of every chunk whose mesh can see this voxel: its blocks and
    // its light (world/column_light.h).
    void set(glm::ivec3 pos, BlockType block);

    // Generates (terrain, then edits) into the cache on demand. For y outside the world returns a
    // shared all-Stone or all-Air chunk without caching. The reference stays valid until the chunk is
    // unloaded.
    const Chunk& chunk(ChunkCoord coord) const;
    bool isLoaded(ChunkCoord coord) const;
    std::size_t loadedChunkCount() const { return m_chunks.size(); }
    // Drops cached chunks farther than radiusXZ from center (Chebyshev distance in x and z).
    void unloadOutside(ChunkCoord center, int radiusXZ) const;

    // 0 until an edit touches the chunk; independent of loading, so it survives unload and reload.
    std::uint64_t chunkRevision(ChunkCoord coord) const;
    // Grows with every set() inside the world's height: while it stands still, no chunkRevision has
    // changed.
    std::uint64_t revision() const { return m_revision; }

    // Sorted by (x, y, z) lexicographically.
    std::vector<BlockEdit> edits() const;
    // Makes edits() exactly `edits` (sorted as edits() gives them, positions inside the world's height), touching
    // only what differs: an edit not in `edits` is dropped (its block reads the terrain again), one that is
    // missing or of another block is set. Only the chunks those blocks can be seen from are bumped, as by set(),
    // so a renderer remeshes just them. A keyframe restored in place (game/state_image.h).
    void setEdits(const std::vector<BlockEdit>& edits);
    // The edits a mesh of `coord` can see: those in its light region's box (lightBoxOf), which holds the
    // chunk and its one-voxel border, in no set order. `out` is cleared first. For building the chunk and
    // its light without the World (gatherPaddedFromTerrain, lightPadded).
    void editsAround(ChunkCoord coord, std::vector<BlockEdit>& out) const;
    std::size_t editCount() const { return m_editCount; }

    // The chunk and a one-voxel border from its neighbours, ready for meshChunk. Loads the chunk
    // itself; neighbours come from the cache when loaded, else from edits and terrain (not loaded).
    void gatherPadded(ChunkCoord coord, PaddedChunk& out) const;

private:
    using EditMap = std::unordered_map<std::uint16_t, BlockType>; // Chunk::index -> block

    void buildChunk(ChunkCoord coord, Chunk& out) const;
    void bumpAround(glm::ivec3 pos); // the revisions of every chunk whose mesh can see the voxel
    const Chunk* loadedOrNull(ChunkCoord coord) const;

    TerrainDef m_def;
    std::uint64_t m_identity;
    std::unordered_map<ChunkCoord, EditMap, ChunkCoordHash> m_edits; // by chunk, so loading is cheap
    std::size_t m_editCount = 0;
    std::unordered_map<ChunkCoord, std::uint64_t, ChunkCoordHash> m_revisions;
    std::uint64_t m_revision = 0;
    // unique_ptr: references handed out by chunk() survive rehashing.
    mutable std::unordered_map<ChunkCoord, std::unique_ptr<Chunk>, ChunkCoordHash> m_chunks;
};

} // namespace world
