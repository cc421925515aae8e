#include "bench_regions.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

#include "binary_greedy_baseline.h"
#include "world/column_light.h"
#include "world/world.h"

namespace bench {

namespace {

// The blocks of `w` around its surface at (32, 32), as region() and lampRegion() lay them out.
std::unique_ptr<Region> regionOf(const world::World& w) {
    auto r = std::make_unique<Region>();
    const int h = world::surfaceHeight(w.terrain(), 32, 32);
    const int cy = std::clamp((h - 16) / world::kChunkSize, 0, world::kWorldHeightChunks - 2);
    std::vector<world::BlockEdit> edits;
    for (int dy = 0; dy < 2; ++dy)
        for (int dz = 0; dz < 2; ++dz)
            for (int dx = 0; dx < 2; ++dx) {
                auto p = std::make_unique<world::PaddedChunk>();
                w.gatherPadded({dx, cy + dy, dz}, *p);
                auto lit = std::make_unique<world::PaddedChunk>(*p);
                w.editsAround({dx, cy + dy, dz}, edits);
                world::lightPadded(w.terrain(), {dx, cy + dy, dz}, edits, lit->light);
                r->chunks.push_back(std::move(p));
                r->lit.push_back(std::move(lit));
            }
    using B = BinaryGreedyBaseline;
    const glm::ivec3 o(-1, cy * world::kChunkSize - 1, -1); // padded origin: p = x, q = z, k = y
    r->bytes.resize(B::kPadded * B::kPadded * B::kPadded);
    for (int p = 0; p < B::kPadded; ++p)
        for (int q = 0; q < B::kPadded; ++q)
            for (int k = 0; k < B::kPadded; ++k)
                r->bytes[B::index(p, q, k)] = static_cast<std::uint8_t>(w.get(o + glm::ivec3(p, k, q)));
    r->columns.resize(B::kPadded * B::kPadded);
    B::buildColumns(r->bytes.data(), r->columns.data());
    const auto solidAt = [&](int p, int q, int k) { return r->bytes[B::index(p, q, k)] != 0; };
    for (int p = 1; p <= B::kInner; ++p)
        for (int q = 1; q <= B::kInner; ++q)
            for (int k = 1; k <= B::kInner; ++k) {
                if (!solidAt(p, q, k)) continue;
                r->anchorVisibleFaces += !solidAt(p + 1, q, k) + !solidAt(p - 1, q, k) + !solidAt(p, q + 1, k) +
                                         !solidAt(p, q - 1, k) + !solidAt(p, q, k + 1) + !solidAt(p, q, k - 1);
            }
    return r;
}

} // namespace

const Region& region(int seed) {
    static std::unique_ptr<Region> cache[4];
    if (seed < 1 || seed > 3) throw std::invalid_argument("bench::region: seed must be 1, 2 or 3");
    std::unique_ptr<Region>& r = cache[seed];
    if (!r) r = regionOf(world::World(world::TerrainDef{static_cast<std::uint64_t>(seed)}));
    return *r;
}

world::BlockType colourLamp(int k) {
    constexpr world::BlockType kLamps[] = {world::BlockType::RedLamp,    world::BlockType::GreenLamp,
                                           world::BlockType::BlueLamp,   world::BlockType::WarmLamp,
                                           world::BlockType::OrangeLamp, world::BlockType::Lamp};
    return kLamps[static_cast<std::size_t>(k) % std::size(kLamps)];
}

const Region& lampRegion(int seed, bool coloured) {
    static std::unique_ptr<Region> cache[4][2];
    if (seed < 1 || seed > 3) throw std::invalid_argument("bench::lampRegion: seed must be 1, 2 or 3");
    std::unique_ptr<Region>& r = cache[seed][coloured ? 1 : 0];
    if (r) return *r;
    world::World w(world::TerrainDef{static_cast<std::uint64_t>(seed)});
    int k = 0;
    for (int z = 8; z < 64; z += 16)
        for (int x = 8; x < 64; x += 16, ++k) {
            const int ground = world::surfaceHeight(w.terrain(), x, z);
            w.set({x, ground + 1, z}, coloured ? colourLamp(k) : world::BlockType::Lamp);
        }
    r = regionOf(w);
    // The region's 64 layers are chosen by the ground at its middle; every lamp must be inside them.
    const auto lamps = std::count_if(r->bytes.begin(), r->bytes.end(), [](std::uint8_t b) {
        return world::blockInfo(static_cast<world::BlockType>(b)).emission.any();
    });
    if (lamps != k)
        throw std::logic_error("bench::lampRegion: " + std::to_string(lamps) + " of its " + std::to_string(k) +
                               " lamps are inside the region");
    return *r;
}

// Unit faces covered by a mesh's quads: each quad's extent across its face's normal, in blocks.
long long coveredFaces(const world::ChunkMesh& mesh) {
    long long n = 0;
    for (std::size_t q = 0; q < mesh.vertices.size(); q += 4) {
        int low[3] = {255, 255, 255}, high[3] = {0, 0, 0};
        for (std::size_t k = q; k < q + 4; ++k) {
            const world::ChunkVertex& v = mesh.vertices[k];
            const int p[3] = {world::xOf(v), world::yOf(v), world::zOf(v)};
            for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], p[a]), high[a] = std::max(high[a], p[a]);
        }
        const int normal = world::faceOf(mesh.vertices[q]) / 2;
        long long area = 1;
        for (int a = 0; a < 3; ++a)
            if (a != normal) area *= high[a] - low[a];
        n += area;
    }
    return n;
}

} // namespace bench
