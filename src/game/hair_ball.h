// A hair ball: a sphere carrying Verlet hair strands (physics::HairSolver), placed in the world like a
// block, spinning at its own rate, carried by the player so its hair swings. This adds the ball's
// pose over time, its colour and the solid blocks the hair collides with; the strands are physics'.
#pragma once
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>

#include "physics/hair.h"
#include "world/world.h"

namespace game {

struct HairBallDef {
    float radius = 0.3f;                   // m
    glm::vec3 colour{0.85f, 0.55f, 0.25f}; // linear RGB, 0..1
    float spinRate = 0.0f;                 // rad/s about the vertical axis
    physics::HairParams hair{};            // strands, nodes, length, damping, patch...
};

// The hair balls the game simulates: the panel's ranges (radius 0.1-1 m, strands up to 1.5 m, spin
// +-6 rad/s, up to 20 iterations) with headroom. Beyond them a ball leaves what a tick can afford (the
// box of blocks its hair may touch grows with the cube of radius + strand length: a 100 m ball with
// 1e6 m strands asked for a 10^19-byte box) or the float range (a 1e30 m strand overflowed the
// float-to-int block lookup). A world file holding such a ball has that record skipped.
inline constexpr float kMaxHairBallRadius = 2.0f, kMaxHairStrandLength = 4.0f, kMaxHairSpinRate = 60.0f,
                       kMaxHairGravity = 1000.0f;
inline constexpr int kMaxHairIterations = 100, kMaxHairSubsteps = 16;

// Throws std::invalid_argument naming the field unless the radius, strand length, spin rate, hair gravity,
// iterations and substeps are within the limits above, the colour is in [0, 1], and
// physics::validateHairParams accepts def.hair. HairBall's constructor and setDef call it.
void validateHairBallDef(const HairBallDef& def);

// Everything a ball carries from one tick to the next, to put it back exactly: a keyframe's (game/state_image.h).
struct HairBallImage {
    HairBallDef def{};
    glm::vec3 centre{0.0f}, previousCentre{0.0f};
    float spin = 0.0f;
    physics::HairSolverState hair;
    physics::HairStepStats stats{};
};

// A serial no ball of this process had: serials mean something only within one process (a keyframe file's balls are
// given new ones as they are read).
std::uint64_t newBallSerial();

class HairBall {
public:
    HairBall(const glm::vec3& centre, const HairBallDef& def = {});
    // The ball the image was taken of, to continue bit for bit: a new serial, or the serial and generation the
    // image was taken at (a keyframe's; game/state_image.h), which stand for exactly this state.
    explicit HairBall(const HairBallImage& image);
    HairBall(const HairBallImage& image, std::uint64_t serial, std::uint64_t generation);
    HairBall(HairBall&&) noexcept;
    HairBall& operator=(HairBall&&) noexcept;
    ~HairBall();

    // Before anything moves the ball in a tick: its centre now is where the tick starts (drawing interpolates
    // from it, and the hair's pose between ticks is taken between it and the tick's end).
    void beginTick() {
        if (m_previousCentre != m_centre) ++m_generation;
        m_previousCentre = m_centre;
    }
    // One tick of dt: spins the host, then steps the hair `hairSteps` substeps of the hair clock
    // (physics::hairClockSteps; none: the hair waits for the next) against the ball itself, the other balls and
    // the world's solid blocks, with the host's pose at the hair's own time: `hairLag` seconds before the
    // tick's end (physics::hairClockLag, < dt), the centre between the tick's start and end, the spin turned
    // back. activeStrands: level of detail.
    void tick(double dt, int hairSteps, double hairLag, const world::World& world,
              std::span<const physics::SphereCollider> others, int activeStrands);
    void setDef(const HairBallDef& def); // rebuilds the strands
    void moveTo(const glm::vec3& centre) {
        if (centre != m_centre) ++m_generation;
        m_centre = centre;
    }
    void setSpin(float radians); // a restored ball's spin angle; rebuilds the strands at that pose
    // A saved ball's hair, to continue bit for bit (physics::HairSolver::restore; throws std::invalid_argument).
    void restoreHair(const physics::HairSolverState& state) {
        ++m_generation;
        m_solver->restore(state);
    }

    const HairBallDef& def() const { return m_def; }
    glm::vec3 centre() const { return m_centre; }
    glm::vec3 previousCentre() const { return m_previousCentre; }
    float spinAngle() const { return m_spin; }
    const physics::HairSolver& solver() const { return *m_solver; }
    // The figures of the last step that did work: while the ball sleeps, those of its last awake step.
    const physics::HairStepStats& lastStats() const { return m_stats; }
    physics::SphereCollider collider() const { return {m_centre, m_def.radius}; }
    HairBallImage image() const { return {m_def, m_centre, m_previousCentre, m_spin, m_solver->state(), m_stats}; }
    // Which ball this is and how often it has changed: while both stand still, so does image() (a sleeping ball's
    // keyframes share one image). A ball made anew takes a serial no other ball had.
    std::uint64_t serial() const { return m_serial; }
    std::uint64_t generation() const { return m_generation; }
    physics::HostPose pose() const;

private:
    HairBallDef m_def;
    glm::vec3 m_centre, m_previousCentre;
    float m_spin = 0.0f;
    std::unique_ptr<physics::HairSolver> m_solver;
    physics::VoxelOccupancy m_voxels;
    physics::HairStepStats m_stats;
    std::uint64_t m_serial;
    std::uint64_t m_generation = 0;
};

} // namespace game
