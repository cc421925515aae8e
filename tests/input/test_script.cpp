#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "input/keys.h"
#include "input/script.h"

namespace {

using input::parseScript;
using input::ScriptError;
using input::ScriptEvent;

// The message of the ScriptError that parsing `text` throws, or "" if it parses.
std::string errorOf(const std::string& text, const std::string& fileName = "walk.txt") {
    try {
        parseScript(text, fileName);
    } catch (const ScriptError& e) {
        return e.what();
    }
    return "";
}

// The message of the ScriptError that loading the file `path` throws; a test failure, and "", when it loads.
std::string loadErrorOf(const std::string& path) {
    try {
        input::loadScript(path);
    } catch (const ScriptError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected ScriptError";
    return "";
}

template <typename T>
const T& single(const std::vector<ScriptEvent>& events) {
    EXPECT_EQ(events.size(), 1u);
    return std::get<T>(events.at(0).event);
}

TEST(Script, EveryCommandParses) {
    const auto events = parseScript("0 key W down\n"
                                    "1 key LEFT_SHIFT up\n"
                                    "2 mouse_move 12.5 -3\n"
                                    "3 mouse_button left down\n"
                                    "4 mouse_button right up\n"
                                    "5 mouse_button middle down\n"
                                    "6 scroll -2\n"
                                    "7 gamepad_axis left_y -0.75\n"
                                    "8 gamepad_axis right_trigger 1\n"
                                    "9 gamepad_button dpad_left down\n"
                                    "10 gamepad_button start up\n"
                                    "11 teleport 1.5 -64 1e3\n"
                                    "12 look -45 89.5\n",
                                    "all.txt");
    ASSERT_EQ(events.size(), 13u);
    for (std::size_t i = 0; i < events.size(); ++i) {
        EXPECT_EQ(events[i].tick, i);
        EXPECT_EQ(events[i].line, static_cast<int>(i) + 1);
    }
    const auto& k0 = std::get<input::KeyEvent>(events[0].event);
    EXPECT_EQ(k0.key, input::key::W);
    EXPECT_TRUE(k0.down);
    const auto& k1 = std::get<input::KeyEvent>(events[1].event);
    EXPECT_EQ(k1.key, input::key::LeftShift);
    EXPECT_FALSE(k1.down);
    const auto& mm = std::get<input::MouseMoveEvent>(events[2].event);
    EXPECT_EQ(mm.dx, 12.5f);
    EXPECT_EQ(mm.dy, -3.0f);
    EXPECT_EQ(std::get<input::MouseButtonEvent>(events[3].event).button, input::MouseButton::Left);
    EXPECT_TRUE(std::get<input::MouseButtonEvent>(events[3].event).down);
    EXPECT_EQ(std::get<input::MouseButtonEvent>(events[4].event).button, input::MouseButton::Right);
    EXPECT_FALSE(std::get<input::MouseButtonEvent>(events[4].event).down);
    EXPECT_EQ(std::get<input::MouseButtonEvent>(events[5].event).button, input::MouseButton::Middle);
    EXPECT_EQ(std::get<input::ScrollEvent>(events[6].event).dy, -2.0f);
    const auto& ax = std::get<input::GamepadAxisEvent>(events[7].event);
    EXPECT_EQ(ax.axis, input::GamepadAxis::LeftY);
    EXPECT_EQ(ax.value, -0.75f);
    EXPECT_EQ(std::get<input::GamepadAxisEvent>(events[8].event).axis, input::GamepadAxis::RightTrigger);
    EXPECT_EQ(std::get<input::GamepadAxisEvent>(events[8].event).value, 1.0f);
    const auto& gb = std::get<input::GamepadButtonEvent>(events[9].event);
    EXPECT_EQ(gb.button, input::GamepadButton::DpadLeft);
    EXPECT_TRUE(gb.down);
    EXPECT_EQ(std::get<input::GamepadButtonEvent>(events[10].event).button, input::GamepadButton::Start);
    EXPECT_FALSE(std::get<input::GamepadButtonEvent>(events[10].event).down);
    const auto& tp = std::get<input::TeleportEvent>(events[11].event);
    EXPECT_EQ(tp.position, glm::vec3(1.5f, -64.0f, 1000.0f));
    const auto& lk = std::get<input::LookEvent>(events[12].event);
    EXPECT_EQ(lk.yawDeg, -45.0f);
    EXPECT_EQ(lk.pitchDeg, 89.5f);
}

TEST(Script, AllGamepadNamesParse) {
    for (const char* axis : {"left_x", "left_y", "right_x", "right_y", "left_trigger", "right_trigger"})
        EXPECT_EQ(errorOf(std::string("0 gamepad_axis ") + axis + " 0"), "") << axis;
    int index = 0;
    for (const char* button : {"a", "b", "x", "y", "left_bumper", "right_bumper", "back", "start", "guide",
                               "left_thumb", "right_thumb", "dpad_up", "dpad_right", "dpad_down", "dpad_left"}) {
        const auto events = parseScript(std::string("0 gamepad_button ") + button + " down", "b.txt");
        EXPECT_EQ(static_cast<int>(single<input::GamepadButtonEvent>(events).button), index++) << button;
    }
}

TEST(Script, BoundaryValuesAreAccepted) {
    EXPECT_EQ(errorOf("0 gamepad_axis left_x -1\n0 gamepad_axis left_x 1\n"), "");
    EXPECT_EQ(errorOf("0 look 0 90\n0 look 0 -90\n0 look 720 0\n"), "");
    EXPECT_EQ(errorOf("9007199254740992 key W down\n"), "");
    EXPECT_EQ(errorOf("0007 key W down\n"), "");
    EXPECT_EQ(errorOf("0 mouse_move -0 .5\n"), "");
}

TEST(Script, CommentsBlankLinesAndWhitespace) {
    const auto events = parseScript("# a walk\n"
                                    "\n"
                                    "   \t  \n"
                                    "  # indented comment\n"
                                    "\t3\tkey\t W  down   # trailing comment\n"
                                    "4 key W up#glued comment\n"
                                    "5 scroll 1 # 2 3\n",
                                    "c.txt");
    ASSERT_EQ(events.size(), 3u);
    EXPECT_EQ(events[0].tick, 3u);
    EXPECT_EQ(events[0].line, 5);
    EXPECT_TRUE(std::get<input::KeyEvent>(events[0].event).down);
    EXPECT_EQ(events[1].line, 6);
    EXPECT_FALSE(std::get<input::KeyEvent>(events[1].event).down);
    EXPECT_EQ(std::get<input::ScrollEvent>(events[2].event).dy, 1.0f);
}

TEST(Script, CommentsDoNotHideRealErrors) {
    // A '#' glued to a token still starts a comment, so the arguments after it are missing.
    EXPECT_NE(errorOf("5 key S# down\n").find("walk.txt:1: 'key' needs 2 arguments"), std::string::npos)
        << errorOf("5 key S# down\n");
}

TEST(Script, EmptyAndCommentOnlyScripts) {
    EXPECT_TRUE(parseScript("", "e.txt").empty());
    EXPECT_TRUE(parseScript("# nothing\n\n  \n", "e.txt").empty());
    EXPECT_EQ(parseScript("1 key W down", "no_newline.txt").size(), 1u);
}

TEST(Script, SortsStablyByTick) {
    const auto events = parseScript("5 key A down\n"
                                    "2 key B down\n"
                                    "5 key C down\n"
                                    "0 key D down\n"
                                    "2 key E down\n"
                                    "5 key F down\n",
                                    "s.txt");
    ASSERT_EQ(events.size(), 6u);
    const std::pair<std::uint64_t, int> expected[] = {{0, 4}, {2, 2}, {2, 5}, {5, 1}, {5, 3}, {5, 6}};
    for (std::size_t i = 0; i < events.size(); ++i) {
        EXPECT_EQ(events[i].tick, expected[i].first) << i;
        EXPECT_EQ(events[i].line, expected[i].second) << i;
    }
    // Large enough that an unstable sort would visibly reorder equal ticks.
    std::string many;
    for (int i = 0; i < 3000; ++i) many += std::to_string((i * 7919) % 5) + " scroll 1\n";
    const auto sorted = parseScript(many, "many.txt");
    ASSERT_EQ(sorted.size(), 3000u);
    for (std::size_t i = 1; i < sorted.size(); ++i) {
        ASSERT_LE(sorted[i - 1].tick, sorted[i].tick);
        if (sorted[i - 1].tick == sorted[i].tick) {
            ASSERT_LT(sorted[i - 1].line, sorted[i].line) << i;
        }
    }
    // A press and its release on one tick stay in file order.
    const auto pair = parseScript("1 key W down\n1 key W up\n0 key S down\n", "p.txt");
    EXPECT_TRUE(std::get<input::KeyEvent>(pair[1].event).down);
    EXPECT_FALSE(std::get<input::KeyEvent>(pair[2].event).down);
}

TEST(Script, CrlfLineEndings) {
    const auto events = parseScript("# windows file\r\n1 key W down\r\n\r\n2 look 10 -20\r\n3 scroll 1", "w.txt");
    ASSERT_EQ(events.size(), 3u);
    EXPECT_EQ(events[0].line, 2);
    EXPECT_EQ(events[1].line, 4);
    EXPECT_EQ(std::get<input::LookEvent>(events[1].event).pitchDeg, -20.0f);
    EXPECT_EQ(events[2].line, 5);
    EXPECT_EQ(errorOf("1 key W down\r\n2 key W dwn\r\n"), "walk.txt:2: expected down or up, got 'dwn'");
}

TEST(Script, LongLinesUpToTheLimit) {
    // Padding between tokens counts towards the line's length; a line at the limit still parses.
    const std::string padding((input::kMaxScriptLineBytes - 16) / 4, ' ');
    const std::string line = padding + "7" + padding + "key" + padding + "W" + padding + "down";
    ASSERT_LE(line.size(), input::kMaxScriptLineBytes);
    const std::string longComment = "# " + std::string(input::kMaxScriptLineBytes - 2, 'x');
    ASSERT_EQ(longComment.size(), input::kMaxScriptLineBytes);
    const auto events = parseScript(longComment + "\n" + line + "\n", "long.txt");
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].tick, 7u);
    EXPECT_EQ(events[0].line, 2);

    // A long bad token is quoted, but cut short: the message stays readable.
    const std::string message = errorOf("1 key W down\n2 key " + std::string(4000, 'Q') + " down\n");
    EXPECT_EQ(message.rfind("walk.txt:2: unknown key 'QQQQ", 0), 0u) << message.substr(0, 200);
    EXPECT_LT(message.size(), 300u);
    EXPECT_NE(message.find("...'"), std::string::npos);
}

TEST(Script, LineLongerThanTheLimitIsRefused) {
    const std::string tooLong = "# " + std::string(input::kMaxScriptLineBytes - 1, 'x');
    ASSERT_EQ(tooLong.size(), input::kMaxScriptLineBytes + 1);
    EXPECT_EQ(errorOf("0 key W down\n" + tooLong + "\n"),
              "walk.txt:2: line of 4097 bytes, longer than the 4096 a script line may have");
    // A megabyte of one line (a binary file, say) is refused the same way, without parsing it.
    EXPECT_EQ(errorOf(std::string(1 << 20, '\0')).rfind("walk.txt:1: line of 1048576 bytes", 0), 0u);
}

TEST(Script, MoreEventsThanTheLimitAreRefused) {
    std::string text;
    text.reserve(input::kMaxScriptEvents * 11 + 64);
    for (std::size_t i = 0; i < input::kMaxScriptEvents; ++i) text += "0 scroll 1\n";
    text += "# comments and blank lines do not count\n\n";
    ASSERT_EQ(parseScript(text, "max.txt").size(), input::kMaxScriptEvents);
    text += "5 scroll 1\n";
    EXPECT_EQ(errorOf(text, "max.txt"),
              "max.txt:1000003: more than 1000000 events; a script may have at most that many");
}

TEST(Script, TriggersTakeTravelZeroToOne) {
    // Travel 0..1 in the script, GLFW's -1..1 in the event: 0 is released, not half pulled.
    const auto events = parseScript("0 gamepad_axis right_trigger 0\n"
                                    "1 gamepad_axis right_trigger 0.5\n"
                                    "2 gamepad_axis left_trigger 1\n"
                                    "3 gamepad_axis left_x -0.5\n",
                                    "t.txt");
    ASSERT_EQ(events.size(), 4u);
    EXPECT_EQ(std::get<input::GamepadAxisEvent>(events[0].event).value, -1.0f);
    EXPECT_EQ(std::get<input::GamepadAxisEvent>(events[1].event).value, 0.0f);
    EXPECT_EQ(std::get<input::GamepadAxisEvent>(events[2].event).axis, input::GamepadAxis::LeftTrigger);
    EXPECT_EQ(std::get<input::GamepadAxisEvent>(events[2].event).value, 1.0f);
    EXPECT_EQ(std::get<input::GamepadAxisEvent>(events[3].event).value, -0.5f); // sticks keep -1..1
    EXPECT_EQ(errorOf("0 gamepad_axis left_trigger -0.5\n"),
              "walk.txt:1: gamepad_axis VALUE '-0.5' is outside 0..1 (trigger travel: 0 released, 1 fully pulled)");
    EXPECT_NE(errorOf("0 gamepad_axis right_trigger 1.01\n").find("outside 0..1"), std::string::npos);
    EXPECT_NE(errorOf("0 gamepad_axis right_trigger -1\n").find("outside 0..1"), std::string::npos);
}

TEST(Script, EventsFromATick) {
    const auto events = parseScript("700 key W up\n0 key W down\n600 key S down\n599 key S up\n", "late.txt");
    const input::LateEvents late = input::eventsFrom(events, 600);
    EXPECT_EQ(late.count, 2u);
    EXPECT_EQ(late.firstLine, 1); // the first in the file, though tick 600 sorts before it
    EXPECT_EQ(input::eventsFrom(events, 701).count, 0u);
    EXPECT_EQ(input::eventsFrom(events, 701).firstLine, 0);
    EXPECT_EQ(input::eventsFrom(events, 0).count, 4u);
}

struct BadCase {
    const char* line;
    const char* expected; // a substring of the message after "FILE:LINE: "
};

TEST(Script, MalformedLinesAreRejectedWithFileAndLine) {
    const BadCase cases[] = {
        // ticks
        {"1.5 key W down", "bad tick '1.5'"},
        {"-1 key W down", "bad tick '-1'"},
        {"+1 key W down", "bad tick '+1'"},
        {"x key W down", "bad tick 'x'"},
        {"key W down", "bad tick 'key'"},
        {"0x10 key W down", "bad tick '0x10'"},
        {"9007199254740993 key W down", "tick '9007199254740993' is beyond 2^53"},
        {"99999999999999999999999 key W down", "is beyond 2^53"},
        // commands
        {"5", "missing command after tick '5'"},
        {"5 jump", "unknown command 'jump'"},
        {"5 KEY W down", "unknown command 'KEY'"},
        // key
        {"5 key SPCE down",
         "unknown key 'SPCE' (GLFW key names without the GLFW_KEY_ prefix, e.g. SPACE, W, LEFT_SHIFT)"},
        {"5 key space down", "unknown key 'space' (key names are upper case: 'SPACE')"},
        {"5 key GLFW_KEY_W down", "drop the GLFW_KEY_ prefix: 'W'"},
        {"5 key W", "'key' needs 2 arguments (key NAME down|up), got 1"},
        {"5 key", "'key' needs 2 arguments (key NAME down|up), got 0"},
        {"5 key W down now", "unexpected extra token 'now'"},
        {"5 key W pressed", "expected down or up, got 'pressed'"},
        {"5 key W DOWN", "expected down or up, got 'DOWN'"},
        {"5 key \x01 down", "unknown key '\\x01'"},
        // mouse
        {"5 mouse_move 1.5x 0", "DX '1.5x' is not a number"},
        {"5 mouse_move nan 0", "DX 'nan' is not a number"},
        {"5 mouse_move 0 inf", "DY 'inf' is not a number"},
        {"5 mouse_move 0 -infinity", "DY '-infinity' is not a number"},
        {"5 mouse_move 0x1p3 0", "DX '0x1p3' is not a number"},
        {"5 mouse_move 1e999 0", "DX '1e999' is out of range"},
        {"5 mouse_move 1e39 0", "DX '1e39' is outside the float range"},
        {"5 mouse_move 1", "'mouse_move' needs 2 arguments (mouse_move DX DY), got 1"},
        {"5 mouse_move 1 2 3", "unexpected extra token '3'"},
        {"5 mouse_button lft down", "unknown mouse button 'lft' (expected left, right or middle)"},
        {"5 mouse_button left", "'mouse_button' needs 2 arguments"},
        {"5 mouse_button left click", "expected down or up, got 'click'"},
        // scroll
        {"5 scroll", "'scroll' needs 1 argument (scroll DY), got 0"},
        {"5 scroll 1 2", "unexpected extra token '2'"},
        {"5 scroll up", "DY 'up' is not a number"},
        // gamepad
        {"5 gamepad_axis left_z 0", "unknown gamepad axis 'left_z'"},
        {"5 gamepad_axis LEFT_X 0", "unknown gamepad axis 'LEFT_X'"},
        {"5 gamepad_axis left_x 1.5", "VALUE '1.5' is outside -1..1"},
        {"5 gamepad_axis left_x -1.0001", "VALUE '-1.0001' is outside -1..1"},
        {"5 gamepad_axis left_x", "'gamepad_axis' needs 2 arguments"},
        {"5 gamepad_axis left_x nan", "VALUE 'nan' is not a number"},
        {"5 gamepad_button z down", "unknown gamepad button 'z'"},
        {"5 gamepad_button a held", "expected down or up, got 'held'"},
        {"5 gamepad_button a down up", "unexpected extra token 'up'"},
        // teleport and look
        {"5 teleport 1 2", "'teleport' needs 3 arguments (teleport X Y Z), got 2"},
        {"5 teleport 1 2 3 4", "unexpected extra token '4'"},
        {"5 teleport 1 nan 3", "Y 'nan' is not a number"},
        {"5 teleport 1 2 3z", "Z '3z' is not a number"},
        {"5 look 0 90.5", "PITCH '90.5' is outside -90..90"},
        {"5 look 0 -91", "PITCH '-91' is outside -90..90"},
        {"5 look inf 0", "YAW 'inf' is not a number"},
        {"5 look 0", "'look' needs 2 arguments (look YAW PITCH), got 1"},
        {"5 look 1,5 0", "YAW '1,5' is not a number"},
    };
    for (const BadCase& c : cases) {
        // Good lines, comments and blank lines before the bad one, so line counting is exercised too.
        const std::string text =
            "# header\n0 key W down\n\n1 key W up # fine\r\n" + std::string(c.line) + "\n6 key W down\n7 nonsense\n";
        const std::string message = errorOf(text);
        const std::string prefix = "walk.txt:5: ";
        EXPECT_EQ(message.rfind(prefix, 0), 0u) << c.line << " -> " << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.line << " -> " << message;
    }
}

TEST(Script, ReportsTheFirstBadLine) {
    EXPECT_EQ(errorOf("0 key W down\n1 key Q sideways\n2 key SPCE down\n", "two.txt"),
              "two.txt:2: expected down or up, got 'sideways'");
    // Sorting by tick happens after parsing, so "first" means first in the file.
    EXPECT_EQ(errorOf("9 bogus\n0 bogus2\n", "order.txt").rfind("order.txt:1: unknown command 'bogus'", 0), 0u);
}

class ScriptFile : public testing::Test {
protected:
    void SetUp() override {
        m_dir = std::filesystem::path(testing::TempDir()) /
                ("minecrappy_script_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::create_directories(m_dir);
    }
    void TearDown() override { std::filesystem::remove_all(m_dir); }
    std::string write(const std::string& name, const std::string& text) {
        const auto path = m_dir / name;
        std::ofstream(path, std::ios::binary) << text;
        return path.string();
    }
    std::filesystem::path m_dir;
};

TEST_F(ScriptFile, LoadsAndNamesTheFileInErrors) {
    const std::string good = write("good.txt", "2 key W up\n1 key W down\n");
    const auto events = input::loadScript(good);
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].tick, 1u);

    const std::string bad = write("bad.txt", "1 key W down\n\n3 key W sideways\n");
    EXPECT_EQ(loadErrorOf(bad), bad + ":3: expected down or up, got 'sideways'");
}

TEST_F(ScriptFile, FileOverTheSizeLimitIsRefused) {
    // At the limit: blank lines are no events, so the file is read whole and parses.
    std::string text(input::kMaxScriptBytes, '\n');
    const std::string atLimit = write("at_limit.txt", text);
    EXPECT_TRUE(input::loadScript(atLimit).empty());
    text += '\n';
    const std::string over = write("over.txt", text);
    EXPECT_EQ(loadErrorOf(over), over + ": larger than 16 MiB (16777216 bytes), the most a script may be");
}

TEST_F(ScriptFile, EndlessFileIsRefused) {
    // /dev/zero never ends: it must be refused after the size limit, not read until memory runs out.
    ASSERT_TRUE(std::filesystem::exists("/dev/zero"));
    const std::string endless = loadErrorOf("/dev/zero");
    EXPECT_EQ(endless.rfind("/dev/zero: larger than 16 MiB", 0), 0u) << endless;
}

TEST_F(ScriptFile, MissingFileAndDirectory) {
    const std::string missing = (m_dir / "does_not_exist.txt").string();
    const std::string missingError = loadErrorOf(missing);
    EXPECT_EQ(missingError.rfind(missing + ": cannot open: ", 0), 0u) << missingError;
    const std::string folderError = loadErrorOf(m_dir.string());
    EXPECT_EQ(folderError.rfind(m_dir.string() + ": cannot ", 0), 0u) << folderError;
}

} // namespace
