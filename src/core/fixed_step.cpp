#include "core/fixed_step.h"

#include <algorithm>
#include <cmath>

namespace core {

FixedStepClock::FixedStepClock(FixedStepDef def) : m_def(def) {
    if (!(m_def.tickSeconds > 0.0)) m_def.tickSeconds = 1.0 / 60.0;
    m_def.maxFrameSeconds = std::max(m_def.maxFrameSeconds, m_def.tickSeconds);
    m_def.maxTicksPerFrame = std::max(m_def.maxTicksPerFrame, 1);
}

int FixedStepClock::advance(double frameSeconds) {
    if (!std::isfinite(frameSeconds) || frameSeconds < 0.0) frameSeconds = 0.0;
    if (frameSeconds > m_def.maxFrameSeconds) {
        m_dropped += frameSeconds - m_def.maxFrameSeconds;
        frameSeconds = m_def.maxFrameSeconds;
    }
    m_accumulator += frameSeconds;
    // A tiny tolerance so that exactly k ticks' worth of time (summed in floating point) yields k ticks.
    const double eps = m_def.tickSeconds * 1e-9;
    int ticks = static_cast<int>(std::floor((m_accumulator + eps) / m_def.tickSeconds));
    if (ticks > m_def.maxTicksPerFrame) {
        m_dropped += (ticks - m_def.maxTicksPerFrame) * m_def.tickSeconds;
        ticks = m_def.maxTicksPerFrame;
        // Keep only the fractional part: the skipped whole ticks are dropped, not queued.
        m_accumulator = std::fmod(m_accumulator, m_def.tickSeconds);
    } else {
        m_accumulator -= ticks * m_def.tickSeconds;
    }
    m_accumulator = std::clamp(m_accumulator, 0.0, m_def.tickSeconds * (1.0 - 1e-12));
    return ticks;
}

} // namespace core
