#include "game/game_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "core/log.h"
#include "game/object_shapes.h"
#include "game/space.h"
#include "world/collision.h"

namespace game {

namespace {

// Whether the game would let a player place a set at `base`: on a solid block, its post and swings clear of
// blocks (game/space.h's placement rule; nothing else stands in a new world).
bool setFits(const world::World& w, const glm::ivec3& base) {
    if (!world::isSolid(w.get(base - glm::ivec3(0, 1, 0)))) return false;
    const auto boxes = pendulumSetBoxes(PendulumSet(base));
    return std::none_of(boxes.begin(), boxes.end(),
                        [&](const world::Aabb& box) { return world::intersectsSolid(w, box); });
}

// Where the demo's set stands: the first spot 5 to 15 m ahead with open air around its post (no trunk, leaves
// or terrace edge within 2 blocks) that also fits; else the nearest that fits 5 to 32 m ahead, straight on or
// up to 40 degrees aside; none when no spot near fits (the demo then has no set).
std::optional<glm::ivec3> demoSetPosition(const world::World& w, const Player& p) {
    const auto surface = [&](float yawOffset, float d) {
        const glm::vec3 at = p.position + glm::normalize(glm::vec3(lookDirection(p.yaw + yawOffset, 0.0f))) * d;
        const int x = static_cast<int>(std::floor(at.x)), z = static_cast<int>(std::floor(at.z));
        return glm::ivec3(x, world::surfaceHeight(w.terrain(), x, z) + 1, z);
    };
    for (float d = 5.0f; d < 16.0f; d += 1.0f) {
        const glm::ivec3 b = surface(0.0f, d);
        bool clear = !world::isSolid(w.get(b));
        for (int dy = 1; dy < 4 && clear; ++dy) {
            for (int dx = -2; dx <= 2 && clear; ++dx) {
                for (int dz = -2; dz <= 2 && clear; ++dz) clear = !world::isSolid(w.get(b + glm::ivec3(dx, dy, dz)));
            }
        }
        if (clear && setFits(w, b)) return b;
    }
    for (float d = 5.0f; d <= 32.0f; d += 1.0f) {
        for (const float aside : {0.0f, -20.0f, 20.0f, -40.0f, 40.0f}) {
            if (const glm::ivec3 b = surface(aside, d); setFits(w, b)) return b;
        }
    }
    return std::nullopt;
}

// Where a carried ball floats: in front of the eye, far enough that its hair clears the camera, or nearer
// where a block, a set or another ball is in the way (game/space.h); where even that is taken, it stays.
void moveCarriedBall(GameState& s) {
    HairBall& ball = s.hairBalls[*s.carriedBall];
    const float distance = 1.2f + ball.def().radius + ball.def().hair.strandLength;
    if (const auto spot = carrySpot(s, *s.carriedBall, distance)) ball.moveTo(*spot);
}

void applyPendulumCommand(GameState& s, const PendulumCommand& c) {
    if (c.set >= s.pendulumSets.size()) return;
    PendulumSet& set = s.pendulumSets[c.set];
    switch (c.op) {
    case PendulumCommand::Op::SetDef: {
        // A longer rod needs more room: refused (like any edit the physics refuses) where it would swing
        // into blocks, the player, a ball or another set.
        const PendulumSet candidate(set.base(), c.def);
        if (!setSpaceFree(s, pendulumSetBoxes(candidate), {std::nullopt, c.set}))
            throw std::invalid_argument("pendulum set: no room to swing a rod that long here");
        set.setDef(c.def);
        break;
    }
    case PendulumCommand::Op::Release:
        set.release();
        break;
    case PendulumCommand::Op::Reset:
        set.reset();
        break;
    }
}

} // namespace

GameState::GameState(const GameDef& d) : def(d), world(d.terrain), day(d.day) {
    player = spawnPlayer(world, def.player);
    previousPlayer = player;
    if (def.demoObjects) {
        // The set, released: it swings from the start. Without a spot for it the balls stand where it would.
        const std::optional<glm::ivec3> spot = demoSetPosition(world, player);
        if (spot) pendulumSets.emplace_back(*spot);
        const glm::vec3 forward = glm::normalize(glm::vec3(lookDirection(player.yaw, 0.0f)));
        const glm::ivec3 set = spot ? *spot : glm::ivec3(glm::floor(player.position + forward * 6.0f));
        // A few hair balls of different colours beside the set, one of them spinning, labelled with their solver
        // in the world: the two still ones on the left side by side, dftl (the game's default) and shake, so
        // their hair can be compared once disturbed (shake keeps swinging longer: it loses no energy to the
        // method); the spinning one on the right dftl, which keeps every length exactly under spin.
        const glm::vec3 ahead = glm::normalize(lookDirection(player.yaw, 0.0f));
        const glm::vec3 side(-ahead.z, 0.0f, ahead.x);
        const glm::vec3 base = glm::vec3(set) + glm::vec3(0.5f, 0.0f, 0.5f);
        const struct {
            float across, height;
            glm::vec3 colour;
            float spin;
            physics::HairMethod solver;
        } balls[] = {{-3.0f, 1.6f, {0.85f, 0.55f, 0.25f}, 0.0f, physics::HairMethod::Dftl},
                     {3.0f, 1.6f, {0.35f, 0.45f, 0.95f}, 1.5f, physics::HairMethod::Dftl},
                     {-5.5f, 2.2f, {0.9f, 0.3f, 0.5f}, 0.0f, physics::HairMethod::Shake}};
        for (const auto& b : balls) {
            HairBallDef hd = def.ballDef;
            hd.hair = physics::hairMethodDefaults(b.solver, hd.hair);
            hd.colour = b.colour;
            hd.spinRate = b.spin;
            const glm::vec3 at = base + side * b.across;
            const int ground = world::surfaceHeight(world.terrain(), static_cast<int>(std::floor(at.x)),
                                                    static_cast<int>(std::floor(at.z)));
            // Its height over the ground under its centre, raised until it stands where a player could put a
            // ball (a higher neighbour, a trunk or leaves can reach into that sphere; a loaded world is held to
            // the same check).
            glm::vec3 centre(at.x, static_cast<float>(ground + 1) + b.height, at.z);
            for (int k = 0; k < 96 && !ballSpaceFree(*this, centre, hd.radius); ++k) centre.y += 0.25f;
            hairBalls.emplace_back(centre, hd);
        }
    }
}

Target targetOf(const GameState& s) {
    Target t;
    const glm::vec3 eye = eyePosition(s.player, s.def.player);
    const glm::vec3 dir = lookDirection(s.player.yaw, s.player.pitch);
    if (const auto hit = world::raycast(s.world, eye, dir, s.def.player.reach)) {
        t.kind = Target::Kind::Block;
        t.block = *hit;
        t.distance = hit->distance;
    }
    // The shapes as the game holds them now (alpha 1), the pose the click acts on; the frame draws the same
    // shapes (object_shapes.h).
    const auto consider = [&](const Shape& shape, Target::Kind kind, std::size_t index) {
        const auto h = rayShape(eye, dir, shape);
        if (h && *h <= s.def.player.reach && (t.kind == Target::Kind::None || *h < t.distance)) {
            t.kind = kind;
            t.index = index;
            t.distance = *h;
        }
    };
    std::vector<Shape> shapes;
    for (std::size_t i = 0; i < s.pendulumSets.size(); ++i) {
        shapes.clear();
        appendPendulumSetShapes(s.pendulumSets[i], 1.0, shapes);
        for (const Shape& shape : shapes) consider(shape, Target::Kind::PendulumSet, i);
    }
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        if (s.carriedBall && *s.carriedBall == i) continue;
        consider(hairBallShape(s.hairBalls[i], 1.0f), Target::Kind::HairBall, i);
    }
    return t;
}

Player spawnPlayer(const world::World& w, const PlayerDef& def) {
    Player p;
    const int x = 0, z = 0;
    int y = world::surfaceHeight(w.terrain(), x, z) + 1;
    // Trees or edits may stand on the surface: climb until the whole body is in air.
    while (y < world::kWorldHeightChunks * world::kChunkSize - 2 &&
           (world::isSolid(w.get({x, y, z})) || world::isSolid(w.get({x, y + 1, z})))) {
        ++y;
    }
    p.position = glm::vec3(x + 0.5f, static_cast<float>(y), z + 0.5f);
    p.yaw = 35.0f;
    p.pitch = -12.0f;
    p.onGround = true;
    (void)def;
    return p;
}

EditResult breakTargeted(GameState& s) {
    const Target target = targetOf(s);
    if (target.kind == Target::Kind::PendulumSet) {
        s.pendulumSets.erase(s.pendulumSets.begin() + static_cast<std::ptrdiff_t>(target.index));
        return EditResult::Done;
    }
    if (target.kind == Target::Kind::HairBall) {
        s.hairBalls.erase(s.hairBalls.begin() + static_cast<std::ptrdiff_t>(target.index));
        if (s.carriedBall && *s.carriedBall > target.index) --*s.carriedBall;
        return EditResult::Done;
    }
    const auto hit = target.kind == Target::Kind::Block ? std::optional<world::RayHit>(target.block) : std::nullopt;
    if (!hit) return EditResult::NothingTargeted;
    if (hit->block.y <= 0) return EditResult::Unbreakable; // the bottom layer keeps the world closed
    s.world.set(hit->block, world::BlockType::Air);
    // A pendulum set standing on that block breaks with it (it is removed, as when broken by hand): a set
    // never floats.
    const glm::ivec3 above = hit->block + glm::ivec3(0, 1, 0);
    std::erase_if(s.pendulumSets, [&](const PendulumSet& set) { return set.base() == above; });
    return EditResult::Done;
}

EditResult placeTargeted(GameState& s) {
    const Target target = targetOf(s);
    if (target.kind != Target::Kind::Block) return EditResult::NothingTargeted;
    const auto hit = std::optional<world::RayHit>(target.block);
    if (hit->normal == glm::ivec3(0)) return EditResult::NothingTargeted;
    const glm::ivec3 pos = hit->block + hit->normal;
    if (pos.y < 0 || pos.y >= world::kWorldHeightChunks * world::kChunkSize) return EditResult::OutOfWorld;
    // Never inside the player: compare the block's cube with the body, shrunk by a hair so that
    // standing flush against a face still allows placing there.
    const world::Aabb body = playerBox(s.player.position, s.def.player);
    const glm::vec3 lo(pos), hi = lo + glm::vec3(1.0f);
    constexpr float kSkin = 1e-3f;
    const bool overlaps = body.min.x + kSkin < hi.x && body.max.x - kSkin > lo.x && body.min.y + kSkin < hi.y &&
                          body.max.y - kSkin > lo.y && body.min.z + kSkin < hi.z && body.max.z - kSkin > lo.z;
    const Item& item = s.player.selectedItem();
    if (item.kind == ItemKind::PendulumSet) {
        // The set is an object, not a block: it stands on the targeted top face, one per spot.
        if (hit->normal != glm::ivec3(0, 1, 0)) return EditResult::NothingTargeted;
        // Only where its post and all four swings have room: no block, player, ball or other set there.
        PendulumSet set(pos); // released
        if (!setSpaceFree(s, pendulumSetBoxes(set))) return EditResult::Occupied;
        s.pendulumSets.push_back(std::move(set));
        return EditResult::Done;
    }
    if (item.kind == ItemKind::HairBall) {
        // Floats above the targeted face, far enough that its hair hangs free; never inside anything.
        const HairBallDef& def = s.def.ballDef;
        const glm::vec3 centre =
            glm::vec3(pos) + glm::vec3(0.5f) + glm::vec3(hit->normal) * (def.radius + 0.5f * def.hair.strandLength);
        if (!ballSpaceFree(s, centre, def.radius)) return EditResult::Occupied;
        s.hairBalls.emplace_back(centre, def);
        return EditResult::Done;
    }
    if (overlaps) return EditResult::WouldOverlapPlayer;
    // Not into a ball's sphere or a set's swing; hair the block covers is pushed out of it by the solver,
    // which wakes when the blocks around it change.
    if (!blockSpaceFreeOfObjects(s, pos)) return EditResult::Occupied;
    s.world.set(pos, item.block);
    return EditResult::Done;
}

int activeStrandsFor(const HairBall& ball, const glm::vec3& viewer, float detail) {
    const float d = glm::length(ball.centre() - viewer);
    const int all =
        std::max(1, static_cast<int>(static_cast<float>(ball.def().hair.strands) * std::clamp(detail, 0.0f, 1.0f)));
    return d > kHairDetailFar ? std::max(all / 4, 1) : d > kHairDetailNear ? std::max(all / 2, 1) : all;
}

void tick(GameState& s, const input::Actions& a, double dt, const TickCommands& commands) {
    ++s.tick;
    s.previousPlayer = s.player;
    for (auto& ball : s.hairBalls) ball.beginTick(); // where each ball starts the tick, before it is carried
    if (a.togglePause) s.paused = !s.paused;
    // The clock is set even while paused (it then stands at the new hour); a refused hour is dropped.
    if (commands.timeOfDay && isClockHour(*commands.timeOfDay)) s.day.hours = *commands.timeOfDay;
    for (const HotbarCommand& c : commands.hotbar) { // a slot out of range (only a hand-built command) is dropped
        if (c.slot >= 0 && c.slot < kHotbarSize && isHoldable(c.item))
            s.player.hotbar[static_cast<std::size_t>(c.slot)] = c.item;
    }
    if (s.paused) {
        for (auto& set : s.pendulumSets) set.hold(); // no step: drawing stops between two states
        return;
    }
    // A panel's edit the physics refuses (its sliders clamp, but commands are input like any other) is
    // dropped; the object keeps its old parameters and the game goes on.
    for (const auto& c : commands.pendulum) {
        try {
            applyPendulumCommand(s, c);
        } catch (const std::invalid_argument&) {}
    }
    for (const auto& c : commands.hair) {
        try {
            if (c.ball >= s.hairBalls.size()) continue;
            validateHairBallDef(c.def); // first: the space test below is only meaningful for a ball the game allows
            // A larger sphere must still fit where the ball is (game/space.h).
            HairBall& ball = s.hairBalls[c.ball];
            if (c.def.radius > ball.def().radius && !ballSpaceFree(s, ball.centre(), c.def.radius, {c.ball, {}}))
                continue;
            ball.setDef(c.def);
        } catch (const std::invalid_argument&) {}
    }
    advance(s.day, dt);

    applyLookAndSelection(s.player, a, s.def.player);
    if (a.teleport) {
        liftOutOfBlocks(s.player, s.world, s.def.player); // never left stuck inside stone
        s.previousPlayer = s.player;                      // a jump cut, not a glide across the map
    }
    if (a.pickBlock) {
        const Target target = targetOf(s);
        if (target.kind != Target::Kind::None) {
            const Item picked = target.kind == Target::Kind::Block         ? Item::ofBlock(target.block.type)
                                : target.kind == Target::Kind::PendulumSet ? Item::pendulumSet()
                                                                           : Item::hairBall();
            Player& p = s.player;
            const auto it = std::find(p.hotbar.begin(), p.hotbar.end(), picked);
            if (it != p.hotbar.end()) {
                p.selectedSlot = static_cast<int>(it - p.hotbar.begin());
            } else {
                p.hotbar[static_cast<std::size_t>(p.selectedSlot)] = picked;
            }
        }
    }
    // Edits use the view of this tick and the position before moving: what the player saw when clicking.
    if (a.breakBlock) breakTargeted(s);
    if (a.place) placeTargeted(s);
    if (a.carry) {
        if (s.carriedBall) {
            s.carriedBall.reset(); // put down where it floats now
        } else if (const Target t = targetOf(s); t.kind == Target::Kind::HairBall) {
            s.carriedBall = t.index;
        }
    }
    movePlayer(s.player, s.world, a, static_cast<float>(dt), s.def.player, playerObstacles(s));
    for (auto& set : s.pendulumSets) set.tick(dt);

    if (s.carriedBall) moveCarriedBall(s);
    // Hair: each ball against the balls in its reach only, all within the tick's budget (game/hair_budget.h).
    HairNeighbours neighbours;
    findHairNeighbours(s.hairBalls, neighbours);
    const glm::vec3 eye = eyePosition(s.player, s.def.player);
    // The hair's own clock: substeps of exactly 1/60 s whatever the tick rate (physics::hairClockSteps).
    s.tickSeconds = dt;
    const int hairSteps =
        physics::hairClockSteps(static_cast<double>(s.tick - 1) * dt, static_cast<double>(s.tick) * dt);
    const double hairLag = physics::hairClockLag(static_cast<double>(s.tick) * dt);
    const std::vector<int> strands =
        shareHairBudget(s, neighbours, eye, lookDirection(s.player.yaw, s.player.pitch), s.def.hairBudget,
                        std::max(hairSteps, 1) * physics::kHairClockSeconds);
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        const std::span<const physics::SphereCollider> others(neighbours.colliders.data() + neighbours.offsets[i],
                                                              neighbours.offsets[i + 1] - neighbours.offsets[i]);
        s.hairBalls[i].tick(dt, hairSteps, hairLag, s.world, others, strands[i]);
    }
#ifdef MINECRAPPY_CHECK_INVARIANTS
    if (const std::string broken = checkInvariants(s); !broken.empty()) {
        core::logError("invariant broken after tick %llu: %s", static_cast<unsigned long long>(s.tick), broken.c_str());
        std::abort();
    }
#endif
}

float hairDrawAlpha(const GameState& s, float alpha) {
    if (!(s.tickSeconds > 0.0) || s.tick == 0) return alpha;
    const double now = static_cast<double>(s.tick) * s.tickSeconds;
    return physics::hairClockAlpha(now, now - (1.0 - static_cast<double>(alpha)) * s.tickSeconds);
}

std::string checkInvariants(const GameState& s) {
    const auto finite3 = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    const Player& p = s.player;
    if (!finite3(p.position) || !finite3(p.velocity) || !std::isfinite(p.yaw) || !std::isfinite(p.pitch))
        return "the player's position, velocity or view is not finite";
    if (!insideBorder(p.position)) return "the player is outside the world border";
    if (!(std::abs(p.pitch) <= 89.0f) || !(p.yaw >= 0.0f && p.yaw < 360.0f)) return "the player's view is out of range";
    if (p.selectedSlot < 0 || p.selectedSlot >= kHotbarSize) return "the selected hotbar slot is out of range";
    for (const Item& item : p.hotbar)
        if (!isHoldable(item)) return "a hotbar slot holds what no slot can (air, or no block)";
    if (s.carriedBall && *s.carriedBall >= s.hairBalls.size()) return "the carried ball does not exist";
    if (std::string day = checkDayClock(s.day); !day.empty()) return day;
    for (std::size_t i = 0; i < s.pendulumSets.size(); ++i) {
        const PendulumSet& set = s.pendulumSets[i];
        if (!insideBorder(glm::vec3(set.base()))) return "pendulum set " + std::to_string(i) + " is outside the border";
        for (int k = 0; k < kPendulumSlots; ++k) {
            const physics::PendulumState st = set.slot(k).state();
            if (!set.diverged(k) && !(std::isfinite(st.theta) && std::isfinite(st.omega)))
                return "pendulum set " + std::to_string(i) + " slot " + std::to_string(k) + " is not finite";
        }
    }
    for (std::size_t i = 0; i < s.hairBalls.size(); ++i) {
        const HairBall& b = s.hairBalls[i];
        if (!finite3(b.centre()) || !insideBorder(b.centre()))
            return "hair ball " + std::to_string(i) + " is not finite or outside the border";
        const physics::HairSolver& h = b.solver();
        const std::size_t nodes = static_cast<std::size_t>(h.strands()) * static_cast<std::size_t>(h.nodesPerStrand());
        for (std::size_t k = 0; k < nodes; ++k) {
            if (!std::isfinite(h.x()[k]) || !std::isfinite(h.y()[k]) || !std::isfinite(h.z()[k]))
                return "hair ball " + std::to_string(i) + " has a non-finite node";
        }
    }
    return placementProblem(s); // every object where the game would have let it be placed (game/space.h)
}

} // namespace game
