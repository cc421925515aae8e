#include "world/light.h"

#include <algorithm>
#include <array>
#include <cstring>

#include <glm/common.hpp>

namespace world {

namespace {

constexpr std::array<glm::ivec3, 6> kSteps{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};

// The block table's light columns, by block value, without a call per voxel.
struct LightProperties {
    std::array<std::uint8_t, 256> opacity{}, emission{};
    std::vector<unsigned char> emitters; // the block values that emit, to look for with memchr
    LightProperties() {
        for (int i = 0; i < 256; ++i) {
            const BlockInfo& info = blockInfo(static_cast<BlockType>(i));
            opacity[static_cast<std::size_t>(i)] = info.lightOpacity;
            emission[static_cast<std::size_t>(i)] = info.lightEmission;
            if (info.lightEmission > 0) emitters.push_back(static_cast<unsigned char>(i));
        }
    }
};
const LightProperties kLight;
int opacityOf(BlockType t) { return kLight.opacity[static_cast<std::uint8_t>(t)]; }

// What light loses from n into v, going by `step` (v = n + step).
int cost(LightChannel c, BlockType into, glm::ivec3 step, int level) {
    const int opacity = opacityOf(into);
    if (c == LightChannel::Sun && step.y == -1 && level == kMaxLight && opacity == 0) return 0;
    return 1 + opacity;
}

int emission(LightChannel c, BlockType t) {
    return c == LightChannel::Block ? kLight.emission[static_cast<std::uint8_t>(t)] : 0;
}

} // namespace

LightField::LightField(glm::ivec3 origin, glm::ivec3 size)
    : m_origin(origin), m_size(glm::max(size, glm::ivec3(1))),
      m_blocks(static_cast<std::size_t>(m_size.x) * m_size.y * m_size.z, BlockType::Air),
      m_light(m_blocks.size(), static_cast<std::uint8_t>(kMaxLight << 4)) {}

bool LightField::contains(glm::ivec3 p) const {
    const glm::ivec3 l = p - m_origin;
    return l.x >= 0 && l.y >= 0 && l.z >= 0 && l.x < m_size.x && l.y < m_size.y && l.z < m_size.z;
}

glm::ivec3 LightField::position(std::size_t i) const {
    const auto sx = static_cast<std::size_t>(m_size.x), sz = static_cast<std::size_t>(m_size.z);
    return m_origin +
           glm::ivec3(static_cast<int>(i % sx), static_cast<int>(i / (sx * sz)), static_cast<int>(i / sx % sz));
}

int LightField::get(LightChannel c, std::size_t i) const {
    return c == LightChannel::Sun ? m_light[i] >> 4 : m_light[i] & 15;
}

void LightField::set(LightChannel c, std::size_t i, int level) {
    m_light[i] = c == LightChannel::Sun ? static_cast<std::uint8_t>((m_light[i] & 15) | level << 4)
                                        : static_cast<std::uint8_t>((m_light[i] & 0xF0) | level);
}

int LightField::level(LightChannel c, glm::ivec3 p) const { return contains(p) ? get(c, index(p)) : 0; }

int LightField::fromNeighbours(LightChannel c, glm::ivec3 v) const {
    const BlockType into = m_blocks[index(v)];
    int best = emission(c, into);
    for (const glm::ivec3& step : kSteps) {
        const glm::ivec3 n = v - step; // light comes from n by `step`
        int from = 0;
        if (contains(n)) {
            from = get(c, index(n));
        } else if (c == LightChannel::Sun && step.y == -1 && n.y == m_origin.y + m_size.y) {
            from = kMaxLight; // the sky above the box
        }
        if (from > 0) best = std::max(best, from - cost(c, into, step, from));
    }
    return std::max(best, 0);
}

std::size_t LightField::spread(LightChannel c, std::vector<std::size_t>& queue) {
    // By index steps, not positions: a voxel's coordinates only decide which of its six neighbours exist.
    const auto sx = static_cast<std::size_t>(m_size.x), sz = static_cast<std::size_t>(m_size.z);
    const std::size_t layer = sx * sz;
    const std::size_t stride[3] = {1, layer, sx}; // along x, y, z: kSteps' axes in order x, y, z
    const int extent[3] = {m_size.x, m_size.y, m_size.z};
    std::size_t visited = 0;
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::size_t i = queue[head];
        const std::size_t y = i / layer, rest = i - y * layer, z = rest / sx, x = rest - z * sx;
        const int at[3] = {static_cast<int>(x), static_cast<int>(y), static_cast<int>(z)};
        const int level = get(c, i);
        ++visited;
        for (int k = 0; k < 6; ++k) {
            const int axis = k / 2;
            const bool up = k % 2 == 0; // kSteps: +x, -x, +y, -y, +z, -z
            if (up ? at[axis] + 1 >= extent[axis] : at[axis] == 0) continue;
            const std::size_t j = up ? i + stride[axis] : i - stride[axis];
            const int to = level - cost(c, m_blocks[j], kSteps[static_cast<std::size_t>(k)], level);
            if (to > get(c, j)) {
                set(c, j, to);
                queue.push_back(j);
            }
        }
    }
    queue.clear();
    return visited;
}

std::size_t LightField::relightAll() {
    std::fill(m_light.begin(), m_light.end(), std::uint8_t{0});
    const int sx = m_size.x, sy = m_size.y, sz = m_size.z;
    const auto column = [&](int x, int z) {
        return static_cast<std::size_t>(x) + static_cast<std::size_t>(sx) * static_cast<std::size_t>(z);
    };
    const std::size_t layer = static_cast<std::size_t>(sx) * static_cast<std::size_t>(sz);
    // Sunlight. Each column is at full level from the top down to its first block that is not clear (the
    // rule's free fall, which no other path can beat); `open` is the lowest such voxel (sy: none). Only the
    // edge of those needs spreading: the lowest open voxel of each column (down into what stops it) and the
    // open voxels beside a column that is not open at their height.
    // Layer by layer from the top, in memory order; `open` stays sy + 1 while a column is open so far.
    std::vector<int> open(layer, sy + 1);
    // Layers of nothing but air from the top down are open sky in every column: filled whole.
    static_assert(static_cast<int>(BlockType::Air) == 0 && sizeof(BlockType) == 1);
    int clearFrom = sy;
    const auto* bytes = reinterpret_cast<const unsigned char*>(m_blocks.data());
    while (clearFrom > 0) {
        const unsigned char* row = bytes + layer * static_cast<std::size_t>(clearFrom - 1);
        if (row[0] != 0 || std::memcmp(row, row + 1, layer - 1) != 0) break;
        --clearFrom;
    }
    std::memset(m_light.data() + layer * static_cast<std::size_t>(clearFrom), kMaxLight << 4,
                layer * static_cast<std::size_t>(sy - clearFrom));
    for (int y = clearFrom - 1; y >= 0; --y) {
        const std::size_t base = layer * static_cast<std::size_t>(y);
        bool any = false;
        for (std::size_t c = 0; c < layer; ++c) {
            if (open[c] != sy + 1) continue;
            if (opacityOf(m_blocks[base + c]) == 0) {
                m_light[base + c] = static_cast<std::uint8_t>(kMaxLight << 4);
                any = true;
            } else {
                open[c] = y + 1;
            }
        }
        if (!any) break;
    }
    for (int& o : open) o = o == sy + 1 ? 0 : o; // open to the bottom
    std::vector<std::size_t> queue;
    // A top block that is not clear (leaves at the top of the box) takes the sky's light through itself.
    const std::size_t top = layer * static_cast<std::size_t>(sy - 1);
    for (std::size_t c = 0; c < layer; ++c) {
        if (open[c] != sy) continue;
        const int level = kMaxLight - cost(LightChannel::Sun, m_blocks[top + c], {0, -1, 0}, kMaxLight);
        if (level > 0) {
            set(LightChannel::Sun, top + c, level);
            queue.push_back(top + c);
        }
    }
    for (int z = 0; z < sz; ++z) {
        for (int x = 0; x < sx; ++x) {
            const int low = open[column(x, z)];
            if (low >= sy) continue;
            int high = low; // the highest of this column's open voxels to seed
            if (x > 0) high = std::max(high, open[column(x - 1, z)] - 1);
            if (x + 1 < sx) high = std::max(high, open[column(x + 1, z)] - 1);
            if (z > 0) high = std::max(high, open[column(x, z - 1)] - 1);
            if (z + 1 < sz) high = std::max(high, open[column(x, z + 1)] - 1);
            for (int y = low; y <= std::min(high, sy - 1); ++y)
                queue.push_back(column(x, z) + layer * static_cast<std::size_t>(y));
        }
    }
    std::size_t visited = spread(LightChannel::Sun, queue);
    // Block light: from the emitters alone, found by memchr (most boxes hold none).
    for (const unsigned char value : kLight.emitters) {
        const unsigned char* at = bytes;
        const unsigned char* const end = bytes + m_blocks.size();
        while ((at = static_cast<const unsigned char*>(std::memchr(at, value, static_cast<std::size_t>(end - at))))) {
            const auto i = static_cast<std::size_t>(at - bytes);
            set(LightChannel::Block, i, emission(LightChannel::Block, m_blocks[i]));
            queue.push_back(i);
            ++at;
        }
    }
    return visited + spread(LightChannel::Block, queue);
}

std::size_t LightField::repair(LightChannel c, glm::ivec3 p) {
    // Removal: clear what may have been lit through p; keep the lit edge around it to spread back from.
    struct Lost {
        std::size_t i;
        int level;
    };
    std::vector<Lost> removal;
    std::vector<std::size_t> refill;
    std::vector<std::size_t> cleared;
    const std::size_t start = index(p);
    removal.push_back({start, get(c, start)});
    set(c, start, 0);
    cleared.push_back(start);
    std::size_t visited = 0;
    for (std::size_t head = 0; head < removal.size(); ++head) {
        const Lost lost = removal[head];
        const glm::ivec3 v = position(lost.i);
        ++visited;
        for (const glm::ivec3& step : kSteps) {
            const glm::ivec3 n = v + step;
            if (!contains(n)) continue;
            const std::size_t j = index(n);
            const int level = get(c, j);
            if (level == 0) continue;
            const bool fedByIt = level < lost.level || (c == LightChannel::Sun && step.y == -1 &&
                                                        lost.level == kMaxLight && level == kMaxLight);
            if (fedByIt) {
                removal.push_back({j, level});
                set(c, j, 0);
                cleared.push_back(j);
            } else {
                refill.push_back(j);
            }
        }
    }
    // Adding: every cleared voxel takes what its neighbours and itself give now (p with its new block), then
    // the light spreads on from there and from the edge.
    for (const std::size_t i : cleared) {
        const int level = fromNeighbours(c, position(i));
        if (level > get(c, i)) {
            set(c, i, level);
            refill.push_back(i);
        }
    }
    return visited + spread(c, refill);
}

std::size_t LightField::setBlock(glm::ivec3 p, BlockType t) {
    if (!contains(p)) return 0;
    m_blocks[index(p)] = t;
    return repair(LightChannel::Sun, p) + repair(LightChannel::Block, p);
}

} // namespace world
