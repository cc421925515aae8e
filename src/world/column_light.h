// The light a chunk's mesh is lit by, as a pure function of the terrain and the edits: what the mesh worker
// and the render thread both compute, so a chunk's light never depends on which of them meshed it or when.
//
// Light loses at least a level with every step sideways (docs/LIGHT.md), so the light of a chunk column and
// its one-voxel border depends only on the blocks within kLightBorder blocks of its footprint, at every
// height. Columns are lit kLightRegion x kLightRegion at a time over their region's light box (the region and
// kLightBorder around it), so neighbours share one relight; a chunk's padded light is cut out of its region's
// LightField (tests/world/test_column_light.cpp checks every column of a region against a far wider box).
//
// Each thread keeps the fields of the last few regions it lit, with the edits they were lit with. A request
// whose edits differ from a kept field's in a few places repairs that field edit by edit (LightField::setBlock,
// whose result equals a relight from scratch), so an edit costs microseconds; anything else relights the
// region from scratch. Either way the light is the same.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "world/chunk.h"
#include "world/mesher.h"
#include "world/terrain.h"
#include "world/world.h"

namespace world {

// Steps light can travel sideways or up from where it changes: a level of kMaxLight still has 1 after
// kMaxLight - 1 steps. (Sunlight falls down without limit.)
inline constexpr int kLightReach = kMaxLight - 1;
// Blocks beyond a chunk column's footprint that its padded light is computed from: the padding voxel and
// kLightReach more. Light from beyond the box would have to cross its edge at kMaxLight - 1 at most and then
// lose a level a step (Light.AColumnsLightNeedsOnlyItsReachAroundIt checks a scene where one block less differs).
inline constexpr int kLightBorder = 1 + kLightReach;

// Chunk columns are lit together, kLightRegion x kLightRegion at a time, in regions aligned to a fixed grid:
// one light box holds a region and kLightBorder around it, so neighbouring columns share one relight instead
// of each lighting its own box (62 x 62 columns of blocks for one 32 x 32 column: 3.75 times its volume; a
// 2 x 2 region's 94 x 94 is 2.16 times the four's). Light is exact in every column of the region (each has
// kLightBorder or more around it), so a chunk's light is the same whatever the region size.
inline constexpr int kLightRegion = 2;

struct LightBox {
    glm::ivec3 origin, size;
    bool contains(glm::ivec3 p) const {
        const glm::ivec3 l = p - origin;
        return l.x >= 0 && l.y >= 0 && l.z >= 0 && l.x < size.x && l.y < size.y && l.z < size.z;
    }
};
// The light region of chunk `coord`'s column: its x and z divided by kLightRegion, rounded down (y is 0).
ChunkCoord lightRegionOf(ChunkCoord coord);
// The light box of the region holding chunk `coord`'s column (its y is ignored): all of the world's height.
LightBox lightBoxOf(ChunkCoord coord);

// The light of chunk `coord`'s padded voxels, from the terrain and `edits` (world positions; those outside
// lightBoxOf(coord) are ignored, their order does not matter), shade rows included. Below the world reads
// dark, above it the open sky.
void lightPadded(const TerrainDef& def, ChunkCoord coord, const std::vector<BlockEdit>& edits, PaddedLight& out);
// The padded chunk, blocks and light, both cut out of its region's field: what gatherPaddedFromTerrain and then
// lightPadded give, without generating the chunk's blocks again (the mesh worker's way).
void gatherAndLight(const TerrainDef& def, ChunkCoord coord, const std::vector<BlockEdit>& edits, PaddedChunk& out);

// The light at a block position, as the meshes around it are lit: from this thread's kept region (lit on a
// miss), remembered until the world changes. In a solid block, the brightest of its six neighbours' (per
// channel); above the world the open sky, below it none. For objects drawn in the world.
struct LocalLight {
    int sun = kMaxLight, red = 0, green = 0, blue = 0; // levels, 0..kMaxLight
    bool operator==(const LocalLight&) const = default;
};
LocalLight lightAt(const World& w, glm::ivec3 pos);

// What this thread's light cache did: for tests and benchmarks.
struct ColumnLightStats {
    long relit = 0;    // regions lit from scratch
    long repaired = 0; // regions repaired edit by edit
    long reused = 0;   // requests answered by a kept region unchanged
};
ColumnLightStats columnLightStats();
// Forgets this thread's kept regions (and its counts).
void clearColumnLight();

// What light has cost every thread of the process since countLightCost(true), for --frame-stats: the CPU of
// streaming's light per voxel of the columns meshed. `cpuSeconds` is the threads' CPU time in propagation
// (relights from scratch and repairs, from the moment a region's blocks are filled: not the terrain, not the
// cut-outs); `columns` counts the distinct chunk columns (x, z, per terrain) whose padded light was asked for,
// which is every column meshed, and `regions` the distinct light regions they lie in; `relitForObjects` the
// relights lightAt made. relit - relitForObjects - regions is how many times the meshes' light lit a region again.
struct LightCost {
    double cpuSeconds = 0;
    long relit = 0, relitForObjects = 0, repaired = 0, columns = 0, regions = 0;
};
// Off unless asked for: then nothing is timed (a repair is a few microseconds) and no column is remembered.
void countLightCost(bool on);
LightCost lightCost();

} // namespace world
