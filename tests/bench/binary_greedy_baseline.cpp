#include "binary_greedy_baseline.h"

#include <bit>
#include <cstring>

namespace bench {

namespace {

constexpr int kP = BinaryGreedyBaseline::kPadded;
constexpr int kN = BinaryGreedyBaseline::kInner;
constexpr std::uint64_t kInnerBits = ~(std::uint64_t{1} << 63 | 1u); // bits 1..62

// x: start along the bits, y: start along the rows, z: slice; w along the bits, h along the rows.
std::uint64_t packQuad(unsigned x, unsigned y, unsigned z, unsigned w, unsigned h, unsigned dir, unsigned type) {
    return std::uint64_t{x} | std::uint64_t{y} << 6 | std::uint64_t{z} << 12 | std::uint64_t{w} << 18 |
           std::uint64_t{h} << 24 | std::uint64_t{dir} << 30 | std::uint64_t{type} << 33;
}

} // namespace

void BinaryGreedyBaseline::buildColumns(const std::uint8_t* blocks, std::uint64_t* columns) {
    for (int p = 0; p < kP; ++p) {
        for (int q = 0; q < kP; ++q) {
            std::uint64_t c = 0;
            for (int k = 0; k < kP; ++k) c |= std::uint64_t{blocks[index(p, q, k)] != 0} << k;
            columns[p * kP + q] = c;
        }
    }
}

int BinaryGreedyBaseline::mesh(const std::uint8_t* blocks, const std::uint64_t* columns,
                               std::vector<std::uint64_t>& quads) {
    quads.clear();
    // Culling: a face shows where a block is solid and its neighbour in that direction is not.
    for (int p = 1; p <= kN; ++p) {
        for (int q = 1; q <= kN; ++q) {
            const std::uint64_t self = columns[p * kP + q];
            const std::uint64_t c = self & kInnerBits;
            m_faces[0][p - 1][q - 1] = (c & ~columns[(p + 1) * kP + q]) >> 1;
            m_faces[1][p - 1][q - 1] = (c & ~columns[(p - 1) * kP + q]) >> 1;
            m_faces[2][q - 1][p - 1] = (c & ~columns[p * kP + q + 1]) >> 1;
            m_faces[3][q - 1][p - 1] = (c & ~columns[p * kP + q - 1]) >> 1;
            m_faces[4][p - 1][q - 1] = c & ~(self >> 1);
            m_faces[5][p - 1][q - 1] = c & ~(self << 1);
        }
    }

    // Faces across the columns (normals along p and q): slice, rows ("forward"), bits ("right").
    for (int dir = 0; dir < 4; ++dir) {
        const bool alongP = dir < 2;
        const auto typeAt = [&](int slice, int row, int bit) {
            return alongP ? blocks[index(slice + 1, row + 1, bit + 1)] : blocks[index(row + 1, slice + 1, bit + 1)];
        };
        for (int s = 0; s < kN; ++s) {
            std::memset(m_forward, 0, kN);
            for (int r = 0; r < kN; ++r) {
                std::uint64_t here = m_faces[dir][s][r];
                if (here == 0) continue;
                const std::uint64_t next = r + 1 < kN ? m_faces[dir][s][r + 1] : 0;
                while (here != 0) {
                    const int b = std::countr_zero(here);
                    const std::uint8_t type = typeAt(s, r, b);
                    if ((next >> b & 1u) != 0 && typeAt(s, r + 1, b) == type) {
                        ++m_forward[b]; // the rectangle goes on in the next row
                        here &= ~(std::uint64_t{1} << b);
                        continue;
                    }
                    int w = 1;
                    for (int bb = b + 1; bb < kN; ++bb) {
                        if ((here >> bb & 1u) == 0 || m_forward[bb] != m_forward[b] || typeAt(s, r, bb) != type) break;
                        m_forward[bb] = 0;
                        ++w;
                    }
                    here &= ~((std::uint64_t{1} << (b + w)) - 1);
                    const int h = m_forward[b] + 1;
                    quads.push_back(packQuad(static_cast<unsigned>(b), static_cast<unsigned>(r + 1 - h),
                                             static_cast<unsigned>(s), static_cast<unsigned>(w),
                                             static_cast<unsigned>(h), static_cast<unsigned>(dir), type));
                    m_forward[b] = 0;
                }
            }
        }
    }

    // Faces along the columns (normal along k): every bit is its own slice; rows p ("forward") and
    // q ("right"), a forward count per (q, bit) and a right count per bit.
    for (int dir = 4; dir < 6; ++dir) {
        std::memset(m_forward, 0, sizeof m_forward);
        std::memset(m_right, 0, sizeof m_right);
        for (int p = 0; p < kN; ++p) {
            for (int q = 0; q < kN; ++q) {
                std::uint64_t here = m_faces[dir][p][q];
                if (here == 0) continue;
                const std::uint64_t forward = p + 1 < kN ? m_faces[dir][p + 1][q] : 0;
                const std::uint64_t right = q + 1 < kN ? m_faces[dir][p][q + 1] : 0;
                std::uint8_t* fwd = m_forward + q * kP;
                while (here != 0) {
                    const int k = std::countr_zero(here);
                    here &= here - 1;
                    const std::uint8_t type = blocks[index(p + 1, q + 1, k)];
                    if (m_right[k] == 0 && (forward >> k & 1u) != 0 && blocks[index(p + 2, q + 1, k)] == type) {
                        ++fwd[k];
                        continue;
                    }
                    if ((right >> k & 1u) != 0 && fwd[k] == fwd[kP + k] && blocks[index(p + 1, q + 2, k)] == type) {
                        fwd[k] = 0;
                        ++m_right[k];
                        continue;
                    }
                    const int w = m_right[k] + 1, h = fwd[k] + 1;
                    quads.push_back(packQuad(static_cast<unsigned>(q + 1 - w), static_cast<unsigned>(p + 1 - h),
                                             static_cast<unsigned>(k), static_cast<unsigned>(w),
                                             static_cast<unsigned>(h), static_cast<unsigned>(dir), type));
                    fwd[k] = 0;
                    m_right[k] = 0;
                }
            }
        }
    }
    return static_cast<int>(quads.size());
}

long long BinaryGreedyBaseline::coveredFaces(const std::vector<std::uint64_t>& quads) {
    long long n = 0;
    for (const std::uint64_t q : quads) n += static_cast<long long>((q >> 18 & 63u) * (q >> 24 & 63u));
    return n;
}

} // namespace bench
