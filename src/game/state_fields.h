// The one list of the simulated state's fields. The state hash and the state dump (game/state_io.cpp) and
// the world file (its columns in save/world_schema.cpp, its writer in save/world_save.cpp, its reader in
// save/world_load.cpp) all walk these functions, so a field added here is hashed, dumped and saved, and the
// schema test (WorldFile.EveryListedFieldIsAColumn) asks for its column. The hair's own fields are
// physics::visitHairState.
//
// A visitor is called as
//   v.value(name, x)          bool, int, std::uint64_t, float, double, and the enums below (saved by name);
//   v.vec(name, x, columns)   glm::vec3 or glm::ivec3: one name in the dump, three columns in the file;
//   v.hotbar(name, items)     the player's hotbar (saved as one text of item names);
//   v.hair(name, hair, strands, nodesPerStrand)  a ball's hair: the live physics::HairSolver or a record's
//                             saved state (physics::visitHairState lists its fields).
// The record types are plain data (const or not), so a visitor may read, write or perturb them.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "game/game_state.h"

namespace game {

using Columns = std::array<const char*, 3>;

// The world's own values: the file's meta table.
struct StateMeta {
    std::uint64_t tick = 0;
    std::uint64_t seed = 0;
    world::TerrainKind terrain{};
    bool paused = false;
    DayClock day{};
};
inline StateMeta metaOf(const GameState& s) {
    return {s.tick, s.world.terrain().seed, s.world.terrain().kind, s.paused, s.day};
}
// The meta keys a file saved before the day clock (schema 4 and older) lacks: it opens at kDefaultHours.
inline bool isDayClockKey(std::string_view key) {
    return key == "time_of_day" || key == "day_length" || key == "day_stopped";
}

struct PendulumSetRecord {
    glm::ivec3 base{0};
    PendulumSetDef def{};
    PendulumSet::Internals internals{};
};
inline PendulumSetRecord recordOf(const PendulumSet& set) { return {set.base(), set.def(), set.internals()}; }

// A ball without its hair, which the visit takes beside it (the live solver is not copied to hash it).
struct HairBallRecord {
    glm::vec3 centre{0.0f};
    float spin = 0.0f; // rad
    HairBallDef def{};
    // The hair as it was, to continue bit for bit; none from a file saved before schema 4 (the hair starts anew).
    std::optional<physics::HairSolverState> hair;
};
inline HairBallRecord recordOf(const HairBall& ball) { return {ball.centre(), ball.spinAngle(), ball.def(), {}}; }

template <class V, class M>
void visitMeta(V& v, M& m) {
    v.value("tick", m.tick);
    v.value("seed", m.seed);
    v.value("terrain", m.terrain);
    v.value("paused", m.paused);
    v.value("time_of_day", m.day.hours);
    v.value("day_length", m.day.dayMinutes); // minutes
    v.value("day_stopped", m.day.stopped);
}

template <class V, class P>
void visitPlayer(V& v, P& p) {
    v.vec("position", p.position, Columns{"px", "py", "pz"});
    v.vec("velocity", p.velocity, Columns{"vx", "vy", "vz"});
    v.value("yaw", p.yaw);
    v.value("pitch", p.pitch);
    v.value("on_ground", p.onGround);
    v.value("flying", p.flying);
    v.value("selected_slot", p.selectedSlot);
    v.hotbar("hotbar", p.hotbar);
}

template <class V, class R>
void visitPendulumSet(V& v, R& r) {
    v.vec("position", r.base, Columns{"x", "y", "z"});
    v.value("release_degrees", r.def.releaseDegrees);
    v.value("length", r.def.length);
    v.value("gravity", r.def.gravity);
    v.value("step_multiplier", r.def.stepMultiplier);
    v.value("released", r.internals.released);
    v.value("previous_time", r.internals.previousTime);
}

// Slot k of a set (the file's pendulum_slots table).
template <class V, class R>
void visitPendulumSlot(V& v, R& r, std::size_t k) {
    auto& in = r.internals.slots[k];
    v.value("method", r.def.methods[k]);
    v.value("diverged", r.internals.diverged[k]);
    v.value("drawn_theta", r.internals.previous[k].theta); // the drawn state of the last tick
    v.value("drawn_omega", r.internals.previous[k].omega);
    v.value("theta", in.state.theta);
    v.value("omega", in.state.omega);
    v.value("time", in.time);
    v.value("time_carry", in.timeCarry);
    v.value("previous_theta", in.previous.theta); // the two-step method's history
    v.value("previous_omega", in.previous.omega);
    v.value("last_step", in.lastStep); // its step, or dopri5's next trial step
    v.value("cart_x", in.x);           // euler-cartesian's position
    v.value("cart_y", in.y);
    v.value("sin_theta", in.sinTheta);
    v.value("exact_theta0", in.exactInitial.theta); // the closed form's start
    v.value("exact_omega0", in.exactInitial.omega);
}

// H: const physics::HairSolver (a live ball) or std::optional<physics::HairSolverState> (a record).
template <class V, class R, class H>
void visitHairBall(V& v, R& r, H& hair) {
    auto& d = r.def;
    auto& h = r.def.hair;
    v.vec("position", r.centre, Columns{"cx", "cy", "cz"});
    v.value("spin", r.spin);
    v.value("radius", d.radius);
    v.vec("colour", d.colour, Columns{"red", "green", "blue"});
    v.value("spin_rate", d.spinRate);
    v.value("strands", h.strands);
    v.value("nodes_per_strand", h.nodesPerStrand);
    v.value("strand_length", h.strandLength);
    v.value("damping", h.dampingPerSecond);
    v.value("gravity", h.gravity);
    v.value("iterations", h.iterations);
    v.value("substeps", h.substeps);
    v.value("patch_half_angle", h.patchHalfAngle);
    v.value("seed", h.seed);
    v.value("max_substep_seconds", h.maxSubstepSeconds);
    v.value("sleep_speed", h.sleepSpeed);
    v.value("sleep_delay", h.sleepDelay);
    v.value("velocity_correction", h.velocityCorrection);
    v.value("solver", h.method);
    v.value("host_collision", h.hostCollision); // schema 6; true (the ball is a collider) in an older file
    v.hair("hair_state", hair, h.strands, h.nodesPerStrand);
}

// Names of the enums the list holds, as files, scripts and the dump spell them.
inline std::string_view enumName(world::TerrainKind k) { return world::terrainName(k); }
inline std::string_view enumName(physics::Method m) { return physics::methodName(m); }
inline std::string_view enumName(physics::HairMethod m) { return physics::hairMethodName(m); }
inline std::optional<world::TerrainKind> enumFromName(std::string_view s, world::TerrainKind) {
    return world::terrainFromName(s);
}
inline std::optional<physics::Method> enumFromName(std::string_view s, physics::Method) {
    return physics::methodFromName(s);
}
inline std::optional<physics::HairMethod> enumFromName(std::string_view s, physics::HairMethod) {
    return physics::hairMethodFromName(s);
}

} // namespace game
