#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "session/options.h"

namespace {

session::ParseOutcome parse(std::vector<const char*> args) {
    args.insert(args.begin(), "minecrappy");
    return session::parseOptions(static_cast<int>(args.size()), args.data());
}

TEST(Options, DefaultsWithoutFlags) {
    const auto r = parse({});
    ASSERT_TRUE(r.options);
    EXPECT_FALSE(r.options->headless);
    EXPECT_EQ(r.options->settings.size.width, 1280);
    EXPECT_EQ(r.options->settings.size.height, 720);
    EXPECT_EQ(r.options->settings.tickRate, 60);
}

TEST(Options, HeadlessContract) {
    const auto r = parse({"--headless", "--ticks", "120", "--size", "640x360", "--seed", "99", "--terrain", "flat",
                          "--screenshot", "a.png", "--dump-state", "a.json"});
    ASSERT_TRUE(r.options) << r.output;
    EXPECT_TRUE(r.options->headless);
    EXPECT_EQ(r.options->ticks, 120u);
    EXPECT_EQ(r.options->settings.size.width, 640);
    EXPECT_EQ(r.options->settings.size.height, 360);
    EXPECT_EQ(r.options->seed, 99u);
    EXPECT_EQ(r.options->terrain, world::TerrainKind::Flat);
    EXPECT_EQ(r.options->screenshot, "a.png");
    EXPECT_EQ(r.options->dumpState, "a.json");
}

TEST(Options, LevelOfDetailAndOcclusionCullingAreOnUnlessTurnedOff) {
    const auto on = parse({});
    ASSERT_TRUE(on.options);
    EXPECT_TRUE(on.options->settings.levelOfDetail);
    const auto off = parse({"--lod", "false"});
    ASSERT_TRUE(off.options);
    EXPECT_FALSE(off.options->settings.levelOfDetail);
    EXPECT_TRUE(on.options->settings.occlusionCulling);
    const auto noCulling = parse({"--occlusion-culling", "false"});
    ASSERT_TRUE(noCulling.options);
    EXPECT_FALSE(noCulling.options->settings.occlusionCulling);
}

TEST(Options, HelpListsEveryFlagWithDefaults) {
    const auto r = parse({"--help"});
    EXPECT_FALSE(r.options);
    EXPECT_EQ(r.exitCode, 0);
    for (const char* flag :
         {"--headless", "--ticks", "--size", "--seed", "--terrain", "--script", "--screenshot", "--dump-state",
          "--tick-rate", "--view-radius", "--fov", "--vsync", "--lod", "--version", "--replay", "--seek"}) {
        EXPECT_NE(r.output.find(flag), std::string::npos) << flag;
    }
    EXPECT_NE(r.output.find("1280x720"), std::string::npos);
}

TEST(Options, BadInputIsExitTwoAndNamesTheFlag) {
    const std::vector<std::vector<const char*>> bad = {
        {"--bogus"},
        {"--ticks", "-3"},
        {"--ticks", "many"},
        {"--size", "100"},
        {"--size", "0x100"},
        {"--size", "640x480junk"},
        {"--terrain", "lava"},
        {"--tick-rate", "0"},
        {"--view-radius", "1000"},
        {"--fov", "nan"}, // found by tests/fuzz/fuzz_cli: CLI::Range passed NaN
        {"--fov", "-NAN"},
        {"--lod", "maybe"},
        {"--occlusion-culling", "sometimes"},
        {"--script", "/nonexistent/walk.txt"},
        {"--screenshot", "x.png"}, // needs --headless
        {"--time-of-day", "-1"},
        {"--time-of-day", "24.5"},
        {"--time-of-day", "nan"},
        {"--day-length", "0.5"},
        {"--seek", "-1"},
        {"--seek", "3"},                                  // needs --headless
        {"--seek", "3", "--headless"},                    // needs --replay or --script
        {"--seek", "99999999999999999999", "--headless"}, // past 2^64 - 1
    };
    for (const auto& args : bad) {
        const auto r = parse(args);
        EXPECT_FALSE(r.options) << args[0];
        EXPECT_EQ(r.exitCode, 2) << args[0];
        const std::string flag = args[0];
        if (flag != "--bogus") {
            EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
        }
        if (flag == "--time-of-day") { // the value too, as the player wrote it
            EXPECT_NE(r.output.find(std::string("'") + args[1] + "'"), std::string::npos) << r.output;
        }
    }
}

TEST(Options, NumbersAboveTwoTo64AreRefusedNotSaturated) {
    const auto max = parse({"--headless", "--seed", "18446744073709551615", "--ticks", "18446744073709551615"});
    ASSERT_TRUE(max.options) << max.output;
    EXPECT_EQ(max.options->seed, 18446744073709551615u);
    EXPECT_EQ(max.options->ticks, 18446744073709551615u);
    for (const char* flag : {"--seed", "--ticks"}) {
        for (const char* value : {"18446744073709551616", "99999999999999999999999999999"}) {
            const auto r = parse({"--headless", flag, value});
            EXPECT_FALSE(r.options) << flag << " " << value;
            EXPECT_EQ(r.exitCode, 2);
            EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
            EXPECT_NE(r.output.find("above 2^64-1"), std::string::npos) << r.output;
        }
    }
}

TEST(Options, ScreenshotNameMustEndInPng) {
    for (const char* name : {"a.png", "shots/A.PNG", "x.Png"}) {
        const auto r = parse({"--headless", "--screenshot", name});
        EXPECT_TRUE(r.options) << name << ": " << r.output;
    }
    for (const char* name : {"a.jpg", "a.png.txt", "png", "a"}) {
        const auto r = parse({"--headless", "--screenshot", name});
        EXPECT_FALSE(r.options) << name;
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_NE(r.output.find("--screenshot"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("writes PNG"), std::string::npos) << r.output;
    }
}

TEST(Options, WorldNoneMeansNoWorldInBothModes) {
    // Headless plays a world only when one is named: "none" must not become a file called none.
    const auto headless = parse({"--headless", "--world", "none"});
    ASSERT_TRUE(headless.options);
    EXPECT_TRUE(headless.options->world.empty());
    // The window plays the default world when none is named, so it keeps "none" to tell the two apart.
    const auto window = parse({"--world", "none"});
    ASSERT_TRUE(window.options);
    EXPECT_EQ(window.options->world, "none");
    const auto named = parse({"--headless", "--world", "w.mcworld"});
    ASSERT_TRUE(named.options);
    EXPECT_EQ(named.options->world, "w.mcworld");
}

TEST(FrameMemory, EstimateGrowsWithPixelsAndIsRefusedOverHalfTheMemory) {
    const std::uint64_t big = session::estimatedFrameBytes(16384, 16384);
    // The issue measured 5.5 GB of peak memory at this size.
    EXPECT_GT(big, 5'000'000'000u);
    EXPECT_LT(big, 6'500'000'000u);
    EXPECT_LT(session::estimatedFrameBytes(1280, 720), 300'000'000u);

    const std::uint64_t fourGb = 4'000'000'000u;
    const std::string message = session::frameMemoryProblem("--size 16384x16384", 16384, 16384, fourGb);
    EXPECT_EQ(message.rfind("--size 16384x16384: ", 0), 0u) << message;
    EXPECT_NE(message.find("needs about 5.8 GB"), std::string::npos) << message;
    EXPECT_NE(message.find("of the 4.0 GB available"), std::string::npos) << message;
    EXPECT_EQ(session::frameMemoryProblem("--size", 1280, 720, fourGb), "");
    EXPECT_EQ(session::frameMemoryProblem("--size", 16384, 16384, 2 * big), ""); // exactly half fits
    EXPECT_NE(session::frameMemoryProblem("--size", 16384, 16384, 2 * big - 2), "");
    EXPECT_EQ(session::frameMemoryProblem("--size", 16384, 16384, std::nullopt), ""); // unknown: not refused

    const auto available = session::availableMemoryBytes();
    ASSERT_TRUE(available) << "this test expects /proc/meminfo with MemAvailable";
    EXPECT_GT(*available, 0u);
}

class OutputPaths : public testing::Test {
protected:
    void SetUp() override {
        m_dir =
            std::filesystem::path(testing::TempDir()) / ("mc_outputs_" + std::to_string(::getpid()) + "_" +
                                                         testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(m_dir);
        std::filesystem::create_directories(m_dir);
        std::ofstream(m_dir / "file.txt") << "x";
    }
    void TearDown() override { std::filesystem::remove_all(m_dir); }
    std::string at(const std::string& name) const { return (m_dir / name).string(); }
    std::filesystem::path m_dir;
};

TEST_F(OutputPaths, WritableOutputsPassAndLeaveNothingBehind) {
    session::Options o;
    o.screenshot = at("x.png");
    o.dumpState = at("s.json");
    o.frameStats = at("f.json");
    o.soakReport = at("file.txt"); // an existing file is replaced
    o.screenshotDir = at("shots");
    o.given.screenshotDir = true;
    EXPECT_EQ(session::checkOutputPaths(o), "");
    // The check tries a real file in each folder and removes it again.
    std::size_t entries = 0;
    for (const auto& e : std::filesystem::directory_iterator(m_dir)) {
        (void)e;
        ++entries;
    }
    EXPECT_EQ(entries, 1u);
}

TEST_F(OutputPaths, EachProblemNamesTheFlagThePathAndTheReason) {
    using session::Options;
    struct Case {
        std::string Options::*field;
        const char* flag;
        std::string path;
        const char* reason;
    };
    const Case cases[] = {
        // One rule for every output file (core/atomic_file.h): its folder must exist.
        {&Options::dumpState, "--dump-state", at("no/such/s.json"), "the folder '"},
        {&Options::screenshot, "--screenshot", at("no/such/x.png"), "does not exist"},
        {&Options::dumpState, "--dump-state", at(""), "not a file name"},
        {&Options::frameStats, "--frame-stats", at("file.txt/f.json"), "is not a folder"},
        {&Options::soakReport, "--soak-report", m_dir.string(), "it is a folder"},
        {&Options::screenshot, "--screenshot", at("file.txt/x.png"), "is not a folder"},
        {&Options::screenshot, "--screenshot", m_dir.string(), "it is a folder"},
        {&Options::screenshotDir, "--screenshot-dir", at("file.txt"), "Not a directory"},
    };
    for (const Case& c : cases) {
        Options o;
        o.given.screenshotDir = true;
        o.*c.field = c.path;
        const std::string message = session::checkOutputPaths(o);
        EXPECT_EQ(message.rfind(std::string(c.flag) + ": cannot write '" + c.path + "': ", 0), 0u) << message;
        EXPECT_NE(message.find(c.reason), std::string::npos) << message;
    }
    // A folder the system refuses even to root (sysfs); the reason is the system's own words.
    ASSERT_TRUE(std::filesystem::is_directory("/sys/kernel")) << "this test expects sysfs at /sys";
    Options o;
    o.screenshot = "/sys/x.png";
    const std::string message = session::checkOutputPaths(o);
    const std::string head = "--screenshot: cannot write '/sys/x.png': ";
    EXPECT_EQ(message.rfind(head, 0), 0u) << message;
    EXPECT_GT(message.size(), head.size());
    // --screenshot-dir is checked only when given: the default folder matters only if F2 is pressed.
    Options notGiven;
    notGiven.screenshotDir = at("file.txt");
    EXPECT_EQ(session::checkOutputPaths(notGiven), "");
}

} // namespace
