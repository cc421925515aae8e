// What save/world_store.h offers besides the database: the hair blob (encodeHairState, decodeHairState),
// takeSnapshot and restore, and removeWorldFiles. The WorldStore itself is in four units sharing
// store_internal.h: world_schema.cpp (the tables and their migrations), record_checks.cpp (what refuses a
// record), world_load.cpp (open() and load()) and world_save.cpp (save() and toImage()).
#include "save/world_store.h"

#include <bit>
#include <cstring>
#include <type_traits>

#include "game/state_io.h"

namespace save {

namespace {

// The hair blob: "MCH2", little-endian u32 strands and u32 nodes per strand, then physics::visitHairState's
// fields in its order: an int as i32, a float as f32, a bool as one byte 0 or 1, a u64, a vector or quaternion
// as its f32 components in glm's order, a node array as strands x nodes f32 (node-major). ("MCH1", the layout of
// the first schema 4 builds, had a pad byte after the flags; its hair starts anew.)
constexpr unsigned char kHairMagic[4] = {'M', 'C', 'H', '2'};
static_assert(std::endian::native == std::endian::little, "the hair blob is written in the machine's byte order");

template <typename T>
void put(std::vector<unsigned char>& out, T v) {
    // resize and copy rather than insert from a pointer: GCC 12 at -O3 warns falsely (-Warray-bounds) on the
    // insert once encodeHairState inlines it.
    const std::size_t at = out.size();
    out.resize(at + sizeof v);
    std::memcpy(out.data() + at, &v, sizeof v);
}

// Reads fixed-size values off the front of a blob; throws std::invalid_argument when it runs out.
struct BlobReader {
    const unsigned char* p;
    std::size_t left;
    template <typename T>
    T get(const char* what) {
        if (left < sizeof(T)) throw std::invalid_argument(std::string("hair_state is cut short at ") + what);
        T v;
        std::memcpy(&v, p, sizeof v);
        p += sizeof v;
        left -= sizeof v;
        return v;
    }
};

struct HairBlobWriter {
    std::vector<unsigned char>& out;
    template <typename T>
    void value(const char* /*name*/, const T& x) {
        if constexpr (std::is_same_v<T, bool>) {
            put(out, static_cast<std::uint8_t>(x ? 1 : 0));
        } else if constexpr (std::is_arithmetic_v<T>) {
            put(out, x);
        } else {
            for (decltype(T::length()) i = 0; i < T::length(); ++i) put(out, x[i]);
        }
    }
    void nodes(const char* /*name*/, const std::vector<float>& a) {
        const auto* p = reinterpret_cast<const unsigned char*>(a.data());
        out.insert(out.end(), p, p + a.size() * sizeof(float));
    }
};

struct HairBlobReader {
    BlobReader& r;
    std::size_t count; // nodes of the ball
    template <typename T>
    void value(const char* name, T& x) {
        if constexpr (std::is_same_v<T, bool>) {
            const auto b = r.get<std::uint8_t>(name);
            if (b > 1) throw std::invalid_argument(std::string("hair_state's ") + name + " is neither 0 nor 1");
            x = b != 0;
        } else if constexpr (std::is_arithmetic_v<T>) {
            x = r.get<T>(name);
        } else {
            for (decltype(T::length()) i = 0; i < T::length(); ++i) x[i] = r.get<float>(name);
        }
    }
    void nodes(const char* name, std::vector<float>& a) {
        if (r.left < count * sizeof(float))
            throw std::invalid_argument(std::string("hair_state is cut short in node array ") + name + " (" +
                                        std::to_string(r.left) + " bytes left of " +
                                        std::to_string(count * sizeof(float)) + ")");
        a.resize(count);
        std::memcpy(a.data(), r.p, count * sizeof(float));
        r.p += count * sizeof(float);
        r.left -= count * sizeof(float);
    }
};

} // namespace

std::vector<unsigned char> encodeHairState(const physics::HairSolverState& s, int strands, int nodesPerStrand) {
    std::vector<unsigned char> out(kHairMagic, kHairMagic + 4);
    put(out, static_cast<std::uint32_t>(strands));
    put(out, static_cast<std::uint32_t>(nodesPerStrand));
    HairBlobWriter w{out};
    physics::visitHairState(s, w);
    return out;
}

physics::HairSolverState decodeHairState(std::span<const unsigned char> blob, int strands, int nodesPerStrand) {
    BlobReader r{blob.data(), blob.size()};
    unsigned char magic[4];
    for (unsigned char& m : magic) m = r.get<unsigned char>("its tag");
    if (std::memcmp(magic, "MCH1", 4) == 0)
        throw std::invalid_argument("hair_state is of the first schema 4 builds' layout (MCH1)");
    if (std::memcmp(magic, kHairMagic, 4) != 0)
        throw std::invalid_argument("hair_state is not a hair blob (no MCH2 tag)");
    const auto savedStrands = r.get<std::uint32_t>("strands"), savedNodes = r.get<std::uint32_t>("nodes");
    if (savedStrands != static_cast<std::uint32_t>(strands) || savedNodes != static_cast<std::uint32_t>(nodesPerStrand))
        throw std::invalid_argument("hair_state is of " + std::to_string(savedStrands) + " x " +
                                    std::to_string(savedNodes) + " nodes, the ball has " + std::to_string(strands) +
                                    " x " + std::to_string(nodesPerStrand));
    physics::HairSolverState s;
    HairBlobReader fields{r, static_cast<std::size_t>(strands) * static_cast<std::size_t>(nodesPerStrand)};
    physics::visitHairState(s, fields);
    if (r.left != 0) throw std::invalid_argument("hair_state has " + std::to_string(r.left) + " bytes past its nodes");
    return s;
}

// ---- snapshots -------------------------------------------------------------------------------------

Snapshot takeSnapshot(const game::GameState& state) {
    Snapshot s;
    s.terrain = state.world.terrain();
    s.tick = state.tick;
    s.paused = state.paused;
    s.day = state.day;
    s.player = state.player;
    s.edits = state.world.edits();
    s.pendulumSets.reserve(state.pendulumSets.size());
    for (const auto& set : state.pendulumSets) {
        game::PendulumSet::Internals in = set.internals();
        for (auto& slot : in.slots) slot.counts.reset(); // not saved: a loaded set counts its cost afresh
        s.pendulumSets.push_back({set.base(), set.def(), in});
    }
    s.hairBalls.reserve(state.hairBalls.size());
    for (const auto& ball : state.hairBalls)
        s.hairBalls.push_back({ball.centre(), ball.spinAngle(), ball.def(), ball.solver().state()});
    // A carried ball is put down where it is: the state that loads is not carrying, so hash it that way
    // (WorldFile.PauseRoundTripsAndACarriedBallIsPutDown checks it against a real reload).
    s.stateHash = game::stateHash(state, /*asPutDown=*/true);
    return s;
}

game::GameState restore(const Snapshot& snap) {
    game::GameDef def;
    def.terrain = snap.terrain;
    def.demoObjects = false;
    game::GameState state(def);
    state.tick = snap.tick;
    state.paused = snap.paused;
    state.day = snap.day;
    if (!snap.resetPlayer) state.player = snap.player; // else the new state's player, at the spawn point
    state.previousPlayer = state.player;
    for (const auto& e : snap.edits) state.world.set(e.pos, e.block);
    state.pendulumSets.reserve(snap.pendulumSets.size());
    for (const auto& r : snap.pendulumSets) {
        state.pendulumSets.emplace_back(r.base, r.def);
        state.pendulumSets.back().restore(r.internals);
    }
    state.hairBalls.reserve(snap.hairBalls.size());
    for (const auto& r : snap.hairBalls) {
        state.hairBalls.emplace_back(r.centre, r.def);
        if (r.spin != 0.0f) state.hairBalls.back().setSpin(r.spin);
        if (r.hair) state.hairBalls.back().restoreHair(*r.hair);
    }
    return state;
}

void removeWorldFiles(const std::filesystem::path& file, std::error_code& ec) {
    std::filesystem::remove(file, ec);
    for (const char* suffix : {"-journal", "-wal", "-shm"}) {
        std::error_code sidecar;
        std::filesystem::remove(file.string() + suffix, sidecar);
        if (sidecar && !ec) ec = sidecar;
    }
}

} // namespace save
