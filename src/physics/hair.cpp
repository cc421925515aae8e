// The hair solver's hot loops. Build flags this file needs (set in CMake, not by pragma):
//   -fno-math-errno   so that sqrtf has no errno side effect and the strand loops vectorise;
//   -ffp-contract=off so that a compiler targeting FMA rounds the vector body and the scalar tail alike,
//                     which keeps threads = N bit-identical to threads = 1.
//
// Layout and order: nodes are node-major SoA (index = node * strands + strand), so every inner loop runs over
// strands with unit stride and no dependence between iterations. Strands are processed in blocks of kBlock so
// that a block's nodes stay in L1/L2 through the Verlet pass and all constraint passes (a 65,536-strand
// ball is 38 MB; sweeping it once per pass would be bound by memory bandwidth).
//
// The per-node arithmetic of each pass (integration, contacts, the methods' projections) is in
// hair_kernels.h, shared with hair-bench's limit kernel; this file orders the passes, places roots, handles
// blocks of voxels, threads, stats and sleep. The defaults per method (hairMethodDefaults) and why the game
// uses dftl: docs/HAIR.md.
#include "physics/hair.h"
#include "physics/hair_kernels.h"

#include "core/hash.h"
#include "core/rng.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>

namespace physics {

namespace {

constexpr int kBlock =
    static_cast<int>(kernels::kMaxLanes); // strands per block: 64 x 16 nodes x 6 floats = 24 KB, in L1
using kernels::pushOutAlongPath;
constexpr int kMaxAutoSubsteps = 16;   // a frame spike is split into at most this many extra substeps
constexpr double kShakeMaxTurn = 0.17; // rad (10 degrees): the largest turn of a segment SHAKE takes in one substep
constexpr int kMaxShakeSubsteps = 4;   // ...in at most this many substeps a step: a whip costs shake 4 steps at most
constexpr int kMaxThreads = 64;

// Rotation (column-major, glm's mat3_cast) plus centre and radius: where the roots go.
struct Frame {
    float m[9];
    glm::vec3 c;
    float r;
};

Frame makeFrame(const HostPose& pose, float radius) {
    const glm::mat3 m = glm::mat3_cast(pose.orientation);
    Frame f{};
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) f.m[col * 3 + row] = m[col][row];
    f.c = pose.centre;
    f.r = radius;
    return f;
}

// The one expression that places a root; rootPosition() and step() both use it, so they agree bit for bit.
inline void placeRoot(const Frame& f, float dx, float dy, float dz, float& ox, float& oy, float& oz) {
    ox = f.c.x + f.r * ((f.m[0] * dx + f.m[3] * dy) + f.m[6] * dz);
    oy = f.c.y + f.r * ((f.m[1] * dx + f.m[4] * dy) + f.m[7] * dz);
    oz = f.c.z + f.r * ((f.m[2] * dx + f.m[5] * dy) + f.m[8] * dz);
}

// Depth of p inside solid voxels (0 when in a free cell): distance to the nearest face with a free neighbour.
float voxelDepth(const VoxelOccupancy& v, float x, float y, float z) {
    const int cx = static_cast<int>(std::floor(x)), cy = static_cast<int>(std::floor(y)),
              cz = static_cast<int>(std::floor(z));
    if (!v.at(cx, cy, cz)) return 0.0f;
    const float p[3] = {x, y, z};
    const int c[3] = {cx, cy, cz};
    float best = 1.0f;
    for (int a = 0; a < 3; ++a) {
        int lo[3] = {cx, cy, cz}, hi[3] = {cx, cy, cz};
        lo[a] -= 1;
        hi[a] += 1;
        if (!v.at(lo[0], lo[1], lo[2])) best = std::min(best, p[a] - static_cast<float>(c[a]));
        if (!v.at(hi[0], hi[1], hi[2])) best = std::min(best, static_cast<float>(c[a] + 1) - p[a]);
    }
    return best;
}

// Moves p out of a solid voxel through the face its path q -> p entered by (the last slab entered), or the
// nearest face with a free neighbour when that one is blocked or q was in the same cell. A node boxed in on all
// six sides stays (nothing sensible to do; the game never asks for hair inside rock). For the methods whose
// contacts have no parent (pbd, xpbd-substeps).
void pushOutOfVoxels(const VoxelOccupancy& v, float& x, float& y, float& z, float qx, float qy, float qz) {
    const int c[3] = {static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)),
                      static_cast<int>(std::floor(z))};
    if (!v.at(c[0], c[1], c[2])) return;
    float* p[3] = {&x, &y, &z};
    const float q[3] = {qx, qy, qz};
    const auto freeSide = [&](int axis, int dir) {
        int n[3] = {c[0], c[1], c[2]};
        n[axis] += dir;
        return !v.at(n[0], n[1], n[2]);
    };
    int bestAxis = -1, bestDir = 0;
    float bestT = -1.0f;
    for (int a = 0; a < 3; ++a) {
        const float lo = static_cast<float>(c[a]), hi = lo + 1.0f, d = *p[a] - q[a];
        if (q[a] < lo && d > 0.0f) {
            const float t = (lo - q[a]) / d;
            if (t > bestT && freeSide(a, -1)) bestT = t, bestAxis = a, bestDir = -1;
        } else if (q[a] >= hi && d < 0.0f) {
            const float t = (q[a] - hi) / -d;
            if (t > bestT && freeSide(a, +1)) bestT = t, bestAxis = a, bestDir = +1;
        }
    }
    if (bestAxis < 0) {
        float bestDist = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a) {
            const float lo = static_cast<float>(c[a]);
            if (freeSide(a, -1) && *p[a] - lo < bestDist) bestDist = *p[a] - lo, bestAxis = a, bestDir = -1;
            if (freeSide(a, +1) && lo + 1.0f - *p[a] < bestDist)
                bestDist = lo + 1.0f - *p[a], bestAxis = a, bestDir = +1;
        }
    }
    if (bestAxis < 0) return;
    *p[bestAxis] = bestDir > 0
                       ? static_cast<float>(c[bestAxis] + 1)
                       : std::nextafter(static_cast<float>(c[bestAxis]), -std::numeric_limits<float>::infinity());
}

// With a parent (follow-the-leader, SHAKE's contact pass), p one segment L from a parent outside every block:
// the node goes onto the plane of the first block face the segment parent -> p crosses, at the point of the
// circle where that plane meets the parent's sphere nearest where the node was at the step's start, so the
// length holds and a node resting on a block stays put unless its parent drags it (friction enough to hold
// hair on the blocks, which are rough). The face is always within the parent's reach and has a free side (the
// cell the segment came from). The circle's point can lie in another block (in a concave edge): then the node
// goes along the edge, one segment from the parent; up to three faces are taken in turn, and a node still
// inside then goes to where the segment first entered a block (outside, that segment short). A parent inside a block
// (it never is after its own contact) falls back to the rule above.
void pushOutOfVoxels(const VoxelOccupancy& v, float& x, float& y, float& z, float qx, float qy, float qz,
                     const float* parent, float L) {
    const auto solid = [&](float a, float b, float c) {
        return v.at(static_cast<int>(std::floor(a)), static_cast<int>(std::floor(b)), static_cast<int>(std::floor(c)));
    };
    if (!solid(x, y, z)) return;
    if (solid(parent[0], parent[1], parent[2])) {
        pushOutOfVoxels(v, x, y, z, qx, qy, qz);
        return;
    }
    float* p[3] = {&x, &y, &z};
    const float q[3] = {qx, qy, qz};
    constexpr float kInf = std::numeric_limits<float>::infinity();
    float entry[3] = {0.0f, 0.0f, 0.0f};
    bool haveEntry = false;
    int held = -1; // the axis of the face the last attempt put the node on, and its plane
    float heldPlane = 0.0f;
    int firstAxis = 0; // the first face entered, and what is left of the segment in its plane
    float firstPlane = 0.0f, firstRho2 = -1.0f;
    const float aim[3] = {x, y, z};
    for (int attempt = 0; attempt < 3; ++attempt) {
        // The cells from the parent's to p's (a voxel walk), up to the first solid one.
        int cell[3], step[3];
        float d[3], tMax[3], tDelta[3];
        for (int a = 0; a < 3; ++a) {
            cell[a] = static_cast<int>(std::floor(parent[a]));
            d[a] = *p[a] - parent[a];
            step[a] = d[a] > 0.0f ? 1 : (d[a] < 0.0f ? -1 : 0);
            tMax[a] = step[a] > 0   ? (static_cast<float>(cell[a] + 1) - parent[a]) / d[a]
                      : step[a] < 0 ? (parent[a] - static_cast<float>(cell[a])) / -d[a]
                                    : kInf;
            tDelta[a] = step[a] != 0 ? 1.0f / std::abs(d[a]) : kInf;
        }
        int axis = -1;
        float tEnter = 0.0f;
        for (int guard = 0; guard < 64; ++guard) {
            const int a = tMax[0] <= tMax[1] ? (tMax[0] <= tMax[2] ? 0 : 2) : (tMax[1] <= tMax[2] ? 1 : 2);
            if (!(tMax[a] <= 1.0f)) break;
            tEnter = tMax[a];
            cell[a] += step[a];
            tMax[a] += tDelta[a];
            if (v.at(cell[0], cell[1], cell[2])) {
                axis = a;
                break;
            }
        }
        if (axis < 0) {
            // Rounding: the walk found no solid cell before p's own. The old rule, then out for sure below.
            if (!solid(x, y, z)) return;
            break;
        }
        // The plane of the face entered, on its free side.
        const float plane =
            step[axis] > 0 ? std::nextafter(static_cast<float>(cell[axis]), -kInf) : static_cast<float>(cell[axis] + 1);
        if (!haveEntry) {
            for (int a = 0; a < 3; ++a) entry[a] = parent[a] + d[a] * tEnter;
            entry[axis] = plane;
            haveEntry = true;
            firstAxis = axis;
            firstPlane = plane;
            firstRho2 = L * L - (parent[axis] - plane) * (parent[axis] - plane);
        }
        *p[axis] = plane;
        if (held >= 0 && held != axis) {
            // A concave edge (a floor and a wall): the node goes along it, one segment from the parent, on the
            // side of the edge where it was.
            const int b = 3 - held - axis;
            const float oa = parent[axis] - plane, oh = parent[held] - heldPlane;
            const float rho2 = L * L - oa * oa - oh * oh;
            const float side = q[b] != parent[b] ? q[b] - parent[b] : d[b];
            *p[held] = heldPlane;
            if (rho2 >= 0.0f) *p[b] = parent[b] + std::copysign(std::sqrt(rho2), side);
        } else {
            const int b1 = (axis + 1) % 3, b2 = (axis + 2) % 3;
            const float off = parent[axis] - plane;
            const float o1 = q[b1] - parent[b1], o2 = q[b2] - parent[b2];
            const float rho2 = L * L - off * off, w2 = o1 * o1 + o2 * o2;
            if (rho2 >= 0.0f && w2 > 1e-12f * L * L) {
                const float k = std::sqrt(rho2 / w2);
                *p[b1] = parent[b1] + o1 * k;
                *p[b2] = parent[b2] + o2 * k;
            }
        }
        if (!solid(x, y, z)) return;
        held = axis;
        heldPlane = plane;
    }
    // Boxed in by the faces tried (the node came from deep inside, as a new ball's straight strands start): the
    // free point of the first face's circle nearest where the walk aimed, tried every 22.5 degrees.
    if (haveEntry && firstRho2 >= 0.0f) {
        const int b1 = (firstAxis + 1) % 3, b2 = (firstAxis + 2) % 3;
        const float r = std::sqrt(firstRho2);
        float best = kInf, bx = 0.0f, by = 0.0f, bz = 0.0f;
        for (int k = 0; k < 16; ++k) {
            const float angle = static_cast<float>(k) * 0.39269908f;
            float c[3];
            c[firstAxis] = firstPlane;
            c[b1] = parent[b1] + r * std::cos(angle);
            c[b2] = parent[b2] + r * std::sin(angle);
            const float dist = (c[0] - aim[0]) * (c[0] - aim[0]) + (c[1] - aim[1]) * (c[1] - aim[1]) +
                               (c[2] - aim[2]) * (c[2] - aim[2]);
            if (dist < best && !solid(c[0], c[1], c[2])) best = dist, bx = c[0], by = c[1], bz = c[2];
        }
        if (best < kInf) {
            x = bx, y = by, z = bz;
            return;
        }
    }
    if (haveEntry && !solid(entry[0], entry[1], entry[2])) {
        x = entry[0], y = entry[1], z = entry[2];
    } else {
        pushOutOfVoxels(v, x, y, z, qx, qy, qz);
    }
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finitePose(const HostPose& p) {
    return finite(p.centre) && std::isfinite(p.orientation.w) && std::isfinite(p.orientation.x) &&
           std::isfinite(p.orientation.y) && std::isfinite(p.orientation.z);
}

} // namespace

// ---------------------------------------------------------------------------------------------------------
// A small persistent pool: workers sleep on a condition variable between steps, so a step pays one wake-up,
// not a thread creation per worker (~20 us each).
struct HairSolver::Pool {
    explicit Pool(int workers) {
        for (int i = 0; i < workers; ++i) m_threads.emplace_back([this, i] { loop(i + 1); });
    }
    ~Pool() {
        {
            std::lock_guard lock(m_mutex);
            m_stop = true;
        }
        m_wake.notify_all();
        for (auto& t : m_threads) t.join();
    }
    int workers() const { return static_cast<int>(m_threads.size()); }
    // Runs task(0) here and task(1..workers) on the workers; returns when all are done.
    template <typename F>
    void run(F& task) {
        {
            std::lock_guard lock(m_mutex);
            m_task = [](void* ctx, int i) { (*static_cast<F*>(ctx))(i); };
            m_ctx = static_cast<void*>(&task);
            m_pending = workers();
            ++m_generation;
        }
        m_wake.notify_all();
        task(0);
        std::unique_lock lock(m_mutex);
        m_done.wait(lock, [this] { return m_pending == 0; });
    }

private:
    void loop(int index) {
        std::uint64_t seen = 0;
        for (;;) {
            void (*task)(void*, int) = nullptr;
            void* ctx = nullptr;
            {
                std::unique_lock lock(m_mutex);
                m_wake.wait(lock, [&] { return m_stop || m_generation != seen; });
                if (m_stop) return;
                seen = m_generation;
                task = m_task;
                ctx = m_ctx;
            }
            task(ctx, index);
            {
                std::lock_guard lock(m_mutex);
                --m_pending;
            }
            m_done.notify_one();
        }
    }
    std::vector<std::thread> m_threads;
    std::mutex m_mutex;
    std::condition_variable m_wake, m_done;
    void (*m_task)(void*, int) = nullptr;
    void* m_ctx = nullptr;
    int m_pending = 0;
    std::uint64_t m_generation = 0;
    bool m_stop = false;
};

// Everything one substep needs, fixed before the strand loops start.
struct HairSolver::Substep {
    Frame frame{};             // the host at the end of this substep
    glm::vec3 oldCentre{0.0f}; // the host centre at its start
    glm::vec3 hostMove{0.0f};  // the centre's move over the previous substep
    float ratio = 1, damp = 1, accelY = 0;
    bool last = false; // the step's last substep: collect the stats
    std::span<const SphereCollider> others;
    const VoxelOccupancy* voxels = nullptr;
};

// ---------------------------------------------------------------------------------------------------------

glm::vec3 pushOutOfSphere(glm::vec3 p, glm::vec3 prev, glm::vec3 centre, float radius) {
    glm::vec3 r = p - centre;
    const glm::vec3 q = prev - centre;
    pushOutAlongPath(r.x, r.y, r.z, q.x, q.y, q.z, radius);
    return r + centre;
}

namespace {
constexpr std::string_view kMethodNames[kHairMethodCount] = {"ftl", "dftl", "pbd", "xpbd-substeps", "shake"};
}

std::string_view hairMethodName(HairMethod method) {
    const int i = static_cast<int>(method);
    return i >= 0 && i < kHairMethodCount ? kMethodNames[i] : std::string_view{};
}

std::optional<HairMethod> hairMethodFromName(std::string_view name) {
    for (int i = 0; i < kHairMethodCount; ++i)
        if (kMethodNames[i] == name) return static_cast<HairMethod>(i);
    return std::nullopt;
}

std::string hairMethodNames() {
    std::string out;
    for (int i = 0; i < kHairMethodCount; ++i) (out += i ? ", " : "") += kMethodNames[i];
    return out;
}

HairParams hairMethodDefaults(HairMethod method, HairParams base) {
    base.method = method;
    switch (method) {
    case HairMethod::Ftl:
    case HairMethod::Dftl:
        base.iterations = 1, base.substeps = 1;
        break; // one pass is exact (see HairMethod)
    case HairMethod::Pbd:
        base.iterations = 4, base.substeps = 1;
        break;
    case HairMethod::XpbdSubsteps:
        base.iterations = 1, base.substeps = 4;
        break;
    case HairMethod::Shake:
        base.iterations = 2, base.substeps = 1;
        break;
    case HairMethod::Count:
        break;
    }
    return base;
}

int hairProjectionsPerNode(const HairParams& p) {
    switch (p.method) {
    case HairMethod::Ftl:
    case HairMethod::Dftl:
    case HairMethod::Pbd:
        return p.iterations * p.substeps;
    case HairMethod::XpbdSubsteps:
        return p.substeps;
    case HairMethod::Shake:
        return (p.iterations + 1) * p.substeps;
    case HairMethod::Count:
        break;
    }
    return 0;
}

int hairSubstepsFor(const HairParams& p, double dt) {
    int n = p.substeps;
    if (p.maxSubstepSeconds > 0.0f && dt > 0.0) {
        // A tick meant as 1/60 s and typed 0.0166667 is a hair over it: a relative slack of 1e-5 keeps it one.
        const double need = std::ceil(dt / p.maxSubstepSeconds * (1.0 - 1e-5));
        n = std::max(n, static_cast<int>(std::min(need, static_cast<double>(p.substeps * kMaxAutoSubsteps))));
    }
    return n;
}

namespace {
// Whole clock substeps up to game time t; the slack keeps n ticks of 1/60 s at n, not n - 1, whatever the rounding.
double clockTicksAt(double t) { return std::floor(t / kHairClockSeconds + 1e-6); }
} // namespace

int hairClockSteps(double from, double to) {
    if (!(std::isfinite(from) && std::isfinite(to)) || !(to > from)) return 0;
    return static_cast<int>(clockTicksAt(to) - clockTicksAt(from));
}

double hairClockLag(double now) {
    if (!std::isfinite(now)) return 0.0;
    const double lag = now - clockTicksAt(now) * kHairClockSeconds;
    // Within a rounding of the clock (n ticks of 1/144 s summed never land exactly on it): on it.
    return lag < 1e-9 ? 0.0 : lag;
}

float hairClockAlpha(double now, double frameTime) {
    const double last = clockTicksAt(now) * kHairClockSeconds; // the hair's latest substep ended here
    const double a = (frameTime - (last - kHairClockSeconds)) / kHairClockSeconds;
    return std::isfinite(a) ? static_cast<float>(std::clamp(a, 0.0, 1.0)) : 1.0f;
}

VoxelOccupancy blockFloor(int halfWidth) {
    VoxelOccupancy v;
    v.origin = {-halfWidth, -2, -halfWidth};
    v.size = {2 * halfWidth, 3, 2 * halfWidth};
    const std::size_t w = 2 * static_cast<std::size_t>(halfWidth);
    v.solid.assign(w * 3 * w, 0);
    for (std::size_t z = 0; z < w; ++z)
        for (std::size_t y = 0; y < 2; ++y)
            for (std::size_t x = 0; x < w; ++x) v.solid[(z * 3 + y) * w + x] = 1;
    return v;
}

void validateHairParams(const HairParams& p) {
    const auto bad = [](const std::string& what) { throw std::invalid_argument("HairParams: " + what); };
    if (p.strands < 1) bad("strands must be >= 1");
    if (p.nodesPerStrand < 2) bad("nodesPerStrand must be >= 2");
    if (static_cast<std::int64_t>(p.strands) * p.nodesPerStrand > kMaxHairNodes)
        bad("strands * nodesPerStrand must be <= " + std::to_string(kMaxHairNodes));
    if (!(std::isfinite(p.strandLength) && p.strandLength > 0.0f)) bad("strandLength must be finite and > 0");
    if (!(std::isfinite(p.dampingPerSecond) && p.dampingPerSecond >= 0.0f))
        bad("dampingPerSecond must be finite and >= 0");
    if (!std::isfinite(p.gravity)) bad("gravity must be finite");
    if (p.iterations < 1 || p.iterations > 1000) bad("iterations must be in 1..1000");
    if (p.substeps < 1 || p.substeps > 1000) bad("substeps must be in 1..1000");
    if (!(p.patchHalfAngle > 0.0f && p.patchHalfAngle <= 3.1416f)) bad("patchHalfAngle must be in (0, pi]");
    if (!(std::isfinite(p.maxSubstepSeconds) && p.maxSubstepSeconds >= 0.0f))
        bad("maxSubstepSeconds must be finite and >= 0");
    if (!(std::isfinite(p.sleepSpeed) && p.sleepSpeed >= 0.0f)) bad("sleepSpeed must be finite and >= 0");
    if (!(std::isfinite(p.sleepDelay) && p.sleepDelay >= 0.0f)) bad("sleepDelay must be finite and >= 0");
    if (!(p.velocityCorrection >= 0.0f && p.velocityCorrection <= 1.0f)) bad("velocityCorrection must be in [0, 1]");
    if (hairMethodName(p.method).empty()) bad("method must be one of " + hairMethodNames());
}

std::vector<glm::vec3> hairRootDirections(int count, float halfAngle, std::uint64_t seed) {
    // R2 sequence (Roberts): additive recurrence on the plastic number, low discrepancy for every prefix.
    // (u, v) -> (y = cos theta uniform on [cos halfAngle, 1], phi = 2 pi v) maps equal areas to equal areas.
    constexpr double g = 1.32471795724474602596;
    constexpr double a1 = 1.0 / g, a2 = 1.0 / (g * g);
    const double s1 = static_cast<double>(core::mix64(seed) >> 11) * 0x1.0p-53;
    const double s2 = static_cast<double>(core::mix64(seed ^ 0x5851F42D4C957F2Dull) >> 11) * 0x1.0p-53;
    const double yMin = std::cos(static_cast<double>(std::min(halfAngle, 3.14159265f)));
    const double yMinClamped = std::clamp(yMin, -1.0, 1.0);
    std::vector<glm::vec3> out;
    out.reserve(static_cast<std::size_t>(std::max(count, 0)));
    for (int k = 0; k < count; ++k) {
        const double u = std::fmod(s1 + a1 * k, 1.0), v = std::fmod(s2 + a2 * k, 1.0);
        const double y = 1.0 - u * (1.0 - yMinClamped);
        const double phi = 2.0 * std::numbers::pi * v;
        const double rxz = std::sqrt(std::max(0.0, 1.0 - y * y));
        out.emplace_back(static_cast<float>(rxz * std::cos(phi)), static_cast<float>(y),
                         static_cast<float>(rxz * std::sin(phi)));
    }
    return out;
}

HairSolver::HairSolver(const HairParams& params, float ballRadius, const HostPose& pose) : m_params(params) {
    validateHairParams(params);
    if (!(std::isfinite(ballRadius) && ballRadius > 0.0f))
        throw std::invalid_argument("HairSolver: ballRadius must be finite and > 0");
    if (!finitePose(pose)) throw std::invalid_argument("HairSolver: pose must be finite");
    m_radius = ballRadius;
    m_segment = params.strandLength / static_cast<float>(params.nodesPerStrand - 1);
    m_s.active = params.strands;
    m_s.pose = pose;
    const std::size_t S = static_cast<std::size_t>(params.strands), N = static_cast<std::size_t>(params.nodesPerStrand);
    for (auto* v : {&m_s.x, &m_s.y, &m_s.z, &m_s.px, &m_s.py, &m_s.pz, &m_s.cx, &m_s.cy, &m_s.cz})
        v->assign(S * N, 0.0f);
    const auto dirs = hairRootDirections(params.strands, params.patchHalfAngle, params.seed);
    m_dirX.resize(S);
    m_dirY.resize(S);
    m_dirZ.resize(S);
    const Frame f = makeFrame(pose, m_radius);
    for (std::size_t s = 0; s < S; ++s) {
        m_dirX[s] = dirs[s].x;
        m_dirY[s] = dirs[s].y;
        m_dirZ[s] = dirs[s].z;
        float rx, ry, rz;
        placeRoot(f, dirs[s].x, dirs[s].y, dirs[s].z, rx, ry, rz);
        // Straight out from the centre; on a tiny ball far from the origin the root rounds onto the centre and
        // that difference is zero (a 1e-7 m ball at y = 40 made NaN hair; found by the game-state fuzzer), so
        // then the root's direction turned by the pose.
        const glm::vec3 fromCentre = glm::vec3(rx, ry, rz) - pose.centre;
        const glm::vec3 out = glm::dot(fromCentre, fromCentre) > 0.0f
                                  ? glm::normalize(fromCentre)
                                  : glm::normalize(glm::mat3_cast(pose.orientation) * dirs[s]);
        for (std::size_t n = 0; n < N; ++n) { // straight out along the normal, at rest
            const std::size_t i = n * S + s;
            const float along = m_segment * static_cast<float>(n);
            m_s.x[i] = m_s.px[i] = n == 0 ? rx : rx + out.x * along;
            m_s.y[i] = m_s.py[i] = n == 0 ? ry : ry + out.y * along;
            m_s.z[i] = m_s.pz[i] = n == 0 ? rz : rz + out.z * along;
        }
    }
}

HairSolver::~HairSolver() = default;

glm::vec3 HairSolver::rootPosition(const HostPose& pose, int strand) const {
    const Frame f = makeFrame(pose, m_radius);
    glm::vec3 out;
    placeRoot(f, m_dirX[strand], m_dirY[strand], m_dirZ[strand], out.x, out.y, out.z);
    return out;
}

void HairSolver::setStrand(int strand, std::span<const glm::vec3> nodes) {
    if (strand < 0 || strand >= strands()) throw std::invalid_argument("HairSolver::setStrand: no such strand");
    if (static_cast<int>(nodes.size()) != nodesPerStrand())
        throw std::invalid_argument("HairSolver::setStrand: needs one position per node");
    for (const glm::vec3& p : nodes)
        if (!finite(p)) throw std::invalid_argument("HairSolver::setStrand: a position is not finite");
    const std::size_t S = static_cast<std::size_t>(strands());
    for (std::size_t n = 0; n < nodes.size(); ++n) {
        const std::size_t i = n * S + static_cast<std::size_t>(strand);
        m_s.x[i] = m_s.px[i] = nodes[n].x;
        m_s.y[i] = m_s.py[i] = nodes[n].y;
        m_s.z[i] = m_s.pz[i] = nodes[n].z;
        m_s.cx[i] = m_s.cy[i] = m_s.cz[i] = 0.0f;
    }
    m_s.lastH = 0.0f; // released at rest: the next step starts from rest
    m_s.hostMove = glm::vec3(0.0f);
    m_s.fresh = false; // at rest in the world, not moving with the host
    wake();
}

void HairSolver::setActiveStrands(int n) {
    n = std::clamp(n, 0, strands());
    if (n > m_s.active) m_s.reseatFrom = m_s.reseatFrom < 0 ? m_s.active : std::min(m_s.reseatFrom, m_s.active);
    m_s.active = n;
    if (m_s.reseatFrom >= m_s.active) m_s.reseatFrom = -1;
}

void HairSolver::wake() {
    m_s.sleeping = false;
    m_s.restTime = 0.0f;
    m_s.window = false;
}

void HairSolver::reseat(int begin, int end, const HostPose& pose) {
    const Frame f = makeFrame(pose, m_radius);
    const std::size_t S = static_cast<std::size_t>(strands());
    for (int s = begin; s < end; ++s) {
        float rx, ry, rz;
        placeRoot(f, m_dirX[s], m_dirY[s], m_dirZ[s], rx, ry, rz);
        const float dx = rx - m_s.x[s], dy = ry - m_s.y[s], dz = rz - m_s.z[s];
        for (int n = 0; n < nodesPerStrand(); ++n) {
            const std::size_t i = static_cast<std::size_t>(n) * S + static_cast<std::size_t>(s);
            m_s.x[i] = m_s.px[i] = n == 0 ? rx : m_s.x[i] + dx;
            m_s.y[i] = m_s.py[i] = n == 0 ? ry : m_s.y[i] + dy;
            m_s.z[i] = m_s.pz[i] = n == 0 ? rz : m_s.z[i] + dz;
            m_s.cx[i] = m_s.cy[i] = m_s.cz[i] = 0.0f;
        }
    }
}

std::uint64_t HairSolver::hashState() const {
    core::Hasher h;
    core::HashFields fields{h};
    visitHairState(m_s, fields);
    return h.value();
}

HairSolverState HairSolver::state() const {
    HairSolverState s = m_s;
    if (!s.window) s.wx.clear(), s.wy.clear(), s.wz.clear(); // what a closed window left behind is not state
    return s;
}

void HairSolver::restore(const HairSolverState& s) {
    const std::size_t count = m_s.x.size();
    const auto allFinite = [](const std::vector<float>& v) {
        return std::all_of(v.begin(), v.end(), [](float f) { return std::isfinite(f); });
    };
    for (const auto* v : {&s.x, &s.y, &s.z, &s.px, &s.py, &s.pz, &s.cx, &s.cy, &s.cz}) {
        if (v->size() != count)
            throw std::invalid_argument("hair state: " + std::to_string(v->size()) +
                                        " node values where the ball has " + std::to_string(count));
        if (!allFinite(*v)) throw std::invalid_argument("hair state: a node value is not finite");
    }
    for (const auto* v : {&s.wx, &s.wy, &s.wz}) {
        if (v->size() != (s.window ? count : 0))
            throw std::invalid_argument("hair state: the sleep window has " + std::to_string(v->size()) +
                                        " values where it needs " + std::to_string(s.window ? count : 0));
        if (!allFinite(*v)) throw std::invalid_argument("hair state: a sleep window value is not finite");
    }
    if (s.active < 0 || s.active > strands())
        throw std::invalid_argument("hair state: active strands " + std::to_string(s.active) + " outside 0.." +
                                    std::to_string(strands()));
    if (s.reseatFrom != -1 && (s.reseatFrom < 0 || s.reseatFrom >= s.active))
        throw std::invalid_argument("hair state: strands to reseat from " + std::to_string(s.reseatFrom) +
                                    " outside -1 or 0.." + std::to_string(s.active - 1));
    if (!finitePose(s.pose) || !finite(s.hostMove) || !(std::isfinite(s.lastH) && s.lastH >= 0.0f) ||
        !(std::isfinite(s.restTime) && s.restTime >= 0.0f))
        throw std::invalid_argument("hair state: a non-finite pose, host move, step or rest time");
    m_s = s;
}

namespace {

// The strand loops, one node level at a time. Pointers are at the level's offset (index = strand) and do not
// alias, so each loop vectorises.
void placeRoots(float* __restrict x, float* __restrict y, float* __restrict z, float* __restrict px,
                float* __restrict py, float* __restrict pz, const float* __restrict dx, const float* __restrict dy,
                const float* __restrict dz, std::size_t lo, std::size_t hi, const Frame& frame) {
    const Frame f = frame;
    for (std::size_t s = lo; s < hi; ++s) { // roots: pinned to the host, history kept for interpolation
        float rx, ry, rz;
        placeRoot(f, dx[s], dy[s], dz[s], rx, ry, rz);
        px[s] = x[s], py[s] = y[s], pz[s] = z[s];
        x[s] = rx, y[s] = ry, z[s] = rz;
    }
}

} // namespace

// One substep for strands [begin, end), block by block: a block's nodes stay in cache through every pass.
void HairSolver::stepRange(const Substep& sub, int begin, int end, HairStepStats& stats, float* scratch) {
    const int N = nodesPerStrand();
    const std::size_t S = static_cast<std::size_t>(strands());
    float* const X = m_s.x.data();
    float* const Y = m_s.y.data();
    float* const Z = m_s.z.data();
    float* const PX = m_s.px.data();
    float* const PY = m_s.py.data();
    float* const PZ = m_s.pz.data();
    float* const CX = m_s.cx.data();
    float* const CY = m_s.cy.data();
    float* const CZ = m_s.cz.data();
    const Frame f = sub.frame;
    const float R = m_radius, L = m_segment;
    const VoxelOccupancy* vox = sub.voxels && !sub.voxels->solid.empty() ? sub.voxels : nullptr;

    for (int b0 = begin; b0 < end; b0 += kBlock) {
        const std::size_t lo = static_cast<std::size_t>(b0);
        const std::size_t hi = static_cast<std::size_t>(std::min(end, b0 + kBlock));
        placeRoots(X, Y, Z, PX, PY, PZ, m_dirX.data(), m_dirY.data(), m_dirZ.data(), lo, hi, f);
        // scratch: the predicted (pre-constraint) positions of this block, level by level.
        const auto predicted = [&](int n, int axis) {
            return scratch + (static_cast<std::size_t>(n) * 3 + static_cast<std::size_t>(axis)) * kBlock;
        };
        const bool host = m_params.hostCollision;
        for (int n = 1; n < N; ++n) {
            const std::size_t o = static_cast<std::size_t>(n) * S;
            // Direct calls, as the limit kernel makes them: a kernel chosen through a function pointer is an
            // indirect call the compiler cannot inline.
            if (host)
                kernels::integrateLevel<true>(X + o, Y + o, Z + o, PX + o, PY + o, PZ + o, CX + o, CY + o, CZ + o,
                                              predicted(n, 0), predicted(n, 1), predicted(n, 2), lo, hi, sub.hostMove,
                                              sub.ratio, sub.damp, sub.accelY, sub.oldCentre, f.c, R);
            else
                kernels::integrateLevel<false>(X + o, Y + o, Z + o, PX + o, PY + o, PZ + o, CX + o, CY + o, CZ + o,
                                               predicted(n, 0), predicted(n, 1), predicted(n, 2), lo, hi, sub.hostMove,
                                               sub.ratio, sub.damp, sub.accelY, sub.oldCentre, f.c, R);
        }
        // Follow the leader root to tip, each node then met by every collider on its contact circle: after one
        // pass every segment has its length (to rounding) unless a contact had no circle.
        // With other colliders about, the host's contact comes last: a node wedged between the host and another
        // ball or a block ends on the host's surface, which moves (the others are taken as still).
        const bool hostLast = host && (vox || !sub.others.empty());
        const auto ftlPass = [&] {
            for (int n = 1; n < N; ++n) {
                const std::size_t o = static_cast<std::size_t>(n) * S, op = o - S;
                if (host && !hostLast)
                    kernels::ftlLevel<true>(X + o, Y + o, Z + o, X + op, Y + op, Z + op, PX + o, PY + o, PZ + o, lo, hi,
                                            L, sub.oldCentre, f.c, R);
                else
                    kernels::ftlLevel<false>(X + o, Y + o, Z + o, X + op, Y + op, Z + op, PX + o, PY + o, PZ + o, lo,
                                             hi, L, sub.oldCentre, f.c, R);
                for (const SphereCollider& c : sub.others)
                    kernels::contactLevel(X + o, Y + o, Z + o, X + op, Y + op, Z + op, PX + o, PY + o, PZ + o, lo, hi,
                                          L, c.centre, c.centre, c.radius);
                if (vox) {
                    for (std::size_t s = lo; s < hi; ++s) {
                        const std::size_t i = o + s, j = op + s;
                        const float parent[3] = {X[j], Y[j], Z[j]};
                        pushOutOfVoxels(*vox, X[i], Y[i], Z[i], PX[i], PY[i], PZ[i], parent, L);
                    }
                }
                if (hostLast)
                    kernels::contactLevel(X + o, Y + o, Z + o, X + op, Y + op, Z + op, PX + o, PY + o, PZ + o, lo, hi,
                                          L, sub.oldCentre, f.c, R);
            }
        };
        kernels::constrain(
            m_params.method, m_params.iterations, ftlPass,
            [&] {
                for (int n = 1; n < N; ++n) {
                    const std::size_t o = static_cast<std::size_t>(n) * S, op = o - S;
                    kernels::pbdLevel(X + op, Y + op, Z + op, X + o, Y + o, Z + o, lo, hi, L, n == 1);
                }
                for (int n = 1; n < N; ++n) {
                    const std::size_t o = static_cast<std::size_t>(n) * S;
                    if (host) kernels::radialPushLevel(X + o, Y + o, Z + o, lo, hi, f.c, R);
                    for (const SphereCollider& c : sub.others) {
                        for (std::size_t s = lo; s < hi; ++s) {
                            const std::size_t i = o + s;
                            float x = X[i] - c.centre.x, y = Y[i] - c.centre.y, z = Z[i] - c.centre.z;
                            pushOutAlongPath(x, y, z, PX[i] - c.centre.x, PY[i] - c.centre.y, PZ[i] - c.centre.z,
                                             c.radius);
                            X[i] = x + c.centre.x, Y[i] = y + c.centre.y, Z[i] = z + c.centre.z;
                        }
                    }
                    if (vox) {
                        for (std::size_t s = lo; s < hi; ++s) {
                            const std::size_t i = o + s;
                            pushOutOfVoxels(*vox, X[i], Y[i], Z[i], PX[i], PY[i], PZ[i]);
                        }
                    }
                }
            },
            [&] {
                // The prediction out of the other colliders first (the host's push was in integrateLevel), so the
                // strand's solve starts from contact positions and the contact pass after it moves little.
                if (vox || !sub.others.empty()) {
                    for (int n = 1; n < N; ++n) {
                        const std::size_t o = static_cast<std::size_t>(n) * S;
                        float* qx = predicted(n, 0);
                        float* qy = predicted(n, 1);
                        float* qz = predicted(n, 2);
                        for (std::size_t s = lo; s < hi; ++s) {
                            const std::size_t i = o + s, l = s - lo;
                            for (const SphereCollider& c : sub.others) {
                                float x = qx[l] - c.centre.x, y = qy[l] - c.centre.y, z = qz[l] - c.centre.z;
                                pushOutAlongPath(x, y, z, PX[i] - c.centre.x, PY[i] - c.centre.y, PZ[i] - c.centre.z,
                                                 c.radius);
                                qx[l] = x + c.centre.x, qy[l] = y + c.centre.y, qz[l] = z + c.centre.z;
                            }
                            if (vox) pushOutOfVoxels(*vox, qx[l], qy[l], qz[l], PX[i], PY[i], PZ[i]);
                        }
                    }
                }
                kernels::shakeBlock(X, Y, Z, PX, PY, PZ, scratch, scratch + static_cast<std::size_t>(N) * 3 * kBlock, S,
                                    static_cast<std::size_t>(N), lo, hi, kBlock, L, m_params.iterations);
                ftlPass();
            });
        if (m_params.method == HairMethod::Dftl && m_params.velocityCorrection > 0.0f) {
            for (int n = 1; n + 1 < N; ++n) {
                const std::size_t o = static_cast<std::size_t>(n) * S, oc = o + S;
                kernels::correctParentVelocity(CX + o, CY + o, CZ + o, X + oc, Y + oc, Z + oc, predicted(n + 1, 0),
                                               predicted(n + 1, 1), predicted(n + 1, 2), lo, hi,
                                               m_params.velocityCorrection, X + o, Y + o, Z + o, f.c, host ? R : -1.0f);
            }
        }
        if (sub.last) blockStats(sub, lo, hi, stats);
    }
}

void HairSolver::blockStats(const Substep& sub, std::size_t lo, std::size_t hi, HairStepStats& stats) const {
    const int N = nodesPerStrand();
    const std::size_t S = static_cast<std::size_t>(strands());
    const float* const X = m_s.x.data();
    const float* const Y = m_s.y.data();
    const float* const Z = m_s.z.data();
    const float* const PX = m_s.px.data();
    const float* const PY = m_s.py.data();
    const float* const PZ = m_s.pz.data();
    const float R = m_radius, L = m_segment;
    const float cx = sub.frame.c.x, cy = sub.frame.c.y, cz = sub.frame.c.z;
    const VoxelOccupancy* vox = sub.voxels && !sub.voxels->solid.empty() ? sub.voxels : nullptr;
    const bool host = m_params.hostCollision;
    // Stats, per lane first so the loops vectorise, then reduced. Squared lengths and distances are kept
    // (their extremes give the extreme errors), so the square roots run once a lane, not once a node.
    float move2[kBlock], len2Max[kBlock], len2Min[kBlock], host2Min[kBlock], pen[kBlock], bad[kBlock], window2[kBlock];
    const std::size_t w = hi - lo;
    constexpr float kHuge = std::numeric_limits<float>::max();
    for (std::size_t l = 0; l < w; ++l) move2[l] = len2Max[l] = pen[l] = bad[l] = window2[l] = 0.0f;
    for (std::size_t l = 0; l < w; ++l) len2Min[l] = host2Min[l] = kHuge;
    for (std::size_t s = lo; s < hi; ++s)
        bad[s - lo] = ((X[s] * 0.0f == 0.0f) & (Y[s] * 0.0f == 0.0f) & (Z[s] * 0.0f == 0.0f)) ? 0.0f : 1.0f;
    for (int n = 1; n < N; ++n) {
        const std::size_t o = static_cast<std::size_t>(n) * S, op = o - S;
        for (std::size_t s = lo; s < hi; ++s) {
            const std::size_t i = o + s, j = op + s, l = s - lo;
            const float x = X[i], y = Y[i], z = Z[i];
            const float mx = x - PX[i], my = y - PY[i], mz = z - PZ[i];
            move2[l] = std::max(move2[l], mx * mx + my * my + mz * mz);
            const float dx = x - X[j], dy = y - Y[j], dz = z - Z[j];
            const float d2 = dx * dx + dy * dy + dz * dz;
            len2Max[l] = std::max(len2Max[l], d2);
            len2Min[l] = std::min(len2Min[l], d2);
            const float rx = x - cx, ry = y - cy, rz = z - cz;
            host2Min[l] = std::min(host2Min[l], rx * rx + ry * ry + rz * rz);
            const bool ok = (x * 0.0f == 0.0f) & (y * 0.0f == 0.0f) & (z * 0.0f == 0.0f) & (d2 == d2);
            bad[l] = ok ? bad[l] : 1.0f;
        }
        if (m_s.window) {
            const float* WX = m_s.wx.data();
            const float* WY = m_s.wy.data();
            const float* WZ = m_s.wz.data();
            for (std::size_t s = lo; s < hi; ++s) {
                const std::size_t i = o + s;
                const float dx = X[i] - WX[i], dy = Y[i] - WY[i], dz = Z[i] - WZ[i];
                window2[s - lo] = std::max(window2[s - lo], dx * dx + dy * dy + dz * dz);
            }
        }
        for (const SphereCollider& c : sub.others) {
            for (std::size_t s = lo; s < hi; ++s) {
                const std::size_t i = o + s;
                const float rx = X[i] - c.centre.x, ry = Y[i] - c.centre.y, rz = Z[i] - c.centre.z;
                pen[s - lo] = std::max(pen[s - lo], c.radius - std::sqrt(rx * rx + ry * ry + rz * rz));
            }
        }
        if (vox) {
            for (std::size_t s = lo; s < hi; ++s) {
                const std::size_t i = o + s;
                pen[s - lo] = std::max(pen[s - lo], voxelDepth(*vox, X[i], Y[i], Z[i]));
            }
        }
    }
    // Across the lanes on the squared values (a square root is monotonic), then one root each.
    float blockMove2 = 0.0f, blockWindow2 = 0.0f, blockLen2Max = 0.0f, blockLen2Min = kHuge, blockHost2 = kHuge,
          blockPen = 0.0f, blockBad = 0.0f;
    for (std::size_t l = 0; l < w; ++l) {
        blockMove2 = std::max(blockMove2, move2[l]);
        blockWindow2 = std::max(blockWindow2, window2[l]);
        blockLen2Max = std::max(blockLen2Max, len2Max[l]);
        blockLen2Min = std::min(blockLen2Min, len2Min[l]);
        blockHost2 = std::min(blockHost2, host2Min[l]);
        blockPen = std::max(blockPen, pen[l]);
        blockBad = std::max(blockBad, bad[l]);
    }
    stats.maxNodeMove = std::max(stats.maxNodeMove, std::sqrt(blockMove2));
    stats.restWindowMove = std::max(stats.restWindowMove, std::sqrt(blockWindow2));
    const float longest = std::abs(std::sqrt(blockLen2Max) / L - 1.0f);
    const float shortest = std::abs(std::sqrt(blockLen2Min) / L - 1.0f);
    stats.maxSegmentError = std::max({stats.maxSegmentError, longest, shortest});
    if (host) stats.maxPenetration = std::max(stats.maxPenetration, R - std::sqrt(blockHost2));
    stats.maxPenetration = std::max(stats.maxPenetration, blockPen);
    stats.nan = stats.nan || blockBad != 0.0f;
}

void HairSolver::runBlocks(const Substep& sub, int threads, HairStepStats* perThread) {
    const int blocks = (m_s.active + kBlock - 1) / kBlock;
    threads = std::min(threads, std::max(blocks, 1));
    auto range = [&](int t) {
        const int b = static_cast<int>(static_cast<std::int64_t>(blocks) * t / threads);
        const int e = static_cast<int>(static_cast<std::int64_t>(blocks) * (t + 1) / threads);
        perThread[t] = HairStepStats{};
        stepRange(sub, std::min(b * kBlock, m_s.active), std::min(e * kBlock, m_s.active), perThread[t],
                  m_scratch[static_cast<std::size_t>(t)].data());
    };
    if (threads <= 1) {
        range(0);
        return;
    }
    if (!m_pool || m_pool->workers() != threads - 1) {
        m_pool.reset();
        m_pool = std::make_unique<Pool>(threads - 1);
    }
    m_pool->run(range);
}

// SHAKE's error estimate: the largest angle any active segment turned through in the last substep, scaled to
// a substep of this step, must stay under kShakeMaxTurn; more substeps where it would not. SHAKE moves nodes
// along the segments' directions at the substep's start, which cannot restore a length once a segment turns
// far (at 60 degrees it gives up), and its error grows with the turn: a whipping tip gets small substeps, a
// hanging strand none extra. From the state alone, so the same state takes the same substeps.
int HairSolver::shakeSubstepsFor(double dt) const {
    if (!(m_s.lastH > 0.0f)) return 1;
    const std::size_t S = static_cast<std::size_t>(strands());
    const auto N = static_cast<std::size_t>(nodesPerStrand());
    const auto active = static_cast<std::size_t>(m_s.active);
    const float* __restrict const X = m_s.x.data();
    const float* __restrict const Y = m_s.y.data();
    const float* __restrict const Z = m_s.z.data();
    const float* __restrict const PX = m_s.px.data();
    const float* __restrict const PY = m_s.py.data();
    const float* __restrict const PZ = m_s.pz.data();
    // Per lane first, then across lanes (as blockStats): a float min into one scalar does not vectorise without
    // fast-math, an element-wise min into an array does. A minimum is exact and skips NaN either way, so minCos
    // is the same value (at worst -0 for +0, and acos gives the same for both).
    constexpr std::size_t B = static_cast<std::size_t>(kBlock);
    float laneMin[B];
    float minCos = 1.0f;
    for (std::size_t lo = 0; lo < active; lo += B) {
        const std::size_t hi = std::min(active, lo + B);
        for (std::size_t l = 0; l < hi - lo; ++l) laneMin[l] = 1.0f;
        for (std::size_t k = 1; k < N; ++k) {
            const std::size_t o = k * S, op = o - S;
            for (std::size_t s = lo; s < hi; ++s) {
                const float ax = X[o + s] - X[op + s], ay = Y[o + s] - Y[op + s], az = Z[o + s] - Z[op + s];
                const float bx = PX[o + s] - PX[op + s], by = PY[o + s] - PY[op + s], bz = PZ[o + s] - PZ[op + s];
                const float d = ax * bx + ay * by + az * bz;
                const float n2 = (ax * ax + ay * ay + az * az) * (bx * bx + by * by + bz * bz);
                const float c = n2 > 0.0f ? d / std::sqrt(n2) : 1.0f;
                laneMin[s - lo] = std::min(laneMin[s - lo], c);
            }
        }
        for (std::size_t l = 0; l < hi - lo; ++l) minCos = std::min(minCos, laneMin[l]);
    }
    const double turn =
        std::acos(std::clamp(static_cast<double>(minCos), -1.0, 1.0)) * dt / static_cast<double>(m_s.lastH);
    const double need = std::ceil(turn / kShakeMaxTurn);
    return static_cast<int>(std::clamp(need, 1.0, static_cast<double>(m_params.substeps * kMaxShakeSubsteps)));
}

HairStepStats HairSolver::step(const HostPose& pose, float dt, std::span<const SphereCollider> others,
                               const VoxelOccupancy* voxels, int threads) {
    HairStepStats out;
    if (!(dt > 0.0f) || !std::isfinite(dt) || !finitePose(pose)) {
        out.nan = true;
        return out;
    }
    for (const SphereCollider& c : others) {
        if (!finite(c.centre) || !std::isfinite(c.radius)) {
            out.nan = true;
            return out;
        }
    }
    threads = std::clamp(threads, 1, kMaxThreads);

    // What the sleeping ball would react to: its host, the other balls within reach, the voxels around it.
    const bool hostStill = pose.centre == m_s.pose.centre && pose.orientation == m_s.pose.orientation;
    core::Hasher env;
    const float reach = m_radius + m_params.strandLength;
    for (const SphereCollider& c : others) {
        if (glm::length(c.centre - pose.centre) >= reach + c.radius) continue;
        env.add(c.centre.x), env.add(c.centre.y), env.add(c.centre.z), env.add(c.radius);
    }
    if (voxels) {
        env.add(voxels->origin.x), env.add(voxels->origin.y), env.add(voxels->origin.z);
        env.add(voxels->size.x), env.add(voxels->size.y), env.add(voxels->size.z);
        env.bytes(voxels->solid.data(), voxels->solid.size());
    }
    if (m_s.sleeping) {
        if (hostStill && env.value() == m_s.envHash && m_s.reseatFrom < 0) return out;
        wake();
    }
    if (m_s.reseatFrom >= 0) {
        reseat(m_s.reseatFrom, m_s.active, m_s.pose);
        m_s.reseatFrom = -1;
    }

    int n = hairSubstepsFor(m_params, static_cast<double>(dt));
    // With automatic substeps on (maxSubstepSeconds > 0, as in the game), shake also splits a step in which a
    // segment would turn further than it can follow (shakeSubstepsFor).
    if (m_params.method == HairMethod::Shake && m_params.maxSubstepSeconds > 0.0f)
        n = std::max(n, shakeSubstepsFor(static_cast<double>(dt)));
    const double h = static_cast<double>(dt) / n;
    out.substeps = n;
    const HostPose from = m_s.pose;
    if (m_s.fresh) {
        // New hair moves with its host: a ball made while it is carried does not leave its hair behind. The
        // first substep's own host move stands in for the history, and every free node's history moves with it.
        const glm::vec3 first =
            (n > 1 ? glm::mix(from.centre, pose.centre, 1.0f / static_cast<float>(n)) : pose.centre) - from.centre;
        const std::size_t S = static_cast<std::size_t>(strands());
        for (std::size_t i = S; i < m_s.px.size(); ++i)
            m_s.px[i] -= first.x, m_s.py[i] -= first.y, m_s.pz[i] -= first.z;
        m_s.hostMove = first;
        m_s.fresh = false;
    }
    if (static_cast<int>(m_threadStats.size()) < threads) m_threadStats.resize(static_cast<std::size_t>(threads));
    if (static_cast<int>(m_scratch.size()) < threads) {
        m_scratch.resize(static_cast<std::size_t>(threads));
        // A block's predicted positions (3 per node), then SHAKE's work (3 per node + 1).
        for (auto& v : m_scratch) v.resize(static_cast<std::size_t>(nodesPerStrand()) * 7 * kBlock);
    }
    for (int k = 1; k <= n; ++k) {
        HostPose target = pose;
        if (k < n) {
            const float a = static_cast<float>(k) / static_cast<float>(n);
            target.centre = glm::mix(from.centre, pose.centre, a);
            target.orientation = glm::slerp(from.orientation, pose.orientation, a);
        }
        const bool fromRest = !(m_s.lastH > 0.0f);
        const double hPrev = fromRest ? h : static_cast<double>(m_s.lastH);
        const kernels::StepCoefficients coef =
            kernels::stepCoefficients(static_cast<double>(m_params.dampingPerSecond), h, hPrev, fromRest);
        Substep sub;
        sub.frame = makeFrame(target, m_radius);
        sub.oldCentre = m_s.pose.centre;
        sub.hostMove = m_s.hostMove;
        sub.ratio = static_cast<float>(coef.ratio);
        sub.damp = static_cast<float>(coef.damp);
        sub.accelY = static_cast<float>(-static_cast<double>(m_params.gravity) * coef.accel);
        sub.last = k == n;
        sub.others = others;
        sub.voxels = voxels;
        runBlocks(sub, threads, m_threadStats.data());
        m_s.hostMove = target.centre - m_s.pose.centre;
        m_s.pose = target;
        m_s.lastH = static_cast<float>(h);
    }
    for (int t = 0; t < threads; ++t) {
        const HairStepStats& s = m_threadStats[static_cast<std::size_t>(t)];
        out.maxNodeMove = std::max(out.maxNodeMove, s.maxNodeMove);
        out.restWindowMove = std::max(out.restWindowMove, s.restWindowMove);
        out.maxSegmentError = std::max(out.maxSegmentError, s.maxSegmentError);
        out.maxPenetration = std::max(out.maxPenetration, s.maxPenetration);
        out.nan = out.nan || s.nan;
        m_threadStats[static_cast<std::size_t>(t)] = HairStepStats{};
    }

    // Sleep: under a still host, every node within sleepSpeed x sleepDelay of where it was when the window began,
    // for sleepDelay seconds: an average speed below sleepSpeed over the window. (Sampling the speed of single
    // steps instead made the test depend on the tick: more samples, more chances to catch a creeping tip.)
    // Velocity is zeroed so waking starts at rest.
    if (!(hostStill && !out.nan && m_params.sleepSpeed > 0.0f)) {
        m_s.restTime = 0.0f;
        m_s.window = false;
    } else if (!m_s.window || out.restWindowMove > m_params.sleepSpeed * m_params.sleepDelay) {
        m_s.wx = m_s.x; // a new window from here
        m_s.wy = m_s.y;
        m_s.wz = m_s.z;
        m_s.window = true;
        m_s.restTime = 0.0f;
    } else {
        m_s.restTime += dt;
    }
    if (m_s.window && m_s.restTime >= m_params.sleepDelay) {
        m_s.px = m_s.x;
        m_s.py = m_s.y;
        m_s.pz = m_s.z;
        std::fill(m_s.cx.begin(), m_s.cx.end(), 0.0f);
        std::fill(m_s.cy.begin(), m_s.cy.end(), 0.0f);
        std::fill(m_s.cz.begin(), m_s.cz.end(), 0.0f);
        m_s.sleeping = true;
        m_s.envHash = env.value();
        m_s.lastH = 0.0f; // asleep means at rest: the waking step starts from rest, with no history
        m_s.hostMove = glm::vec3(0.0f);
    }
    return out;
}

} // namespace physics
