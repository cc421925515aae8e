// Keyframes of a session: its whole state every `interval` ticks, kept within a memory budget, so that a seek
// (Session::seek) restores the nearest keyframe at or before its tick and steps forward from there, the way
// Box2D v3.2's recordings seek. Over the budget the spacing doubles: every keyframe off the new spacing is
// dropped (the first one, the start, stays). Parts a keyframe shares with the one before it (a sleeping ball's
// hair, edits that did not change: game/state_image.h) are counted once.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <unordered_map>

#include "game/state_image.h"
#include "input/mapper.h"
#include "session/settings.h"

namespace session {

struct Keyframe {
    game::StateImage state;
    input::InputMapper mapper;  // the keys and buttons a script holds down, the script's pending events
    std::size_t scriptNext = 0; // the next script event to apply
};

class KeyframeStore {
public:
    static constexpr std::uint64_t kDefaultInterval = kDefaultKeyframeInterval;                 // ticks
    static constexpr std::size_t kDefaultBudget = std::size_t{kDefaultKeyframeBudgetMiB} << 20; // bytes

    // Throws std::invalid_argument for an interval of 0 or a budget of 0.
    KeyframeStore(std::uint64_t interval, std::size_t budgetBytes);

    // Whether a keyframe of this tick would be kept (on the spacing, not held yet).
    bool wants(std::uint64_t tick) const;
    // Keeps `k`, then widens the spacing while over the budget. The first keyframe is kept whatever it costs: the
    // caller checks it against the budget (bytes()).
    void add(Keyframe k);
    // The keyframe of the greatest tick <= tick; nullptr when there is none.
    const Keyframe* atOrBelow(std::uint64_t tick) const;
    std::uint64_t interval() const { return m_interval; }
    std::size_t budget() const { return m_budget; }
    std::size_t bytes() const { return m_bytes; }
    std::size_t size() const { return m_frames.size(); }
    const std::map<std::uint64_t, Keyframe>& frames() const { return m_frames; }

private:
    // Counts a keyframe's parts in (+1) or out (-1): a part shared by several keyframes is counted once.
    void count(const Keyframe& k, int sign);
    std::map<std::uint64_t, Keyframe> m_frames;
    std::unordered_map<const void*, std::size_t> m_holders; // a shared part -> the keyframes holding it
    std::uint64_t m_interval;
    std::size_t m_budget;
    std::size_t m_bytes = 0;
};

} // namespace session
