#include "game/state_io.h"

#include <cstdio>

#include "core/hash.h"

namespace game {

namespace {
void hashVec(core::Hasher& h, const glm::vec3& v) {
    h.add(v.x);
    h.add(v.y);
    h.add(v.z);
}
nlohmann::json vecJson(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }
} // namespace

std::uint64_t stateHash(const GameState& s, bool asPutDown) {
    core::Hasher h;
    h.add(s.tick);
    h.add(s.world.terrain().seed);
    h.add(s.world.terrain().kind);
    const Player& p = s.player;
    hashVec(h, p.position);
    hashVec(h, p.velocity);
    h.add(p.yaw);
    h.add(p.pitch);
    h.add(p.onGround);
    h.add(p.flying);
    h.add(p.selectedSlot);
    for (const auto& item : p.hotbar) {
        h.add(item.kind);
        h.add(item.block);
    }
    h.add(s.paused);
    h.add(static_cast<std::uint64_t>(s.pendulumSets.size()));
    for (const auto& set : s.pendulumSets) {
        h.add(set.base().x);
        h.add(set.base().y);
        h.add(set.base().z);
        const PendulumSetDef& d = set.def();
        h.add(d.releaseDegrees);
        h.add(d.length);
        h.add(d.gravity);
        h.add(d.stepMultiplier);
        h.add(set.released());
        h.add(set.time());
        // Everything the next step reads: the drawn states of the last tick, the two-step method's history,
        // dopri5's next trial step, the time's compensation, the cartesian position, the closed form's start.
        const PendulumSet::Internals in = set.internals();
        h.add(in.previousTime);
        for (int i = 0; i < kPendulumSlots; ++i) {
            const auto k = static_cast<std::size_t>(i);
            h.add(d.methods[k]);
            h.add(set.slot(i).state().theta);
            h.add(set.slot(i).state().omega);
            h.add(set.diverged(i));
            h.add(in.previous[k].theta);
            h.add(in.previous[k].omega);
            const physics::Pendulum::Internals& p = in.slots[k];
            for (const double v : {p.time, p.timeCarry, p.previous.theta, p.previous.omega, p.lastStep, p.x, p.y,
                                   p.sinTheta, p.exactInitial.theta, p.exactInitial.omega})
                h.add(v);
        }
    }
    h.add(static_cast<std::uint64_t>(s.hairBalls.size()));
    for (const auto& ball : s.hairBalls) {
        hashVec(h, ball.centre());
        h.add(ball.spinAngle());
        const HairBallDef& d = ball.def();
        h.add(d.radius);
        hashVec(h, d.colour);
        h.add(d.spinRate);
        h.add(d.hair.strands);
        h.add(d.hair.nodesPerStrand);
        h.add(d.hair.strandLength);
        h.add(d.hair.dampingPerSecond);
        h.add(d.hair.iterations);
        h.add(d.hair.substeps);
        h.add(d.hair.patchHalfAngle);
        h.add(d.hair.seed);
        h.add(d.hair.method);
        h.add(d.hair.maxSubstepSeconds);
        h.add(d.hair.sleepSpeed);
        h.add(d.hair.sleepDelay);
        h.add(d.hair.velocityCorrection);
        h.add(d.hair.gravity);
        h.add(ball.solver().hashState()); // every node and everything the solver carries to its next step
    }
    const bool carried = s.carriedBall.has_value() && !asPutDown;
    h.add(carried);
    h.add(static_cast<std::uint64_t>(carried ? *s.carriedBall : 0));
    const auto edits = s.world.edits();
    h.add(static_cast<std::uint64_t>(edits.size()));
    for (const auto& e : edits) {
        h.add(e.pos.x);
        h.add(e.pos.y);
        h.add(e.pos.z);
        h.add(e.block);
    }
    return h.value();
}

std::string hashToHex(std::uint64_t hash) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
    return buf;
}

nlohmann::json dumpState(const GameState& s) {
    using nlohmann::json;
    const Player& p = s.player;
    json hotbar = json::array();
    for (const auto& item : p.hotbar) hotbar.push_back(std::string(itemName(item)));
    json pendulums = json::array();
    for (const auto& set : s.pendulumSets) {
        const physics::PendulumParams params = set.params();
        json slots = json::array();
        for (int i = 0; i < kPendulumSlots; ++i) {
            const physics::PendulumState st = set.slot(i).state();
            slots.push_back(
                {{"compass", std::string(compassName(i))},
                 {"method", std::string(physics::methodName(set.def().methods[static_cast<std::size_t>(i)]))},
                 {"theta", st.theta},
                 {"omega", st.omega},
                 {"energy", physics::energy(params, st)},
                 {"diverged", set.diverged(i)}});
        }
        pendulums.push_back({{"position", {set.base().x, set.base().y, set.base().z}},
                             {"released", set.released()},
                             {"time", set.time()},
                             {"release_degrees", set.def().releaseDegrees},
                             {"length", set.def().length},
                             {"step_multiplier", set.def().stepMultiplier},
                             {"slots", slots}});
    }
    json hairBalls = json::array();
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        const HairBall& ball = s.hairBalls[i];
        const HairBallDef& d = ball.def();
        hairBalls.push_back({{"position", vecJson(ball.centre())},
                             {"radius", d.radius},
                             {"colour", vecJson(d.colour)},
                             {"damping", d.hair.dampingPerSecond},
                             {"spin_rate", d.spinRate},
                             {"strands", d.hair.strands},
                             {"active_strands", ball.solver().activeStrands()},
                             {"nodes", d.hair.nodesPerStrand},
                             {"strand_length", d.hair.strandLength},
                             {"sleeping", ball.solver().sleeping()},
                             {"carried", s.carriedBall == i},
                             {"solver", std::string(physics::hairMethodName(d.hair.method))},
                             {"iterations", d.hair.iterations},
                             {"substeps", d.hair.substeps},
                             {"max_segment_error", ball.lastStats().maxSegmentError},
                             {"hair_hash", hashToHex(ball.solver().hashState())}});
    }
    json edits = json::array();
    for (const auto& e : s.world.edits()) {
        edits.push_back({{"pos", {e.pos.x, e.pos.y, e.pos.z}}, {"block", std::string(world::blockInfo(e.block).name)}});
    }
    return {
        {"tick", s.tick},
        {"state_hash", hashToHex(stateHash(s))},
        {"seed", s.world.terrain().seed},
        {"terrain", std::string(world::terrainName(s.world.terrain().kind))},
        {"paused", s.paused},
        {"player",
         {{"position", vecJson(p.position)},
          {"velocity", vecJson(p.velocity)},
          {"yaw", p.yaw},
          {"pitch", p.pitch},
          {"on_ground", p.onGround},
          {"flying", p.flying},
          {"selected_slot", p.selectedSlot},
          {"selected_block", std::string(itemName(p.selectedItem()))},
          {"hotbar", hotbar}}},
        {"edits", edits},
        {"pendulums", pendulums},
        {"hair_balls", hairBalls},
    };
}

} // namespace game
