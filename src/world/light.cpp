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
    std::array<std::uint8_t, 256> opacity{};
    std::array<std::uint8_t, 256> loss{};      // 1 + opacity: what light loses entering the block (but see sunCost())
    std::array<std::uint32_t, 256> emission{}; // the block's light colour as three lanes (Lanes, below)
    std::vector<unsigned char> emitters;       // the block values that emit, to look for with memchr
    LightProperties();
};
int opacityOf(BlockType t);

// What sunlight loses from n into v, going by `step` (v = n + step).
int sunCost(BlockType into, glm::ivec3 step, int level) {
    const int opacity = opacityOf(into);
    if (step.y == -1 && level == kMaxLight && opacity == 0) return 0;
    return 1 + opacity;
}

// Sunlight's four bits in a light word (world/light_level.h).
struct SunBits {
    static int get(std::uint16_t b) { return b >> LightLevel::kSunShift; }
    static std::uint16_t with(std::uint16_t b, int level) {
        return static_cast<std::uint16_t>((b & LightLevel::kColourBits) | static_cast<unsigned>(level)
                                                                              << LightLevel::kSunShift);
    }
};

// The three colour channels of a light word spread into the low seven bits of three bytes of a 32-bit word (red,
// green, blue from the high byte down), so that one subtraction or comparison works on all three at once without
// a borrow crossing from one channel into the next: each byte is a channel's level with bit 7 free as a guard.
namespace Lanes {
constexpr std::uint32_t kOnes = 0x010101u, kGuard = 0x808080u;
inline std::uint32_t of(std::uint16_t b) {
    const std::uint32_t c = b & LightLevel::kColourBits;
    return (c & 0xFu) | (c & 0xF0u) << 4 | (c & 0xF00u) << 8;
}
inline std::uint16_t colourBits(std::uint32_t lanes) {
    return static_cast<std::uint16_t>((lanes & 0xFu) | (lanes >> 4 & 0xF0u) | (lanes >> 8 & 0xF00u));
}
inline std::uint16_t with(std::uint16_t b, std::uint32_t lanes) {
    return static_cast<std::uint16_t>((b & LightLevel::kSunBits) | colourBits(lanes));
}
// 0xFF in each byte whose guard bit is set in `guards`, 0 elsewhere.
inline std::uint32_t byteMask(std::uint32_t guards) { return (guards >> 7) * 0xFFu; }
// Each channel less `loss` (1..255), at least 0.
inline std::uint32_t less(std::uint32_t lanes, int loss) {
    if (loss > kMaxLight) return 0;
    const std::uint32_t t = (lanes | kGuard) - static_cast<std::uint32_t>(loss) * kOnes; // guard kept where >= loss
    return t & ~kGuard & byteMask(t & kGuard);
}
// The guard bit of each byte where a's channel is at least b's.
inline std::uint32_t atLeast(std::uint32_t a, std::uint32_t b) { return ((a | kGuard) - b) & kGuard; }
inline std::uint32_t max(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t m = byteMask(atLeast(a, b));
    return (a & m) | (b & ~m);
}
// The guard bit of each byte whose channel is above 0 (a level is at most 15: adding 127 never carries).
inline std::uint32_t nonZero(std::uint32_t a) { return (a + 0x7F7F7Fu) & kGuard; }
// Whether some channel is above 1: what a voxel needs to give light to a neighbour (every step costs a level).
inline bool canGive(std::uint32_t a) { return (a & ~kOnes) != 0; }
} // namespace Lanes

LightProperties::LightProperties() {
    for (int i = 0; i < 256; ++i) {
        const BlockInfo& info = blockInfo(static_cast<BlockType>(i));
        opacity[static_cast<std::size_t>(i)] = info.lightOpacity;
        loss[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::min(1 + info.lightOpacity, 255));
        const LightColour e = info.emission;
        emission[static_cast<std::size_t>(i)] = Lanes::of(LightLevel::of(0, e.red, e.green, e.blue).bits);
        if (e.any()) emitters.push_back(static_cast<unsigned char>(i));
    }
}
const LightProperties kLight;
int opacityOf(BlockType t) { return kLight.opacity[static_cast<std::uint8_t>(t)]; }

// A voxel waiting in a spreading queue: its index and its coordinates in the box, so that which neighbours
// exist is known without dividing the index (two divisions a voxel were a fifth of a relight).
struct Node {
    std::uint32_t i;
    std::uint16_t x, y, z;
};

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

// The two passes light is repaired and spread in: sunlight alone, and the three colour channels together.
enum class Pass { Sun, Colour };

// The spreading pass P over a box of `size` (blocks and light in LightField::index order): every voxel in
// `queue` passes its levels on to its neighbours under the rule (light.h), and every neighbour it raises
// spreads in turn. Returns the voxels taken from the queue, which it leaves empty.
template <Pass P>
std::size_t spreadFrom(const unsigned char* blocks, std::uint16_t* light, glm::ivec3 size, std::vector<Node>& queue) {
    std::size_t head = 0;
    for (; head < queue.size(); ++head) {
        const Node n = queue[head];
        if constexpr (P == Pass::Sun) {
            const int level = SunBits::get(light[n.i]);
            if (level <= 1) continue; // nothing to give: every neighbour costs at least a level (but falling sunlight)
            forEachNeighbour(n, size, [&](Node m, int k) {
                int loss = kLight.loss[blocks[m.i]];
                if (k == 3 && level == kMaxLight && loss == 1) loss = 0; // falling straight down through air
                const int to = level - loss;
                if (to > SunBits::get(light[m.i])) {
                    light[m.i] = SunBits::with(light[m.i], to);
                    queue.push_back(m);
                }
            });
        } else {
            const std::uint32_t lanes = Lanes::of(light[n.i]);
            if (!Lanes::canGive(lanes)) continue;
            forEachNeighbour(n, size, [&](Node m, int) {
                const std::uint32_t to = Lanes::less(lanes, kLight.loss[blocks[m.i]]);
                const std::uint32_t was = Lanes::of(light[m.i]);
                const std::uint32_t now = Lanes::max(to, was);
                if (now != was) {
                    light[m.i] = Lanes::with(light[m.i], now);
                    queue.push_back(m);
                }
            });
        }
    }
    queue.clear();
    return head;
}

// What pass P's channels of voxel v get from its neighbours and itself under the rule (light.h), the sky above
// the box's top layer included: a sunlight level, or the colour channels' lanes.
template <Pass P>
std::uint32_t levelFromNeighbours(const unsigned char* blocks, const std::uint16_t* light, glm::ivec3 size, Node v) {
    const int loss = kLight.loss[blocks[v.i]];
    if constexpr (P == Pass::Sun) {
        int best = 0;
        const auto from = [&](int level, bool fromAbove) {
            if (level <= 0) return;
            // Sunlight falling straight down at full level into a clear block keeps its level.
            const bool falls = fromAbove && level == kMaxLight && loss == 1;
            best = std::max(best, falls ? level : level - loss);
        };
        forEachNeighbour(v, size, [&](Node m, int k) { from(SunBits::get(light[m.i]), k == 2); });
        if (v.y + 1 == size.y) from(kMaxLight, true); // the sky above the box
        return static_cast<std::uint32_t>(std::max(best, 0));
    } else {
        std::uint32_t best = kLight.emission[blocks[v.i]];
        forEachNeighbour(v, size,
                         [&](Node m, int) { best = Lanes::max(best, Lanes::less(Lanes::of(light[m.i]), loss)); });
        return best;
    }
}

// Repairs sunlight after the block at `start` changed (light.h): a removal pass clears every voxel whose light
// may have come through it (levels below the one lost, and the column under a lost full level), keeping the lit
// edge around what it clears; then every cleared voxel takes what its neighbours and itself give now, and the
// light spreads on from there and from the edge. Returns the voxels the passes visited.
std::size_t repairSun(const unsigned char* blocks, std::uint16_t* light, glm::ivec3 size, Node start) {
    const auto get = [&](std::uint32_t i) { return SunBits::get(light[i]); };
    const auto set = [&](std::uint32_t i, int level) { light[i] = SunBits::with(light[i], level); };
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
            const bool fedByIt = level < lost.level || (k == 3 && lost.level == kMaxLight && level == kMaxLight);
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
        const int level = static_cast<int>(levelFromNeighbours<Pass::Sun>(blocks, light, size, v));
        if (level > get(v.i)) {
            set(v.i, level);
            refill.push_back(v);
        }
    }
    return head + spreadFrom<Pass::Sun>(blocks, light, size, refill);
}

// The same for the three colour channels at once: a voxel's channels are cleared where they are below the
// channel lost next to them (each channel's removal as sunlight's, carried in lanes), a voxel goes to the edge
// where a channel lost beside it is at least as bright, and the cleared voxels take what reaches them per channel.
std::size_t repairColour(const unsigned char* blocks, std::uint16_t* light, glm::ivec3 size, Node start) {
    struct Lost {
        Node n;
        std::uint32_t lanes; // the levels each channel lost here (0 where it kept its light)
    };
    thread_local std::vector<Lost> removal;
    thread_local std::vector<Node> cleared, refill;
    removal.clear(), cleared.clear(), refill.clear();
    removal.push_back({start, Lanes::of(light[start.i])});
    light[start.i] = Lanes::with(light[start.i], 0);
    cleared.push_back(start);
    std::size_t head = 0;
    for (; head < removal.size(); ++head) {
        const Lost lost = removal[head];
        if (lost.lanes == 0) continue;
        forEachNeighbour(lost.n, size, [&](Node m, int) {
            const std::uint32_t lanes = Lanes::of(light[m.i]);
            if (lanes == 0) return;
            const std::uint32_t below = ~Lanes::atLeast(lanes, lost.lanes) & Lanes::kGuard;
            const std::uint32_t fed = Lanes::byteMask(below & Lanes::nonZero(lanes));
            if (fed != 0) {
                removal.push_back({m, lanes & fed});
                light[m.i] = Lanes::with(light[m.i], lanes & ~fed);
                cleared.push_back(m);
            }
            if ((Lanes::atLeast(lanes, lost.lanes) & Lanes::nonZero(lost.lanes)) != 0) refill.push_back(m);
        });
    }
    for (const Node v : cleared) {
        const std::uint32_t was = Lanes::of(light[v.i]);
        const std::uint32_t now = Lanes::max(was, levelFromNeighbours<Pass::Colour>(blocks, light, size, v));
        if (now != was) {
            light[v.i] = Lanes::with(light[v.i], now);
            refill.push_back(v);
        }
    }
    return head + spreadFrom<Pass::Colour>(blocks, light, size, refill);
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
    const LightLevel l{m_light[i]};
    switch (c) {
    case LightChannel::Sun:
        return l.sun();
    case LightChannel::Red:
        return l.red();
    case LightChannel::Green:
        return l.green();
    case LightChannel::Blue:
        return l.blue();
    }
    return 0;
}

int LightField::level(LightChannel c, glm::ivec3 p) const { return contains(p) ? get(c, index(p)) : 0; }

std::size_t LightField::relightAll() {
    std::fill(m_light.begin(), m_light.end(), std::uint16_t{0});
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
    std::fill(m_light.begin() + static_cast<std::ptrdiff_t>(layer * static_cast<std::size_t>(clearFrom)), m_light.end(),
              kOpenSky.bits);
    // Below that, layer by layer from the top: `still` (0xFF or 0 a column) says whether a column is open so far,
    // its open voxels take the full level, and `counted` counts them, so that its lowest open voxel `open` is
    // clearFrom less that count (0: open to the bottom; sy: closed at the very top). Byte-wide and without a
    // branch, so that the compiler vectorises it; it ends at the first layer where every column is closed.
    thread_local std::vector<std::uint8_t> still, counted;
    thread_local std::vector<int> open; // kept per thread, like the queue below: nothing allocated per relight
    still.assign(layer, 0xFF);
    counted.assign(layer, 0);
    open.assign(layer, clearFrom);
    std::uint16_t* const lightWords = m_light.data();
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
        std::uint16_t* lit = lightWords + layer * static_cast<std::size_t>(y);
        std::uint8_t any = 0;
        for (std::size_t c = 0; c < layer; ++c) {
            // Light falls freely (opacity 0) through air and through the values no block has (read as air) alone
            // (Light.OnlyAirLetsSunlightFallFreely): compares the compiler vectorises, not a table look-up.
            const unsigned char b = row[c];
            const auto clear = static_cast<std::uint8_t>(0u - static_cast<unsigned>((b == 0) | (b >= kBlockTypeCount)));
            const auto s = static_cast<std::uint8_t>(stillAt[c] & clear);
            stillAt[c] = s;
            lit[c] = static_cast<std::uint16_t>((s & 0xF0u) << 8); // 0xF000 (kOpenSky) where still open
            static_assert(kOpenSky.bits == 0xF000);
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
        const int level = kMaxLight - sunCost(m_blocks[top + c], {0, -1, 0}, kMaxLight);
        if (level > 0) {
            m_light[top + c] = SunBits::with(m_light[top + c], level);
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
    std::size_t visited = spreadFrom<Pass::Sun>(bytes, lightWords, m_size, queue);
    // Block light, its three channels at once: from the emitters alone, found by memchr (most boxes hold none).
    for (const unsigned char value : kLight.emitters) {
        const unsigned char* at = bytes;
        const unsigned char* const end = bytes + m_blocks.size();
        while ((at = static_cast<const unsigned char*>(std::memchr(at, value, static_cast<std::size_t>(end - at))))) {
            const auto i = static_cast<std::size_t>(at - bytes);
            m_light[i] = Lanes::with(m_light[i], kLight.emission[value]);
            const std::size_t y = i / layer, c = i - y * layer;
            queue.push_back(node(c, static_cast<int>(y)));
            ++at;
        }
    }
    return visited + spreadFrom<Pass::Colour>(bytes, lightWords, m_size, queue);
}

std::size_t LightField::setBlock(glm::ivec3 p, BlockType t) {
    if (!contains(p)) return 0;
    const std::size_t i = index(p);
    m_blocks[i] = t;
    const glm::ivec3 l = p - m_origin;
    const Node start{static_cast<std::uint32_t>(i), static_cast<std::uint16_t>(l.x), static_cast<std::uint16_t>(l.y),
                     static_cast<std::uint16_t>(l.z)};
    const auto* blocks = reinterpret_cast<const unsigned char*>(m_blocks.data());
    return repairSun(blocks, m_light.data(), m_size, start) + repairColour(blocks, m_light.data(), m_size, start);
}

} // namespace world
