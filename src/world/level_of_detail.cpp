#include "world/level_of_detail.h"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace world {

namespace {

constexpr int kN = kChunkSize; // 32
using Row = std::uint64_t;

} // namespace

void coarsenPadded(const PaddedChunk& fine, int factor, PaddedChunk& out) {
    if (factor != 2 && factor != 4) throw std::invalid_argument("coarsenPadded: factor must be 2 or 4");
    if (fine.blocks.stale) throw std::invalid_argument("coarsenPadded: the fine chunk's solid rows are stale");
    std::memcpy(out.blocks.untrackedData(), fine.blocks.data(), PaddedChunk::kVolume);
    std::memcpy(out.solid, fine.solid, sizeof out.solid);
    out.light = fine.light; // the fine voxels' light: a coarse face's air side is air in the fine chunk too
    out.blocks.stale = false;
    const auto* in = reinterpret_cast<const unsigned char*>(fine.blocks.data());
    auto* to = reinterpret_cast<unsigned char*>(out.blocks.untrackedData());
    const Row cellBits = (Row{1} << factor) - 1;
    for (int cy = 1; cy <= kN; cy += factor) {
        for (int cz = 1; cz <= kN; cz += factor) {
            for (int cx = 1; cx <= kN; cx += factor) {
                const Row mask = cellBits << cx;
                unsigned char type = 0; // Air
                for (int y = cy + factor - 1; y >= cy && type == 0; --y) {
                    for (int z = cz; z < cz + factor; ++z) {
                        const Row hit = fine.solid[y][z] & mask;
                        if (hit != 0) {
                            type = in[PaddedChunk::index(std::countr_zero(hit), y, z)];
                            break;
                        }
                    }
                }
                for (int y = cy; y < cy + factor; ++y) {
                    for (int z = cz; z < cz + factor; ++z) {
                        std::memset(to + PaddedChunk::index(cx, y, z), type, static_cast<std::size_t>(factor));
                        out.solid[y][z] = type != 0 ? out.solid[y][z] | mask : out.solid[y][z] & ~mask;
                    }
                }
            }
        }
    }
}

void meshAtDetail(const PaddedChunk& fine, MeshMode mode, int cell, PaddedChunk& scratch, ChunkMesh& out) {
    if (cell > 1) coarsenPadded(fine, cell, scratch);
    meshChunk(cell > 1 ? scratch : fine, out, mode);
}

} // namespace world
