// Level of detail for distant chunks: a padded chunk rebuilt from coarser cells, and the mesh of a chunk
// at a level of detail, which the render thread and the mesh worker both build (render/chunk_lod.h picks
// the level). Pure functions of their input, like meshChunk: they never read the world and know nothing
// of GL.
#pragma once
#include "world/chunk_vertex.h"
#include "world/mesher.h"
#include "world/padded_chunk.h"

namespace world {

// Level of detail for distant chunks: `out` is `fine` with the chunk's inside rebuilt from cells of
// factor^3 blocks (factor 2 or 4). A cell holding solid blocks is filled from its bottom up to its highest
// solid layer, air above, so the ground keeps its height (a cell solid to its top would stand up to
// factor - 1 blocks above it, a step at each boundary between levels); it takes one type: its highest
// emissive block's, so that a lamp stays in sight beside its light, or else that of its highest solid block
// (grass stays on top). The one-block border stays fine. Meshed as usual, a coarse chunk needs far fewer
// quads, and it leaves no gap at any seam: it covers at least every solid block of `fine`, and its border
// faces are culled only against solid fine neighbours, which every level of detail also covers.
// `fine.blocks` must not be stale.
void coarsenPadded(const PaddedChunk& fine, int factor, PaddedChunk& out);

// The mesh of `fine` at a level of detail: cell 1 meshes it as it is, 2 or 4 coarsens it into
// `scratch` first. What both the render thread and the mesh worker build.
void meshAtDetail(const PaddedChunk& fine, MeshMode mode, int cell, PaddedChunk& scratch, ChunkMesh& out);

} // namespace world
