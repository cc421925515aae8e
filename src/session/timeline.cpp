#include "session/timeline.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <variant>

#include "game/state_io.h"

namespace session {

std::string_view markName(Timeline::MarkKind kind) {
    switch (kind) {
    case Timeline::MarkKind::Build:
        return "place or break";
    case Timeline::MarkKind::Carry:
        return "carry";
    case Timeline::MarkKind::Edit:
        return "panel edit";
    case Timeline::MarkKind::Time:
        return "time of day";
    case Timeline::MarkKind::Pause:
        return "pause";
    }
    return "event";
}

Timeline::Timeline(Session& session, std::uint64_t keyframeInterval, std::size_t budgetBytes) : m_session(session) {
    const auto end = session.replayEndTick();
    if (!end) throw std::invalid_argument("a timeline needs a replay of a recording");
    m_first = session.replayStartTick();
    m_last = *end;
    m_target = session.state().tick;
    m_position = static_cast<double>(m_target);
    session.keepKeyframes(keyframeInterval, budgetBytes);
    // The marks: a recording's event at tick T is applied in the step from state tick T, so it shows from T + 1.
    for (const input::ScriptEvent& e : session.script()) {
        Mark m{e.tick + 1, MarkKind::Edit};
        if (e.edit) {
            m.kind = e.edit->object == "time" ? MarkKind::Time : MarkKind::Edit;
        } else if (const auto* a = std::get_if<input::ActionsEvent>(&e.event)) {
            if (a->actions.place || a->actions.breakBlock) {
                m.kind = MarkKind::Build;
            } else if (a->actions.carry) {
                m.kind = MarkKind::Carry;
            } else if (a->actions.togglePause) {
                m.kind = MarkKind::Pause;
            } else {
                continue;
            }
        } else {
            continue;
        }
        if (m.tick <= m_last) m_marks.push_back(m);
    }
}

void Timeline::moveSession() {
    if (!m_active) return;
    if (m_diverged && m_target > *m_diverged) m_target = *m_diverged; // nothing true lies past it
    try {
        m_session.seekToward(m_target, kSeekBudgetSeconds);
    } catch (const ReplayDiverged& e) {
        // The step that left the recording has been made: the state is the diverged one, at that tick.
        m_diverged = e.tick();
        m_divergence = e.what();
        m_playing = false;
        m_target = e.tick();
        m_position = static_cast<double>(m_target);
    }
}

void Timeline::advance(double seconds) {
    if (!m_active) return;
    if (m_playing) {
        const auto last = static_cast<double>(m_diverged ? *m_diverged : m_last);
        m_position += speed() * seconds / m_session.tickSeconds();
        if (m_position <= static_cast<double>(m_first) || m_position >= last) m_playing = false;
        m_position = std::clamp(m_position, static_cast<double>(m_first), last);
        m_target = static_cast<std::uint64_t>(std::floor(m_position));
    }
    moveSession();
}

void Timeline::togglePlay() {
    m_playing = !m_playing;
    if (m_playing && m_forward && m_target >= m_last) m_position = static_cast<double>(m_first); // from the start again
    if (m_playing && !m_forward && m_target <= m_first) m_position = static_cast<double>(m_last);
}

void Timeline::step(std::int64_t ticks) {
    const auto now = static_cast<std::int64_t>(m_target);
    jumpTo(static_cast<std::uint64_t>(std::max<std::int64_t>(0, now + ticks)));
}

void Timeline::faster() { m_speed = std::min(m_speed + 1, std::size(kSpeeds) - 1); }
void Timeline::slower() { m_speed = m_speed > 0 ? m_speed - 1 : 0; }

void Timeline::jumpTo(std::uint64_t tick) {
    m_playing = false;
    m_target = std::clamp(tick, m_first, m_diverged ? *m_diverged : m_last);
    m_position = static_cast<double>(m_target);
    moveSession();
}

void Timeline::nextMark() {
    const auto it = std::find_if(m_marks.begin(), m_marks.end(), [&](const Mark& m) { return m.tick > m_target; });
    if (it != m_marks.end()) jumpTo(it->tick);
}

void Timeline::previousMark() {
    const auto it = std::find_if(m_marks.rbegin(), m_marks.rend(), [&](const Mark& m) { return m.tick < m_target; });
    if (it != m_marks.rend()) jumpTo(it->tick);
}

void Timeline::takeOver() {
    if (!m_active) return;
    // A far seek still catching up is finished first: the take-over is at the tick asked for.
    while (m_session.state().tick != m_target) moveSession();
    m_session.takeOver();
    m_active = false;
    m_playing = false;
}

std::uint64_t Timeline::hash() {
    if (m_hashTick != tick()) {
        m_hash = game::stateHash(m_session.state());
        m_hashTick = tick();
    }
    return m_hash;
}

} // namespace session
