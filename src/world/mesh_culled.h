// The culled reference mesher's entry point, for meshChunk (mesher.cpp) alone, which dispatches
// MeshMode::Culled to it: other files and layers call meshChunk, never this.
#pragma once
#include "world/chunk_vertex.h"
#include "world/padded_chunk.h"

namespace world::detail {

// Appends to `out` one quad per visible face of `in`'s own blocks, with the greedy mesher's vertex layout,
// occlusion and smooth light (what MeshMode::Culled means; mesher.h).
void meshCulled(const PaddedChunk& in, VertexList& out);

} // namespace world::detail
