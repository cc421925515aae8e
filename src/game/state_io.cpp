#include "game/state_io.h"

#include <cstdio>
#include <type_traits>

#include "core/hash.h"
#include "game/state_fields.h"

namespace game {

namespace {

// The order of the whole state: the world's values, the player, the sets with their slots, the balls, which
// ball is carried, the edits. Both the hash and the dump walk it; the field lists are game/state_fields.h.
template <class V>
void visitGame(V& v, const GameState& s, bool asPutDown) {
    const StateMeta meta = metaOf(s);
    visitMeta(v, meta);
    v.object("player", [&] { visitPlayer(v, s.player); });
    v.list("pendulums", s.pendulumSets.size(), [&](std::size_t i) {
        const PendulumSetRecord r = recordOf(s.pendulumSets[i]);
        visitPendulumSet(v, r);
        v.list("slots", kPendulumSlots, [&](std::size_t k) { visitPendulumSlot(v, r, k); });
    });
    v.list("hair_balls", s.hairBalls.size(), [&](std::size_t i) {
        const HairBallRecord r = recordOf(s.hairBalls[i]);
        visitHairBall(v, r, s.hairBalls[i].solver());
    });
    const bool carried = s.carriedBall.has_value() && !asPutDown;
    v.value("carried", carried);
    v.value("carried_ball", static_cast<std::uint64_t>(carried ? *s.carriedBall : 0));
    v.edits("edits", s.world.edits());
}

struct HashVisitor {
    core::Hasher& h;
    template <class T>
    void value(const char* /*name*/, const T& x) {
        h.add(x);
    }
    template <class T>
    void vec(const char* /*name*/, const T& x, Columns /*columns*/) {
        h.add(x.x), h.add(x.y), h.add(x.z);
    }
    void hotbar(const char* /*name*/, const std::array<Item, kHotbarSize>& items) {
        for (const Item& item : items) h.add(item.kind), h.add(item.block);
    }
    void hair(const char* /*name*/, const physics::HairSolver& solver, int /*strands*/, int /*nodes*/) {
        h.add(solver.hashState());
    }
    template <class F>
    void object(const char* /*name*/, F&& f) {
        f();
    }
    template <class F>
    void list(const char* /*name*/, std::size_t n, F&& f) {
        h.add(static_cast<std::uint64_t>(n));
        for (std::size_t i = 0; i < n; ++i) f(i);
    }
    void edits(const char* /*name*/, const std::vector<world::BlockEdit>& edits) {
        h.add(static_cast<std::uint64_t>(edits.size()));
        for (const auto& e : edits) h.add(e.pos.x), h.add(e.pos.y), h.add(e.pos.z), h.add(e.block);
    }
};

// Numbers as numbers, enums by name, vectors and quaternions as arrays; the hair's node arrays are left out
// (a ball's `hair_hash` stands for them).
struct DumpVisitor {
    nlohmann::json* out;
    template <class T>
    static nlohmann::json json(const T& x) {
        if constexpr (std::is_enum_v<T>) {
            return std::string(enumName(x));
        } else if constexpr (std::is_arithmetic_v<T>) {
            return x;
        } else {
            nlohmann::json a = nlohmann::json::array();
            for (decltype(T::length()) i = 0; i < T::length(); ++i) a.push_back(x[i]);
            return a;
        }
    }
    template <class T>
    void value(const char* name, const T& x) {
        (*out)[name] = json(x);
    }
    template <class T>
    void vec(const char* name, const T& x, Columns /*columns*/) {
        (*out)[name] = json(x);
    }
    void nodes(const char* /*name*/, const std::vector<float>& /*array*/) {}
    void hotbar(const char* name, const std::array<Item, kHotbarSize>& items) {
        nlohmann::json a = nlohmann::json::array();
        for (const Item& item : items) a.push_back(std::string(itemName(item)));
        (*out)[name] = a;
    }
    void hair(const char* name, const physics::HairSolver& solver, int /*strands*/, int /*nodes*/) {
        nlohmann::json j = nlohmann::json::object();
        DumpVisitor inner{&j};
        const physics::HairSolverState state = solver.state();
        physics::visitHairState(state, inner);
        (*out)[name] = j;
    }
    template <class F>
    void object(const char* name, F&& f) {
        nlohmann::json* parent = out;
        out = &(*parent)[name];
        *out = nlohmann::json::object();
        f();
        out = parent;
    }
    template <class F>
    void list(const char* name, std::size_t n, F&& f) {
        nlohmann::json* parent = out;
        (*parent)[name] = nlohmann::json::array();
        for (std::size_t i = 0; i < n; ++i) {
            out = &(*parent)[name].emplace_back(nlohmann::json::object());
            f(i);
        }
        out = parent;
    }
    void edits(const char* name, const std::vector<world::BlockEdit>& edits) {
        nlohmann::json a = nlohmann::json::array();
        for (const auto& e : edits)
            a.push_back({{"pos", {e.pos.x, e.pos.y, e.pos.z}}, {"block", std::string(world::blockInfo(e.block).name)}});
        (*out)[name] = a;
    }
};

} // namespace

std::uint64_t stateHash(const GameState& s, bool asPutDown) {
    core::Hasher h;
    HashVisitor v{h};
    visitGame(v, s, asPutDown);
    return h.value();
}

std::string hashToHex(std::uint64_t hash) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
    return buf;
}

nlohmann::json dumpState(const GameState& s) {
    nlohmann::json j = nlohmann::json::object();
    DumpVisitor v{&j};
    visitGame(v, s, /*asPutDown=*/false);
    // Derived values beside the state, for people and checks: none of them is state.
    j["state_hash"] = hashToHex(stateHash(s));
    j["player"]["selected_block"] = std::string(itemName(s.player.selectedItem()));
    for (std::size_t i = 0; i < s.pendulumSets.size(); ++i) {
        const PendulumSet& set = s.pendulumSets[i];
        nlohmann::json& out = j["pendulums"][i];
        out["time"] = set.time();
        for (int k = 0; k < kPendulumSlots; ++k) {
            nlohmann::json& slot = out["slots"][static_cast<std::size_t>(k)];
            slot["compass"] = std::string(compassName(k));
            slot["energy"] = physics::energy(set.params(), set.slot(k).state());
        }
    }
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        const HairBall& ball = s.hairBalls[i];
        nlohmann::json& out = j["hair_balls"][i];
        out["carried"] = s.carriedBall == i;
        out["max_segment_error"] = ball.lastStats().maxSegmentError;
        out["hair_hash"] = hashToHex(ball.solver().hashState());
    }
    return j;
}

} // namespace game
