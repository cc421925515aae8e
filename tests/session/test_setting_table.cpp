// The settings table (session/setting_table.h) walked row by row through everything it drives: the command line,
// the settings file, the clamps, the recording header and the state hash. The settings panel's walk is in
// tests/ui/test_settings_panel.cpp (it needs Dear ImGui, which the unit tests do not link).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "game/state_io.h"
#include "session/options.h"
#include "session/session.h"
#include "session/setting_table.h"

namespace {

namespace fs = std::filesystem;
using session::SettingRow;
using session::SettingType;

// A value of the row's type as the command line writes it.
std::string number(double v, SettingType type) {
    if (type == SettingType::Float) {
        std::ostringstream o;
        o.precision(9);
        o << v;
        return o.str();
    }
    return std::to_string(static_cast<long long>(v));
}

std::string textOf(const SettingRow& row, double v) {
    std::string text = number(v, row.type);
    if (row.type == SettingType::Size) { // piecewise: GCC 12 warns falsely (-Wrestrict) on "x" + std::string&&
        text += 'x';
        text += number(v, row.type);
    }
    return text;
}

// The values a row must take (both ends and the middle) and refuse (one past each end, or no value of its type).
struct Walk {
    std::vector<std::string> good, bad;
};

Walk walkOf(const SettingRow& row) {
    if (row.type == SettingType::Bool) return {{"true", "false"}, {"\"true\"", "2"}};
    const bool whole = row.type != SettingType::Float;
    const double step = whole ? 1.0 : (row.hi - row.lo) * 1e-3;
    const double mid = whole ? std::floor((row.lo + row.hi) / 2) : (row.lo + row.hi) / 2;
    return {{textOf(row, row.lo), textOf(row, mid), textOf(row, row.hi)},
            {textOf(row, row.lo - step), textOf(row, row.hi + step)}};
}

session::ParseOutcome parse(std::vector<const char*> args) {
    args.insert(args.begin(), "minecrappy");
    return session::parseOptions(static_cast<int>(args.size()), args.data());
}

// The file's text of one setting: Size in quotes, as the file writes it.
std::string fileText(const SettingRow& row, const std::string& value) {
    std::string text = "[";
    text += row.section;
    text += "]\n";
    text += row.key;
    text += " = ";
    text += row.type == SettingType::Size ? "\"" + value + "\"" : value;
    text += "\n";
    return text;
}

// Every row, at both ends, in the middle and one past each end: the flag takes exactly the good values (and exit
// 2 naming the flag for the others), the file reads them (a warning naming the key and line for the others, and the
// default kept), the clamp holds a value past an end to that end, and the file written reads back the same. Catches
// a flag or a file check with its own range (view_radius 2..32 written twice was the issue), a range off by one.
TEST(SettingTable, EveryRowWalksThroughTheFlagTheFileAndTheClamp) {
    ASSERT_GE(session::kSettingRows.size(), 15u); // the precondition: the table is the game's, not an empty one
    for (const SettingRow& row : session::kSettingRows) {
        SCOPED_TRACE(std::string(row.key));
        const Walk walk = walkOf(row);
        for (const std::string& value : walk.good) {
            session::Settings parsed;
            EXPECT_EQ(session::parseSetting(row, value, parsed), "") << value;
            const std::string expected = session::settingText(row, parsed);

            const session::SettingsLoad load = session::parseSettings(fileText(row, value), "s.toml");
            // The one rule across rows: the trigger's release below its press (the other at its default).
            const bool acrossRows =
                !load.warnings.empty() && load.warnings[0].find("must be below trigger_press") != std::string::npos;
            EXPECT_TRUE(load.warnings.size() == acrossRows) << value << ": " << load.warnings[0];
            if (!acrossRows || row.key != "trigger_release") {
                EXPECT_EQ(session::settingText(row, load.settings), expected) << value;
            }

            session::Settings written = parsed;
            session::clampSettings(written);
            const session::SettingsLoad back = session::parseSettings(session::settingsText(written), "s.toml");
            EXPECT_TRUE(back.warnings.empty());
            EXPECT_EQ(back.settings, written) << value;

            if (row.flag.empty()) continue;
            const std::string flag(row.flag);
            const auto r = parse({flag.c_str(), value.c_str()});
            ASSERT_TRUE(r.options) << flag << " " << value << ": " << r.output;
            EXPECT_EQ(session::settingText(row, r.options->settings), expected);
            EXPECT_TRUE(r.options->given.setting(row.key));
        }
        for (const std::string& value : walk.bad) {
            session::Settings untouched;
            EXPECT_NE(session::parseSetting(row, value, untouched), "") << value;
            EXPECT_EQ(untouched, session::Settings{}) << value;

            const session::SettingsLoad load = session::parseSettings(fileText(row, value), "s.toml");
            ASSERT_EQ(load.warnings.size(), 1u) << value;
            const std::string key = std::string(row.section) + "." + std::string(row.key);
            EXPECT_EQ(load.warnings[0].rfind("s.toml:2: key '" + key + "'", 0), 0u) << load.warnings[0];
            EXPECT_EQ(session::settingText(row, load.settings), session::settingDefaultText(row));

            if (row.flag.empty()) continue;
            const std::string flag(row.flag);
            const auto r = parse({flag.c_str(), value.c_str()});
            EXPECT_FALSE(r.options) << flag << " " << value;
            EXPECT_EQ(r.exitCode, 2);
            EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
        }
        if (row.type == SettingType::Bool) continue;
        for (const double past : {row.lo - 1.0, row.hi + 1.0, row.lo - 1e6, row.hi + 1e6}) {
            session::Settings s;
            session::parseSetting(row, textOf(row, std::clamp(past, row.lo, row.hi)), s); // the end it is held to
            const std::string end = session::settingText(row, s);
            if (row.type == SettingType::Int) row.intRef(s) = static_cast<int>(past);
            if (row.type == SettingType::Float) row.floatRef(s) = static_cast<float>(past);
            if (row.type == SettingType::Size) row.sizeRef(s) = {static_cast<int>(past), static_cast<int>(past)};
            session::clampSetting(row, s);
            EXPECT_EQ(session::settingText(row, s), end) << past;
        }
    }
}

// Each row's default is the Settings member's initializer, and it is inside the row's range; the flag's help shows it.
TEST(SettingTable, DefaultsAreInRangeAndTheHelpShowsThem) {
    const auto help = parse({"--help"});
    for (const SettingRow& row : session::kSettingRows) {
        SCOPED_TRACE(std::string(row.key));
        session::Settings d;
        EXPECT_EQ(session::parseSetting(row, session::settingDefaultText(row), d), "");
        EXPECT_FALSE(row.label.empty());
        EXPECT_FALSE(row.help.empty());
        if (!row.flag.empty()) {
            const auto at = help.output.find(std::string(row.flag) + " ");
            ASSERT_NE(at, std::string::npos);
            const std::string line = help.output.substr(at, help.output.find('\n', at) - at);
            std::string shown = "="; // CLI11 writes "--fov NUMBER=70.0"
            shown += session::settingDefaultText(row);
            const auto found = line.find(shown);
            ASSERT_NE(found, std::string::npos) << line;
            const std::size_t after = found + shown.size(); // the whole value: "=2" must not pass for "=20"
            EXPECT_TRUE(after == line.size() || line[after] == ' ') << line;
        }
    }
}

class SimulationColumn : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = fs::temp_directory_path() / ("mc_setting_table_" + std::to_string(::getpid()));
        fs::create_directories(m_dir);
        // Actions rather than device events: the simulation's input, whatever the bindings and sensitivities.
        // A big hair ball so that the smallest hair budget binds.
        std::ofstream(m_dir / "walk.txt") << "0 act move=0,1 sprint\n"
                                             "2 hair 0 strands=2000 iterations=8\n"
                                             "20 act move=1,0 yaw=30\n";
    }
    void TearDown() override { fs::remove_all(m_dir); }

    // The state hash after 30 ticks of the script with these settings, as the game runs them (mergeSettings).
    std::uint64_t hashWith(session::Settings settings, bool script = true) const {
        session::Options o;
        o.headless = true;
        o.settingsFile.reset();
        if (script) o.script = (m_dir / "walk.txt").string();
        session::mergeSettings(o, settings);
        session::Session s(o);
        for (int i = 0; i < 30; ++i) s.step();
        return game::stateHash(s.state());
    }

    fs::path m_dir;
};

// Another value of the row than its default: its low end, or its high end where the default is the low end.
session::Settings changed(const SettingRow& row) {
    session::Settings s;
    const std::string def = session::settingDefaultText(row);
    if (row.type == SettingType::Bool) {
        row.boolRef(s) = !row.boolRef(s);
    } else {
        session::parseSetting(row, textOf(row, row.lo), s);
        if (session::settingText(row, s) == def) session::parseSetting(row, textOf(row, row.hi), s);
    }
    return s;
}

// The column "changes the simulation" is what the state hash sees: every row marked so changes the hash of the same
// script when it alone changes, and no other row does (the view, the frame size, vsync, level of detail, culling and
// the input tuning leave the simulation alone, so two window sizes replay to the same hash). Catches a row marked
// wrongly either way, and a setting that leaks into the simulation (the view radius deciding what is loaded, say).
TEST_F(SimulationColumn, IsWhatTheStateHashSees) {
    const std::uint64_t base = hashWith({});
    // The precondition of "no other row changes it": the script changes the state (the player walks and turns,
    // the hair ball grows), so an equal hash is not an idle scene.
    ASSERT_NE(hashWith({}, false), base);
    int simulated = 0;
    for (const SettingRow& row : session::kSettingRows) {
        SCOPED_TRACE(std::string(row.key));
        const session::Settings other = changed(row);
        ASSERT_FALSE(session::sameSetting(row, other, session::Settings{})); // the precondition: the value differs
        EXPECT_EQ(hashWith(other) != base, row.simulation);
        simulated += row.simulation;
    }
    EXPECT_EQ(simulated, 5); // hair detail, hair budget, tick rate, day length, day cycle
}

} // namespace
