// The 64^3 terrain regions the mesher benchmarks and the speed gate mesh: the same blocks for our mesher
// (eight padded chunks, under the open sky and lit) and for the binary greedy anchor (binary_greedy_baseline.h).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "world/mesher.h"

namespace bench {

// A 64^3 block region of the game's terrain around the surface: the 2 x 2 x 2 chunks from chunk (0, cy, 0),
// padded for our mesher, and the same blocks (with a one-block border, so a 62^3 mesh) laid out as the anchor
// expects, its occupancy columns built beforehand as its world would keep them.
struct Region {
    std::vector<std::unique_ptr<world::PaddedChunk>> chunks; // under the open sky: meshed as before light
    std::vector<std::unique_ptr<world::PaddedChunk>> lit;    // the same blocks lit (world::lightPadded)
    std::vector<std::uint8_t> bytes;
    std::vector<std::uint64_t> columns;
    long long anchorVisibleFaces = 0; // faces of the anchor's 62^3, counted block by block
};

// Seeds 1 to 3; built once per process.
const Region& region(int seed);
// The same region with 16 lamps standing on its ground (a 4 x 4 grid 16 blocks apart), white or of every colour
// in turn: its `lit` chunks lit by them, its bytes and columns holding them. Seeds 1 to 3; built once per process.
const Region& lampRegion(int seed, bool coloured);
// The lamps of every colour in turn (k = 0, 1, ...): red, green, blue, warm, orange, white. What lampRegion and the
// speed gate's lamp scenes place.
world::BlockType colourLamp(int k);

// Unit faces covered by a mesh's quads: each quad's extent across its face's normal, in blocks.
long long coveredFaces(const world::ChunkMesh& mesh);

} // namespace bench
