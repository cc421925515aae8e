// Verlet hair on a ball: strands of nodes rooted on a sphere (or a patch of it) that the game moves and
// spins. Each step (in substeps of at most maxSubstepSeconds) pins the roots to the host exactly, moves the
// free nodes by the exact solution for gravity and damping over the step (an exponential integrator in
// Verlet form, exact for constant acceleration under any step), then restores the segment lengths by the
// chosen HairMethod while meeting the host ball, other balls and solid voxels in a way that keeps lengths. A
// ball whose hair has stayed put under a still host sleeps until disturbed; level of detail simulates a
// prefix of the strands, which are ordered so that every prefix is spread evenly over the patch. docs/HAIR.md
// has the methods' measured accuracy, stability and cost.
//
// Fixes to the seed write-up ("Hair Simulator"): its variable-step Verlet lacked the step-ratio factor (motion
// followed the frame count, not time); its damping was per step; it added the host's acceleration on top of
// roots that already move with the host (counting the motion twice: here the roots are pinned and no host
// acceleration is added); it sampled roots with uniform theta (clustered at the poles: here by area); and its
// nearest-surface push threw fast nodes out of the far side (here the path decides the side).
//
// It must never touch GL, a clock, a file or global state; step() allocates nothing after the first call
// with a given thread count, and the same inputs give the same state bit for bit, whatever the thread count.
// The hot loops are in hair.cpp, which must be compiled with -fno-math-errno (so sqrtf vectorises) and
// -ffp-contract=off (so vector and scalar code round alike; see hair.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace physics {

// How a step keeps the segments at their rest length (docs/HAIR.md charts them against each other):
// - Ftl: follow-the-leader (Mueller et al. 2012): each node put back at one segment length from its parent,
//   root to tip. Exact length in one pass, but only children move, so a free strand loses energy and its tip
//   does not converge to the true motion as the step shrinks.
// - Dftl: Ftl plus the velocity correction of "dynamic FTL" (a share of each child's correction fed back to
//   its parent's velocity): tips stop whipping and hair settles.
// - Pbd: Gauss-Seidel length constraints (both ends move, mass-weighted), `iterations` passes a substep.
//   Lengths are exact only in the limit of many iterations.
// - XpbdSubsteps: small steps (Macklin et al. 2019): `substeps` substeps of one Pbd iteration each (the
//   constraints are inextensible, so XPBD's compliance is zero and it is Pbd with one iteration a substep).
// - Shake: the strand's lengths solved together, per strand, by Newton's method on the tridiagonal system of
//   the SHAKE equations (constraint directions from the last positions; `iterations` Newton iterations),
//   then one follow-the-leader pass for contacts. Exact length and no numerical energy loss of FTL's kind:
//   with the time-corrected Verlet step it is the RATTLE/SHAKE scheme, second order and symplectic.
// Every method meets colliders (host ball, other balls, blocks) in a way that keeps lengths: a node found
// inside one goes where the collider's surface meets the sphere of one segment length around its parent
// (for a block, on the first face the segment from the parent crosses, or along the edge where two meet);
// where they do not meet (the parent itself inside, a node boxed in), it goes out the nearest way and that
// segment's length gives (the stats report it).
enum class HairMethod : std::uint8_t { Ftl, Dftl, Pbd, XpbdSubsteps, Shake, Count };
inline constexpr int kHairMethodCount = static_cast<int>(HairMethod::Count);
// "ftl", "dftl", "pbd", "xpbd-substeps", "shake"; "" for Count or anything outside the enum.
std::string_view hairMethodName(HairMethod method);
// Exact (case-sensitive) inverse of hairMethodName; nullopt for anything else.
std::optional<HairMethod> hairMethodFromName(std::string_view name);
// "ftl, dftl, pbd, xpbd-substeps, shake": for messages that list the choices.
std::string hairMethodNames();

struct HairParams {
    int strands = 512;          // strands on the ball, 1 .. kMaxHairNodes / nodesPerStrand
    int nodesPerStrand = 12;    // including the root, >= 2
    float strandLength = 0.45f; // m, root to tip, > 0
    float dampingPerSecond =
        2.5f;              // 1/s, >= 0: velocity relative to the host centre decays as exp(-d t), whatever the step
    float gravity = 9.81f; // m/s^2, along -y
    int iterations = 1;    // constraint + contact passes (shake: Newton iterations) a substep, >= 1; the defaults
                           // are hairMethodDefaults(method): one pass of (d)ftl already keeps every length
    int substeps = 1;      // substeps per step(), >= 1 (a long step is split further: maxSubstepSeconds)
    float patchHalfAngle = 3.14159265f; // rad around the ball's local +y, (0, pi]; pi = the whole sphere
    std::uint64_t seed = 1;             // rotates the low-discrepancy root pattern; same seed, same roots
    float maxSubstepSeconds =
        1.0f / 60.0f;         // s: a step longer than this is split into more substeps (0 = never): the hair runs at
                              // 60 Hz or faster whatever the tick rate, so it looks and settles alike at every rate
    float sleepSpeed = 0.01f; // m/s: hair whose nodes all stay within sleepSpeed x sleepDelay of where they
    float sleepDelay = 0.5f;  // s: were this long ago, with the host still, falls asleep (an average speed over
                              // the window, not sampled steps, so the test is the same at every tick rate)
    float velocityCorrection = 0.5f;      // [0, 1]: share of a child's constraint correction fed back to its parent's
                                          // velocity (Dftl only; the other methods ignore it)
    HairMethod method = HairMethod::Dftl; // see HairMethod; Count is refused
    bool hostCollision = true; // false: the host ball is no collider (the lab's free chain); roots still pinned
};

// The iterations and substeps each method is meant to run with in the game (chosen from the lab's charts,
// docs/HAIR.md); a panel switching method starts from these.
HairParams hairMethodDefaults(HairMethod method, HairParams base = {});
// Constraint projections per free node per step() (no automatic extra substeps): the work unit of the
// lab's charts. ftl, dftl, pbd: iterations x substeps; xpbd-substeps: substeps; shake: (iterations + 1) x
// substeps (the Newton iterations and the contact pass).
int hairProjectionsPerNode(const HairParams& params);
// Substeps step(dt) runs: params.substeps, more when a substep would be longer than maxSubstepSeconds (up to
// 16 times as many: a long frame spike is then stepped coarser rather than stalling the game). With automatic
// substeps on (maxSubstepSeconds > 0), step() runs shake in more substeps still where a segment would turn more
// than 10 degrees in one (an error estimate from the last substep's turn; see HAIR.md), up to 4 a step.
int hairSubstepsFor(const HairParams& params, double dt);

// The game's hair clock: hair moves in substeps of exactly 1/60 s at every tick rate, so that it behaves the
// same at 30, 60, 144 or 240 Hz (the solver's dissipation, settle times and contacts depend on its step; see
// HAIR.md, "Frame-rate independence"). hairClockSteps(from, to): the hair substeps whose end falls in the game
// time (from, to] (s): 1 a tick at 60 Hz, 2 at 30 Hz, 0 or 1 at 144 Hz, 1 in 4 ticks at 240 Hz.
inline constexpr double kHairClockSeconds = 1.0 / 60.0;
int hairClockSteps(double from, double to);
// How long before game time `now` the hair's latest clock substep ended (s, in [0, 1/60)): the game gives the
// solver its host's pose at that time, not at the tick's end. 0 when `now` is on the clock (rounding aside).
double hairClockLag(double now);
// Where a frame at game time `frameTime` lies between the hair's last two clock substeps before `now`, for
// drawing between them (0: the earlier, 1: the later), clamped to [0, 1].
float hairClockAlpha(double now, double frameTime);

inline constexpr std::int64_t kMaxHairNodes = std::int64_t{1} << 26; // strands * nodesPerStrand above this is refused

struct HostPose {
    glm::vec3 centre{0.0f};
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f}; // local -> world, unit (w, x, y, z)
};

struct SphereCollider {
    glm::vec3 centre;
    float radius;
};

// Solid voxels around the ball, filled by the game each step (1 = solid unit cube at integer coords).
struct VoxelOccupancy {
    glm::ivec3 origin{0};
    glm::ivec3 size{0};              // covers [origin, origin + size)
    std::vector<std::uint8_t> solid; // x fastest, then y, then z; size.x * size.y * size.z entries
    bool at(int x, int y, int z) const {
        const int lx = x - origin.x, ly = y - origin.y, lz = z - origin.z;
        if (lx < 0 || ly < 0 || lz < 0 || lx >= size.x || ly >= size.y || lz >= size.z) return false;
        const std::size_t i =
            (static_cast<std::size_t>(lz) * static_cast<std::size_t>(size.y) + static_cast<std::size_t>(ly)) *
                static_cast<std::size_t>(size.x) +
            static_cast<std::size_t>(lx);
        return i < solid.size() && solid[i] != 0;
    }
};

// A floor of blocks for studies and tests: solid for y in [-2, 0) (its top at y = 0) and x, z in
// [-halfWidth, halfWidth), with one free layer above it in the box.
VoxelOccupancy blockFloor(int halfWidth);

struct HairStepStats {
    float maxSegmentError = 0; // max | |segment| / restLength - 1 | after the step
    float maxPenetration = 0;  // m, deepest node inside the host ball, another ball or a solid voxel after the step
    bool nan = false;          // a non-finite node position (or a non-finite pose / dt was given)
    float maxNodeMove = 0;     // m, largest distance a free node moved in the last substep of this step
    float restWindowMove = 0;  // m, largest distance of a node from where it was when the host last stood still
                               // with the hair moving under sleepSpeed on average (the sleep test; 0 otherwise)
    int substeps = 0;          // substeps the step ran (hairSubstepsFor, shake's turn-chosen ones included; 0 asleep)
};

// One time-corrected Verlet update of one coordinate, exact for constant acceleration whatever the steps:
//   x' = x + r dH + (r (x - prev) - r dH) e^{-d h} + a h (h + hPrev) / 2,   r = h / hPrev,
// where dH is the host centre's move over the previous step (damping acts on velocity relative to the host,
// so a host moving steadily drags no wake). `ratio` = r, `damp` = e^{-d h}, `accelTerm` = a h (h + hPrev) / 2.
template <typename T>
constexpr T verletStep(T x, T prev, T hostMove, T ratio, T damp, T accelTerm) {
    const T carried = hostMove * ratio;
    return x + carried + ((x - prev) * ratio - carried) * damp + accelTerm;
}

// The collision the solver applies to a node against a sphere: `p` came from `prev` this step. If the path
// enters the sphere, p goes onto the tangent plane at the entry point and then radially onto the surface (out
// on the side it came from, never through to the far side, however fast it moved); if prev was already
// inside, out the nearest way.
glm::vec3 pushOutOfSphere(glm::vec3 p, glm::vec3 prev, glm::vec3 centre, float radius);

// Everything a HairSolver carries from one step to the next beyond what its constructor derives from the
// params, the radius and the pose (segment length, root directions): with it a new solver continues bit for bit
// as the one it was taken from. Node arrays are node-major (HairSolver::x()); the sleep window's (wx, wy, wz)
// only while `window` is set, else empty.
struct HairSolverState {
    int active = 0;
    int reseatFrom = -1;
    HostPose pose{};
    glm::vec3 hostMove{0.0f};
    float lastH = 0.0f;
    bool fresh = true;
    bool sleeping = false;
    float restTime = 0.0f;
    bool window = false;
    std::uint64_t envHash = 0;
    std::vector<float> x, y, z, px, py, pz, cx, cy, cz, wx, wy, wz;
};

// The one list of a HairSolverState's fields, in order. HairSolver::hashState(), the state dump and the world
// file's hair blob (save::encodeHairState and its reader) all walk it, so a field added to the struct and
// here is hashed, dumped and saved alike. S is HairSolverState, const or not; the visitor is called as
// v.value(name, x) for int, float, bool, std::uint64_t, glm::vec3 and glm::quat, and v.nodes(name, array) for
// the node arrays. The sleep window's arrays are visited only while `window` is set (a reader has set it by
// then, since it comes first).
template <class S, class V>
void visitHairState(S& s, V& v) {
    v.value("active", s.active);
    v.value("reseat_from", s.reseatFrom);
    v.value("pose_centre", s.pose.centre);
    v.value("pose_orientation", s.pose.orientation);
    v.value("host_move", s.hostMove);
    v.value("last_substep", s.lastH);
    v.value("fresh", s.fresh);
    v.value("sleeping", s.sleeping);
    v.value("rest_time", s.restTime);
    v.value("window", s.window);
    v.value("environment_hash", s.envHash);
    v.nodes("x", s.x), v.nodes("y", s.y), v.nodes("z", s.z);
    v.nodes("px", s.px), v.nodes("py", s.py), v.nodes("pz", s.pz);
    v.nodes("cx", s.cx), v.nodes("cy", s.cy), v.nodes("cz", s.cz);
    if (s.window) v.nodes("wx", s.wx), v.nodes("wy", s.wy), v.nodes("wz", s.wz);
}

class HairSolver {
public:
    // Throws std::invalid_argument (naming the field) for params outside the documented ranges, a radius that
    // is not finite and > 0, or a non-finite pose.
    HairSolver(const HairParams& params, float ballRadius, const HostPose& pose);
    ~HairSolver();
    HairSolver(const HairSolver&) = delete;
    HairSolver& operator=(const HairSolver&) = delete;

    // Advances by dt with the host now at `pose` (roots are placed exactly there). others: other balls.
    // dt <= 0, a non-finite dt or pose: nothing changes and the stats say nan = true.
    HairStepStats step(const HostPose& pose, float dt, std::span<const SphereCollider> others = {},
                       const VoxelOccupancy* voxels = nullptr, int threads = 1);

    int strands() const { return m_params.strands; }
    int nodesPerStrand() const { return m_params.nodesPerStrand; }
    int activeStrands() const { return m_s.active; }
    // Level of detail: only the first n strands (clamped to [0, strands()]) are simulated; the rest keep their
    // last state and are not drawn. Strands that come back are carried rigidly to their root and start at rest.
    void setActiveStrands(int n);

    // Node-major SoA: index = node * strands() + strand. Previous positions are the Verlet history (also what
    // the renderer interpolates from).
    const float* x() const { return m_s.x.data(); }
    const float* y() const { return m_s.y.data(); }
    const float* z() const { return m_s.z.data(); }
    const float* prevX() const { return m_s.px.data(); }
    const float* prevY() const { return m_s.py.data(); }
    const float* prevZ() const { return m_s.pz.data(); }
    // Dftl's velocity corrections (a displacement added to the next Verlet step), same layout.
    const float* correctionX() const { return m_s.cx.data(); }
    const float* correctionY() const { return m_s.cy.data(); }
    const float* correctionZ() const { return m_s.cz.data(); }
    // Length of the last substep (s); 0 when the next step starts from rest (new, released, or woken).
    float lastSubstepSeconds() const { return m_s.lastH; }

    bool sleeping() const { return m_s.sleeping; }
    void wake();

    float ballRadius() const { return m_radius; }
    const HairParams& params() const { return m_params; }
    float segmentLength() const { return m_segment; }
    // Unit direction of a strand's root in the ball's local frame (y up = the patch centre).
    glm::vec3 rootDirection(int strand) const { return {m_dirX[strand], m_dirY[strand], m_dirZ[strand]}; }
    // Where step() puts a root for this pose, computed exactly as step() does (bit for bit).
    glm::vec3 rootPosition(const HostPose& pose, int strand) const;
    // Of everything in HairSolverState, bit for bit: two solvers of the same params and radius with the same
    // hash take the same next step.
    std::uint64_t hashState() const;
    HairSolverState state() const;
    // Continues from a state taken from a solver of the same params and radius. Throws std::invalid_argument
    // (naming what) for arrays of the wrong size, non-finite values or counters out of range; the solver is
    // unchanged then.
    void restore(const HairSolverState& state);
    // Puts one strand's nodes (root first, nodes.size() == nodesPerStrand()) at rest at these positions,
    // as the lab's chain study releases a strand; the root is moved back onto the host at the next step.
    // Wakes the solver. Throws std::invalid_argument for a wrong count or a non-finite position.
    void setStrand(int strand, std::span<const glm::vec3> nodes);

private:
    struct Pool;
    struct Substep;
    void runBlocks(const Substep& s, int threads, HairStepStats* perThread);
    int shakeSubstepsFor(double dt) const;
    void stepRange(const Substep& s, int begin, int end, HairStepStats& stats, float* scratch);
    // The figures of strands [lo, hi) after the step's last substep, folded into stats.
    void blockStats(const Substep& s, std::size_t lo, std::size_t hi, HairStepStats& stats) const;
    void reseat(int begin, int end, const HostPose& pose);

    HairParams m_params;
    float m_radius = 0;
    float m_segment = 0;
    HairSolverState m_s;                       // everything carried from one step to the next (visitHairState lists it)
    std::vector<float> m_dirX, m_dirY, m_dirZ; // root directions, local frame
    std::unique_ptr<Pool> m_pool;
    std::vector<HairStepStats> m_threadStats;
    std::vector<std::vector<float>> m_scratch; // per thread: one block's predicted positions
};

// Root directions (unit, local frame, +y = patch centre) for `count` strands, area-uniform on the cap
// y >= cos(halfAngle), ordered so that every prefix is spread evenly (a Cranley-Patterson-rotated R2
// low-discrepancy sequence; `seed` picks the rotation).
std::vector<glm::vec3> hairRootDirections(int count, float halfAngle, std::uint64_t seed);

// Throws std::invalid_argument naming the first field out of range.
void validateHairParams(const HairParams& params);

} // namespace physics
