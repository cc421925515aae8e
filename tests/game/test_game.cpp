#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "game/game_state.h"
#include "game/state_io.h"

namespace {

game::GameDef flatDef() {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.terrain.seed = 3;
    return def;
}

void settle(game::GameState& s, int ticks = 30) {
    for (int i = 0; i < ticks; ++i) game::tick(s, {}, 1.0f / 60.0f);
}

// The flat world's player settled on the ground, then looking north at `pitch` degrees (one more tick).
game::GameState settledLooking(float pitch) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions look;
    look.lookAbsolute = glm::vec2(0.0f, pitch);
    game::tick(s, look, 1.0f / 60.0f);
    return s;
}

TEST(Game, SpawnsStandingOnTheGround) {
    game::GameState s(flatDef());
    EXPECT_FLOAT_EQ(s.player.position.y, 33.0f); // flat grass top is y = 32
    settle(s);
    EXPECT_TRUE(s.player.onGround);
    EXPECT_NEAR(s.player.position.y, 33.0f, 1e-3f);
}

TEST(Game, WalkingForwardFollowsYaw) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions a;
    a.lookAbsolute = glm::vec2(90.0f, 0.0f); // east, +X
    game::tick(s, a, 1.0f / 60.0f);
    const glm::vec3 start = s.player.position;
    input::Actions walk;
    walk.move = {0.0f, 1.0f};
    for (int i = 0; i < 120; ++i) game::tick(s, walk, 1.0f / 60.0f);
    const glm::vec3 d = s.player.position - start;
    EXPECT_GT(d.x, 7.0f); // ~4.3 m/s for 2 s, minus the ramp-up
    EXPECT_LT(d.x, 8.7f);
    EXPECT_NEAR(d.z, 0.0f, 1e-3f);
    EXPECT_NEAR(d.y, 0.0f, 1e-3f);
}

TEST(Game, JumpReachesTheHeightGravityAllows) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions jump;
    jump.jump = true;
    float top = s.player.position.y;
    game::tick(s, jump, 1.0f / 60.0f);
    for (int i = 0; i < 60; ++i) {
        game::tick(s, {}, 1.0f / 60.0f);
        top = std::max(top, s.player.position.y);
    }
    const game::PlayerDef def;
    const float ideal = def.jumpSpeed * def.jumpSpeed / (2.0f * def.gravity); // continuous apex
    EXPECT_NEAR(top - 33.0f, ideal, 0.1f); // semi-implicit Euler undershoots by about v*dt/2
    EXPECT_GT(top - 33.0f, 1.0f);          // clears a one-block step
    EXPECT_TRUE(s.player.onGround);
}

TEST(Game, FallingAtTerminalSpeedNeverTunnels) {
    game::GameState s(flatDef());
    input::Actions tp;
    tp.teleport = glm::vec3(0.5f, 120.0f, 0.5f);
    game::tick(s, tp, 1.0f / 60.0f);
    s.player.velocity.y = -1000.0f;                        // far beyond anything the game allows
    for (int i = 0; i < 10; ++i) game::tick(s, {}, 0.25f); // and huge steps
    EXPECT_NEAR(s.player.position.y, 33.0f, 1e-3f);
    EXPECT_TRUE(s.player.onGround);
}

TEST(Game, BreakAndPlaceOnTheTargetedFace) {
    game::GameState s = settledLooking(-60.0f); // north and down: hits the ground ahead
    const game::Target target = game::targetOf(s);
    ASSERT_EQ(target.kind, game::Target::Kind::Block);
    const auto hit = std::optional<world::RayHit>(target.block);
    EXPECT_EQ(hit->block.y, 32);
    EXPECT_EQ(hit->normal, glm::ivec3(0, 1, 0));

    input::Actions place;
    place.selectSlot = 6; // brick
    place.place = true;
    game::tick(s, place, 1.0f / 60.0f);
    EXPECT_EQ(s.world.get(hit->block + glm::ivec3(0, 1, 0)), world::BlockType::Brick);

    input::Actions brk;
    brk.breakBlock = true;
    game::tick(s, brk, 1.0f / 60.0f);
    EXPECT_EQ(s.world.get(hit->block + glm::ivec3(0, 1, 0)), world::BlockType::Air);
    const auto edits = s.world.edits();
    ASSERT_EQ(edits.size(), 1u); // the latest value per position
    EXPECT_EQ(edits[0].block, world::BlockType::Air);
}

// The lamp is on the hotbar where LT/RT (selectDelta, one step a pull) reach it, and places like any block.
// Mutation caught: the hotbar without the lamp.
TEST(Game, TheLampIsReachedByCyclingTheHotbarAndPlaces) {
    game::GameState s = settledLooking(-60.0f);
    const game::Target target = game::targetOf(s);
    ASSERT_EQ(target.kind, game::Target::Kind::Block);
    ASSERT_EQ(s.player.selectedSlot, 0);
    int pulls = 0;
    while (!(s.player.selectedItem().kind == game::ItemKind::Block &&
             s.player.selectedItem().block == world::BlockType::Lamp) &&
           pulls < game::kHotbarSize) {
        input::Actions rt;
        rt.selectDelta = 1;
        game::tick(s, rt, 1.0f / 60.0f);
        ++pulls;
    }
    ASSERT_LT(pulls, game::kHotbarSize) << "no hotbar slot holds the lamp";
    input::Actions place;
    place.place = true;
    game::tick(s, place, 1.0f / 60.0f);
    EXPECT_EQ(s.world.get(target.block.block + glm::ivec3(0, 1, 0)), world::BlockType::Lamp);
}

// A click where the frame shows only sky leaves a pendulum set alone (the case: standing beside
// the demo set's foot, looking straight up past its arm). The hit shapes used to be a post twice as wide as
// drawn and a solid 2.4 m plate for the two arms.
TEST(Game, AClickAtTheSkyBesideASetLeavesIt) {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    game::GameState s(def);
    ASSERT_EQ(s.pendulumSets.size(), 1u) << "precondition: the demo set";
    const glm::vec3 foot = glm::vec3(s.pendulumSets[0].base()) + glm::vec3(0.5f, 0.0f, 0.5f);
    // Between two arms, 0.6 m from each, under the plate the old hit shape spanned.
    s.player.position = foot + glm::vec3(0.6f, 0.0f, -0.6f);
    s.player.pitch = 89.0f;
    s.previousPlayer = s.player;
    EXPECT_EQ(game::targetOf(s).kind, game::Target::Kind::None);
    input::Actions click;
    click.breakBlock = true;
    game::tick(s, click, 1.0f / 60.0f);
    EXPECT_EQ(s.pendulumSets.size(), 1u);
    // Looking straight up under an arm hits it, and the click removes the set.
    s.player.position = foot + glm::vec3(0.6f, 0.0f, 0.0f);
    s.previousPlayer = s.player;
    EXPECT_EQ(game::targetOf(s).kind, game::Target::Kind::PendulumSet);
    game::tick(s, click, 1.0f / 60.0f);
    EXPECT_TRUE(s.pendulumSets.empty());
}

TEST(Game, NeverPlacesInsideThePlayer) {
    // Looking straight down: the targeted face is the top of the block under the feet, and the new
    // block would be where the player stands.
    game::GameState s = settledLooking(-89.0f);
    EXPECT_EQ(game::placeTargeted(s), game::EditResult::WouldOverlapPlayer);
    EXPECT_EQ(s.world.editCount(), 0u);
}

TEST(Game, BottomLayerIsUnbreakable) {
    game::GameDef def = flatDef();
    game::GameState s(def);
    input::Actions a;
    a.teleport = glm::vec3(0.5f, 1.0f, 0.5f);
    a.lookAbsolute = glm::vec2(0.0f, -89.0f);
    for (int y = 32; y >= 1; --y) s.world.set({0, y, 0}, world::BlockType::Air);
    game::tick(s, a, 1.0f / 60.0f);
    EXPECT_EQ(game::breakTargeted(s), game::EditResult::Unbreakable);
}

TEST(Game, PauseFreezesTheSimulation) {
    game::GameState s(flatDef());
    settle(s);
    input::Actions p;
    p.togglePause = true;
    game::tick(s, p, 1.0f / 60.0f);
    ASSERT_TRUE(s.paused);
    const glm::vec3 before = s.player.position;
    input::Actions walk;
    walk.move = {0.0f, 1.0f};
    walk.place = true;
    for (int i = 0; i < 30; ++i) game::tick(s, walk, 1.0f / 60.0f);
    EXPECT_EQ(s.player.position, before);
    EXPECT_EQ(s.world.editCount(), 0u);
}

TEST(Game, SameActionsSameHashDifferentActionsDifferentHash) {
    auto run = [](bool turn) {
        game::GameState s(game::GameDef{});
        for (int i = 0; i < 200; ++i) {
            input::Actions a;
            a.move = {0.3f, 1.0f};
            a.yawDelta = turn ? 0.5f : 0.0f;
            a.jump = (i % 50) == 0;
            a.breakBlock = (i % 37) == 0;
            game::tick(s, a, 1.0f / 60.0f);
        }
        return game::stateHash(s);
    };
    EXPECT_EQ(run(true), run(true));
    EXPECT_NE(run(true), run(false));
}

TEST(Game, HashIgnoresWhichChunksAreLoaded) {
    game::GameState a(game::GameDef{}), b(game::GameDef{});
    for (int x = -2; x <= 2; ++x) b.world.chunk({x, 1, 0}); // a renderer would do this
    EXPECT_EQ(game::stateHash(a), game::stateHash(b));
}

// The state hash sees the smallest change of every piece of simulated state a later tick reads: the tick,
// pause, the player, every pendulum slot's state and integrator history, every hair ball's pose, definition
// and hair (one node by one ulp), the carried ball and the edits. Each change is made through the state's own
// API and must give another hash. Catches a field left out of game::stateHash (the pendulum histories and the
// hair nodes were, before).
TEST(Game, TheHashSeesTheSmallestChangeOfEverySimulatedField) {
    const game::GameDef def = flatDef();
    // GameState is move-only: the base is made afresh for every change, the same way each time.
    const auto makeBase = [&] {
        game::GameState s(def);
        game::PendulumSetDef d = s.pendulumSets.at(0).def();
        d.methods = {physics::Method::Midpoint, physics::Method::Dopri5, physics::Method::EulerCartesian,
                     physics::Method::Exact};
        s.pendulumSets[0].setDef(d);
        s.pendulumSets[0].release();
        s.hairBalls.emplace_back(s.player.position + glm::vec3(2.0f, 0.5f, 0.0f));
        settle(s, 20);
        return s;
    };
    game::GameState base = makeBase();
    ASSERT_FALSE(base.hairBalls[0].solver().sleeping()) << "precondition: the hair is awake";
    const std::uint64_t reference = game::stateHash(base);
    const auto up = [](auto v) { return std::nextafter(v, std::numeric_limits<decltype(v)>::infinity()); };
    using Change = std::function<void(game::GameState&)>;
    std::vector<std::pair<std::string, Change>> changes = {
        {"tick", [](game::GameState& s) { s.tick += 1; }},
        {"paused", [](game::GameState& s) { s.paused = !s.paused; }},
        {"player.position.x", [&](game::GameState& s) { s.player.position.x = up(s.player.position.x); }},
        {"player.position.y", [&](game::GameState& s) { s.player.position.y = up(s.player.position.y); }},
        {"player.velocity.z", [&](game::GameState& s) { s.player.velocity.z = up(s.player.velocity.z); }},
        {"player.yaw", [&](game::GameState& s) { s.player.yaw = up(s.player.yaw); }},
        {"player.pitch", [&](game::GameState& s) { s.player.pitch = up(s.player.pitch); }},
        {"player.onGround", [](game::GameState& s) { s.player.onGround = !s.player.onGround; }},
        {"player.flying", [](game::GameState& s) { s.player.flying = !s.player.flying; }},
        {"player.selectedSlot", [](game::GameState& s) { s.player.selectedSlot = (s.player.selectedSlot + 1) % 9; }},
        {"player.hotbar", [](game::GameState& s) { s.player.hotbar[0] = game::Item::hairBall(); }},
        {"edit",
         [](game::GameState& s) {
             s.world.set({3, 40, 3}, world::BlockType::Brick);
         }},
        {"carried", [](game::GameState& s) { s.carriedBall = 0; }},
        {"ball.centre",
         [&](game::GameState& s) {
             glm::vec3 c = s.hairBalls[0].centre();
             c.x = up(c.x);
             s.hairBalls[0].moveTo(c);
         }},
        {"ball.spinRate",
         [&](game::GameState& s) {
             game::HairBallDef d = s.hairBalls[0].def();
             d.spinRate = up(d.spinRate);
             physics::HairSolverState hair = s.hairBalls[0].solver().state();
             s.hairBalls[0].setDef(d);
             s.hairBalls[0].restoreHair(hair); // the definition alone changes, not the hair
         }},
    };
    // One node of the hair, by one ulp, in each array the solver carries.
    for (int a = 0; a < 9; ++a) {
        changes.emplace_back("hair array " + std::to_string(a), [a, &up](game::GameState& s) {
            physics::HairSolverState hair = s.hairBalls[0].solver().state();
            std::vector<float>* arrays[] = {&hair.x,  &hair.y,  &hair.z,  &hair.px, &hair.py,
                                            &hair.pz, &hair.cx, &hair.cy, &hair.cz};
            float& f = (*arrays[a])[arrays[a]->size() - 1];
            f = up(f);
            s.hairBalls[0].restoreHair(hair);
        });
    }
    // Every double of every pendulum slot's internals, and the set's own.
    using Internals = game::PendulumSet::Internals;
    const auto setField = [&](const std::string& name, const std::function<void(Internals&)>& f) {
        changes.emplace_back(name, [f](game::GameState& s) {
            Internals in = s.pendulumSets[0].internals();
            f(in);
            s.pendulumSets[0].restore(in);
        });
    };
    setField("previousTime", [&](Internals& in) { in.previousTime = up(in.previousTime); });
    setField("released", [](Internals& in) { in.released = !in.released; });
    for (std::size_t k = 0; k < game::kPendulumSlots; ++k) {
        const std::string slot = "slot " + std::to_string(k) + " ";
        setField(slot + "drawn theta", [&, k](Internals& in) { in.previous[k].theta = up(in.previous[k].theta); });
        setField(slot + "diverged", [k](Internals& in) { in.diverged[k] = !in.diverged[k]; });
        setField(slot + "theta", [&, k](Internals& in) { in.slots[k].state.theta = up(in.slots[k].state.theta); });
        setField(slot + "omega", [&, k](Internals& in) { in.slots[k].state.omega = up(in.slots[k].state.omega); });
        setField(slot + "time", [&, k](Internals& in) { in.slots[k].time = up(in.slots[k].time); });
        setField(slot + "timeCarry", [&, k](Internals& in) { in.slots[k].timeCarry = up(in.slots[k].timeCarry); });
        setField(slot + "history theta",
                 [&, k](Internals& in) { in.slots[k].previous.theta = up(in.slots[k].previous.theta); });
        setField(slot + "lastStep", [&, k](Internals& in) { in.slots[k].lastStep = up(in.slots[k].lastStep); });
    }
    setField("slot 2 cartesian x", [&](Internals& in) { in.slots[2].x = up(in.slots[2].x); });
    setField("slot 3 exact start",
             [&](Internals& in) { in.slots[3].exactInitial.theta = up(in.slots[3].exactInitial.theta); });
    for (const auto& [name, change] : changes) {
        game::GameState copy = makeBase();
        ASSERT_EQ(game::stateHash(copy), reference) << "precondition: the copy is the base";
        change(copy);
        EXPECT_NE(game::stateHash(copy), reference) << name;
    }
}

// A teleport into stone moves the body to the nearest whole-block height in its column where it fits, checked
// against a brute-force look at every cell the body overlaps and every nearer height. Catches a teleport that
// leaves the body inside the stone (the game before the lift) or one that takes the first free height upward
// when a nearer one lies below.
TEST(Game, ATeleportIntoStoneLiftsTheBodyToTheNearestHeightWhereItFits) {
    game::GameDef def;
    def.terrain.seed = 7;
    def.demoObjects = false;
    game::GameState s(def);
    const auto overlapsSolid = [&](glm::vec3 feet) {
        const world::Aabb box = game::playerBox(feet, def.player);
        for (int y = static_cast<int>(std::floor(box.min.y)); static_cast<float>(y) < box.max.y; ++y)
            for (int z = static_cast<int>(std::floor(box.min.z)); static_cast<float>(z) < box.max.z; ++z)
                for (int x = static_cast<int>(std::floor(box.min.x)); static_cast<float>(x) < box.max.x; ++x)
                    if (world::isSolid(s.world.get({x, y, z}))) return true;
        return false;
    };
    for (const glm::vec3 target : {glm::vec3(0.5f, 20.0f, 0.5f), glm::vec3(7.3f, 5.5f, -3.8f)}) {
        ASSERT_TRUE(overlapsSolid(target)) << "precondition: the target is inside blocks";
        input::Actions a;
        a.teleport = target;
        game::tick(s, a, 1.0 / 60.0);
        const glm::vec3 p = s.player.position;
        EXPECT_EQ(p.x, target.x);
        EXPECT_EQ(p.z, target.z);
        EXPECT_FALSE(overlapsSolid(p)) << "stuck inside blocks at y = " << p.y;
        EXPECT_EQ(p.y, std::floor(p.y)) << "feet at a whole block";
        for (int h = 0; h <= world::kWorldHeight; ++h) {
            const float d = std::abs(static_cast<float>(h) - target.y), mine = std::abs(p.y - target.y);
            if (d < mine || (d == mine && static_cast<float>(h) > p.y)) {
                EXPECT_TRUE(overlapsSolid({target.x, static_cast<float>(h), target.z})) << "a nearer fit at " << h;
            }
        }
    }
}

TEST(Game, DumpHasTheContractFields) {
    game::GameState s(flatDef());
    s.world.set({1, 33, 1}, world::BlockType::Planks);
    const auto j = game::dumpState(s);
    EXPECT_EQ(j["tick"], 0);
    EXPECT_EQ(j["state_hash"].get<std::string>().size(), 16u);
    EXPECT_EQ(j["player"]["position"].size(), 3u);
    EXPECT_TRUE(j["player"].contains("yaw"));
    EXPECT_TRUE(j["player"].contains("pitch"));
    EXPECT_EQ(j["player"]["selected_block"], "grass");
    ASSERT_EQ(j["edits"].size(), 1u);
    EXPECT_EQ(j["edits"][0]["pos"], nlohmann::json::array({1, 33, 1}));
    EXPECT_EQ(j["edits"][0]["block"], "planks");
}

// The clock goes round once in its day length, and not at all while stopped or while the game is paused.
// Mutation caught: advancing by dt * 24 / dayMinutes (the length taken as seconds): the half day would pass 60
// times over and the clock would not read 18.
TEST(DayClock, GoesRoundOnceADayAndStandsStillWhenStoppedOrPaused) {
    game::DayClock c;
    c.dayMinutes = 2.0;
    c.hours = 6.0;
    const double dt = 1.0 / 60.0;
    for (int i = 0; i < 3600; ++i) game::advance(c, dt); // one minute: half of the day
    EXPECT_NEAR(c.hours, 18.0, 1e-9);
    for (int i = 0; i < 3600; ++i) game::advance(c, dt); // past midnight, round to 6 again
    EXPECT_NEAR(c.hours, 6.0, 1e-9);
    EXPECT_TRUE(game::checkDayClock(c).empty());
    c.stopped = true;
    const double before = c.hours;
    game::advance(c, 1000.0);
    EXPECT_EQ(c.hours, before); // unchanged, bit for bit

    game::GameState s(flatDef());
    ASSERT_FALSE(s.day.stopped); // precondition: a running clock, which only the pause holds
    input::Actions pause;
    pause.togglePause = true;
    game::tick(s, pause, dt);
    ASSERT_TRUE(s.paused);
    const double paused = s.day.hours;
    for (int i = 0; i < 10; ++i) game::tick(s, {}, dt);
    EXPECT_EQ(s.day.hours, paused);
    // Set while paused, the clock stands at the new hour.
    game::TickCommands at3;
    at3.timeOfDay = 3.0;
    game::tick(s, {}, dt, at3);
    game::tick(s, {}, dt);
    EXPECT_EQ(s.day.hours, 3.0);
}

// A `time` command sets the hour before the tick moves the clock on, and the hour is in the dump and the hash.
// Mutation caught: applying the command after advance() (the clock would read exactly 18).
TEST(DayClock, ATimeCommandSetsTheHourAndTheHashAndDumpSeeIt) {
    game::GameState a(flatDef()), b(flatDef());
    ASSERT_EQ(game::stateHash(a), game::stateHash(b));
    game::TickCommands c;
    c.timeOfDay = 18.0;
    game::tick(a, {}, 1.0 / 60.0, c);
    game::tick(b, {}, 1.0 / 60.0);
    EXPECT_EQ(a.day.hours, 18.0 + (1.0 / 60.0) * 24.0 / (game::kDefaultDayMinutes * 60.0));
    EXPECT_NE(game::stateHash(a), game::stateHash(b));
    const auto j = game::dumpState(a);
    EXPECT_EQ(j["time_of_day"].get<double>(), a.day.hours);
    EXPECT_EQ(j["day_length"].get<double>(), game::kDefaultDayMinutes);
    EXPECT_EQ(j["day_stopped"].get<bool>(), false);
}

// What --time-of-day and `time` take: 0 to 24 (24 is midnight, read as 0), nothing else; and the recording's
// text of an hour reads back bit for bit. Mutation caught: a range check of hours < 25.
TEST(DayClock, HoursParseFromZeroToTwentyFourAndReadBackExactly) {
    EXPECT_EQ(game::parseHours("0"), 0.0);
    EXPECT_EQ(game::parseHours("24"), 0.0);
    EXPECT_EQ(game::parseHours("6.25"), 6.25);
    for (const char* bad : {"-1", "24.5", "nan", "inf", "", "12h", " 12", "-0.0001"}) {
        try {
            (void)game::parseHours(bad);
            ADD_FAILURE() << "'" << bad << "' was taken";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos) << e.what();
        }
    }
    std::uint64_t x = 12345;
    for (int i = 0; i < 1000; ++i) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        const double h = static_cast<double>(x >> 11) / 9007199254740992.0 * 24.0;
        EXPECT_EQ(game::parseHours(game::exactHours(h)), h) << game::exactHours(h);
    }
    EXPECT_EQ(game::clockText(18.5), "18:30");
}

} // namespace
