#include "world/light.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/common.hpp>

#include "world/light_level.h"

namespace world {

namespace {

// The block table's light columns, by block value, without a call per voxel.
struct LightProperties {
    std::array<std::uint8_t, 256> opacity{};
    std::array<std::uint8_t, 256> loss{};      // 1 + opacity: what light loses entering the block (but see sunCost())
    std::array<std::uint32_t, 256> emission{}; // the block's light colour as three lanes (Lanes, below)
    // The block values that emit: a run of emitterCount from firstEmitter (the constructor checks it is one).
    unsigned char firstEmitter = 0, emitterCount = 0;
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
constexpr std::uint32_t spread(std::uint32_t c) { return (c & 0xFu) | (c & 0xF0u) << 4 | (c & 0xF00u) << 8; }
// of() as a look-up (16 KB): one load where the shifts and masks were five operations a neighbour.
const std::array<std::uint32_t, 4096> kSpread = [] {
    std::array<std::uint32_t, 4096> t{};
    for (std::uint32_t c = 0; c < 4096; ++c) t[c] = spread(c);
    return t;
}();
inline std::uint32_t of(std::uint16_t b) { return kSpread[b & LightLevel::kColourBits]; }

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
// The colour bits a light word's colour gives a step into air, by those bits (each channel one less, at least 0):
// one look-up a voxel spread, where the lanes took a dozen operations.
const std::array<std::uint16_t, 4096> kIntoAir = [] {
    std::array<std::uint16_t, 4096> t{};
    for (std::uint32_t c = 0; c < 4096; ++c) t[c] = colourBits(less(spread(c), 1));
    return t;
}();
} // namespace Lanes

LightProperties::LightProperties() {
    for (int i = 0; i < 256; ++i) {
        const BlockInfo& info = blockInfo(static_cast<BlockType>(i));
        opacity[static_cast<std::size_t>(i)] = info.lightOpacity;
        loss[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::min(1 + info.lightOpacity, 255));
        const LightColour e = info.emission;
        emission[static_cast<std::size_t>(i)] = Lanes::of(LightLevel::of(0, e.red, e.green, e.blue).bits);
        if (!e.any()) continue;
        if (emitterCount == 0) firstEmitter = static_cast<unsigned char>(i);
        if (i != firstEmitter + emitterCount) throw std::logic_error("light: the blocks that emit are not one run");
        ++emitterCount;
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

// The queues' allocator: a Node made without a value is left unset, so that spreadColour can make room in its
// queue without writing it first (zeroing the room cost its colour pass 8 %).
template <class T>
struct LeftUnset : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = LeftUnset<U>;
    };
    LeftUnset() = default;
    template <class U>
    explicit LeftUnset(const LeftUnset<U>&) {}
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... A>
    void construct(U* p, A&&... a) {
        ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
    }
};
using NodeQueue = std::vector<Node, LeftUnset<Node>>;

// Calls f(j, x, y, z, k) for each neighbour of n inside a box of `size`: its index and coordinates, and k its step
// (+x, -x, +y, -y, +z, -z for 0 to 5). Scalars, not a Node: a Node built in 16-bit stores and passed whole to a
// lambda the compiler does not inline is read back as a word, a store-forwarding stall a neighbour (it made a
// lamp's repair five times slower).
template <typename F>
void forEachNeighbour(Node n, glm::ivec3 size, F&& f) {
    const auto sx = static_cast<std::uint32_t>(size.x), layer = sx * static_cast<std::uint32_t>(size.z);
    const auto u16 = [](int v) { return static_cast<std::uint16_t>(v); };
    if (n.x + 1 < size.x) f(n.i + 1, u16(n.x + 1), n.y, n.z, 0);
    if (n.x > 0) f(n.i - 1, u16(n.x - 1), n.y, n.z, 1);
    if (n.y + 1 < size.y) f(n.i + layer, n.x, u16(n.y + 1), n.z, 2);
    if (n.y > 0) f(n.i - layer, n.x, u16(n.y - 1), n.z, 3);
    if (n.z + 1 < size.z) f(n.i + sx, n.x, n.y, u16(n.z + 1), 4);
    if (n.z > 0) f(n.i - sx, n.x, n.y, u16(n.z - 1), 5);
}

// On a lambda given to forEachNeighbour: inlined at each of its six calls. GCC left the colour removal's out of
// line (a call a neighbour), which cost a lamp's repair a quarter of its time.
#if defined(__GNUC__)
#define MC_NEIGHBOUR_INLINE __attribute__((always_inline))
#else
#define MC_NEIGHBOUR_INLINE
#endif

// The two passes light is repaired and spread in: sunlight alone, and the three colour channels together.
enum class Pass { Sun, Colour };

// The sunlight spreading pass over a box of `size` (blocks and light in LightField::index order): every voxel in
// `queue` passes its level on to its neighbours under the rule (light.h), and every neighbour it raises spreads in
// turn. Returns the voxels taken from the queue, which it leaves empty.
std::size_t spreadSun(const unsigned char* blocks, std::uint16_t* light, glm::ivec3 size, NodeQueue& queue) {
    std::size_t head = 0;
    for (; head < queue.size(); ++head) {
        const Node n = queue[head];
        const int level = SunBits::get(light[n.i]);
        if (level <= 1) continue; // nothing to give: every neighbour costs at least a level (but falling sunlight)
        // Neighbours +x, -x, +y, -y, +z, -z in turn; light comes to each from n.
        const auto visit = [&](bool exists, std::uint32_t j, std::uint16_t x, std::uint16_t y, std::uint16_t z,
                               bool down) {
            if (!exists) return;
            int loss = kLight.loss[blocks[j]];
            if (down && level == kMaxLight && loss == 1) loss = 0; // falling straight down through air
            const int to = level - loss;
            if (to > SunBits::get(light[j])) {
                light[j] = SunBits::with(light[j], to);
                queue.push_back({j, x, y, z});
            }
        };
        const auto sx = static_cast<std::uint32_t>(size.x), layer = sx * static_cast<std::uint32_t>(size.z);
        const std::uint16_t x = n.x, y = n.y, z = n.z;
        const auto u16 = [](int v) { return static_cast<std::uint16_t>(v); };
        visit(x + 1 < size.x, n.i + 1, u16(x + 1), y, z, false);
        visit(x > 0, n.i - 1, u16(x - 1), y, z, false);
        visit(y + 1 < size.y, n.i + layer, x, u16(y + 1), z, false);
        visit(y > 0, n.i - layer, x, u16(y - 1), z, true);
        visit(z + 1 < size.z, n.i + sx, x, y, u16(z + 1), false);
        visit(z > 0, n.i - sx, x, y, u16(z - 1), false);
    }
    queue.clear();
    return head;
}

// The same for the three colour channels together. A loop of its own, with the queue written through a pointer
// (room for six more made before each voxel), the bounds in registers and the common step first: a neighbour that
// already has at least what a step into air brings in every channel is left after one test (a test for equal light
// before it, a second branch, cost a tenth where the branch predictor was cold, as between the speed gate's
// rounds), and only a neighbour that a step into air would raise reads its block. Written so, a relight's colour
// pass took 0.78-0.80 of the time it took as a branch of one spreading template for both passes (docs/LIGHT.md,
// "Costs").
std::size_t spreadColour(const unsigned char* blocks, std::uint16_t* light, glm::ivec3 size, NodeQueue& queue) {
    const auto sx = static_cast<std::uint32_t>(size.x), layer = sx * static_cast<std::uint32_t>(size.z);
    const auto lastX = static_cast<std::uint16_t>(size.x - 1), lastY = static_cast<std::uint16_t>(size.y - 1),
               lastZ = static_cast<std::uint16_t>(size.z - 1);
    std::size_t end = queue.size(); // the queue's entries are [0, end); past it, room
    queue.resize(end + std::max<std::size_t>(end, 64));
    Node* q = queue.data();
    std::size_t head = 0;
    for (; head < end; ++head) {
        const Node n = q[head];
        const std::uint16_t ownBits = light[n.i] & LightLevel::kColourBits;
        const std::uint16_t intoAirBits = Lanes::kIntoAir[ownBits];
        if (intoAirBits == 0) continue; // nothing to give: no channel above 1
        if (queue.size() - end < 6) {   // shrunk to the entries first, so that growing copies only them
            const std::size_t room = 2 * queue.size();
            queue.resize(end);
            queue.resize(room);
            q = queue.data();
        }
        const std::uint32_t intoAir = Lanes::of(intoAirBits);
        const auto visit = [&](std::uint32_t j, std::uint16_t x, std::uint16_t y, std::uint16_t z) MC_NEIGHBOUR_INLINE {
            const std::uint16_t word = light[j], wasBits = word & LightLevel::kColourBits;
            const std::uint32_t was = Lanes::of(wasBits);
            if ((~Lanes::atLeast(was, intoAir) & Lanes::kGuard) == 0) return;
            const int loss = kLight.loss[blocks[j]];
            std::uint32_t to = intoAir;
            if (loss != 1) {
                if (loss > kMaxLight) return; // nothing gets into it
                to = Lanes::less(Lanes::of(ownBits), loss);
                if ((~Lanes::atLeast(was, to) & Lanes::kGuard) == 0) return;
            }
            light[j] = Lanes::with(word, Lanes::max(to, was));
            q[end++] = Node{j, x, y, z};
        };
        const std::uint16_t x = n.x, y = n.y, z = n.z;
        const auto u16 = [](int v) { return static_cast<std::uint16_t>(v); };
        if (x != lastX) visit(n.i + 1, u16(x + 1), y, z);
        if (x != 0) visit(n.i - 1, u16(x - 1), y, z);
        if (y != lastY) visit(n.i + layer, x, u16(y + 1), z);
        if (y != 0) visit(n.i - layer, x, u16(y - 1), z);
        if (z != lastZ) visit(n.i + sx, x, y, u16(z + 1));
        if (z != 0) visit(n.i - sx, x, y, u16(z - 1));
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
        forEachNeighbour(v, size,
                         [&](std::uint32_t j, std::uint16_t, std::uint16_t, std::uint16_t, int k)
                             MC_NEIGHBOUR_INLINE { from(SunBits::get(light[j]), k == 2); });
        if (v.y + 1 == size.y) from(kMaxLight, true); // the sky above the box
        return static_cast<std::uint32_t>(std::max(best, 0));
    } else {
        std::uint32_t best = kLight.emission[blocks[v.i]];
        if (loss > kMaxLight) return best; // nothing gets into it: its own light only
        forEachNeighbour(v, size,
                         [&](std::uint32_t j, std::uint16_t, std::uint16_t, std::uint16_t, int) MC_NEIGHBOUR_INLINE {
                             // Most neighbours of a cleared voxel were cleared too: no light, nothing to work out.
                             if ((light[j] & LightLevel::kColourBits) != 0)
                                 best = Lanes::max(best, Lanes::less(Lanes::of(light[j]), loss));
                         });
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
    thread_local NodeQueue cleared, refill;
    removal.clear(), cleared.clear(), refill.clear();
    removal.push_back({start, get(start.i)});
    set(start.i, 0);
    cleared.push_back(start);
    std::size_t head = 0;
    for (; head < removal.size(); ++head) {
        const Lost lost = removal[head];
        forEachNeighbour(
            lost.n, size,
            [&](std::uint32_t j, std::uint16_t x, std::uint16_t y, std::uint16_t z, int k) MC_NEIGHBOUR_INLINE {
                const int level = get(j);
                if (level == 0) return;
                const bool fedByIt = level < lost.level || (k == 3 && lost.level == kMaxLight && level == kMaxLight);
                if (fedByIt) {
                    removal.push_back({{j, x, y, z}, level});
                    set(j, 0);
                    cleared.push_back({j, x, y, z});
                } else {
                    refill.push_back({j, x, y, z});
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
    return head + spreadSun(blocks, light, size, refill);
}

// The same for the three colour channels at once: a voxel's channels are cleared where they are below the
// channel lost next to them (each channel's removal as sunlight's, carried in lanes), and a voxel goes to the edge
// where a channel lost beside it is at least as bright. Unlike sunlight's, nothing but the edge, the emitters and
// the changed voxel can light a cleared voxel again (block light has no sky), so those alone are refilled: an
// emitter cleared keeps its own light and spreads it, the changed voxel takes what its neighbours and itself give.
std::size_t repairColour(const unsigned char* blocks, std::uint16_t* light, glm::ivec3 size, Node start) {
    struct Lost {
        Node n;
        std::uint32_t lanes; // the levels each channel lost here (0 where it kept its light)
    };
    thread_local std::vector<Lost> removal;
    thread_local NodeQueue refill;
    removal.clear(), refill.clear();
    removal.push_back({start, Lanes::of(light[start.i])});
    light[start.i] = Lanes::with(light[start.i], 0);
    std::size_t head = 0;
    for (; head < removal.size(); ++head) {
        const Lost lost = removal[head];
        if (lost.lanes == 0) continue;
        const std::uint32_t lostChannels = Lanes::nonZero(lost.lanes);
        forEachNeighbour(lost.n, size,
                         [&](std::uint32_t j, std::uint16_t x, std::uint16_t y, std::uint16_t z, int)
                             MC_NEIGHBOUR_INLINE {
                                 const std::uint32_t lanes = Lanes::of(light[j]);
                                 if (lanes == 0) return;
                                 const std::uint32_t atLeast = Lanes::atLeast(lanes, lost.lanes);
                                 if ((atLeast & lostChannels) != 0)
                                     refill.push_back({j, x, y, z}); // lit from elsewhere: the edge
                                 const std::uint32_t fed = Lanes::byteMask(~atLeast & Lanes::nonZero(lanes));
                                 if (fed == 0) return;
                                 removal.push_back({{j, x, y, z}, lanes & fed});
                                 const std::uint32_t own = kLight.emission[blocks[j]];
                                 light[j] = Lanes::with(light[j], Lanes::max(lanes & ~fed, own));
                                 if (own != 0) refill.push_back({j, x, y, z});
                             });
    }
    const std::uint32_t was = Lanes::of(light[start.i]);
    const std::uint32_t now = Lanes::max(was, levelFromNeighbours<Pass::Colour>(blocks, light, size, start));
    if (now != was) {
        light[start.i] = Lanes::with(light[start.i], now);
        refill.push_back(start);
    }
    return head + spreadColour(blocks, light, size, refill);
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
    int written = clearFrom; // the lowest layer the pass below writes whole; under it the light starts at 0
    for (int y = clearFrom - 1; y >= 0; --y) {
        written = y;
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
    std::fill(m_light.begin(), m_light.begin() + static_cast<std::ptrdiff_t>(layer * static_cast<std::size_t>(written)),
              std::uint16_t{0});
    thread_local NodeQueue queue;
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
    std::size_t visited = spreadSun(bytes, lightWords, m_size, queue);
    // Block light, its three channels at once: from the emitters alone (most boxes hold none). Their values are one
    // run (kLight.firstEmitter, emitterCount), and none is in the open sky's layers. A 1 KiB chunk of the blocks is
    // looked through again, in 64-byte pieces, only where the least of its bytes less the run's first value (a
    // loop the compiler vectorises) is inside the run, and only such a piece byte by byte (six memchr passes, one a
    // lamp, took a sixth of a relight).
    const std::size_t count = layer * static_cast<std::size_t>(clearFrom);
    const auto seed = [&](std::size_t i) {
        m_light[i] = Lanes::with(m_light[i], kLight.emission[bytes[i]]);
        const std::size_t y = i / layer, c = i - y * layer;
        queue.push_back(node(c, static_cast<int>(y)));
    };
    const unsigned char first = kLight.firstEmitter, emitters = kLight.emitterCount;
    const auto isEmitter = [first, emitters](unsigned char b) {
        return static_cast<unsigned char>(b - first) < emitters;
    };
    const auto anyEmitter = [&](std::size_t from, std::size_t to) { // the least distance above the run's start
        unsigned char least = 0xFF;
        for (std::size_t i = from; i < to; ++i) least = std::min(least, static_cast<unsigned char>(bytes[i] - first));
        return least < emitters;
    };
    constexpr std::size_t kChunk = 1024, kPiece = 64;
    for (std::size_t from = 0; emitters > 0 && from < count; from += kChunk) {
        const std::size_t to = std::min(count, from + kChunk);
        if (!anyEmitter(from, to)) continue;
        for (std::size_t piece = from; piece < to; piece += kPiece) {
            const std::size_t pieceEnd = std::min(to, piece + kPiece);
            if (!anyEmitter(piece, pieceEnd)) continue;
            for (std::size_t i = piece; i < pieceEnd; ++i)
                if (isEmitter(bytes[i])) seed(i);
        }
    }
    return visited + spreadColour(bytes, lightWords, m_size, queue);
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
