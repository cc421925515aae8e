#include "world/collision.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "world/world.h"

namespace world {

namespace {

// Voxel indices must fit an int with room to spare; boxes beyond this do not collide.
constexpr double kMaxCoordinate = 1 << 30;

struct SpanOverlap {
    long long first, last; // voxel indices overlapped with positive length; empty if first > last
};

SpanOverlap overlap(double lo, double hi) {
    return {static_cast<long long>(std::floor(lo)), static_cast<long long>(std::ceil(hi)) - 1};
}

bool usable(const Aabb& b) {
    for (int a = 0; a < 3; ++a) {
        if (!(std::abs(b.min[a]) < kMaxCoordinate) || !(std::abs(b.max[a]) < kMaxCoordinate)) return false;
    }
    return true;
}

// Shortens a move along `axis` so that the box stops kCollisionSkin short of the first obstacle it would
// enter; obstacles the box already overlaps, or that it does not overlap across the axis, are passed by.
float clipAgainstObstacles(const Aabb& box, int axis, float move, std::span<const Aabb> obstacles, bool& blocked) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (const Aabb& o : obstacles) {
        if (!(box.min[u] < o.max[u] && box.max[u] > o.min[u] && box.min[v] < o.max[v] && box.max[v] > o.min[v]))
            continue;
        if (move > 0.0f && box.max[axis] <= o.min[axis] && box.max[axis] + move > o.min[axis] - kCollisionSkin) {
            move = std::max(0.0f, o.min[axis] - kCollisionSkin - box.max[axis]);
            blocked = true;
        } else if (move < 0.0f && box.min[axis] >= o.max[axis] && box.min[axis] + move < o.max[axis] + kCollisionSkin) {
            move = std::min(0.0f, o.max[axis] + kCollisionSkin - box.min[axis]);
            blocked = true;
        }
    }
    return move;
}

// `emptyFromY`: every voxel with y >= this is known to be air (the world's ceiling), which bounds the
// scan when flying up or moving sideways above the world.
template <typename BlockAt>
float sweepVoxels(BlockAt& blockAt, Aabb& box, int axis, float delta, int emptyFromY, bool& blocked) {
    blocked = false;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const SpanOverlap ru = overlap(box.min[u], box.max[u]), rv = overlap(box.min[v], box.max[v]);
    const long long lowestY = axis == 1 ? LLONG_MIN : (u == 1 ? ru.first : rv.first);

    const auto layerSolid = [&](long long k) {
        if (axis == 1 ? k >= emptyFromY : lowestY >= emptyFromY) return false;
        for (long long iu = ru.first; iu <= ru.last; ++iu) {
            for (long long iv = rv.first; iv <= rv.last; ++iv) {
                glm::ivec3 p;
                p[axis] = static_cast<int>(k);
                p[u] = static_cast<int>(iu);
                p[v] = static_cast<int>(iv);
                if (isSolid(blockAt(p))) return true;
            }
        }
        return false;
    };

    float moved = delta;
    float face = 0.0f; // the blocking face, when blocked
    if (delta > 0.0f) {
        // Layers whose lower face lies at or ahead of the leading face and is reached by the move.
        const long long first = static_cast<long long>(std::ceil(box.max[axis]));
        long long last =
            static_cast<long long>(std::ceil(std::min(static_cast<double>(box.max[axis]) + delta, kMaxCoordinate))) - 1;
        if (axis == 1) last = std::min(last, static_cast<long long>(emptyFromY) - 1);
        for (long long k = first; k <= last; ++k) {
            if (layerSolid(k)) {
                face = static_cast<float>(k);
                moved = std::max(0.0f, (face - kCollisionSkin) - box.max[axis]);
                blocked = true;
                break;
            }
        }
    } else {
        // Layers whose upper face lies at or behind the trailing face and is reached by the move.
        const long long first = static_cast<long long>(std::floor(box.min[axis])) - 1;
        const long long last =
            static_cast<long long>(std::floor(std::max(static_cast<double>(box.min[axis]) + delta, -kMaxCoordinate)));
        for (long long k = first; k >= last; --k) {
            if (layerSolid(k)) {
                face = static_cast<float>(k + 1);
                moved = std::min(0.0f, (face + kCollisionSkin) - box.min[axis]);
                blocked = true;
                break;
            }
        }
    }
    box.min[axis] += moved;
    box.max[axis] += moved;
    // Far from the origin the skin can round away; the box may then touch the face, never cross it,
    // or the next sweep would start beyond the face and tunnel.
    if (blocked && moved != 0.0f) {
        const float over = delta > 0.0f ? box.max[axis] - face : face - box.min[axis];
        if (over > 0.0f) {
            const float back = delta > 0.0f ? -over : over;
            box.min[axis] += back;
            box.max[axis] += back;
            moved += back;
        }
    }
    return moved;
}

template <typename BlockAt>
float sweepAxis(BlockAt& blockAt, Aabb& box, int axis, float delta, int emptyFromY, bool& blocked,
                std::span<const Aabb> obstacles) {
    blocked = false;
    if (delta == 0.0f || !std::isfinite(delta)) return 0.0f;
    if (!obstacles.empty()) delta = clipAgainstObstacles(box, axis, delta, obstacles, blocked);
    if (delta == 0.0f) return 0.0f;
    bool blockedByVoxel = false;
    const float moved = sweepVoxels(blockAt, box, axis, delta, emptyFromY, blockedByVoxel);
    blocked = blocked || blockedByVoxel;
    return moved;
}

template <typename BlockAt>
SweepResult sweep(BlockAt& blockAt, Aabb& box, glm::vec3 delta, int emptyFromY, std::span<const Aabb> obstacles) {
    SweepResult r{glm::vec3(0.0f), glm::bvec3(false)};
    if (!usable(box)) return r;
    for (const int axis : {1, 0, 2}) {
        bool blocked = false;
        r.moved[axis] = sweepAxis(blockAt, box, axis, delta[axis], emptyFromY, blocked, obstacles);
        r.blocked[axis] = blocked;
    }
    return r;
}

template <typename BlockAt>
bool overlapsSolid(BlockAt& blockAt, const Aabb& box) {
    if (!usable(box)) return false;
    const SpanOverlap rx = overlap(box.min.x, box.max.x), ry = overlap(box.min.y, box.max.y),
                      rz = overlap(box.min.z, box.max.z);
    for (long long y = ry.first; y <= ry.last; ++y) {
        for (long long z = rz.first; z <= rz.last; ++z) {
            for (long long x = rx.first; x <= rx.last; ++x) {
                if (isSolid(blockAt(glm::ivec3(static_cast<int>(x), static_cast<int>(y), static_cast<int>(z)))))
                    return true;
            }
        }
    }
    return false;
}

} // namespace

SweepResult moveAabb(const World& world, Aabb& box, glm::vec3 delta, std::span<const Aabb> obstacles) {
    auto blockAt = [&](glm::ivec3 p) { return world.get(p); };
    return sweep(blockAt, box, delta, kWorldHeight, obstacles);
}

SweepResult moveAabb(const std::function<BlockType(glm::ivec3)>& blockAt, Aabb& box, glm::vec3 delta) {
    if (!blockAt) {
        box.min += delta;
        box.max += delta;
        return {delta, glm::bvec3(false)};
    }
    return sweep(blockAt, box, delta, INT_MAX, {});
}

bool intersectsSolid(const World& world, const Aabb& box) {
    auto blockAt = [&](glm::ivec3 p) { return world.get(p); };
    return overlapsSolid(blockAt, box);
}

bool intersectsSolid(const std::function<BlockType(glm::ivec3)>& blockAt, const Aabb& box) {
    return blockAt && overlapsSolid(blockAt, box);
}

} // namespace world
