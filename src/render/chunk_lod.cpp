// Level of detail for chunk meshes: which cell size and mesh mode each ring of chunks is meshed at
// (chunk_lod.h says why this is a unit of its own).
#include "render/chunk_lod.h"

namespace render {

ChunkDetail ChunkLod::detailAt(world::ChunkCoord c, world::ChunkCoord center, bool levelOfDetail) {
    const int d = world::columnDistance(c, center);
    if (d <= kDetailRadius) return {world::MeshMode::GreedyStrips, 1};
    if (!levelOfDetail || d <= kCoarseRadius) return {world::MeshMode::GreedyFlat, 1};
    return {world::MeshMode::GreedyFlat, d <= kCoarserRadius ? 2 : 4};
}

} // namespace render
