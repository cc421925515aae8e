// Recorded sessions (session/recording.h): what a tick consumed reads back bit for bit, a replay reaches the
// recorded state hashes, and a recording that is damaged, cut short, newer or for another world is refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "core/atomic_file.h"
#include "game/command_text.h"
#include "game/state_io.h"
#include "input/script.h"
#include "save/world_store.h"
#include "session/options.h"
#include "session/recording.h"
#include "session/session.h"
#include "session/setting_table.h"

namespace {

namespace fs = std::filesystem;

class Recordings : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_dir = fs::temp_directory_path() / ("mc_rec_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    fs::path file(const std::string& name) const { return m_dir / name; }
    void write(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }
    std::string read(const std::string& name) const {
        std::ifstream in(file(name));
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
    // Runs `ticks` ticks of the demo scene with a script, optionally recording; returns the hash after each tick.
    std::vector<std::uint64_t> run(const std::string& script, const std::string& record, std::uint64_t ticks) const {
        session::Options o;
        o.headless = true;
        o.settingsFile.reset();
        if (!script.empty()) o.script = file(script).string();
        if (!record.empty()) o.record = file(record).string();
        session::Session s(o);
        std::vector<std::uint64_t> hashes;
        for (std::uint64_t t = 0; t < ticks; ++t) {
            s.step();
            hashes.push_back(game::stateHash(s.state()));
        }
        return hashes;
    }

    // Writes `text` as `name` (rec.mcscript) and replays a tick of it: the refusal's message, or "accepted".
    std::string replayRefusal(const std::string& text, const std::string& name = "rec.mcscript") const {
        write(name, text);
        try {
            run(name, "", 1);
        } catch (const input::ScriptError& e) {
            return e.what();
        } catch (const save::WorldFileError& e) {
            return e.what();
        }
        return "accepted";
    }
    static std::string replacedIn(std::string text, const std::string& from, const std::string& to) {
        text.replace(text.find(from), from.size(), to);
        return text;
    }

    fs::path m_dir;
};

// A walk with a jump and a look, a hair ball's colour and strands changed, a pendulum set's rods lengthened
// and released: input and both panels' edits.
const char* kScript = "0 key W down\n"
                      "12 key SPACE down\n"
                      "14 key SPACE up\n"
                      "20 mouse_move 35.5 -12.25\n"
                      "25 hair 0 colour=0.1,0.9,0.3 strands=300 method=shake iterations=4\n"
                      "30 pendulum 0 set release=75 length=1.25 methods=verlet,rk4,dopri5,exact\n"
                      "31 pendulum 0 release\n"
                      "35 time 18.25\n"
                      "40 key W up\n";

TEST_F(Recordings, AReplayReachesTheRecordedHashAtEveryTickAndTheEditsAreInTheFile) {
    write("walk.txt", kScript);
    const auto live = run("walk.txt", "rec.mcscript", 80);
    const std::string text = read("rec.mcscript");
    ASSERT_TRUE(session::isRecording(text)); // precondition: the recording was written
    EXPECT_NE(text.find("25 hair 0 radius="), std::string::npos) << text;
    EXPECT_NE(text.find("30 pendulum 0 set release=75 length=1.25 gravity=9.81 step=1 methods=verlet,rk4,dopri5,exact"),
              std::string::npos);
    EXPECT_NE(text.find("31 pendulum 0 release"), std::string::npos);
    EXPECT_NE(text.find("35 time 18.25\n"), std::string::npos);
    EXPECT_NE(text.find("# end 80"), std::string::npos);
    const auto replayed = run("rec.mcscript", "", 80);
    EXPECT_EQ(replayed, live);
    // Precondition of the comparison: the edits and the walk changed the state (else equal hashes prove little).
    EXPECT_NE(live[24], live[26]);
    EXPECT_NE(live[33], live[35]);
    const auto unscripted = run("", "", 80);
    EXPECT_NE(unscripted.back(), live.back());
}

// The block picker's choice is a script's `hotbar SLOT ITEM` line: a script puts the red lamp into slot 6 and a
// pendulum set into slot 2, selects slot 6 and places what it holds, looking down: the world holds a red lamp, the
// recording writes both lines, and the replay reaches the same hashes. A bad slot or name is refused naming the
// line. Mutation caught (tried): a recorder that leaves the hotbar commands out (the replay places a lamp).
TEST_F(Recordings, AHotbarLinePutsAnyBlockInASlotAndTheRecordingKeepsIt) {
    write("pick.txt", "0 hotbar 6 red_lamp\n"
                      "1 hotbar 2 pendulum_set\n"
                      "3 look 180 -60\n"
                      "4 key 6 down\n5 key 6 up\n"
                      "8 mouse_button right down\n9 mouse_button right up\n");
    const auto live = run("pick.txt", "pick.mcscript", 20);
    const std::string text = read("pick.mcscript");
    EXPECT_NE(text.find("0 hotbar 6 red_lamp\n"), std::string::npos) << text;
    EXPECT_NE(text.find("1 hotbar 2 pendulum_set\n"), std::string::npos) << text;
    EXPECT_EQ(run("pick.mcscript", "", 20), live);
    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    o.script = file("pick.txt").string();
    session::Session s(o);
    for (int t = 0; t < 20; ++t) s.step();
    EXPECT_EQ(s.state().player.hotbar[5], game::Item::ofBlock(world::BlockType::RedLamp));
    EXPECT_EQ(s.state().player.hotbar[1], game::Item::pendulumSet());
    const auto& edits = s.state().world.edits();
    EXPECT_TRUE(std::any_of(edits.begin(), edits.end(),
                            [](const world::BlockEdit& e) { return e.block == world::BlockType::RedLamp; }));
    const auto refusal = [&](const std::string& line) { return replayRefusal(line, "bad.txt"); };
    EXPECT_NE(refusal("1 hotbar 0 stone\n").find("bad.txt:1: hotbar: slot 0 is not 1 to 9"), std::string::npos)
        << refusal("1 hotbar 0 stone\n");
    EXPECT_NE(refusal("1 hotbar 3 glowstone\n").find("'glowstone' is no block or object (one of grass,"),
              std::string::npos)
        << refusal("1 hotbar 3 glowstone\n");
    EXPECT_NE(refusal("1 hotbar 3 air\n").find("bad.txt:1: hotbar: 'air' is no block or object"), std::string::npos)
        << refusal("1 hotbar 3 air\n");
}

// Carrying a hair ball: the player is put 2.5 m south of the first demo ball, looking at it, picks it up (Q),
// walks with it and puts it down; the recording replays to the same hashes with the ball carried on the way.
TEST_F(Recordings, CarryingAHairBallReplaysToTheSameState) {
    glm::vec3 centre;
    {
        session::Options o;
        o.headless = true;
        o.settingsFile.reset();
        const session::Session probe(o);
        ASSERT_FALSE(probe.state().hairBalls.empty()); // precondition: the demo scene has balls
        centre = probe.state().hairBalls[0].centre();
    }
    const glm::vec3 feet = centre + glm::vec3(0.0f, -1.62f, 2.5f); // eye level with the centre, south of it
    std::ostringstream script;
    script << "0 teleport " << feet.x << " " << feet.y << " " << feet.z << "\n"
           << "0 look 0 0\n" // north: towards the ball
           << "5 key Q down\n6 key Q up\n"
           << "10 key D down\n40 key D up\n"
           << "50 key Q down\n51 key Q up\n";
    write("carry.txt", script.str());
    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    o.script = file("carry.txt").string();
    o.record = file("carry.mcscript").string();
    std::vector<std::uint64_t> live;
    bool carried = false;
    {
        session::Session s(o);
        for (int t = 0; t < 80; ++t) {
            s.step();
            carried = carried || s.state().carriedBall.has_value();
            live.push_back(game::stateHash(s.state()));
        }
    }
    ASSERT_TRUE(carried) << "the ball was never picked up: the test's aim is off";
    EXPECT_EQ(run("carry.mcscript", "", 80), live);
}

TEST_F(Recordings, ATamperedTickStopsTheReplayAtTheFirstHashAfterIt) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 80);
    std::string text = read("rec.mcscript");
    const std::size_t at = text.find("\n33 act ");
    ASSERT_NE(at, std::string::npos); // precondition: tick 33 had input (W held)
    text.insert(text.find('\n', at + 1), " yaw=30");
    write("rec.mcscript", text);
    try {
        run("rec.mcscript", "", 80);
        FAIL() << "the tampered replay ran to the end";
    } catch (const session::ReplayDiverged& e) {
        EXPECT_EQ(e.tick(), 40u) << e.what(); // the state after tick 33 changed; hashes every 10 ticks
        EXPECT_NE(std::string(e.what()).find("tick 40"), std::string::npos) << e.what();
    }
}

TEST_F(Recordings, ActWordsReadBackBitForBit) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> any(-1000.0f, 1000.0f), unit(-0.7f, 0.7f);
    for (int i = 0; i < 2000; ++i) {
        input::Actions a;
        a.move = {unit(rng), unit(rng)};
        a.yawDelta = any(rng) * 1e-3f;
        a.pitchDelta = any(rng);
        a.selectDelta = i % 5 - 2;
        a.selectSlot = i % 10 - 1;
        if (i % 3 == 0) a.teleport = glm::vec3(any(rng), any(rng), any(rng));
        if (i % 4 == 0) a.lookAbsolute = glm::vec2(any(rng), unit(rng) * 90.0f);
        a.jump = i % 2 == 0;
        a.toggleHelp = i % 7 == 0;
        const std::string line = "5 act " + input::actWords(a);
        const auto events = input::parseScript(line, "t");
        ASSERT_EQ(events.size(), 1u);
        const auto& b = std::get<input::ActionsEvent>(events[0].event).actions;
        ASSERT_EQ(b.move, a.move) << line;
        ASSERT_EQ(b.yawDelta, a.yawDelta) << line;
        ASSERT_EQ(b.pitchDelta, a.pitchDelta) << line;
        ASSERT_EQ(b.selectDelta, a.selectDelta);
        ASSERT_EQ(b.selectSlot, a.selectSlot);
        ASSERT_EQ(b.teleport, a.teleport) << line;
        ASSERT_EQ(b.lookAbsolute, a.lookAbsolute) << line;
        ASSERT_EQ(b.jump, a.jump);
        ASSERT_EQ(b.toggleHelp, a.toggleHelp);
    }
    EXPECT_EQ(input::actWords(input::Actions{}), "");
}

TEST_F(Recordings, PanelEditsReadBackAsTheSameCommands) {
    game::HairCommand h;
    h.ball = 3;
    h.def.radius = 0.37f;
    h.def.colour = {0.1f, 0.2f, 0.3f};
    h.def.hair.method = physics::HairMethod::XpbdSubsteps;
    h.def.hair.seed = 123456789012345ULL;
    h.def.hair.hostCollision = false;
    const game::HairCommand h2 = game::hairCommandFrom(3, game::hairCommandWords(h));
    EXPECT_EQ(h2.def.radius, h.def.radius);
    EXPECT_EQ(h2.def.colour, h.def.colour);
    EXPECT_EQ(h2.def.hair.method, h.def.hair.method);
    EXPECT_EQ(h2.def.hair.seed, h.def.hair.seed);
    EXPECT_EQ(h2.def.hair.hostCollision, false);
    game::PendulumCommand p;
    p.op = game::PendulumCommand::Op::SetDef;
    p.def.releaseDegrees = 0.1 + 0.2; // not a short decimal
    const game::PendulumCommand p2 = game::pendulumCommandFrom(0, game::pendulumCommandWords(p));
    EXPECT_EQ(p2.def.releaseDegrees, p.def.releaseDegrees);
    EXPECT_EQ(p2.def.methods, p.def.methods);
    EXPECT_THROW(game::pendulumCommandFrom(0, {"spin"}), std::invalid_argument);
    EXPECT_THROW(game::hairCommandFrom(0, {"radius=big"}), std::invalid_argument);
    EXPECT_THROW(game::hairCommandFrom(0, {"colour=1,2"}), std::invalid_argument);
}

TEST_F(Recordings, ABadEditLineStopsTheRunBeforeItsFirstTickNamingTheLine) {
    write("bad.txt", "0 key W down\n5 hair 0 radius=big\n");
    try {
        run("bad.txt", "", 1);
        FAIL() << "a bad edit line was accepted";
    } catch (const input::ScriptError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.txt:2: hair: 'radius=big'"), std::string::npos) << e.what();
    }
}

// The pause menu's time slider (Session::queueTimeOfDay) sets a paused game's clock at the next tick, and a
// recording keeps it: the replay reaches the same hashes. An hour outside [0, 24) is ignored. Mutation caught:
// the tick dropping the time command while paused (the clock would still read the pause's hour).
TEST_F(Recordings, ThePauseMenusTimeIsSetWhilePausedAndRecorded) {
    std::vector<std::uint64_t> live;
    {
        session::Options o;
        o.headless = true;
        o.settingsFile.reset();
        o.record = file("rec.mcscript").string();
        session::Session s(o);
        s.requestPauseToggle();
        s.step();
        ASSERT_TRUE(s.state().paused); // the precondition: the clock stands still
        s.queueTimeOfDay(21.25);
        s.step();
        EXPECT_EQ(s.state().day.hours, 21.25);
        s.queueTimeOfDay(24.0); // not an hour the clock can read: ignored
        s.queueTimeOfDay(-1.0);
        for (int i = 0; i < 20; ++i) s.step();
        EXPECT_EQ(s.state().day.hours, 21.25);
        live.push_back(game::stateHash(s.state()));
    }
    EXPECT_NE(read("rec.mcscript").find("1 time 21.25\n"), std::string::npos) << read("rec.mcscript");
    EXPECT_EQ(run("rec.mcscript", "", 22).back(), live.back());
}

// `time` takes what --time-of-day takes; a bad hour stops the run before its first tick, naming the line.
// Mutation caught: parseHours accepting 24.5 (a range check of < 25).
TEST_F(Recordings, ABadTimeLineIsRefusedNamingTheLine) {
    for (const char* hours : {"-1", "24.5", "nan", "noon"}) {
        write("bad.txt", std::string("0 key W down\n3 time ") + hours + "\n");
        try {
            run("bad.txt", "", 1);
            ADD_FAILURE() << "time " << hours << " was accepted";
        } catch (const input::ScriptError& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("bad.txt:2: time: '") + hours + "'"), std::string::npos)
                << e.what();
        }
    }
}

TEST_F(Recordings, DamagedNewerCutOrMismatchedRecordingsAreRefusedWithTheReason) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 30);
    const std::string good = read("rec.mcscript");
    const auto refusal = [&](const std::string& text) { return replayRefusal(text); };
    const auto replaced = [&](const std::string& from, const std::string& to) { return replacedIn(good, from, to); };
    EXPECT_NE(refusal(good.substr(0, good.size() / 2)).find("cut short"), std::string::npos);
    EXPECT_NE(refusal(replaced("# version 0.1.0", "# version 9.0")).find("newer than this game"), std::string::npos);
    EXPECT_NE(refusal(replaced("# seed 1", "# seed 2")).find("does not match its start world"), std::string::npos);
    EXPECT_NE(refusal(replaced("# hash 0 ", "# hash 0 f")).find("malformed recording line"), std::string::npos);
    EXPECT_NE(refusal(replaced("# tick_rate 60", "# tick_rate 0")).find(":7: tick_rate 0: out of range 10..1000"),
              std::string::npos);
    fs::remove(file("rec.mcscript.start.mcworld"));
    EXPECT_NE(refusal(good).find("cannot open"), std::string::npos);
    EXPECT_EQ(refusal(good.substr(0, 0)), "accepted"); // an empty script is a script, not a recording
}

// The header's values are checked before the first tick, each refusal naming its line: a version that is no
// release number, a hair detail that is none of the settings' levels (NaN included), a hair budget outside the
// settings' range (1 kept the hair still, and the replay passed while hashes left the hair out). Catches a
// parser that takes any number again.
TEST_F(Recordings, HeaderValuesOutsideWhatTheGameWritesAreRefusedNamingTheLine) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 30);
    const std::string good = read("rec.mcscript");
    const auto refusal = [&](const std::string& from, const std::string& to) -> std::string {
        std::string t = good;
        const auto at = t.find(from);
        if (at == std::string::npos) return "not found: " + from; // the precondition: the header has the line
        t.replace(at, from.size(), to);
        write("rec.mcscript", t);
        try {
            run("rec.mcscript", "", 1);
        } catch (const input::ScriptError& e) {
            return e.what();
        }
        return "accepted";
    };
    const std::string version = refusal("# version 0.1.0", "# version banana");
    EXPECT_NE(version.find("rec.mcscript:2: version 'banana' is not a Minecrappy release number"), std::string::npos)
        << version;
    const std::string nan = refusal("# hair_detail 2", "# hair_detail nan");
    EXPECT_NE(nan.find("rec.mcscript:5: hair_detail nan: expected a whole number"), std::string::npos) << nan;
    const std::string half = refusal("# hair_detail 2", "# hair_detail 0.3");
    EXPECT_NE(half.find(":5: hair_detail 0.3"), std::string::npos) << half;
    const std::string budget = refusal("# hair_budget 1000", "# hair_budget 1");
    EXPECT_NE(budget.find("rec.mcscript:6: hair_budget 1: out of range 100..100000"), std::string::npos) << budget;
    EXPECT_EQ(refusal("# hair_budget 1000", "# hair_budget 1000"), "accepted"); // the good one replays
}

// A header edited by hand names its line: a day line that disagrees with the start world (whose own day gives the
// recorded start hash) is named as edited, not reported as a changed start world; a header key given twice is
// refused naming both lines, as is a second hash of one tick. Catches the parser that took the last of two
// values silently and the replay that said only "its start world ... is not the state it was recorded from".
TEST_F(Recordings, AnEditedOrDuplicatedHeaderLineIsNamed) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 30);
    const std::string good = read("rec.mcscript");
    const auto lineOf = [&](const std::string& text) {
        const auto at = good.find(text);
        return at == std::string::npos ? -1 : static_cast<int>(std::count(good.begin(), good.begin() + at, '\n')) + 1;
    };
    const int dayLength = lineOf("# day_length 20.0\n"), dayCycle = lineOf("# day_cycle true\n");
    const int hash0 = lineOf("# hash 0 ");
    ASSERT_GT(dayLength, 0) << good; // the precondition: the header holds the lines the test edits
    ASSERT_GT(dayCycle, 0) << good;
    ASSERT_GT(hash0, 0) << good;
    const auto refusal = [&](const std::string& text) { return replayRefusal(text); };
    const auto replaced = [&](const std::string& from, const std::string& to) { return replacedIn(good, from, to); };
    const std::string f = file("rec.mcscript").string();
    EXPECT_EQ(refusal(replaced("# day_length 20.0\n", "# day_length 5.0\n")),
              f + ":" + std::to_string(dayLength) + ": '# day_length 5.0' is not the day length of its start world " +
                  f + ".start.mcworld (20.0, which its start hash agrees with): the header was edited");
    EXPECT_EQ(refusal(replaced("# day_cycle true\n", "# day_cycle false\n")),
              f + ":" + std::to_string(dayCycle) + ": '# day_cycle false' is not what its start world " + f +
                  ".start.mcworld holds (true, which its start hash agrees with): the header was edited");
    EXPECT_EQ(refusal(replaced("# day_length 20.0\n", "# day_length 20.0\n# day_length 5.0\n")),
              f + ":" + std::to_string(dayLength + 1) + ": '# day_length' is given a second time (first at line " +
                  std::to_string(dayLength) + "); a recording's header holds each key once");
    const std::string hashLine = good.substr(good.find("# hash 0 "), 26);
    EXPECT_EQ(refusal(replaced(hashLine, hashLine + hashLine)),
              f + ":" + std::to_string(hash0 + 1) + ": a second hash of tick 0; a recording has one for each");
    EXPECT_EQ(refusal(good), "accepted"); // the unedited file replays
}

// Recordings made before the day clock (formats 1 and 2) hash a state without the time of day: they cannot replay
// and are refused before the first tick, saying why; a newer format is refused as newer. Catches a reader that
// still takes format 2 (its replay would diverge at the first hash, with no reason given).
TEST_F(Recordings, FormatsBeforeTheDayClockAreRefusedSayingWhy) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 30);
    const std::string text = read("rec.mcscript");
    const std::string current = "# minecrappy recording " + std::to_string(session::kRecordingFormat) + "\n";
    ASSERT_EQ(text.rfind(current, 0), 0u) << text.substr(0, 40); // the precondition: the current format was written
    for (const int format : {1, 2, session::kRecordingFormat + 1}) {
        std::string old = text;
        old.replace(0, current.size(), "# minecrappy recording " + std::to_string(format) + "\n");
        write("old.mcscript", old);
        try {
            run("old.mcscript", "", 30);
            ADD_FAILURE() << "format " << format << " was replayed";
        } catch (const input::ScriptError& e) {
            const std::string why =
                format < session::kRecordingFormat ? "was made before the day clock" : "this game reads format";
            EXPECT_NE(std::string(e.what()).find("old.mcscript:1: recording format " + std::to_string(format)),
                      std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
    }
}

// A header value the game could have written but this run did not: the replay steps with it, its hair moves
// differently, and the first hash line after that stops it (ReplayDiverged, exit 3 in the game). Before the
// hash covered the hair, hair_detail 0.5 replayed to the end. Catches a hash that leaves the hair out again.
TEST_F(Recordings, AChangedHairDetailStopsTheReplayAtTheFirstHashAfterTheHairDiffers) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 30);
    std::string text = read("rec.mcscript");
    const auto at = text.find("# hair_detail 2\n");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 16, "# hair_detail 1\n");
    write("rec.mcscript", text);
    try {
        run("rec.mcscript", "", 30);
        FAIL() << "a replay with half the hair simulated reached the end";
    } catch (const session::ReplayDiverged& e) {
        EXPECT_EQ(e.tick(), 10u) << e.what(); // the first hash line after the start (hash_every 10)
    }
}

// A replay takes every simulation setting from its header: a flag asking for another value is refused before the
// first tick, naming the recorded value and the flag, and the same value is accepted. Catches a replay that ignores
// a given flag (its run would diverge at the first hash) or refuses one that agrees.
TEST_F(Recordings, AReplayRefusesASimulationFlagWithAnotherValue) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 20);
    const struct {
        const char *key, *other, *refusal;
    } cases[] = {
        {"tick_rate", "120", "recorded with tick_rate 60; this run asks for --tick-rate 120"},
        {"hair_detail", "1", "recorded with hair_detail 2; this run asks for --hair-detail 1"},
        {"hair_budget", "500", "recorded with hair_budget 1000; this run asks for --hair-budget 500"},
        {"day_length", "3", "recorded with day_length 20.0; this run asks for --day-length 3.0"},
        {"day_cycle", "false", "recorded with day_cycle true; this run asks for --day-cycle false"},
    };
    std::size_t simulationRows = 0;
    for (const session::SettingRow& row : session::kSettingRows) simulationRows += row.simulation;
    ASSERT_EQ(simulationRows, std::size(cases)); // the precondition: every simulation row has its case
    for (const auto& c : cases) {
        SCOPED_TRACE(c.key);
        const session::SettingRow& row = *session::findSetting(c.key);
        const std::size_t index = static_cast<std::size_t>(&row - session::kSettingRows.data());
        for (const bool same : {false, true}) {
            session::Options o;
            o.headless = true;
            o.settingsFile.reset();
            o.script = file("rec.mcscript").string();
            o.given.settings[index] = true;
            if (!same) {
                ASSERT_EQ(session::parseSetting(row, c.other, o.settings), "");
            }
            try {
                session::Session replay(o);
                EXPECT_TRUE(same) << "another " << c.key << " was accepted";
            } catch (const input::ScriptError& e) {
                EXPECT_FALSE(same) << e.what();
                EXPECT_NE(std::string(e.what()).find(c.refusal), std::string::npos) << e.what();
            }
        }
    }
}

// The files of a folder, by name.
std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// A session killed while recording over an older recording (here: its recorder dropped without finish(), as
// SIGKILL leaves it) leaves the older recording and its start world replayable, and at worst a start world no
// recording names. The wrong implementation this catches: writing FILE.start.mcworld when recording starts (the
// old recording then fails "its header ... does not match its start world").
TEST_F(Recordings, ARecordingKilledOverAnOlderOneLeavesTheOlderOneReplayable) {
    write("walk.txt", kScript);
    const auto live = run("walk.txt", "rec.mcscript", 60);
    ASSERT_TRUE(fs::exists(file("rec.mcscript.start.mcworld"))); // precondition: the first pair
    {
        session::Options o;
        o.headless = true;
        o.settingsFile.reset();
        o.seed = 2; // another world: a start world of its own would not match the older recording's header
        const session::Session other(o);
        session::RecordingHeader h;
        h.version = MC_VERSION;
        h.seed = 2;
        h.terrain = "default";
        const session::Recorder killed(file("rec.mcscript"), h, save::takeSnapshot(other.state()),
                                       game::stateHash(other.state()));
        EXPECT_EQ(filesIn(m_dir), (std::vector<std::string>{"rec.mcscript", "rec.mcscript.start.2.mcworld",
                                                            "rec.mcscript.start.mcworld", "walk.txt"}));
    }
    EXPECT_EQ(run("rec.mcscript", "", 60), live);
}

// A recording that replaces an older one replaces the pair: the new file names its own start world and the older
// start world is removed; the next one takes the first name again.
TEST_F(Recordings, ANewRecordingReplacesTheOlderRecordingAndItsStartWorld) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 30);
    const auto second = run("walk.txt", "rec.mcscript", 50);
    EXPECT_EQ(filesIn(m_dir), (std::vector<std::string>{"rec.mcscript", "rec.mcscript.start.2.mcworld", "walk.txt"}));
    EXPECT_NE(read("rec.mcscript").find("# start_world rec.mcscript.start.2.mcworld\n"), std::string::npos);
    EXPECT_EQ(run("rec.mcscript", "", 50), second);
    const auto third = run("walk.txt", "rec.mcscript", 40);
    EXPECT_EQ(filesIn(m_dir), (std::vector<std::string>{"rec.mcscript", "rec.mcscript.start.mcworld", "walk.txt"}));
    EXPECT_EQ(run("rec.mcscript", "", 40), third);
}

// A recording that cannot be written (the rename fails, as on a full disk) takes its start world with it and leaves
// the older pair as it was.
TEST_F(Recordings, ARecordingThatCannotBeWrittenLeavesTheOlderPairAsItWas) {
    write("walk.txt", kScript);
    const auto live = run("walk.txt", "rec.mcscript", 40);
    const std::string before = read("rec.mcscript");
    {
        session::Options o;
        o.headless = true;
        o.settingsFile.reset();
        o.seed = 2;
        o.record = file("rec.mcscript").string();
        session::Session s(o);
        s.step();
        ASSERT_TRUE(fs::exists(file("rec.mcscript.start.2.mcworld"))); // precondition: its start world was written
        core::setWriteFault({core::WriteFault::Point::Rename, ENOSPC, 0});
        EXPECT_THROW(s.finishRecording(), core::OutputError);
        core::clearWriteFault();
    }
    EXPECT_EQ(read("rec.mcscript"), before);
    EXPECT_EQ(filesIn(m_dir), (std::vector<std::string>{"rec.mcscript", "rec.mcscript.start.mcworld", "walk.txt"}));
    EXPECT_EQ(run("rec.mcscript", "", 40), live);
}

// A recording made through a symbolic link keeps its start world beside the file the link leads to, and replays
// from either name; a pipe or a device is refused before anything is written.
TEST_F(Recordings, TheStartWorldLiesBesideTheFileALinkLeadsToAndADeviceIsRefused) {
    write("walk.txt", kScript);
    fs::create_directories(file("a"));
    fs::create_directories(file("b"));
    std::ofstream(file("b/real.mcscript")) << "placeholder\n";
    fs::create_symlink(file("b/real.mcscript"), file("a/link.mcscript"));
    const auto live = run("walk.txt", "a/link.mcscript", 30);
    EXPECT_TRUE(fs::is_symlink(file("a/link.mcscript")));
    EXPECT_EQ(filesIn(file("a")), std::vector<std::string>{"link.mcscript"});
    EXPECT_EQ(filesIn(file("b")), (std::vector<std::string>{"real.mcscript", "real.mcscript.start.mcworld"}));
    EXPECT_EQ(run("b/real.mcscript", "", 30), live);
    EXPECT_EQ(run("a/link.mcscript", "", 30), live);

    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    o.record = "/dev/null";
    try {
        session::Session s(o);
        FAIL() << "a recording onto /dev/null was accepted";
    } catch (const core::OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("'/dev/null': a recording is a file"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists("/dev/null.start.mcworld"));
}

// A world's day is the world's: saved with --day-length 5 --day-cycle false, it opens with that day and the
// saved hash; a flag on the command line wins for the session; a recording made on it replays (its header
// holds the day the session ran). The wrong implementation this catches: the settings' day put over the
// loaded world's (it opened with 20 minutes and the clock running, another hash).
TEST_F(Recordings, AWorldsDayComesBackWithItAndAFlagOverridesIt) {
    const auto options = [&](std::vector<std::string> flags) {
        flags.insert(flags.begin(),
                     {"minecrappy", "--headless", "--settings", "none", "--world", file("w.mcworld").string()});
        std::vector<const char*> argv;
        argv.reserve(flags.size());
        for (const auto& f : flags) argv.push_back(f.c_str());
        auto parsed = session::parseOptions(static_cast<int>(argv.size()), argv.data());
        EXPECT_TRUE(parsed.options.has_value()) << parsed.output;
        return *parsed.options;
    };
    std::uint64_t saved = 0;
    {
        session::Session s(options({"--day-length", "5", "--day-cycle", "false", "--time-of-day", "17"}));
        for (int t = 0; t < 30; ++t) s.step();
        ASSERT_TRUE(s.saveNow().empty());
        saved = game::stateHash(s.state());
        ASSERT_EQ(s.state().day.dayMinutes, 5.0); // precondition: the flags made the day
        ASSERT_TRUE(s.state().day.stopped);
    }
    {
        session::Session s(options({}));
        EXPECT_EQ(s.state().day.dayMinutes, 5.0);
        EXPECT_TRUE(s.state().day.stopped);
        EXPECT_EQ(game::stateHash(s.state()), saved);
        EXPECT_EQ(s.options().settings.dayLengthMinutes, 5.0f); // what the settings panel shows
        EXPECT_FALSE(s.options().settings.dayCycle);
    }
    {
        session::Session s(options({"--day-length", "7"}));
        EXPECT_EQ(s.state().day.dayMinutes, 7.0);
        EXPECT_TRUE(s.state().day.stopped); // the flag given wins, the other is the world's
    }
    std::vector<std::uint64_t> live;
    {
        session::Options o = options({});
        o.record = file("day.mcscript").string();
        session::Session s(o);
        for (int t = 0; t < 20; ++t) {
            s.step();
            live.push_back(game::stateHash(s.state()));
        }
    }
    EXPECT_NE(read("day.mcscript").find("# day_length 5.0\n"), std::string::npos) << read("day.mcscript");
    EXPECT_EQ(run("day.mcscript", "", 20), live);
}

// In a replay the recording's header holds the day; the settings panel's day length changes the replayed world's
// day like any edit the recording lacks, and the replay stops at the next hash line (CAPTURE.md says so). The
// wrong implementation this catches: a panel whose day never reaches a replayed world (tried). Dropping the day
// length from the hash alone is not caught: the hour it moves differently is hashed too.
TEST_F(Recordings, APanelDayLengthInAReplayStopsItAtTheNextHash) {
    write("walk.txt", kScript);
    run("walk.txt", "rec.mcscript", 40);
    session::Options o;
    o.headless = true;
    o.settingsFile.reset();
    o.script = file("rec.mcscript").string();
    session::Session s(o);
    s.step();
    session::Settings changed = s.options().settings;
    changed.dayLengthMinutes *= 2.0f;
    ASSERT_TRUE(s.applySettings(changed).empty()); // precondition: nothing kept (no recording runs)
    ASSERT_EQ(s.state().day.dayMinutes, static_cast<double>(changed.dayLengthMinutes));
    try {
        for (int t = 1; t < 40; ++t) s.step();
        FAIL() << "the replay ran on with another day";
    } catch (const session::ReplayDiverged& e) {
        EXPECT_EQ(e.tick(), 10u) << e.what();
    }
}

TEST(RecordingVersions, CompareNumberByNumber) {
    EXPECT_LT(session::compareVersions("0.9.9", "0.10.0"), 0);
    EXPECT_EQ(session::compareVersions("0.1.0", "0.1.0"), 0);
    EXPECT_GT(session::compareVersions("1.0", "0.99.99"), 0);
}

} // namespace
