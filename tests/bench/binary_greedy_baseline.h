// The anchor our mesher is measured against: a binary greedy mesher written here from the published
// algorithm (cgerikj/binary-greedy-meshing, version 2), not from its code. It is deliberately that
// algorithm and nothing more, so the benchmark compares like with like:
// - input: a 64^3 block region (a 62^3 mesh and a one-block border) as bytes, plus its occupancy as
//   64-bit columns prepared by the caller, as the published mesher expects of the world's storage;
// - faces culled 64 at a time by AND-NOT of neighbouring columns;
// - faces across the columns merged "forward" by counting matching rows, then "right" across bits
//   with equal counts; faces along the columns merged with two counters per bit;
// - output: one 8-byte quad per rectangle (position 3 x 6 bits, size 2 x 6 bits, block type), no
//   ambient occlusion, no vertices, no tiles.
// Used only by tests/bench; the game never runs it.
#pragma once
#include <cstdint>
#include <vector>

namespace bench {

class BinaryGreedyBaseline {
public:
    static constexpr int kPadded = 64;
    static constexpr int kInner = kPadded - 2; // 62

    // Block bytes in (p, q, k) order: index k + 64 * (q + 64 * p); 0 is air.
    static constexpr int index(int p, int q, int k) { return k + kPadded * (q + kPadded * p); }

    // Occupancy: bit k of column(p, q) is set when the block at (p, q, k) is not air.
    static void buildColumns(const std::uint8_t* blocks, std::uint64_t* columns /* 64 * 64 */);

    // Meshes the inner 62^3; `quads` is cleared and refilled. Returns the number of quads.
    int mesh(const std::uint8_t* blocks, const std::uint64_t* columns, std::vector<std::uint64_t>& quads);

    // Unit faces covered by a quad list (sum of width x height): the benchmark checks that it equals
    // the number of visible faces, so the anchor is known to do the whole job before it is timed.
    static long long coveredFaces(const std::vector<std::uint64_t>& quads);

private:
    // Visible faces, per direction: [direction][slice][row], bits along the third axis.
    std::uint64_t m_faces[6][kInner][kInner];
    std::uint8_t m_forward[kInner * kPadded]; // forward merge counts, per (row, bit)
    std::uint8_t m_right[kPadded];            // right merge counts, per bit (faces along columns)
};

} // namespace bench
