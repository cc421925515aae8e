// Keyframes and seeking (session/keyframes.h, game/state_image.h): a seek to any tick, forward or backward,
// reaches the state a straight run has at that tick, in the state hash and in everything the hash leaves out
// (the panels' traces, what is drawn between ticks, each ball's last figures), at several tick rates, with
// keyframes dropped by a small budget, in a replay of a recording; and a restored world keeps its World.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "core/hash.h"
#include "game/command_text.h"
#include "game/state_image.h"
#include "game/state_io.h"
#include "input/script.h"
#include "session/keyframe_file.h"
#include "session/keyframes.h"
#include "session/options.h"
#include "session/session.h"
#include "session/timeline.h"

namespace {

namespace fs = std::filesystem;

// What the state hash leaves out but a restored keyframe must bring back too.
std::uint64_t extrasDigest(const game::GameState& s) {
    core::Hasher h;
    h.add(s.def.hairDetail), h.add(s.def.hairBudget), h.add(s.tickSeconds);
    for (const glm::vec3& v : {s.previousPlayer.position, s.previousPlayer.velocity})
        h.add(v.x), h.add(v.y), h.add(v.z);
    h.add(s.previousPlayer.yaw), h.add(s.previousPlayer.pitch);
    h.add(s.carriedBall ? static_cast<std::uint64_t>(*s.carriedBall) : ~std::uint64_t{0});
    for (const game::PendulumSet& set : s.pendulumSets) {
        const game::PendulumTrace& t = set.trace();
        h.add(static_cast<std::uint64_t>(t.head)), h.add(static_cast<std::uint64_t>(t.size));
        const auto floats = [&](const std::vector<float>& v) { h.bytes(v.data(), v.size() * sizeof(float)); };
        floats(t.time), floats(t.exactTheta);
        for (int k = 0; k < game::kPendulumSlots; ++k) floats(t.theta[k]), floats(t.energyError[k]);
        for (int k = 0; k < game::kPendulumSlots; ++k) h.add(set.evaluationsPerSecond(k)); // the cost column
    }
    for (const game::HairBall& b : s.hairBalls) {
        const physics::HairStepStats& st = b.lastStats();
        h.add(st.maxSegmentError), h.add(st.maxPenetration), h.add(st.maxNodeMove), h.add(st.restWindowMove);
        h.add(st.substeps), h.add(st.nan);
        h.add(b.previousCentre().x), h.add(b.previousCentre().y), h.add(b.previousCentre().z);
    }
    return h.value();
}

class Keyframes : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_dir = fs::temp_directory_path() / ("mc_keyframes_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }
    fs::path file(const std::string& name) const { return m_dir / name; }

    // A session of the demo scene that carries a ball and walks with it (a key held for 50 ticks), puts it down,
    // places a lamp and a brick and breaks one, turns a ball's host collision off, changes a pendulum set and
    // the time, and holds W over 160 ticks; hair detail at a half.
    std::string scenario() const {
        glm::vec3 centre;
        {
            const session::Session probe(options(60));
            centre = probe.state().hairBalls.at(0).centre();
        }
        const glm::vec3 feet = centre + glm::vec3(0.0f, -1.62f, 2.5f);
        std::ostringstream s;
        s << "0 teleport " << feet.x << " " << feet.y << " " << feet.z << "\n0 look 0 0\n"
          << "5 key Q down\n6 key Q up\n10 key D down\n60 key D up\n70 key Q down\n71 key Q up\n"
          << "75 look 180 -60\n76 key 6 down\n77 key 6 up\n80 mouse_button right down\n81 mouse_button right up\n"
          << "90 key 7 down\n91 key 7 up\n95 mouse_button right down\n96 mouse_button right up\n"
          << "100 mouse_button left down\n101 mouse_button left up\n"
          << "110 hair 1 host_collision=false\n"
          << "120 pendulum 0 set release=75 length=1.25 methods=verlet,rk4,dopri5,exact\n121 pendulum 0 release\n"
          << "130 time 18.25\n140 key W down\n300 key W up\n";
        const fs::path path = file("scenario.txt");
        std::ofstream(path) << s.str();
        return path.string();
    }
    static session::Options options(int tickRate) {
        session::Options o;
        o.headless = true;
        o.settingsFile.reset();
        o.settings.tickRate = tickRate;
        o.settings.hairDetail = 1;
        return o;
    }
    struct Straight {
        std::vector<std::uint64_t> hash, extras; // of the state at tick t (index t)
        bool carried = false, lamp = false, held = false;
    };
    static Straight straight(const session::Options& o, std::uint64_t ticks) {
        session::Session s(o);
        Straight out;
        out.hash.push_back(game::stateHash(s.state()));
        out.extras.push_back(extrasDigest(s.state()));
        for (std::uint64_t t = 0; t < ticks; ++t) {
            s.step();
            out.hash.push_back(game::stateHash(s.state()));
            out.extras.push_back(extrasDigest(s.state()));
            out.carried = out.carried || s.state().carriedBall.has_value();
            for (const world::BlockEdit& e : s.state().world.edits())
                out.lamp = out.lamp || e.block == world::BlockType::Lamp;
            out.held = out.held || (t > 150 && t < 290 && glm::length(s.state().player.velocity) > 1.0f);
        }
        return out;
    }

    fs::path m_dir;
};

// Random seeks, forward and backward, against a straight run at 30, 60 and 144 ticks a second, the second time
// with a budget of three keyframes (the spacing doubles and keyframes are dropped). Mutations caught: a restore
// that leaves the edits (or the carried ball, a trace, the held keys, the ball's stats) as they were.
TEST_F(Keyframes, ASeekReachesTheStraightRunsStateAtEveryTickRate) {
    const std::string script = scenario();
    constexpr std::uint64_t kTicks = 360;
    for (const int rate : {30, 60, 144}) {
        session::Options o = options(rate);
        o.script = script;
        const Straight ref = straight(o, kTicks);
        ASSERT_TRUE(ref.carried && ref.lamp && ref.held) << "precondition: the scenario carries, places a lamp, walks";
        for (const bool small : {false, true}) {
            session::Session s(o);
            s.keepKeyframes(16, small ? std::size_t{1} << 40 : session::KeyframeStore::kDefaultBudget);
            if (small) {
                // Three keyframes' worth of the first one: the store must drop some.
                s.keepKeyframes(16, 3 * s.keyframes()->bytes());
            }
            std::mt19937_64 rng(static_cast<std::uint64_t>(rate) * 7 + small);
            std::vector<std::uint64_t> targets{kTicks, 5, 200, 199, 17, 300};
            for (int i = 0; i < 14; ++i) targets.push_back(rng() % (kTicks + 1));
            for (const std::uint64_t t : targets) {
                s.seek(t);
                ASSERT_EQ(s.state().tick, t);
                ASSERT_EQ(game::stateHash(s.state()), ref.hash[t]) << rate << " Hz, tick " << t << " small " << small;
                ASSERT_EQ(extrasDigest(s.state()), ref.extras[t]) << rate << " Hz, tick " << t << " small " << small;
            }
            if (small) {
                EXPECT_GT(s.keyframes()->interval(), 16u) << "precondition: the small budget dropped keyframes";
                EXPECT_LE(s.keyframes()->bytes(), s.keyframes()->budget());
            }
        }
    }
}

// A seek keeps the World (a renderer's meshes stay) and bumps only the chunks whose blocks differ.
TEST_F(Keyframes, ASeekKeepsTheWorldAndBumpsOnlyTheEditedChunks) {
    session::Options o = options(60);
    o.script = scenario();
    session::Session s(o);
    s.keepKeyframes(16, session::KeyframeStore::kDefaultBudget);
    s.seek(360);
    ASSERT_GT(s.state().world.editCount(), 0u); // precondition: edits to take back
    const std::uint64_t identity = s.state().world.identity();
    const auto far = world::ChunkCoord{40, 1, 40};
    const world::ChunkCoord near = world::chunkOf(s.state().world.edits().front().pos);
    const std::uint64_t farRevision = s.state().world.chunkRevision(far);
    const std::uint64_t nearRevision = s.state().world.chunkRevision(near);
    s.seek(20);
    EXPECT_EQ(s.state().world.identity(), identity);
    EXPECT_EQ(s.state().world.editCount(), 0u);
    EXPECT_EQ(s.state().world.chunkRevision(far), farRevision);
    EXPECT_GT(s.state().world.chunkRevision(near), nearRevision) << "the edited chunk is bumped, to be remeshed";
}

// What a seek refuses: past a replay's end (naming its last tick), behind the state in a script without keyframes
// (a replay goes back to its start), while recording;
// and a keyframe interval of 0 or a budget below one keyframe (naming the value).
TEST_F(Keyframes, BadSeeksAndSettingsAreRefusedNamingTheValue) {
    session::Options o = options(60);
    o.script = scenario();
    o.record = file("rec.mcscript").string();
    {
        session::Session s(o);
        for (int t = 0; t < 40; ++t) s.step();
        EXPECT_THROW(s.seek(10), session::SeekError); // recording
        s.finishRecording();
    }
    session::Options r = options(60);
    r.script = file("rec.mcscript").string();
    session::Session s(r);
    try {
        s.seek(41);
        ADD_FAILURE() << "a seek past the end was made";
    } catch (const session::SeekError& e) {
        EXPECT_NE(std::string(e.what()).find("rec.mcscript, 40"), std::string::npos) << e.what();
    }
    EXPECT_THROW(s.seekToward(41, 1.0), session::SeekError) << "a seek in slices checks the end too";
    EXPECT_EQ(s.state().tick, 0u);
    s.seek(30);
    s.seek(3); // a replay keeps no keyframes here, but its start: the seek restores it
    ASSERT_TRUE(s.lastRestore());
    EXPECT_STREQ(s.lastRestore()->source, "the start world");
    {
        session::Options plain = options(60); // a script that is no recording has no start to go back to
        plain.script = o.script;
        session::Session p(plain);
        p.seek(30);
        try {
            p.seek(3);
            ADD_FAILURE() << "a seek behind the state without keyframes was made";
        } catch (const session::SeekError& e) {
            EXPECT_NE(std::string(e.what()).find("tick 3 is behind"), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(s.keepKeyframes(0, 1 << 20), std::invalid_argument);
    try {
        s.keepKeyframes(10, 1000);
        ADD_FAILURE() << "a budget of 1000 bytes held a keyframe";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("budget of 1000 bytes"), std::string::npos) << e.what();
    }
    // In a replay the recording's hashes are checked on the way: a seek back and forth reaches its end.
    s.keepKeyframes(8, session::KeyframeStore::kDefaultBudget);
    s.seek(40);
    s.seek(33);
    s.seek(40);
    EXPECT_EQ(s.state().tick, 40u);
}

// Sleeping balls share their image between keyframes; awake ones do not. The share is what keeps a long session's
// keyframes within the budget (a default ball's hair is about 221 KB).
TEST_F(Keyframes, ASleepingBallsHairIsSharedBetweenKeyframes) {
    session::Options o = options(60);
    session::Session s(o);
    s.keepKeyframes(30, session::KeyframeStore::kDefaultBudget);
    s.seek(1800); // half a minute: the still balls fall asleep
    const auto& frames = s.keyframes()->frames();
    const auto last = std::prev(frames.end()), before = std::prev(last);
    int shared = 0, asleep = 0;
    for (std::size_t i = 0; i < s.state().hairBalls.size(); ++i) {
        const bool sleeping = last->second.state.hairBalls[i].image->hair.sleeping;
        asleep += sleeping;
        const bool same = last->second.state.hairBalls[i].image == before->second.state.hairBalls[i].image;
        shared += same;
        if (same) {
            EXPECT_TRUE(sleeping) << "ball " << i << " shared while awake";
        }
    }
    ASSERT_GT(asleep, 0) << "precondition: a demo ball sleeps after half a minute";
    EXPECT_EQ(shared, asleep);
}

// The timeline over a recording of the scenario (session/timeline.h): played forwards and backwards at 1x and 8x,
// stepped a tick back and forth and jumped to its marks, every tick it shows is the straight run's state; its
// marks are the recording's edits. Mutations caught: playing that ignores the direction (8x "backwards" goes on
// forwards), marks at the line's tick rather than the tick that shows it.
TEST_F(Keyframes, TheTimelineShowsTheStraightRunsStateAtEveryTickItReaches) {
    session::Options o = options(60);
    o.script = scenario();
    o.record = file("rec.mcscript").string();
    const Straight ref = straight(o, 360); // records it
    session::Options r = options(60);
    r.script = o.record;
    r.replay = true;
    session::Session s(r);
    session::Timeline t(s, 16, session::KeyframeStore::kDefaultBudget);
    ASSERT_EQ(t.lastTick(), 360u);
    const auto shows = [&](const char* what) {
        ASSERT_LE(s.state().tick, 360u);
        ASSERT_EQ(t.hash(), ref.hash[s.state().tick]) << what << " at tick " << s.state().tick;
        ASSERT_EQ(extrasDigest(s.state()), ref.extras[s.state().tick]) << what << " at tick " << s.state().tick;
    };
    t.togglePlay();
    std::vector<std::uint64_t> seen;
    for (int frame = 0; frame < 200 && t.playing(); ++frame) { // 1x forwards: 60 ticks a second
        t.advance(1.0 / 60.0);
        shows("playing");
        seen.push_back(t.tick());
    }
    EXPECT_EQ(seen.back(), 200u);
    ASSERT_TRUE(t.playing());
    t.togglePlay(); // pause
    t.reverse();
    for (int i = 0; i < 4; ++i) t.faster(); // 8x backwards
    EXPECT_EQ(t.speed(), -8.0);
    t.togglePlay();
    std::uint64_t frames = 0, last = t.tick();
    while (t.playing() && frames < 200) {
        t.advance(1.0 / 60.0);
        shows("playing backwards");
        EXPECT_LE(t.tick(), last);
        last = t.tick();
        ++frames;
    }
    EXPECT_EQ(t.tick(), 0u) << "8x backwards stops at the start";
    t.jumpTo(250);
    while (t.catchingUp()) t.advance(0.0);
    shows("a jump");
    for (int i = 0; i < 5; ++i) {
        t.step(-1);
        while (t.catchingUp()) t.advance(0.0);
        shows("a tick back");
    }
    EXPECT_EQ(t.tick(), 245u);
    // The marks: the hair, pendulum and time lines (applied in the step from their tick: shown from the next).
    std::vector<std::uint64_t> edits;
    for (const auto& m : t.marks())
        if (m.kind != session::Timeline::MarkKind::Build && m.kind != session::Timeline::MarkKind::Carry)
            edits.push_back(m.tick);
    EXPECT_EQ(edits, (std::vector<std::uint64_t>{111, 121, 122, 131}));
    t.jumpTo(0);
    t.nextMark();
    while (t.catchingUp()) t.advance(0.0);
    EXPECT_EQ(t.tick(), t.marks().front().tick);
    shows("the first mark");
}

// Taking over at tick 150 and giving the recording's own inputs from there gives the recording's states; with
// --record the new recording starts at 150 and replays to them.
TEST_F(Keyframes, ATakeOverFollowedByTheSameInputsIsTheOriginal) {
    session::Options o = options(60);
    o.script = scenario();
    o.record = file("rec.mcscript").string();
    const Straight ref = straight(o, 360);
    session::Options r = options(60);
    r.script = o.record;
    r.replay = true;
    r.headless = false; // the window's timeline: records only from a take-over
    r.record = file("taken.mcscript").string();
    {
        session::Session s(r);
        const std::vector<input::ScriptEvent> lines = s.script();
        session::Timeline t(s, 16, session::KeyframeStore::kDefaultBudget);
        t.jumpTo(300);
        while (t.catchingUp()) t.advance(0.0);
        t.jumpTo(150); // back: from a keyframe
        while (t.catchingUp()) t.advance(0.0);
        t.takeOver();
        ASSERT_FALSE(t.active());
        EXPECT_FALSE(s.replayEndTick()) << "the session left the replay";
        EXPECT_EQ(s.keyframes(), nullptr) << "live play keeps no keyframes";
        for (std::uint64_t tick = 150; tick < 360; ++tick) {
            for (const input::ScriptEvent& e : lines) {
                if (e.tick != tick) continue;
                if (!e.edit) {
                    s.mapper().handle(e.event);
                } else if (e.edit->object == "time") {
                    s.queueTimeOfDay(game::parseHours(e.edit->words.at(0)));
                } else if (e.edit->object == "pendulum") {
                    s.queue(
                        std::vector<game::PendulumCommand>{game::pendulumCommandFrom(e.edit->index, e.edit->words)});
                } else {
                    s.queue(std::vector<game::HairCommand>{game::hairCommandFrom(e.edit->index, e.edit->words)});
                }
            }
            s.step();
            ASSERT_EQ(game::stateHash(s.state()), ref.hash[tick + 1]) << "tick " << tick + 1;
        }
        s.finishRecording();
    }
    session::Options again = options(60);
    again.script = file("taken.mcscript").string();
    session::Session replayed(again);
    ASSERT_EQ(replayed.state().tick, 150u) << "the new recording starts at the take-over";
    ASSERT_EQ(replayed.replayEndTick(), std::optional<std::uint64_t>(360));
    replayed.seek(360); // its hashes checked on the way
    EXPECT_EQ(game::stateHash(replayed.state()), ref.hash[360]);
}

// A recording with a tampered line: the timeline stops where the replay leaves it (the next hash line), shows the
// tick and the message, goes no further, and can still go back. Mutation caught: the divergence not caught (the
// exception leaves the timeline, as it ends the game headless).
TEST_F(Keyframes, TheTimelineStopsWhereAReplayLeavesTheRecording) {
    session::Options o = options(60);
    o.script = scenario();
    o.record = file("rec.mcscript").string();
    const Straight ref = straight(o, 360);
    std::string text;
    {
        std::ifstream in(o.record);
        std::stringstream b;
        b << in.rdbuf();
        text = b.str();
    }
    const std::size_t at = text.find("\n200 act ");
    ASSERT_NE(at, std::string::npos) << "precondition: the walk has a line at tick 200";
    text.insert(text.find('\n', at + 1), " yaw=20");
    std::ofstream(file("tampered.mcscript")) << text;
    session::Options r = options(60);
    r.script = file("tampered.mcscript").string();
    r.replay = true;
    session::Session s(r);
    session::Timeline t(s, 16, session::KeyframeStore::kDefaultBudget);
    t.jumpTo(300);
    while (t.catchingUp()) t.advance(0.0);
    ASSERT_TRUE(t.divergedAt());
    EXPECT_EQ(*t.divergedAt(), 210u);
    EXPECT_EQ(t.tick(), 210u);
    EXPECT_NE(t.divergence().find("at tick 210"), std::string::npos) << t.divergence();
    t.jumpTo(300);
    EXPECT_EQ(t.target(), 210u) << "nothing past the divergence";
    t.jumpTo(150);
    while (t.catchingUp()) t.advance(0.0);
    EXPECT_EQ(t.hash(), ref.hash[150]) << "before it, the recording's states";
}

// The keyframe file beside a recording (session/keyframe_file.h), every 50 ticks, at 30, 60 and 144 Hz: a replay's
// seeks to random ticks, forward and backward, restore from it (the first keyframe holds the carried ball, the later
// ones host_collision off and W held; hair detail is a half) and reach the straight run's state, hash and extras.
// Mutations caught: a trace or the pendulums' evaluation counts left out of the file (extras differ); the held input
// not rebuilt for a file keyframe (the script's next event from 0: the replay diverges); the file's serials kept.
TEST_F(Keyframes, FileKeyframesSeekToTheStraightRunsStateAtEveryTickRate) {
    const std::string script = scenario();
    constexpr std::uint64_t kTicks = 360;
    for (const int rate : {30, 60, 144}) {
        session::Options o = options(rate);
        o.script = script;
        o.record = file("rec" + std::to_string(rate) + ".mcscript").string();
        o.settings.keyframeFileInterval = 45; // rounded up to 50
        const Straight ref = straight(o, kTicks);
        ASSERT_TRUE(ref.carried && ref.lamp && ref.held) << "precondition: the scenario carries, places a lamp, walks";
        session::Options r = options(rate);
        r.script = o.record;
        r.replay = true;
        const std::uint64_t before = game::newBallSerial(); // every ball of the recording had a smaller one
        session::Session s(r);
        ASSERT_EQ(s.fileKeyframes().size(), 7u) << "precondition: ticks 50 to 350 in the file";
        EXPECT_TRUE(s.keyframeWarnings().empty());
        // Serials mean something only in the process that wrote the file: each is given a new one, so a file's ball
        // is never taken for a ball of this process that happens to have its serial and generation.
        for (const auto& [tick, k] : s.fileKeyframes())
            for (const game::StateImage::Ball& b : k.image.hairBalls) EXPECT_GT(b.serial, before) << tick;
        EXPECT_TRUE(s.fileKeyframes().begin()->second.image.carriedBall) << "precondition: tick 50 carries a ball";
        std::mt19937_64 rng(static_cast<std::uint64_t>(rate));
        std::vector<std::uint64_t> targets{349, 50, 351, 120, 299, 7};
        for (int i = 0; i < 10; ++i) targets.push_back(rng() % (kTicks + 1));
        int fromFile = 0;
        for (const std::uint64_t t : targets) {
            s.seek(t);
            ASSERT_EQ(s.state().tick, t);
            fromFile += s.lastRestore() && std::string(s.lastRestore()->source) == "the keyframe file";
            ASSERT_EQ(game::stateHash(s.state()), ref.hash[t]) << rate << " Hz, tick " << t;
            ASSERT_EQ(extrasDigest(s.state()), ref.extras[t]) << rate << " Hz, tick " << t;
        }
        EXPECT_GE(fromFile, 5) << "precondition: the seeks restored from the file";
    }
}

// A keyframe file's damage: a flipped byte (the checksum tells), a changed player with its checksum made right
// again (the restored state's hash tells), a keyframe file of another recording, a file cut short. Each is named
// in a warning, and the seek goes from an earlier keyframe to the straight run's state. Mutations caught: the
// checksum not compared (the flipped byte is read), the restored hash not checked (the seek lands elsewhere).
TEST_F(Keyframes, ADamagedKeyframeIsLeftOutWithAWarningAndTheSeekGoesAroundIt) {
    session::Options o = options(60);
    o.script = scenario();
    o.record = file("rec.mcscript").string();
    o.settings.keyframeFileInterval = 50;
    const Straight ref = straight(o, 360);
    const fs::path keys = session::keyframeFilePath(o.record);
    std::string bytes;
    {
        std::ifstream in(keys, std::ios::binary);
        std::stringstream b;
        b << in.rdbuf();
        bytes = b.str();
    }
    struct Entry {
        std::uint64_t tick;
        std::size_t at, length; // the entry's header and its payload's length
    };
    std::vector<Entry> entries;
    for (std::size_t at = 24; at < bytes.size();) {
        std::uint64_t head[4];
        std::memcpy(head, bytes.data() + at, sizeof head);
        entries.push_back({head[0], at, head[2]});
        at += 32 + head[2];
    }
    ASSERT_EQ(entries.size(), 7u) << "precondition: keyframes at ticks 50 to 350";
    const auto replay = [&](const std::string& keyBytes) {
        std::ofstream(keys, std::ios::binary) << keyBytes;
        session::Options r = options(60);
        r.script = o.record;
        r.replay = true;
        return std::make_unique<session::Session>(r);
    };
    const auto mentions = [](const std::vector<std::string>& warnings, const std::string& what) {
        for (const std::string& w : warnings)
            if (w.find(what) != std::string::npos) return true;
        return false;
    };
    { // tick 200: a byte of its payload flipped
        std::string damaged = bytes;
        damaged[entries[3].at + 32 + entries[3].length / 2] ^= 0x40;
        auto s = replay(damaged);
        EXPECT_TRUE(mentions(s->keyframeWarnings(), "tick 200 is damaged"))
            << ::testing::PrintToString(s->keyframeWarnings());
        EXPECT_EQ(s->fileKeyframes().count(200), 0u);
        s->seek(230);
        ASSERT_TRUE(s->lastRestore());
        EXPECT_EQ(s->lastRestore()->tick, 150u);
        EXPECT_EQ(game::stateHash(s->state()), ref.hash[230]);
        EXPECT_EQ(extrasDigest(s->state()), ref.extras[230]);
    }
    { // tick 300: the player moved a metre east, the checksum made to match
        std::string damaged = bytes;
        const std::size_t payload = entries[5].at + 32, x = payload + 8 + 1 + 8 + 8 + 1; // tick, paused, day: player.x
        float px;
        std::memcpy(&px, damaged.data() + x, sizeof px);
        px += 1.0f;
        std::memcpy(damaged.data() + x, &px, sizeof px);
        core::Hasher h;
        h.bytes(damaged.data() + payload, entries[5].length);
        const std::uint64_t sum = h.value();
        std::memcpy(damaged.data() + entries[5].at + 24, &sum, sizeof sum);
        auto s = replay(damaged);
        ASSERT_EQ(s->fileKeyframes().count(300), 1u) << "precondition: its checksum passes";
        s->seek(320);
        EXPECT_TRUE(mentions(s->keyframeWarnings(), "tick 300 cannot be restored"))
            << ::testing::PrintToString(s->keyframeWarnings());
        ASSERT_TRUE(s->lastRestore());
        EXPECT_EQ(s->lastRestore()->tick, 250u);
        EXPECT_EQ(game::stateHash(s->state()), ref.hash[320]);
        EXPECT_EQ(extrasDigest(s->state()), ref.extras[320]);
    }
    { // cut short in the keyframe of tick 250: the ones before it are kept
        auto s = replay(bytes.substr(0, entries[4].at + 100));
        EXPECT_TRUE(mentions(s->keyframeWarnings(), "cut short or damaged"))
            << ::testing::PrintToString(s->keyframeWarnings());
        EXPECT_EQ(s->fileKeyframes().size(), 4u);
        s->seek(340);
        EXPECT_EQ(s->lastRestore()->tick, 200u);
        EXPECT_EQ(game::stateHash(s->state()), ref.hash[340]);
    }
    { // the keyframes of another recording (the same scenario without the time change): none is used
        std::string text;
        {
            std::ifstream in(o.script);
            std::stringstream b;
            b << in.rdbuf();
            text = b.str();
        }
        text.erase(text.find("130 time 18.25\n"), 15);
        std::ofstream(file("other.txt")) << text;
        session::Options other = o;
        other.script = file("other.txt").string();
        other.record = file("other.mcscript").string();
        (void)straight(other, 360);
        std::ifstream in(session::keyframeFilePath(other.record), std::ios::binary);
        std::stringstream b;
        b << in.rdbuf();
        auto s = replay(b.str());
        EXPECT_TRUE(mentions(s->keyframeWarnings(), "is not of this recording"))
            << ::testing::PrintToString(s->keyframeWarnings());
        EXPECT_LT(s->fileKeyframes().size(), 3u) << "only those before the time change can be this recording's";
        s->seek(350);
        EXPECT_EQ(game::stateHash(s->state()), ref.hash[350]);
    }
}

// A keyframe budget below one keyframe of the replay is refused before the first tick, naming the value (the
// program exits with 2); a larger one is taken. The start world holds ten balls: one keyframe is 2.1 MiB.
TEST_F(Keyframes, ABudgetBelowOneKeyframeOfTheReplayIsRefused) {
    session::Options w = options(60);
    w.world = file("balls.mcworld").string();
    {
        session::Session s(w);
        const glm::vec3 at = s.state().player.position;
        for (int i = 0; i < 7; ++i)
            s.state().hairBalls.emplace_back(at + glm::vec3(4.0f * static_cast<float>(i) - 12.0f, 12.0f, -8.0f),
                                             game::HairBallDef{});
        ASSERT_TRUE(s.saveNow().empty());
    }
    session::Options o = w;
    o.record = file("rec.mcscript").string();
    {
        session::Session s(o);
        ASSERT_EQ(s.state().hairBalls.size(), 10u) << "precondition: the world's ten balls";
        s.step();
    }
    session::Options r = options(60);
    r.script = o.record;
    r.replay = true;
    r.settings.keyframeBudgetMiB = 2;
    try {
        session::Session s(r);
        ADD_FAILURE() << "a budget of 2 MiB held a keyframe of ten balls";
    } catch (const session::SeekError& e) {
        std::printf("%s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("--keyframe-budget 2: one keyframe of"), std::string::npos) << e.what();
    }
    r.settings.keyframeBudgetMiB = 3;
    EXPECT_NO_THROW(session::Session{r});
}

// Worlds > Recordings > Play (Session::openReplay): a file that is no recording is refused and the session goes on as
// it was (its state, its world); a recording turns the session into its replay (the world played so far saved
// first), which seeks to the recording's end state. Mutation caught: the world let go before the replay is read (a
// refused file would leave the session without its world).
TEST_F(Keyframes, ARecordingOpenedFromTheMenuReplaysAndABadOneChangesNothing) {
    session::Options o = options(60);
    o.script = scenario();
    o.record = file("rec.mcscript").string();
    const Straight ref = straight(o, 200);
    session::Options live = options(60);
    live.world = file("live.mcworld").string();
    session::Session s(live);
    for (int t = 0; t < 30; ++t) s.step();
    const std::uint64_t before = game::stateHash(s.state());
    EXPECT_THROW(s.openReplay(o.script), input::ScriptError); // a script, not a recording
    EXPECT_EQ(game::stateHash(s.state()), before);
    ASSERT_TRUE(s.hasWorld());
    EXPECT_FALSE(s.replayEndTick());
    s.openReplay(o.record);
    EXPECT_FALSE(s.hasWorld());
    ASSERT_TRUE(s.replayEndTick());
    EXPECT_EQ(*s.replayEndTick(), 200u);
    EXPECT_EQ(game::stateHash(s.state()), ref.hash[0]);
    s.seek(200);
    EXPECT_EQ(game::stateHash(s.state()), ref.hash[200]);
    session::Options reopen = options(60);
    reopen.world = live.world;
    const session::Session saved(reopen);
    EXPECT_EQ(saved.state().tick, 30u) << "the world played before the replay was saved";
}

// A ball whose hair falls asleep again in the step that woke it (a sleep delay of 0) has changed: its generation
// must say so, or a keyframe would share the image of before (found by review). Mutation caught: the generation
// bumped only when the solver's sleeping flag changed.
TEST(HairBallGeneration, AStepThatWakesAndSleepsAgainCounts) {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    game::GameState s(def);
    game::HairBallDef ball;
    ball.hair.sleepDelay = 0.0f;
    const glm::vec3 centre(0.5f, 34.5f, 0.5f);
    s.hairBalls.emplace_back(centre, ball);
    int t = 0;
    while (!s.hairBalls[0].solver().sleeping() && t < 3000) game::tick(s, {}, 1.0 / 60.0), ++t;
    ASSERT_TRUE(s.hairBalls[0].solver().sleeping()) << "precondition: the ball falls asleep";
    const std::uint64_t generation = s.hairBalls[0].generation(), hair = s.hairBalls[0].solver().hashState();
    s.world.set(glm::ivec3(1, 33, 0), world::BlockType::Stone); // in the hair's reach: it wakes
    game::tick(s, {}, 1.0 / 60.0);
    ASSERT_NE(s.hairBalls[0].solver().hashState(), hair) << "precondition: the step moved the hair";
    EXPECT_NE(s.hairBalls[0].generation(), generation);
}

} // namespace
