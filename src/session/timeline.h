// A replay played in the window as a timeline (minecrappy --replay FILE): play and pause, a tick forward and back,
// speeds from 1/8 to 8 times either way, a jump to any tick or to the recording's events, and taking over. It
// moves the session with Session::seekToward, so a far jump catches up over several frames instead of freezing
// one, and a step back restores a keyframe (session/keyframes.h). No GL and no ImGui: the window draws it
// (ui::drawTimeline) and feeds it keys and clicks; tests drive it directly.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "session/session.h"

namespace session {

class Timeline {
public:
    // What happened at a tick of the recording, read from its lines (they hold intents: a place that hit nothing
    // is marked too).
    enum class MarkKind { Build, Carry, Edit, Time, Pause };
    struct Mark {
        std::uint64_t tick = 0;
        MarkKind kind = MarkKind::Edit;
    };
    static constexpr double kSpeeds[] = {0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0};
    // The CPU time a frame gives a seek that has to step forward (the rest of the frame draws).
    static constexpr double kSeekBudgetSeconds = 0.012;

    // `session` must replay a recording; keeps keyframes in it (every interval ticks within budgetBytes).
    Timeline(Session& session, std::uint64_t keyframeInterval, std::size_t budgetBytes);

    // A frame of `seconds`: while playing, the position moves on at the speed (backwards when reversed), stopping
    // at either end; then the session moves toward it within kSeekBudgetSeconds.
    void advance(double seconds);
    void togglePlay();
    bool playing() const { return m_playing; }
    // One tick (or n) forward or back: pauses.
    void step(std::int64_t ticks);
    // Faster or slower within kSpeeds; reverse() turns the direction.
    void faster();
    void slower();
    void reverse() { m_forward = !m_forward; }
    double speed() const { return m_forward ? kSpeeds[m_speed] : -kSpeeds[m_speed]; }
    // Jumps (pausing) to a tick, clamped to the recording; to the next or previous mark.
    void jumpTo(std::uint64_t tick);
    void nextMark();
    void previousMark();
    // Leaves the timeline at target() (a seek still catching up is finished first): the session plays live from
    // exactly that state (Session::takeOver).
    void takeOver();
    bool active() const { return m_active; }

    std::uint64_t firstTick() const { return m_first; }
    std::uint64_t lastTick() const { return m_last; }
    std::uint64_t target() const { return m_target; }
    // The tick on screen (the session's; behind target() while a far seek catches up).
    std::uint64_t tick() const { return m_session.state().tick; }
    bool catchingUp() const { return tick() != m_target; }
    const std::vector<Mark>& marks() const { return m_marks; }
    // Where the replay left the recording (a hash that differs: session::ReplayDiverged), once a move reached it:
    // the timeline then stops there, shows the tick and the message, and goes no further; it can still go back.
    std::optional<std::uint64_t> divergedAt() const { return m_diverged; }
    const std::string& divergence() const { return m_divergence; }
    // The state hash of what is on screen, computed once a tick.
    std::uint64_t hash();

private:
    void moveSession();
    Session& m_session;
    std::vector<Mark> m_marks;
    std::uint64_t m_first = 0, m_last = 0, m_target = 0;
    double m_position = 0.0; // ticks, fractional while playing
    bool m_playing = false, m_forward = true, m_active = true;
    std::size_t m_speed = 3; // kSpeeds[3] = 1
    std::uint64_t m_hashTick = ~std::uint64_t{0}, m_hash = 0;
    std::optional<std::uint64_t> m_diverged;
    std::string m_divergence;
};

std::string_view markName(Timeline::MarkKind kind);

} // namespace session
