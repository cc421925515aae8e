#include "session/keyframes.h"

#include <stdexcept>

namespace session {

KeyframeStore::KeyframeStore(std::uint64_t interval, std::size_t budgetBytes)
    : m_interval(interval), m_budget(budgetBytes) {
    if (interval == 0) throw std::invalid_argument("the keyframe interval must be at least 1 tick");
    if (budgetBytes == 0) throw std::invalid_argument("the keyframe budget must be above 0");
}

bool KeyframeStore::wants(std::uint64_t tick) const {
    return tick % m_interval == 0 && m_frames.find(tick) == m_frames.end();
}

void KeyframeStore::add(Keyframe k) {
    const std::uint64_t tick = k.state.tick;
    if (const auto old = m_frames.find(tick); old != m_frames.end()) {
        count(old->second, -1);
        m_frames.erase(old);
    }
    count(m_frames.emplace(tick, std::move(k)).first->second, +1);
    while (m_bytes > m_budget && m_frames.size() > 1) {
        m_interval *= 2;
        const std::uint64_t first = m_frames.begin()->first;
        for (auto it = m_frames.begin(); it != m_frames.end();) {
            if (it->first != first && it->first % m_interval != 0) {
                count(it->second, -1);
                it = m_frames.erase(it);
            } else {
                ++it;
            }
        }
    }
}

const Keyframe* KeyframeStore::atOrBelow(std::uint64_t tick) const {
    auto it = m_frames.upper_bound(tick);
    if (it == m_frames.begin()) return nullptr;
    return &std::prev(it)->second;
}

void KeyframeStore::count(const Keyframe& k, int sign) {
    const std::size_t own = sizeof(Keyframe) + k.state.hairBalls.capacity() * sizeof(game::StateImage::Ball);
    m_bytes = sign > 0 ? m_bytes + own : m_bytes - own;
    game::forEachPart(k.state, [&](const void* part, std::size_t size) {
        if (sign > 0) {
            if (m_holders[part]++ == 0) m_bytes += size;
        } else if (const auto it = m_holders.find(part); --it->second == 0) {
            m_bytes -= size;
            m_holders.erase(it);
        }
    });
}

} // namespace session
