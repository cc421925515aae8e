#include <gtest/gtest.h>

#include <vector>

#include "app/options.h"

namespace {

app::ParseOutcome parse(std::vector<const char*> args) {
    args.insert(args.begin(), "minecrappy");
    return app::parseOptions(static_cast<int>(args.size()), args.data());
}

TEST(Options, DefaultsWithoutFlags) {
    const auto r = parse({});
    ASSERT_TRUE(r.options);
    EXPECT_FALSE(r.options->headless);
    EXPECT_EQ(r.options->width, 1280);
    EXPECT_EQ(r.options->height, 720);
    EXPECT_EQ(r.options->tickRate, 60);
}

TEST(Options, HeadlessContract) {
    const auto r = parse({"--headless", "--ticks", "120", "--size", "640x360", "--seed", "99", "--terrain", "flat",
                          "--screenshot", "a.png", "--dump-state", "a.json"});
    ASSERT_TRUE(r.options) << r.output;
    EXPECT_TRUE(r.options->headless);
    EXPECT_EQ(r.options->ticks, 120u);
    EXPECT_EQ(r.options->width, 640);
    EXPECT_EQ(r.options->height, 360);
    EXPECT_EQ(r.options->seed, 99u);
    EXPECT_EQ(r.options->terrain, world::TerrainKind::Flat);
    EXPECT_EQ(r.options->screenshot, "a.png");
    EXPECT_EQ(r.options->dumpState, "a.json");
}

TEST(Options, HelpListsEveryFlagWithDefaults) {
    const auto r = parse({"--help"});
    EXPECT_FALSE(r.options);
    EXPECT_EQ(r.exitCode, 0);
    for (const char* flag : {"--headless", "--ticks", "--size", "--seed", "--terrain", "--script", "--screenshot",
                             "--dump-state", "--tick-rate", "--view-radius", "--fov", "--vsync", "--version"}) {
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
        {"--script", "/nonexistent/walk.txt"},
        {"--screenshot", "x.png"}, // needs --headless
    };
    for (const auto& args : bad) {
        const auto r = parse(args);
        EXPECT_FALSE(r.options) << args[0];
        EXPECT_EQ(r.exitCode, 2) << args[0];
        const std::string flag = args[0];
        if (flag != "--bogus") {
            EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
        }
    }
}

} // namespace
