#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <vector>

#include "session/options.h"
#include "session/settings.h"

namespace {

namespace fs = std::filesystem;

class SettingsFile : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = fs::temp_directory_path() / ("mc_settings_" + std::to_string(::getpid()) + "_" +
                                             ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }

    fs::path path(const char* name = "settings.toml") const { return m_dir / name; }
    static void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }
    static std::string read(const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }

    fs::path m_dir;
};

// The one warning that names this key, or an empty string.
std::string warningFor(const session::SettingsLoad& load, const std::string& key) {
    std::string found;
    for (const auto& w : load.warnings)
        if (w.find("'" + key + "'") != std::string::npos) found = w;
    return found;
}

TEST_F(SettingsFile, MissingFileIsCreatedWithCommentsAndLoadsBackToDefaults) {
    const fs::path file = m_dir / "sub" / "dir" / "settings.toml";
    const auto first = session::loadSettings(file);
    EXPECT_TRUE(first.created);
    EXPECT_TRUE(first.warnings.empty());
    EXPECT_EQ(first.settings, session::Settings{});
    ASSERT_TRUE(fs::exists(file));
    const std::string text = read(file);
    EXPECT_EQ(text, session::defaultSettingsText());
    EXPECT_NE(text.find("# "), std::string::npos);
    for (const char* key :
         {"fov", "view_radius", "tick_rate", "size = \"1280x720\"", "vsync", "hair_detail", "sensitivity", "invert_y",
          "stick_deadzone", "trigger_press", "forward = \"W\"", "jump = \"SPACE\"", "jump = \"a\""}) {
        EXPECT_NE(text.find(key), std::string::npos) << key;
    }

    const auto second = session::loadSettings(file);
    EXPECT_FALSE(second.created);
    EXPECT_TRUE(second.warnings.empty()) << second.warnings.front();
    EXPECT_EQ(second.settings, session::Settings{});
    EXPECT_EQ(read(file), text);
}

TEST_F(SettingsFile, SaveAndLoadRoundTrip) {
    session::Settings s;
    s.fov = 91.3f;
    s.viewRadius = 17;
    s.tickRate = 240;
    s.size = {1920, 1080};
    s.vsync = false;
    s.hairDetail = 0;
    s.hairBudgetThousands = 4321;
    s.input.mouseDegreesPerPixel = 0.0731f;
    s.input.invertY = true;
    s.input.stickDeadzone = 0.22f;
    s.input.lookStickDegreesPerSecond = 333.3f;
    s.input.triggerPress = 0.8f;
    s.input.triggerRelease = 0.1f;
    s.input.keys.forward = input::keyFromName("UP").value();
    s.input.keys.jump = input::keyFromName("KP_ADD").value();
    s.input.keys.help = -1;
    s.input.pad.jump = input::GamepadButton::X;
    s.input.pad.pickBlock = input::GamepadButton::A; // a swap: sharing X would warn
    s.input.pad.carry = input::GamepadButton::Count;

    const fs::path file = path();
    session::saveSettings(s, file);
    EXPECT_FALSE(fs::exists(file.string() + ".tmp." + std::to_string(::getpid())));
    const auto load = session::loadSettings(file);
    EXPECT_FALSE(load.created);
    EXPECT_TRUE(load.warnings.empty()) << load.warnings.front();
    EXPECT_EQ(load.settings, s);
    EXPECT_NE(read(file).find("help = \"none\""), std::string::npos);
}

TEST_F(SettingsFile, SaveFailureThrowsNamingTheFile) {
    const fs::path blocker = path("not_a_dir");
    write(blocker, "x");
    const fs::path file = blocker / "settings.toml";
    try {
        session::saveSettings(session::Settings{}, file);
        FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
}

TEST_F(SettingsFile, EveryBadValueWarnsWithKeyAndLineAndFallsBack) {
    const fs::path file = path();
    // Line numbers matter: each bad value's line is checked below.
    write(file,
          "[graphics]\n"              // 1
          "fov = 500.0\n"             // 2 out of range
          "view_radius = \"far\"\n"   // 3 wrong type
          "window_width = 1600\n"     // 4 old name of size, written beside it
          "size = \"100\"\n"          // 5 not WxH
          "vsync = 1\n"               // 6 wrong type
          "hair_detail = 1\n"         // 7 good
          "colour = \"red\"\n"        // 8 unknown key
          "[simulation]\n"            // 9
          "tick_rate = 5\n"           // 10 out of range
          "[mouse]\n"                 // 11
          "sensitivity = nan\n"       // 12 NaN
          "invert_y = true\n"         // 13 good
          "[gamepad_tuning]\n"        // 14
          "stick_deadzone = 0.95\n"   // 15 out of range
          "trigger_press = 0.5\n"     // 16 good
          "trigger_release = 0.7\n"   // 17 above press
          "[keys]\n"                  // 18
          "forward = \"UP\"\n"        // 19 good
          "jump = \"SPACEBAR\"\n"     // 20 unknown key name
          "sprint = 341\n"            // 21 wrong type
          "[gamepad]\n"               // 22
          "jump = \"triangle\"\n"     // 23 unknown button name
          "place = \"left_bumper\"\n" // 24 good
          "[sound]\n"                 // 25 unknown section
          "volume = 3\n");            // 26
    const auto load = session::loadSettings(file);
    EXPECT_FALSE(load.created);
    const session::Settings d;
    const std::string f = file.string();

    struct Expect {
        const char* key;
        int line;
        const char* what;
    };
    const Expect expected[] = {
        {"graphics.fov", 2, "out of range"},
        {"graphics.view_radius", 3, "expected a whole number"},
        {"graphics.window_width", 4, "which line 5 sets; 'graphics.size' wins"},
        {"graphics.size", 5, "expected WIDTHxHEIGHT"},
        {"graphics.vsync", 6, "expected true or false"},
        {"graphics.colour", 8, "unknown key"},
        {"simulation.tick_rate", 10, "out of range"},
        {"mouse.sensitivity", 12, "not a number"},
        {"gamepad_tuning.stick_deadzone", 15, "out of range"},
        {"gamepad_tuning.trigger_release", 17, "below trigger_press"},
        {"keys.jump", 20, "unknown key name"},
        {"keys.sprint", 21, "expected a key name"},
        {"gamepad.jump", 23, "unknown button name"},
        {"break", 24, "actions 'place' and 'break' share gamepad button left_bumper"}, // break is on LB too
        {"sound", 25, "unknown section"},
    };
    for (const auto& e : expected) {
        const std::string w = warningFor(load, e.key);
        ASSERT_FALSE(w.empty()) << e.key;
        EXPECT_EQ(w.rfind(f + ":" + std::to_string(e.line) + ": ", 0), 0u) << w;
        EXPECT_NE(w.find(e.what), std::string::npos) << w;
    }
    EXPECT_EQ(load.warnings.size(), std::size(expected));
    // The documented message shape, with the value and the default used.
    EXPECT_EQ(warningFor(load, "graphics.fov"),
              f + ":2: key 'graphics.fov' = 500.0: out of range 30.0..120.0; using 70.0");
    EXPECT_NE(warningFor(load, "keys.jump").find("= \"SPACEBAR\""), std::string::npos);
    EXPECT_NE(warningFor(load, "keys.jump").find("using \"SPACE\""), std::string::npos);
    EXPECT_NE(warningFor(load, "mouse.sensitivity").find("= nan"), std::string::npos);

    const session::Settings& s = load.settings;
    EXPECT_EQ(s.fov, d.fov);
    EXPECT_EQ(s.viewRadius, d.viewRadius);
    EXPECT_EQ(s.size, d.size); // the new key's bad value gives the default; the old key beside it is not read
    EXPECT_TRUE(load.notes.empty());
    EXPECT_FALSE(load.migrated);
    EXPECT_EQ(s.vsync, d.vsync);
    EXPECT_EQ(s.hairDetail, 1);
    EXPECT_EQ(s.tickRate, d.tickRate);
    EXPECT_EQ(s.input.mouseDegreesPerPixel, d.input.mouseDegreesPerPixel);
    EXPECT_TRUE(s.input.invertY);
    EXPECT_EQ(s.input.stickDeadzone, d.input.stickDeadzone);
    EXPECT_EQ(s.input.triggerPress, 0.5f);
    EXPECT_LT(s.input.triggerRelease, s.input.triggerPress);
    EXPECT_EQ(s.input.triggerRelease, d.input.triggerRelease);
    EXPECT_EQ(s.input.keys.forward, input::keyFromName("UP").value());
    EXPECT_EQ(s.input.keys.jump, d.input.keys.jump);
    EXPECT_EQ(s.input.keys.sprint, d.input.keys.sprint);
    EXPECT_EQ(s.input.pad.jump, d.input.pad.jump);
    EXPECT_EQ(s.input.pad.place, input::GamepadButton::LeftBumper);
}

TEST(SettingsBindings, DefaultsShareNoKeyOrButton) {
    EXPECT_TRUE(session::bindingConflicts(session::Settings{}).empty())
        << session::bindingConflicts(session::Settings{}).front();
}

TEST(SettingsBindings, SharedKeysButtonsAndHotbarDigitsAreNamed) {
    session::Settings s;
    s.input.keys.sprint = s.input.keys.jump;
    s.input.keys.carry = input::keyFromName("3").value();
    s.input.pad.toggleFly = s.input.pad.pause;
    s.input.keys.help = s.input.keys.overlay = -1; // two unbound actions share nothing
    s.input.pad.selectPrev = s.input.pad.selectNext = input::GamepadButton::Count;
    const std::vector<std::string> expected = {
        "actions 'jump' and 'sprint' share key SPACE",
        "action 'carry' uses key 3, which also selects hotbar slot 3",
        "actions 'toggle_fly' and 'pause' share gamepad button start",
    };
    EXPECT_EQ(session::bindingConflicts(s), expected);
}

TEST_F(SettingsFile, SharedBindingWarnsAtTheLaterLine) {
    const fs::path file = path();
    write(file,
          "[keys]\n"           // 1
          "jump = \"F\"\n"     // 2: toggle_fly keeps its default F
          "interact = \"Q\"\n" // 3
          "carry = \"Q\"\n"    // 4
          "[gamepad]\n"        // 5
          "sprint = \"a\"\n"); // 6: jump keeps its default a
    const auto load = session::loadSettings(file);
    const std::string f = file.string();
    const std::vector<std::string> expected = {
        f + ":2: actions 'jump' and 'toggle_fly' share key F; one press does both",
        f + ":4: actions 'interact' and 'carry' share key Q; one press does both",
        f + ":6: actions 'jump' and 'sprint' share gamepad button a; one press does both",
    };
    EXPECT_EQ(load.warnings, expected);
    // A warning, not a refusal: the bindings stay as written.
    EXPECT_EQ(load.settings.input.keys.carry, input::keyFromName("Q").value());
}

TEST_F(SettingsFile, IntegersAreAcceptedForFloatsAndMissingKeysAreSilent) {
    const fs::path file = path();
    write(file, "[graphics]\nfov = 90\n");
    const auto load = session::loadSettings(file);
    EXPECT_TRUE(load.warnings.empty());
    EXPECT_EQ(load.settings.fov, 90.0f);
    EXPECT_EQ(load.settings.viewRadius, session::Settings{}.viewRadius);
}

TEST_F(SettingsFile, NonTomlFileIsLeftUnchangedAndGivesDefaults) {
    const fs::path file = path();
    const std::string garbage = "[graphics\nfov = = 3\n\x01\x02 not toml at all\n";
    write(file, garbage);
    const auto load = session::loadSettings(file);
    EXPECT_FALSE(load.created);
    EXPECT_EQ(load.settings, session::Settings{});
    ASSERT_EQ(load.warnings.size(), 1u);
    EXPECT_NE(load.warnings[0].find(file.string()), std::string::npos) << load.warnings[0];
    EXPECT_NE(load.warnings[0].find('1'), std::string::npos) << load.warnings[0];
    EXPECT_EQ(read(file), garbage);
}

TEST_F(SettingsFile, DirectoryInPlaceOfTheFileIsAWarningNotACrash) {
    const fs::path file = path("dir.toml");
    fs::create_directories(file);
    const auto load = session::loadSettings(file);
    EXPECT_FALSE(load.created);
    EXPECT_EQ(load.settings, session::Settings{});
    EXPECT_EQ(load.warnings.size(), 1u);
}

TEST(SettingsPath, FollowsXdgThenHome) {
    const char* oldXdg = std::getenv("XDG_CONFIG_HOME");
    const char* oldHome = std::getenv("HOME");
    const std::string savedXdg = oldXdg ? oldXdg : "", savedHome = oldHome ? oldHome : "";
    ::setenv("XDG_CONFIG_HOME", "/cfg", 1);
    ::setenv("HOME", "/home/u", 1);
    EXPECT_EQ(session::defaultSettingsPath(), fs::path("/cfg/minecrappy/settings.toml"));
    ::unsetenv("XDG_CONFIG_HOME");
    EXPECT_EQ(session::defaultSettingsPath(), fs::path("/home/u/.config/minecrappy/settings.toml"));
    if (oldXdg) ::setenv("XDG_CONFIG_HOME", savedXdg.c_str(), 1);
    if (oldHome) {
        ::setenv("HOME", savedHome.c_str(), 1);
    } else {
        ::unsetenv("HOME");
    }
}

TEST(SettingsPath, HairDetailFractions) {
    EXPECT_EQ(session::hairDetailFraction(0), 0.25f);
    EXPECT_EQ(session::hairDetailFraction(1), 0.5f);
    EXPECT_EQ(session::hairDetailFraction(2), 1.0f);
}

session::ParseOutcome parse(std::vector<const char*> args) {
    args.insert(args.begin(), "minecrappy");
    return session::parseOptions(static_cast<int>(args.size()), args.data());
}

session::Settings fileSettings() {
    session::Settings s;
    s.size = {1000, 800};
    s.tickRate = 120;
    s.viewRadius = 12;
    s.fov = 85.0f;
    s.vsync = false;
    return s;
}

TEST(SettingsFlags, FileWinsWhenNoFlagIsGiven) {
    auto r = parse({});
    ASSERT_TRUE(r.options);
    session::Options o = *r.options;
    session::Settings s = fileSettings();
    session::mergeSettings(o, s);
    EXPECT_EQ(s, fileSettings());
    EXPECT_EQ(o.settings.size.width, 1000);
    EXPECT_EQ(o.settings.size.height, 800);
    EXPECT_EQ(o.settings.tickRate, 120);
    EXPECT_EQ(o.settings.viewRadius, 12);
    EXPECT_EQ(o.settings.fov, 85.0f);
    EXPECT_FALSE(o.settings.vsync);
}

TEST(SettingsFlags, FlagsGivenOverrideTheFileEvenWhenEqualToTheDefault) {
    // 1280x720, 60 and true are the built-in defaults: only ->count() can tell they were given.
    auto r = parse({"--size", "1280x720", "--tick-rate", "60", "--vsync", "true"});
    ASSERT_TRUE(r.options) << r.output;
    session::Options o = *r.options;
    EXPECT_TRUE(o.given.setting("size") && o.given.setting("tick_rate") && o.given.setting("vsync"));
    EXPECT_FALSE(o.given.setting("fov") || o.given.setting("view_radius"));
    session::Settings s = fileSettings();
    session::mergeSettings(o, s);
    EXPECT_EQ(o.settings.size.width, 1280);
    EXPECT_EQ(s.size.width, 1280);
    EXPECT_EQ(s.size.height, 720);
    EXPECT_EQ(o.settings.tickRate, 60);
    EXPECT_TRUE(o.settings.vsync);
    EXPECT_TRUE(s.vsync);
    EXPECT_EQ(o.settings.viewRadius, 12); // from the file
    EXPECT_EQ(o.settings.fov, 85.0f);

    auto r2 = parse({"--fov", "100", "--view-radius", "4"});
    ASSERT_TRUE(r2.options);
    session::Options o2 = *r2.options;
    session::Settings s2 = fileSettings();
    session::mergeSettings(o2, s2);
    EXPECT_EQ(o2.settings.fov, 100.0f);
    EXPECT_EQ(o2.settings.viewRadius, 4);
    EXPECT_EQ(o2.settings.size.width, 1000);
}

TEST(SettingsFlags, SettingsFlagPicksTheFileOrNone) {
    auto none = parse({"--settings", "none"});
    ASSERT_TRUE(none.options);
    EXPECT_FALSE(none.options->settingsFile);
    auto custom = parse({"--settings", "/tmp/x.toml"});
    ASSERT_TRUE(custom.options);
    EXPECT_EQ(*custom.options->settingsFile, fs::path("/tmp/x.toml"));
    auto def = parse({});
    ASSERT_TRUE(def.options);
    EXPECT_EQ(*def.options->settingsFile, session::defaultSettingsPath());
    auto help = parse({"--help"});
    EXPECT_NE(help.output.find("--settings"), std::string::npos);
}

// A file written before the window size became the frame size "size": its two keys are read as the new one, with a
// note each; the file is rewritten with the new key and the old text kept beside it, and the next load has nothing to
// say. A file with a bad value beside the old keys is not rewritten: the player's text stays to be fixed. Catches a
// rename that drops the old keys (the window would open at 1280x720) or rewrites a file the player must fix.
TEST_F(SettingsFile, RenamedKeysAreMigratedWithANote) {
    const fs::path file = path();
    const std::string old = "[graphics]\nwindow_width = 1920\nwindow_height = 1080\nfov = 90.0\n";
    write(file, old);
    const auto load = session::loadSettings(file);
    EXPECT_TRUE(load.warnings.empty()) << load.warnings.front();
    EXPECT_TRUE(load.migrated);
    EXPECT_EQ(load.settings.size, (session::PixelSize{1920, 1080}));
    EXPECT_EQ(load.settings.fov, 90.0f);
    ASSERT_EQ(load.notes.size(), 3u);
    EXPECT_EQ(load.notes[0], file.string() + ":2: key 'graphics.window_width' is now 'graphics.size'; read as such");
    EXPECT_EQ(load.notes[1], file.string() + ":3: key 'graphics.window_height' is now 'graphics.size'; read as such");
    EXPECT_NE(load.notes[2].find("rewritten with the new key names"), std::string::npos) << load.notes[2];
    EXPECT_EQ(read(file.string() + ".old"), old);
    EXPECT_NE(read(file).find("size = \"1920x1080\""), std::string::npos);
    EXPECT_EQ(read(file).find("window_width"), std::string::npos);
    const auto again = session::loadSettings(file);
    EXPECT_TRUE(again.notes.empty() && again.warnings.empty() && !again.migrated);
    EXPECT_EQ(again.settings, load.settings);

    const std::string bad = "[graphics]\nwindow_width = 1920\nfov = 500.0\n";
    write(file, bad);
    const auto kept = session::loadSettings(file);
    EXPECT_EQ(kept.warnings.size(), 1u);
    EXPECT_EQ(kept.settings.size.width, 1920);
    EXPECT_EQ(read(file), bad);
    // A second migration keeps the first backup: the new one takes the next free name.
    write(file, old);
    const auto second = session::loadSettings(file);
    EXPECT_TRUE(second.migrated);
    EXPECT_EQ(read(file.string() + ".old.1"), old);

    // An old key's bad value names that key and the default of its own side.
    write(file, "[graphics]\nwindow_width = 1920\nwindow_height = 5\n");
    const auto side = session::loadSettings(file);
    ASSERT_EQ(side.warnings.size(), 1u);
    EXPECT_EQ(side.warnings[0], file.string() + ":3: key 'graphics.window_height' = 5: expected a whole number in "
                                                "16..16384 each side; using 720");
    EXPECT_EQ(side.settings.size, (session::PixelSize{1920, 720}));
}

// An old key beside the new one that replaced it: the new key wins, whichever line comes first, and the warning
// names both lines; the file is left as written (a rewrite would fold the old key into the new one). Catches the
// reader that let the later-sorted old key override one side ("1024x768" then window_width = 800 ran at 800x768 and
// was rewritten so).
TEST_F(SettingsFile, AnOldKeyBesideItsNewNameIsIgnoredAndNamed) {
    const fs::path file = path();
    for (const std::string& text : {std::string("[graphics]\nsize = \"1024x768\"\nwindow_width = 800\n"),
                                    std::string("[graphics]\nwindow_width = 800\nsize = \"1024x768\"\n")}) {
        write(file, text);
        const auto load = session::loadSettings(file);
        EXPECT_EQ(load.settings.size, (session::PixelSize{1024, 768})) << text;
        ASSERT_EQ(load.warnings.size(), 1u) << text;
        const bool oldFirst = text.find("window_width") < text.find("size");
        EXPECT_EQ(load.warnings[0],
                  file.string() + ":" + (oldFirst ? "2" : "3") +
                      ": key 'graphics.window_width' is the old name of 'graphics.size', which line " +
                      (oldFirst ? "3" : "2") +
                      " sets; 'graphics.size' wins, 'graphics.window_width' "
                      "ignored");
        EXPECT_FALSE(load.migrated);
        EXPECT_EQ(read(file), text);
    }
}

} // namespace
