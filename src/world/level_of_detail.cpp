#include "world/level_of_detail.h"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace world {

namespace {

constexpr int kN = kChunkSize; // 32
using Row = std::uint64_t;

// The block types that give light, as bytes, and a table of them.
struct EmissiveTypes {
    EmissiveTypes() {
        for (int t = 0; t < kBlockTypeCount; ++t) {
            if (!blockInfo(static_cast<BlockType>(t)).emission.any()) continue;
            types.push_back(static_cast<unsigned char>(t));
            is[static_cast<std::size_t>(t)] = true;
        }
    }
    std::vector<unsigned char> types;
    std::array<bool, 256> is{};
};
const EmissiveTypes& emissiveTypes() {
    static const EmissiveTypes types; // built on first use: blockInfo's table lives in another file
    return types;
}

// The cell's highest emissive block (the first in its layer), or `otherwise` when it has none.
unsigned char emissiveIn(const EmissiveTypes& emissive, const unsigned char* in, int cx, int cy, int cz, int factor,
                         unsigned char otherwise) {
    for (int y = cy + factor - 1; y >= cy; --y)
        for (int z = cz; z < cz + factor; ++z)
            for (int x = cx; x < cx + factor; ++x) {
                const unsigned char t = in[PaddedChunk::index(x, y, z)];
                if (emissive.is[t]) return t;
            }
    return otherwise;
}

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
    // Most chunks hold no emissive block: one memchr a type (the border too, which only costs a scan of
    // the cells) decides whether the cells need looking through for one.
    const EmissiveTypes& emissive = emissiveTypes();
    bool anyEmissive = false;
    for (const unsigned char t : emissive.types)
        anyEmissive = anyEmissive || std::memchr(in, t, PaddedChunk::kVolume) != nullptr;
    const Row cellBits = (Row{1} << factor) - 1;
    for (int cy = 1; cy <= kN; cy += factor) {
        for (int cz = 1; cz <= kN; cz += factor) {
            for (int cx = 1; cx <= kN; cx += factor) {
                const Row mask = cellBits << cx;
                unsigned char type = 0; // Air
                int top = cy - 1;       // the cell's highest solid layer
                for (int y = cy + factor - 1; y >= cy && type == 0; --y) {
                    for (int z = cz; z < cz + factor; ++z) {
                        const Row hit = fine.solid[y][z] & mask;
                        if (hit != 0) {
                            type = in[PaddedChunk::index(std::countr_zero(hit), y, z)];
                            top = y;
                            break;
                        }
                    }
                }
                if (anyEmissive && type != 0) type = emissiveIn(emissive, in, cx, cy, cz, factor, type);
                for (int y = cy; y < cy + factor; ++y) {
                    const unsigned char t = y <= top ? type : 0;
                    for (int z = cz; z < cz + factor; ++z) {
                        std::memset(to + PaddedChunk::index(cx, y, z), t, static_cast<std::size_t>(factor));
                        out.solid[y][z] = t != 0 ? out.solid[y][z] | mask : out.solid[y][z] & ~mask;
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
