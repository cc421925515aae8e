#include "session/keyframes.h"

#include <stdexcept>
#include <unordered_set>

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
    m_frames.insert_or_assign(tick, std::move(k));
    count();
    while (m_bytes > m_budget && m_frames.size() > 1) {
        m_interval *= 2;
        const std::uint64_t first = m_frames.begin()->first;
        for (auto it = m_frames.begin(); it != m_frames.end();) {
            it = it->first != first && it->first % m_interval != 0 ? m_frames.erase(it) : std::next(it);
        }
        count();
    }
}

const Keyframe* KeyframeStore::atOrBelow(std::uint64_t tick) const {
    auto it = m_frames.upper_bound(tick);
    if (it == m_frames.begin()) return nullptr;
    return &std::prev(it)->second;
}

void KeyframeStore::count() {
    std::unordered_set<const void*> seen;
    std::size_t bytes = 0;
    for (const auto& [tick, k] : m_frames) {
        bytes += sizeof(Keyframe) + k.state.hairBalls.capacity() * sizeof(game::StateImage::Ball);
        game::forEachPart(k.state, [&](const void* part, std::size_t size) {
            if (seen.insert(part).second) bytes += size;
        });
    }
    m_bytes = bytes;
}

} // namespace session
