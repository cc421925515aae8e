// A pendulum set: a post standing on a block with four pendulums hung from arms pointing north, east,
// south and west, each stepped by its own method, all released together from the same angle, so a
// player sees the integrators drift apart. Stepped by the game's fixed tick; no drawing here.
// The physics lives in physics::Pendulum; this adds placement, the shared controls and the traces the
// panel plots.
#pragma once
#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "physics/pendulum.h"

namespace game {

enum class Compass { North, East, South, West, Count };
inline constexpr int kPendulumSlots = static_cast<int>(Compass::Count);

// The rods and gravities a set may have (physics/pendulum.h, shared with the lab).
using physics::kMaxPendulumGravity;
using physics::kMaxPendulumLength;
using physics::kMinPendulumLength;

struct PendulumSetDef {
    double releaseDegrees = 60.0; // release angle of all four, from hanging straight down
    double length = 1.0;          // rod length (m), all four
    double gravity = 9.81;        // m/s^2
    double stepMultiplier = 1.0;  // each tick steps the methods by tick length x this (and runs that much faster)
    std::array<physics::Method, kPendulumSlots> methods{physics::Method::Exact, physics::Method::Euler,
                                                        physics::Method::Midpoint, physics::Method::Trapezoid};
};

struct PendulumTrace { // the last few seconds, for the panel's plots
    static constexpr std::size_t kSamples = 600;
    std::vector<float> time;                                           // simulated seconds since release
    std::array<std::vector<float>, kPendulumSlots> theta, energyError; // rad; (E - E0) / (m g L)
    std::vector<float> exactTheta;                                     // the exact solution at the same times
    std::size_t head = 0;                                              // ring buffer: next write position
    std::size_t size = 0;
};

class PendulumSet {
public:
    // base: the block the post stands in (its foot sits on the block below). Starts released, swinging.
    PendulumSet(glm::ivec3 base, const PendulumSetDef& def = {});

    void tick(double dt);                   // one game tick; does nothing while held (not released)
    void hold();                            // a tick without a step (the game is paused)
    void release();                         // let go from the release angle (restarts time)
    void reset();                           // back to the release angle, held still
    void setDef(const PendulumSetDef& def); // new parameters: resets

    const PendulumSetDef& def() const { return m_def; }
    glm::ivec3 base() const { return m_base; }
    bool released() const { return m_released; }
    double time() const { return m_slots[0].time(); }
    const physics::Pendulum& slot(int i) const { return m_slots[static_cast<std::size_t>(i)]; }
    // The state one tick ago, for drawing between ticks.
    const physics::PendulumState& previousState(int i) const { return m_previous[static_cast<std::size_t>(i)]; }
    double previousTime() const { return m_previousTime; }
    bool diverged(int i) const { return m_diverged[static_cast<std::size_t>(i)]; }
    const PendulumTrace& trace() const { return m_trace; }
    physics::PendulumParams params() const;
    double initialEnergy() const;
    // (E - E0) / (m g L) of slot i's current state: the energy drift the panel, trace and soak show.
    double energyError(int i) const;
    // Slot i's point on the work-precision chart, live: |theta - theta_exact| now (rad, wrapped to (-pi, pi]),
    // and its cost so far in force evaluations per simulated second (physics::Pendulum::evaluations() over the
    // time since release). NaN before the first step, for a diverged slot and for the exact slot itself.
    double angleError(int i) const;
    double evaluationsPerSecond(int i) const;
    // The state to draw between the last two ticks: stepped methods interpolate linearly, and the exact
    // one is evaluated at the same interpolated time, so the reference never leads or lags by a tick.
    physics::PendulumState drawnState(int slot, double alpha) const;

    // Everything a set carries besides its base and def (the trace excepted), for saving a world
    // (src/save): restore(internals()) on a set with the same base and def resumes bit for bit. The trace
    // starts over from the restored state.
    struct Internals {
        bool released = true;
        double previousTime = 0.0;
        std::array<physics::PendulumState, kPendulumSlots> previous{};
        std::array<bool, kPendulumSlots> diverged{};
        std::array<physics::Pendulum::Internals, kPendulumSlots> slots{};
    };
    Internals internals() const;
    // Throws std::invalid_argument (nothing changed) for a non-finite value. The trace starts anew.
    void restore(const Internals& in);
    // The panel's plots as they were (a keyframe file's; session/keyframe_file.h), after restore(): every array
    // PendulumTrace::kSamples long, head and size within them. Throws std::invalid_argument (nothing changed)
    // otherwise.
    void restoreTrace(PendulumTrace trace);

    // Geometry (world metres): the pivot of slot i, the plane it swings in (unit horizontal vector
    // along which the bob moves for positive theta), and the post's height above its foot.
    glm::vec3 pivot(int i) const;
    glm::vec3 swingAxis(int i) const;
    glm::vec3 bobPosition(int i, double theta) const;
    float postHeight() const;
    static constexpr float kArmLength = 1.2f;  // m: longer than the default rod, so a swing never reaches the post
    static constexpr float kBobRadius = 0.12f; // m

private:
    void record();
    glm::ivec3 m_base;
    PendulumSetDef m_def;
    std::array<physics::Pendulum, kPendulumSlots> m_slots;
    std::array<physics::PendulumState, kPendulumSlots> m_previous{};
    std::array<bool, kPendulumSlots> m_diverged{};
    double m_previousTime = 0.0;
    bool m_released = true;
    PendulumTrace m_trace;
    // The closed form for the current parameters: its set-up (elliptic integrals) is done once per
    // parameter change, not per tick for the trace and per slot per frame for drawing.
    physics::ExactPendulum m_exact;
};

std::string_view compassName(int slot); // "north", "east", "south", "west"
// The colour a method is drawn and labelled in, everywhere (world, panel, lab charts' order).
glm::vec3 methodColour(physics::Method method);

} // namespace game
