// Procedural terrain: every block of the world before edits, as a pure function of (TerrainDef,
// position). Chunks, slabs and single voxels are all produced by one routine (generateBox), so a
// block reads the same whichever way and in whichever order it is asked for: that is what keeps
// chunk borders seamless, trees included.
// Its results must never depend on state kept between calls, on edits, or on what has been generated
// before; the one thing it keeps, per thread, is the columns of recent footprints (pure results of
// the TerrainDef and the footprint), which it reuses rather than computing again.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

#include <glm/vec3.hpp>

#include "world/block.h"
#include "world/chunk.h"

namespace world {

enum class TerrainKind { Default, Flat };

std::optional<TerrainKind> terrainFromName(std::string_view name); // "default", "flat"
std::string_view terrainName(TerrainKind kind);

struct TerrainDef {
    std::uint64_t seed = 1; // any value; equal seeds give equal worlds
    TerrainKind kind = TerrainKind::Default;
};

// Flat layout: stone up to 28, dirt 29..31, grass at 32.
inline constexpr int kFlatSurface = 32;

// Fills `out` with the chunk's 32^3 blocks.
void generateChunk(const TerrainDef& def, ChunkCoord coord, Chunk& out);

// Any axis-aligned box: `out` holds size.x * size.y * size.z blocks, index x + size.x * (z + size.z * y)
// relative to `origin`. Below y = 0 reads Stone, from kWorldHeight up reads Air.
void generateBox(const TerrainDef& def, glm::ivec3 origin, glm::ivec3 size, BlockType* out);

// One block; costs a few hundred nanoseconds, so bulk users should prefer generateBox.
BlockType terrainBlock(const TerrainDef& def, glm::ivec3 pos);

// y of the topmost solid terrain block in the column (trees excluded).
int surfaceHeight(const TerrainDef& def, int x, int z);

} // namespace world
