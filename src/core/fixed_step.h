// The fixed-timestep clock: turns irregular frame times into whole simulation ticks.
// It never calls a clock itself (the caller passes frame durations), so headless runs and tests drive it
// with exact numbers. It must never let one slow frame snowball into ever longer catch-up frames.
#pragma once
#include <cstdint>

namespace core {

struct FixedStepDef {
    double tickSeconds = 1.0 / 60.0; // length of one simulation tick (s)
    double maxFrameSeconds = 0.25;   // a longer frame (debugger, window drag) is clamped to this (s)
    int maxTicksPerFrame = 8;        // beyond this the game slows down instead of spiralling
};

class FixedStepClock {
public:
    explicit FixedStepClock(FixedStepDef def = {});

    // Adds one frame's duration and returns how many ticks to run now.
    int advance(double frameSeconds);
    // Fraction of a tick accumulated but not yet simulated, in [0, 1): render at previous + alpha * (current -
    // previous).
    double alpha() const { return m_accumulator / m_def.tickSeconds; }
    double tickSeconds() const { return m_def.tickSeconds; }
    // Simulation time dropped by clamping and the per-frame cap since construction (s).
    double droppedSeconds() const { return m_dropped; }

private:
    FixedStepDef m_def;
    double m_accumulator = 0.0;
    double m_dropped = 0.0;
};

} // namespace core
