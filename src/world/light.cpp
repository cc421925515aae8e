#include "world/light.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>

#include "world/light_level.h"

namespace world {

namespace {

// The block table's light columns, by block value, without a call per voxel.
struct LightProperties {
    std::array<std::uint8_t, 256> opacity{}, emission{};
    std::array<std::uint8_t, 256> loss{}; // 1 + opacity: what light loses entering the block (but see cost())
    std::vector<unsigned char> emitters;  // the block values that emit, to look for with memchr
    LightProperties() {
        for (int i = 0; i < 256; ++i) {
            const BlockInfo& info = blockInfo(static_cast<BlockType>(i));
            opacity[static_cast<std::size_t>(i)] = info.lightOpacity;
            loss[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::min(1 + info.lightOpacity, 255));
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

// Channel C's four bits in a light byte (world/light_level.h).
template <LightChannel C>
struct ChannelBits {
    static constexpr int kShift = C == LightChannel::Sun ? LightLevel::kSunShift : 0;
    static constexpr unsigned kMask = C == LightChannel::Sun ? LightLevel::kSunBits : LightLevel::kBlockBits;
    static int get(std::uint8_t b) { return static_cast<int>((b & kMask) >> kShift); }
    static std::uint8_t with(std::uint8_t b, int level) {
        return static_cast<std::uint8_t>((b & ~kMask) | static_cast<unsigned>(level) << kShift);
    }
};

// A voxel waiting in a spreading queue: its index and its coordinates in the box, so that which neighbours
// exist is known without dividing the index (two divisions a voxel were a fifth of a relight).
struct Node {
    std::uint32_t i;
    std::uint16_t x, y, z;
};

// The spreading pass of channel C over a box of `size` (blocks and light in LightField::index order): every
// voxel in `queue` passes its level on to its neighbours under the rule (light.h), and every neighbour it
// raises spreads in turn. Returns the voxels taken from the queue, which it leaves empty.
template <LightChannel C>
std::size_t spreadFrom(const unsigned char* blocks, std::uint8_t* light, glm::ivec3 size, std::vector<Node>& queue) {
    using Bits = ChannelBits<C>;
    const auto sx = static_cast<std::uint32_t>(size.x), layer = sx * static_cast<std::uint32_t>(size.z);
    const int last[3] = {size.x - 1, size.y - 1, size.z - 1};
    std::size_t head = 0;
    for (; head < queue.size(); ++head) {
        const Node n = queue[head];
        const int level = Bits::get(light[n.i]);
        if (level <= 1) continue; // nothing to give: every neighbour costs at least a level (but falling sunlight)
        // Neighbours +x, -x, +y, -y, +z, -z in turn; light comes to each from n.
        const auto visit = [&](bool exists, std::uint32_t j, std::uint16_t x, std::uint16_t y, std::uint16_t z,
                               bool down) {
            if (!exists) return;
            int loss = kLight.loss[blocks[j]];
            if (C == LightChannel::Sun && down && level == kMaxLight && loss == 1) loss = 0;
            const int to = level - loss;
            if (to > Bits::get(light[j])) {
                light[j] = Bits::with(light[j], to);
                queue.push_back({j, x, y, z});
            }
        };
        const std::uint16_t x = n.x, y = n.y, z = n.z;
        visit(x < last[0], n.i + 1, static_cast<std::uint16_t>(x + 1), y, z, false);
        visit(x > 0, n.i - 1, static_cast<std::uint16_t>(x - 1), y, z, false);
        visit(y < last[1], n.i + layer, x, static_cast<std::uint16_t>(y + 1), z, false);
        visit(y > 0, n.i - layer, x, static_cast<std::uint16_t>(y - 1), z, true);
        visit(z < last[2], n.i + sx, x, y, static_cast<std::uint16_t>(z + 1), false);
        visit(z > 0, n.i - sx, x, y, static_cast<std::uint16_t>(z - 1), false);
    }
    queue.clear();
    return head;
}

std::size_t spreadNodes(LightChannel c, const unsigned char* blocks, std::uint8_t* light, glm::ivec3 size,
                        std::vector<Node>& queue) {
    return c == LightChannel::Sun ? spreadFrom<LightChannel::Sun>(blocks, light, size, queue)
                                  : spreadFrom<LightChannel::Block>(blocks, light, size, queue);
}

// Calls f(m, k) for each neighbour m of n inside a box of `size`, k its step: +x, -x, +y, -y, +z, -z for 0 to 5.
template <typename F>
void forEachNeighbour(Node n, glm::ivec3 size, F&& f) {
    const auto sx = static_cast<std::uint32_t>(size.x), layer = sx * static_cast<std::uint32_t>(size.z);
    const auto u16 = [](int v) { return static_cast<std::uint16_t>(v); };
    if (n.x + 1 < size.x) f(Node{n.i + 1, u16(n.x + 1), n.y, n.z}, 0);
    if (n.x > 0) f(Node{n.i - 1, u16(n.x - 1), n.y, n.z}, 1);
    if (n.y + 1 < size.y) f(Node{n.i + layer, n.x, u16(n.y + 1), n.z}, 2);
    if (n.y > 0) f(Node{n.i - layer, n.x, u16(n.y - 1), n.z}, 3);
    if (n.z + 1 < size.z) f(Node{n.i + sx, n.x, n.y, u16(n.z + 1)}, 4);
    if (n.z > 0) f(Node{n.i - sx, n.x, n.y, u16(n.z - 1)}, 5);
}

// The level of channel C that voxel v gets from its neighbours and itself under the rule (light.h), the sky above
// the box's top layer included.
template <LightChannel C>
int levelFromNeighbours(const unsigned char* blocks, const std::uint8_t* light, glm::ivec3 size, Node v) {
    const int loss = kLight.loss[blocks[v.i]];
    int best = C == LightChannel::Block ? kLight.emission[blocks[v.i]] : 0;
    const auto from = [&](int level, bool fromAbove) {
        if (level <= 0) return;
        // Sunlight falling straight down at full level into a clear block keeps its level.
        const bool falls = C == LightChannel::Sun && fromAbove && level == kMaxLight && loss == 1;
        best = std::max(best, falls ? level : level - loss);
    };
    forEachNeighbour(v, size, [&](Node m, int k) { from(ChannelBits<C>::get(light[m.i]), k == 2); });
    if (C == LightChannel::Sun && v.y + 1 == size.y) from(kMaxLight, true); // the sky above the box
    return std::max(best, 0);
}

// Repairs channel C after the block at `start` changed (light.h): a removal pass clears every voxel whose light
// may have come through it (levels below the one lost, and sunlight's columns under a lost full level), keeping
// the lit edge around what it clears; then every cleared voxel takes what its neighbours and itself give now,
// and the light spreads on from there and from the edge. Returns the voxels the passes visited.
template <LightChannel C>
std::size_t repairFrom(const unsigned char* blocks, std::uint8_t* light, glm::ivec3 size, Node start) {
    const auto get = [&](std::uint32_t i) { return ChannelBits<C>::get(light[i]); };
    const auto set = [&](std::uint32_t i, int level) { light[i] = ChannelBits<C>::with(light[i], level); };
    struct Lost {
        Node n;
        int level;
    };
    // Kept per thread: an edit allocates nothing once a thread has repaired one of its size.
    thread_local std::vector<Lost> removal;
    thread_local std::vector<Node> cleared, refill;
    removal.clear(), cleared.clear(), refill.clear();
    removal.push_back({start, get(start.i)});
    set(start.i, 0);
    cleared.push_back(start);
    std::size_t head = 0;
    for (; head < removal.size(); ++head) {
        const Lost lost = removal[head];
        forEachNeighbour(lost.n, size, [&](Node m, int k) {
            const int level = get(m.i);
            if (level == 0) return;
            const bool fedByIt = level < lost.level ||
                                 (C == LightChannel::Sun && k == 3 && lost.level == kMaxLight && level == kMaxLight);
            if (fedByIt) {
                removal.push_back({m, level});
                set(m.i, 0);
                cleared.push_back(m);
            } else {
                refill.push_back(m);
            }
        });
    }
    for (const Node v : cleared) {
        const int level = levelFromNeighbours<C>(blocks, light, size, v);
        if (level > get(v.i)) {
            set(v.i, level);
            refill.push_back(v);
        }
    }
    return head + spreadFrom<C>(blocks, light, size, refill);
}

} // namespace

namespace {

// The spreading queue holds 32-bit indices and 16-bit coordinates (Node).
glm::ivec3 checkedSize(glm::ivec3 size) {
    const glm::ivec3 s = glm::max(size, glm::ivec3(1));
    constexpr int kMostAlong = 0xFFFF;
    if (s.x > kMostAlong || s.y > kMostAlong || s.z > kMostAlong ||
        static_cast<std::uint64_t>(s.x) * static_cast<std::uint64_t>(s.y) * static_cast<std::uint64_t>(s.z) >
            0xFFFFFFFFull) {
        throw std::length_error("LightField: a box of " + std::to_string(s.x) + " x " + std::to_string(s.y) + " x " +
                                std::to_string(s.z) +
                                " blocks is larger than light supports (65535 along an axis, "
                                "2^32 - 1 in all)");
    }
    return s;
}

} // namespace

LightField::LightField(glm::ivec3 origin, glm::ivec3 size)
    : m_origin(origin), m_size(checkedSize(size)),
      m_blocks(static_cast<std::size_t>(m_size.x) * m_size.y * m_size.z, BlockType::Air),
      m_light(m_blocks.size(), kOpenSky.bits) {}

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
    return c == LightChannel::Sun ? LightLevel{m_light[i]}.sun() : LightLevel{m_light[i]}.block();
}

void LightField::set(LightChannel c, std::size_t i, int level) {
    const LightLevel l{m_light[i]};
    m_light[i] = c == LightChannel::Sun ? LightLevel::of(level, l.block()).bits : LightLevel::of(l.sun(), level).bits;
}

int LightField::level(LightChannel c, glm::ivec3 p) const { return contains(p) ? get(c, index(p)) : 0; }

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
    // Layers of nothing but air from the top down are open sky in every column: filled whole.
    static_assert(static_cast<int>(BlockType::Air) == 0 && sizeof(BlockType) == 1);
    int clearFrom = sy;
    const auto* bytes = reinterpret_cast<const unsigned char*>(m_blocks.data());
    while (clearFrom > 0) {
        const unsigned char* row = bytes + layer * static_cast<std::size_t>(clearFrom - 1);
        if (row[0] != 0 || std::memcmp(row, row + 1, layer - 1) != 0) break;
        --clearFrom;
    }
    std::memset(m_light.data() + layer * static_cast<std::size_t>(clearFrom), kOpenSky.bits,
                layer * static_cast<std::size_t>(sy - clearFrom));
    // Below that, layer by layer from the top: `still` (0xFF or 0 a column) says whether a column is open so far,
    // its open voxels take the full level, and `counted` counts them, so that its lowest open voxel `open` is
    // clearFrom less that count (0: open to the bottom; sy: closed at the very top). Byte-wide and without a
    // branch, so that the compiler vectorises it; it ends at the first layer where every column is closed.
    thread_local std::vector<std::uint8_t> still, counted;
    thread_local std::vector<int> open; // kept per thread, like the queue below: nothing allocated per relight
    still.assign(layer, 0xFF);
    counted.assign(layer, 0);
    open.assign(layer, clearFrom);
    std::uint8_t* const lightBytes = m_light.data();
    // Raw pointers: the light's byte stores may alias anything, and would make the compiler reload a vector's.
    std::uint8_t* const stillAt = still.data();
    std::uint8_t* const countedAt = counted.data();
    int* const openAt = open.data();
    const auto fold = [&] { // counts fit a byte for 255 layers
        for (std::size_t c = 0; c < layer; ++c) openAt[c] -= countedAt[c];
        std::memset(countedAt, 0, layer);
    };
    int sinceFold = 0;
    for (int y = clearFrom - 1; y >= 0; --y) {
        const unsigned char* row = bytes + layer * static_cast<std::size_t>(y);
        std::uint8_t* lit = lightBytes + layer * static_cast<std::size_t>(y);
        std::uint8_t any = 0;
        for (std::size_t c = 0; c < layer; ++c) {
            // Light falls freely (opacity 0) through air and through the values no block has (read as air) alone
            // (Light.OnlyAirLetsSunlightFallFreely): compares the compiler vectorises, not a table look-up.
            const unsigned char b = row[c];
            const auto clear = static_cast<std::uint8_t>(0u - static_cast<unsigned>((b == 0) | (b >= kBlockTypeCount)));
            const auto s = static_cast<std::uint8_t>(stillAt[c] & clear);
            stillAt[c] = s;
            lit[c] = static_cast<std::uint8_t>(s & kOpenSky.bits);
            countedAt[c] = static_cast<std::uint8_t>(countedAt[c] - s); // s is 0xFF: one more
            any |= s;
        }
        if (++sinceFold == 255) {
            fold();
            sinceFold = 0;
        }
        if (any == 0) break;
    }
    fold();
    thread_local std::vector<Node> queue;
    queue.clear();
    const auto node = [&](std::size_t c, int y) {
        const auto x = static_cast<std::uint16_t>(c % static_cast<std::size_t>(sx));
        const auto z = static_cast<std::uint16_t>(c / static_cast<std::size_t>(sx));
        return Node{static_cast<std::uint32_t>(c + layer * static_cast<std::size_t>(y)), x,
                    static_cast<std::uint16_t>(y), z};
    };
    // A top block that is not clear (leaves at the top of the box) takes the sky's light through itself.
    const std::size_t top = layer * static_cast<std::size_t>(sy - 1);
    for (std::size_t c = 0; c < layer; ++c) {
        if (open[c] != sy) continue;
        const int level = kMaxLight - cost(LightChannel::Sun, m_blocks[top + c], {0, -1, 0}, kMaxLight);
        if (level > 0) {
            set(LightChannel::Sun, top + c, level);
            queue.push_back(node(c, sy - 1));
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
            for (int y = low; y <= std::min(high, sy - 1); ++y) queue.push_back(node(column(x, z), y));
        }
    }
    std::size_t visited = spreadNodes(LightChannel::Sun, bytes, lightBytes, m_size, queue);
    // Block light: from the emitters alone, found by memchr (most boxes hold none).
    for (const unsigned char value : kLight.emitters) {
        const unsigned char* at = bytes;
        const unsigned char* const end = bytes + m_blocks.size();
        while ((at = static_cast<const unsigned char*>(std::memchr(at, value, static_cast<std::size_t>(end - at))))) {
            const auto i = static_cast<std::size_t>(at - bytes);
            set(LightChannel::Block, i, emission(LightChannel::Block, m_blocks[i]));
            const std::size_t y = i / layer, c = i - y * layer;
            queue.push_back(node(c, static_cast<int>(y)));
            ++at;
        }
    }
    return visited + spreadNodes(LightChannel::Block, bytes, lightBytes, m_size, queue);
}

std::size_t LightField::setBlock(glm::ivec3 p, BlockType t) {
    if (!contains(p)) return 0;
    const std::size_t i = index(p);
    m_blocks[i] = t;
    const glm::ivec3 l = p - m_origin;
    const Node start{static_cast<std::uint32_t>(i), static_cast<std::uint16_t>(l.x), static_cast<std::uint16_t>(l.y),
                     static_cast<std::uint16_t>(l.z)};
    const auto* blocks = reinterpret_cast<const unsigned char*>(m_blocks.data());
    return repairFrom<LightChannel::Sun>(blocks, m_light.data(), m_size, start) +
           repairFrom<LightChannel::Block>(blocks, m_light.data(), m_size, start);
}

} // namespace world
