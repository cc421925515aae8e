// MeshMode::Culled: deliberately the plain per-voxel loop, sharing nothing with the greedy mesher's bit
// tricks (mesher.cpp) except the vertex layout (mesh_quads.h), so that tests can hold the greedy mesher
// against it.
#include "world/mesh_culled.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "world/mesh_quads.h"

namespace world {

namespace {

template <int D>
void emitCulledFace(const PaddedChunk& in, QuadSink& out, int x, int y, int z, BlockType t) {
    constexpr DirInfo di = kDirs[D];
    const int* n = kFaceNormals[D];
    const int q[3] = {x + n[0], y + n[1], z + n[2]};
    if (isSolid(in.get(q[0], q[1], q[2]))) return;
    unsigned pattern = 0;
    for (int db = -1; db <= 1; ++db) {
        for (int dc = -1; dc <= 1; ++dc) {
            int p[3] = {q[0], q[1], q[2]};
            p[di.b] += db;
            p[di.c] += dc;
            if (isSolid(in.get(p[0], p[1], p[2]))) pattern |= 1u << ((dc + 1) + 3 * (db + 1));
        }
    }
    // Smooth light, written out voxel by voxel: per corner, the mean of the voxels that are not solid among
    // the air-side one, the two beside the corner and the diagonal one (not when both beside it are solid).
    const auto lightAt = [&](const int(&p)[3]) {
        return LightLevel{in.light.level[static_cast<std::size_t>(PaddedChunk::index(p[0], p[1], p[2]))]};
    };
    CornerLight light = 0;
    for (int cb = 0; cb < 2; ++cb) {
        for (int cc = 0; cc < 2; ++cc) {
            int sideC[3] = {q[0], q[1], q[2]}, sideB[3] = {q[0], q[1], q[2]}, diagonal[3] = {q[0], q[1], q[2]};
            sideC[di.c] += 2 * cc - 1;
            sideB[di.b] += 2 * cb - 1;
            diagonal[di.c] += 2 * cc - 1;
            diagonal[di.b] += 2 * cb - 1;
            const bool solidC = isSolid(in.get(sideC[0], sideC[1], sideC[2]));
            const bool solidB = isSolid(in.get(sideB[0], sideB[1], sideB[2]));
            const bool solidD = isSolid(in.get(diagonal[0], diagonal[1], diagonal[2]));
            const LightLevel mid = lightAt(q);
            int sun = mid.sun(), red = mid.red(), green = mid.green(), blue = mid.blue(), count = 1;
            const auto add = [&](LightLevel l) {
                sun += l.sun(), red += l.red(), green += l.green(), blue += l.blue(), ++count;
            };
            if (!solidC) add(lightAt(sideC));
            if (!solidB) add(lightAt(sideB));
            if (!solidD && !(solidB && solidC)) add(lightAt(diagonal));
            const auto mean = [&](int sum) { return static_cast<int>(std::lround(double(sum) / count)); };
            light |= CornerLight{LightLevel::of(mean(sun), mean(red), mean(green), mean(blue)).bits}
                     << (16 * (cc + 2 * cb));
        }
    }
    const int pos[3] = {x - 1, y - 1, z - 1};
    out.quad<D>(pos[di.a], pos[di.b], pos[di.c], 1, 1, faceTiles().t[D][static_cast<std::uint8_t>(t)],
                kAoTable[pattern], light);
}

void meshCulled(const PaddedChunk& in, QuadSink& out) {
    for (int y = 1; y <= kN; ++y) {
        for (int z = 1; z <= kN; ++z) {
            for (int x = 1; x <= kN; ++x) {
                const BlockType t = in.get(x, y, z);
                if (!isSolid(t)) continue;
                emitCulledFace<kFacePosX>(in, out, x, y, z, t);
                emitCulledFace<kFaceNegX>(in, out, x, y, z, t);
                emitCulledFace<kFacePosY>(in, out, x, y, z, t);
                emitCulledFace<kFaceNegY>(in, out, x, y, z, t);
                emitCulledFace<kFacePosZ>(in, out, x, y, z, t);
                emitCulledFace<kFaceNegZ>(in, out, x, y, z, t);
            }
        }
    }
}

} // namespace

namespace detail {

void meshCulled(const PaddedChunk& in, VertexList& out) {
    QuadSink sink(out);
    world::meshCulled(in, sink); // the loop above, in the unnamed namespace
}

} // namespace detail

} // namespace world
