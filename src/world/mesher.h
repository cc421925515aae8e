// CPU meshing of one chunk into plain vertex arrays: greedy (the default) or one quad per face.
// Input is the chunk plus a one-voxel border taken from its neighbours, so faces against neighbouring
// chunks are culled and ambient occlusion is seamless across chunk borders.
// Pure function of its input: it never reads the world, never allocates beyond growing the output
// vector, and knows nothing of GL (uploading the vertices is the renderer's business).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "world/block.h"
#include "world/chunk.h"

namespace world {

struct PaddedChunk {
    static constexpr int kSize = kChunkSize + 2;
    static constexpr int kVolume = kSize * kSize * kSize;
    // Padded coordinates 0..33; the chunk's own block (x, y, z) is at (x + 1, y + 1, z + 1).
    // Same order as Chunk: x fastest, then z, then y.
    static constexpr int index(int x, int y, int z) { return x + kSize * (z + kSize * y); }
    BlockType get(int x, int y, int z) const { return blocks[static_cast<std::size_t>(index(x, y, z))]; }
    void set(int x, int y, int z, BlockType t) { blocks[static_cast<std::size_t>(index(x, y, z))] = t; }

    std::array<BlockType, kVolume> blocks{}; // all Air
};

// Face directions, as stored in ChunkVertex::face.
enum Face : std::uint8_t { kFacePosX, kFaceNegX, kFacePosY, kFaceNegY, kFacePosZ, kFaceNegZ, kFaceCount };
inline constexpr int kFaceNormals[kFaceCount][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};

// x, y, z: corner, chunk-local 0..32. u, v: texture coordinates in blocks, so the tile repeats across a
// merged quad; on side faces v = 0 at the top edge and grows downward and u grows to the right as seen
// from outside; on top and bottom faces u runs along x and v along z. ao: 3 open .. 0 fully occluded.
struct ChunkVertex {
    std::uint8_t x, y, z, face, u, v, tile, ao;
};
static_assert(sizeof(ChunkVertex) == 8);

// Four vertices per quad; triangles (0, 1, 2) and (0, 2, 3) are counter-clockwise seen from outside,
// and the split diagonal is chosen so occlusion interpolates without the anisotropy artefact.
struct ChunkMesh {
    std::vector<ChunkVertex> vertices;
    std::size_t quadCount() const { return vertices.size() / 4; }
};

// Greedy merges coplanar faces with the same tile and the same uniform occlusion into rectangles, so
// a merged quad renders exactly like the faces it replaces. GreedyUnlit leaves occlusion out (every
// corner fully lit) so that faces merge by tile alone: the level of detail for distant chunks, where
// occlusion is about a pixel wide and the triangle count is what costs. Culled emits one quad per
// visible face and is the reference for tests and benchmarks.
enum class MeshMode { Greedy, GreedyUnlit, Culled };

// Clears `out` first and reuses its capacity.
void meshChunk(const PaddedChunk& in, ChunkMesh& out, MeshMode mode = MeshMode::Greedy);

} // namespace world
