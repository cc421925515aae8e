// CPU meshing of one chunk into plain vertex arrays: greedy (the default) or one quad per face.
// Input is the chunk plus a one-voxel border taken from its neighbours (padded_chunk.h), so faces against
// neighbouring chunks are culled and ambient occlusion is seamless across chunk borders; output is
// ChunkVertex quads (chunk_vertex.h). Made beside a mesh: level_of_detail.h, culling_data.h, plane_order.h.
// Pure function of its input: it never reads the world, never allocates beyond growing the output
// vector, and knows nothing of GL (uploading the vertices is the renderer's business).
#pragma once
#include "world/chunk_vertex.h"
#include "world/padded_chunk.h"

namespace world {

// Greedy merges coplanar faces with the same tile and the same uniform occlusion into rectangles, so
// a merged quad renders exactly like the faces it replaces. GreedyStrips merges further: faces whose
// occlusion changes along one axis of the face only (a floor along a wall) merge along the other axis,
// with the same tile and corners, into strips one face wide; the occlusion of such a strip is linear
// across it and constant along it, so every point is shaded as the faces shade themselves (and either
// diagonal splits it alike). What the renderer draws near the camera. GreedyFlat leaves occlusion out
// and lights each face flat by the voxel on its air side, so that faces merge by tile and that one light:
// the level of detail for distant chunks, where occlusion is about a pixel wide and the triangle count is
// what costs. Culled emits one quad
// per visible face and is the reference for tests and benchmarks.
enum class MeshMode { Greedy, GreedyFlat, Culled, GreedyStrips };

// Clears `out` first and reuses its capacity.
void meshChunk(const PaddedChunk& in, ChunkMesh& out, MeshMode mode = MeshMode::GreedyStrips);

} // namespace world
