// The frame rate the F3 overlay shows: the mean over the frames of the last second or so, computed from
// frame TIMES (frames / their total duration), never as an average of per-frame rates. An average of
// rates is dominated by the shortest frames: one near-zero first frame (the window's first swap) read
// as tens of thousands of fps and took many seconds to decay. Pure: the caller passes each frame's
// duration, so tests feed exact sequences. Never reads a clock.
#pragma once
#include <cmath>
#include <cstddef>
#include <deque>

namespace core {

class FrameRate {
public:
    // windowSeconds: how much recent time the average covers (s).
    explicit FrameRate(double windowSeconds = 1.0) : m_window(windowSeconds > 0.0 ? windowSeconds : 1.0) {}

    // Adds one frame's duration (s). A negative or non-finite duration (a clock that stepped back)
    // counts as a zero-length frame rather than corrupting the sum.
    void addFrame(double seconds) {
        const double d = std::isfinite(seconds) && seconds > 0.0 ? seconds : 0.0;
        m_frames.push_back(d);
        m_sum += d;
        // Keep the newest frames that cover the window; the oldest goes once the rest cover it alone.
        while (m_frames.size() > 1 && m_sum - m_frames.front() >= m_window) {
            m_sum -= m_frames.front();
            m_frames.pop_front();
        }
        // Re-add from scratch now and then so rounding in the running sum cannot drift.
        if (++m_sinceResum >= kResumEvery) {
            m_sinceResum = 0;
            m_sum = 0.0;
            for (const double f : m_frames) m_sum += f;
        }
    }

    // Frames per second over the window; 0 before any time has passed.
    double fps() const { return m_sum > 0.0 ? static_cast<double>(m_frames.size()) / m_sum : 0.0; }
    // Mean frame duration over the window (ms); 0 before any frame.
    double frameMs() const { return m_frames.empty() ? 0.0 : 1000.0 * m_sum / static_cast<double>(m_frames.size()); }
    // Frames the average covers now.
    std::size_t frames() const { return m_frames.size(); }

private:
    static constexpr int kResumEvery = 4096;

    double m_window;
    std::deque<double> m_frames; // durations, oldest first (s)
    double m_sum = 0.0;
    int m_sinceResum = 0;
};

} // namespace core
