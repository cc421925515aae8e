// The project's binary greedy baseline (tests/bench/binary_greedy_baseline.cpp) against the published mesher
// it stands for (cgerikj/binary-greedy-meshing, src/mesher.h), on the same blocks in one process. Built and run
// by scripts/compare-anchor.sh, which fetches the published file at a pinned commit into a temporary folder:
// that code is never committed here. Both get the 64^3 terrain regions of the mesher benchmark (seeds 1-3,
// bytes and occupancy columns in the layout both expect) and must cover every visible face in as many quads. Prints
// each mesher's median time per region over interleaved rounds and the ratio baseline / published.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#define BM_VECTOR std::vector
#include "mesher.h" // the published one, from the folder the script gives with -I

#include "binary_greedy_baseline.h"
#include "world/world.h"

namespace {

struct Region {
    std::vector<std::uint8_t> bytes;
    std::vector<std::uint64_t> columns;
    long long visibleFaces = 0;
};

// As tests/bench/bench_mesher.cpp's region(): the 2 x 2 x 2 chunks at the surface near the origin.
Region region(int seed) {
    using B = bench::BinaryGreedyBaseline;
    Region r;
    const world::World w(world::TerrainDef{static_cast<std::uint64_t>(seed)});
    const int h = world::surfaceHeight(w.terrain(), 32, 32);
    const int cy = std::clamp((h - 16) / world::kChunkSize, 0, world::kWorldHeightChunks - 2);
    const glm::ivec3 o(-1, cy * world::kChunkSize - 1, -1);
    r.bytes.resize(B::kPadded * B::kPadded * B::kPadded);
    for (int p = 0; p < B::kPadded; ++p)
        for (int q = 0; q < B::kPadded; ++q)
            for (int k = 0; k < B::kPadded; ++k)
                r.bytes[B::index(p, q, k)] = static_cast<std::uint8_t>(w.get(o + glm::ivec3(p, k, q)));
    r.columns.resize(B::kPadded * B::kPadded);
    B::buildColumns(r.bytes.data(), r.columns.data());
    const auto solid = [&](int p, int q, int k) { return r.bytes[B::index(p, q, k)] != 0; };
    for (int p = 1; p <= B::kInner; ++p)
        for (int q = 1; q <= B::kInner; ++q)
            for (int k = 1; k <= B::kInner; ++k)
                if (solid(p, q, k))
                    r.visibleFaces += !solid(p + 1, q, k) + !solid(p - 1, q, k) + !solid(p, q + 1, k) +
                                      !solid(p, q - 1, k) + !solid(p, q, k + 1) + !solid(p, q, k - 1);
    return r;
}

long long covered(const std::uint64_t* quads, std::size_t n) {
    long long faces = 0;
    for (std::size_t i = 0; i < n; ++i)
        faces += static_cast<long long>((quads[i] >> 18 & 63u) * (quads[i] >> 24 & 63u));
    return faces;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    const int rounds = argc > 1 ? std::atoi(argv[1]) : 2000;
    using Clock = std::chrono::steady_clock;
    std::vector<double> ratios;
    for (int seed = 1; seed <= 3; ++seed) {
        Region r = region(seed);
        bench::BinaryGreedyBaseline ours;
        std::vector<std::uint64_t> ourQuads;
        std::vector<std::uint64_t> faceMasks(CS_2 * 6), published(1 << 16);
        std::vector<std::uint8_t> forward(CS_2), right(CS);
        MeshData md;
        md.faceMasks = faceMasks.data();
        md.opaqueMask = r.columns.data();
        md.forwardMerged = forward.data();
        md.rightMerged = right.data();
        md.vertices = &published;
        md.maxVertices = static_cast<int>(published.size());
        const auto runOurs = [&] { ours.mesh(r.bytes.data(), r.columns.data(), ourQuads); };
        const auto runPublished = [&] { mesh(r.bytes.data(), md); };
        runOurs();
        runPublished();
        // Both do the whole job: every visible face once (the published count is one past its last quad).
        const long long a = covered(ourQuads.data(), ourQuads.size());
        const long long b = covered(published.data(), static_cast<std::size_t>(md.vertexCount - 1));
        if (a != r.visibleFaces || b != r.visibleFaces ||
            ourQuads.size() != static_cast<std::size_t>(md.vertexCount - 1)) {
            std::fprintf(stderr,
                         "seed %d: baseline covers %lld faces in %zu quads, published %lld in %d, region %lld\n", seed,
                         a, ourQuads.size(), b, md.vertexCount - 1, r.visibleFaces);
            return 1;
        }
        std::vector<double> tOurs, tPublished;
        // Turn about, so that neither always runs on the caches the other has just filled.
        const auto time = [](auto&& run) {
            const auto t0 = Clock::now();
            run();
            return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
        };
        for (int i = 0; i < rounds; ++i) {
            if (i % 2 == 0) {
                tOurs.push_back(time(runOurs));
                tPublished.push_back(time(runPublished));
            } else {
                tPublished.push_back(time(runPublished));
                tOurs.push_back(time(runOurs));
            }
        }
        const double mo = median(tOurs), mp = median(tPublished);
        ratios.push_back(mo / mp);
        std::printf("seed %d: baseline %.1f us (%zu quads), published %.1f us (%d quads), baseline / published %.3f\n",
                    seed, mo, ourQuads.size(), mp, md.vertexCount - 1, mo / mp);
    }
    std::printf("median baseline / published: %.3f\n", median(ratios));
    return 0;
}
