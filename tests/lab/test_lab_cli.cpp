// minecrappy-lab's command line, run in-process: exit codes (0 done, 2 bad usage or input, 1 runtime
// failure), messages that name the flag, and runs that write their files.
#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../temp_dir.h"
#include "lab_run.h"

namespace {

using lab_test::runLab;

std::filesystem::path freshDir(const std::string& what) {
    return test_util::freshRandomTempDir("mc_lab_cli_test_", what);
}

std::vector<std::string> pendulumArgs(const std::string& csv) {
    return {"pendulum", "--method", "verlet", "--dt", "0.01", "--theta0", "30", "--seconds", "0.5", "--csv", csv};
}

TEST(LabCli, HelpAndNoCommandExitZero) {
    for (const auto& args : {std::vector<std::string>{"--help"}, std::vector<std::string>{}}) {
        const auto r = runLab(args);
        EXPECT_EQ(r.code, 0);
        for (const char* word : {"minecrappy-lab", "pendulum", "work-precision", "stability", "seed-figures"}) {
            EXPECT_NE(r.out.find(word), std::string::npos) << word;
        }
    }
}

TEST(LabCli, CommandHelpListsEveryFlagWithItsDefault) {
    const auto r = runLab({"pendulum", "--help"});
    EXPECT_EQ(r.code, 0);
    for (const char* flag : {"--method", "--dt", "--theta0", "--omega0", "--length", "--g", "--mass", "--seconds",
                             "--csv", "euler-cartesian", "symplectic-euler", "=9.81", "=0", "=1"}) {
        EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
    }
    for (const char* command : {"work-precision", "stability", "seed-figures"}) {
        const auto h = runLab({command, "--help"});
        EXPECT_EQ(h.code, 0) << command;
        EXPECT_NE(h.out.find("--out"), std::string::npos) << command;
    }
}

TEST(LabCli, VersionAndUnknownCommand) {
    const auto v = runLab({"--version"}, "9.8.7");
    EXPECT_EQ(v.code, 0);
    EXPECT_EQ(v.out, "minecrappy-lab 9.8.7\n");
    const auto bogus = runLab({"bogus"});
    EXPECT_EQ(bogus.code, 2);
    EXPECT_NE(bogus.err.find("bogus"), std::string::npos) << bogus.err;
}

TEST(LabCli, BadValuesExitTwoAndNameTheFlag) {
    const auto dir = freshDir("bad");
    const std::string csv = (dir / "x.csv").string();
    struct Case {
        std::string flag;
        std::string value; // replaces the flag's value in a good command; "" removes the flag
    };
    const std::vector<Case> cases = {
        {"--method", "leapfrog"}, {"--method", ""},    {"--dt", "0"},     {"--dt", "-0.01"},     {"--dt", "nan"},
        {"--dt", "inf"},          {"--dt", "fast"},    {"--dt", ""},      {"--theta0", "north"}, {"--theta0", "nan"},
        {"--seconds", "0"},       {"--seconds", "-1"}, {"--seconds", ""}, {"--csv", ""},
    };
    for (const auto& c : cases) {
        auto args = pendulumArgs(csv);
        for (std::size_t i = 0; i + 1 < args.size(); ++i) {
            if (args[i] != c.flag) continue;
            if (c.value.empty()) {
                args.erase(args.begin() + static_cast<std::ptrdiff_t>(i),
                           args.begin() + static_cast<std::ptrdiff_t>(i) + 2);
            } else {
                args[i + 1] = c.value;
            }
            break;
        }
        const auto r = runLab(args);
        EXPECT_EQ(r.code, 2) << c.flag << " " << c.value;
        EXPECT_NE(r.err.find(c.flag), std::string::npos) << c.flag << " " << c.value << ": " << r.err;
    }
    const std::vector<std::pair<std::string, std::string>> extra = {
        {"--length", "0"}, {"--length", "-1"}, {"--g", "0"}, {"--g", "-9.81"}, {"--mass", "0"}, {"--omega0", "x"}};
    for (const auto& [flag, value] : extra) {
        auto args = pendulumArgs(csv);
        args.push_back(flag);
        args.push_back(value);
        const auto r = runLab(args);
        EXPECT_EQ(r.code, 2) << flag << " " << value;
        EXPECT_NE(r.err.find(flag), std::string::npos) << flag << ": " << r.err;
    }
    const auto unknownMethod =
        runLab({"pendulum", "--method", "leapfrog", "--dt", "0.01", "--theta0", "1", "--seconds", "1", "--csv", csv});
    EXPECT_NE(unknownMethod.err.find("rk4"), std::string::npos) << "lists the valid methods: " << unknownMethod.err;
    EXPECT_FALSE(std::filesystem::exists(csv)); // nothing written for a refused run
    std::filesystem::remove_all(dir);
}

TEST(LabCli, TooManyStepsIsRefused) {
    const auto dir = freshDir("steps");
    auto args = pendulumArgs((dir / "x.csv").string());
    args[4] = "1e-7"; // --dt
    args[8] = "100";  // --seconds: 1e9 steps
    const auto r = runLab(args);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--dt"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("50000000"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.csv"));
    std::filesystem::remove_all(dir);
}

TEST(LabCli, PendulumRunWritesItsCsvAndSaysWhere) {
    const auto dir = freshDir("run");
    const auto csv = dir / "verlet.csv";
    const auto r = runLab(pendulumArgs(csv.string()));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find(csv.string()), std::string::npos) << r.out;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "t,theta,omega,energy,theta_exact,energy_error");
    std::size_t rows = 0;
    for (std::string l; std::getline(in, l);) ++rows;
    EXPECT_EQ(rows, 51u); // 0.5 s / 0.01 s, plus t = 0
    std::filesystem::remove_all(dir);
}

TEST(LabCli, OutputThatCannotBeMadeIsNamed) {
    const auto dir = freshDir("out");
    // A missing folder for --csv is bad input (2), named.
    const auto missing = runLab(pendulumArgs((dir / "nope" / "x.csv").string()));
    EXPECT_EQ(missing.code, 2);
    EXPECT_NE(missing.err.find("--csv"), std::string::npos) << missing.err;
    // An --out folder that cannot be created (a file is in the way) is bad input too.
    std::ofstream(dir / "file").put('x');
    const auto blocked = runLab({"seed-figures", "--out", (dir / "file" / "figs").string()});
    EXPECT_EQ(blocked.code, 2);
    EXPECT_NE(blocked.err.find("--out"), std::string::npos) << blocked.err;
    std::filesystem::remove_all(dir);
}

// As in the game, an output the system will not take is exit 2 with the system's reason.
TEST(LabCli, UnwritableFileIsExitTwoWithTheSystemsReason) {
    // /proc refuses new files even to root, unlike a read-only permission bit. Minecrappy runs on
    // Linux only (OSMesa, /proc/self/exe), so /proc is always there.
    ASSERT_TRUE(std::filesystem::is_directory("/proc/self"));
    const auto r = runLab(pendulumArgs("/proc/minecrappy-lab-test.csv"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("cannot write '/proc/minecrappy-lab-test.csv': creating a file in '/proc': "),
              std::string::npos)
        << r.err;
    // A full disk: /dev/full takes nothing.
    const auto full = runLab(pendulumArgs("/dev/full"));
    EXPECT_EQ(full.code, 2);
    EXPECT_NE(full.err.find(std::strerror(ENOSPC)), std::string::npos) << full.err;
}

// Every physical parameter within the game's ranges, refused with exit 2 naming the flag: a rod of 1 mm to
// 16 m, gravity up to 1e4 m/s^2, a mass up to 1e6 kg.
TEST(LabCli, PendulumParametersOutsideTheGamesRangesAreRefused) {
    const auto dir = freshDir("ranges");
    const std::string csv = (dir / "x.csv").string();
    const auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = pendulumArgs(csv);
        args.insert(args.end(), extra.begin(), extra.end());
        return runLab(args);
    };
    for (const auto& [flag, value] : std::vector<std::pair<std::string, std::string>>{
             {"--length", "0.0009"}, {"--length", "16.5"}, {"--g", "10001"}, {"--mass", "2e6"}, {"--dt", "-1"}}) {
        const auto r = with({flag, value});
        EXPECT_EQ(r.code, 2) << flag << " " << value;
        EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(csv)) << flag << " " << value;
    }
    EXPECT_EQ(with({"--length", "0.001"}).code, 0) << "the shortest rod the game takes";
    EXPECT_EQ(with({"--length", "16", "--g", "10000"}).code, 0);
    std::filesystem::remove_all(dir);
}

TEST(LabCli, SeedFiguresWritesEveryFigure) {
    const auto dir = freshDir("seed");
    const auto r = runLab({"seed-figures", "--out", (dir / "figs").string()});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* stem : {"seed_dt1ms", "seed_dt16ms", "seed_dt33ms"}) {
        for (const char* ext : {".svg", ".csv"}) {
            const auto path = dir / "figs" / (std::string(stem) + ext);
            EXPECT_TRUE(std::filesystem::is_regular_file(path)) << path;
            EXPECT_NE(r.out.find(path.string()), std::string::npos) << r.out;
        }
    }
    std::filesystem::remove_all(dir);
}

} // namespace

namespace {

TEST(LabCli, NewMethodsAndCommandsRefuseBadValuesWithExitTwoAndWriteNothing) {
    const auto dir = freshDir("new-bad");
    const std::string csv = (dir / "d.csv").string();
    // dopri5's tolerance: zero and negative by the flag's own check, too small by the run's validation.
    for (const std::string tolerance : {"0", "-1e-6", "1e-20", "2"}) {
        const auto r = runLab({"pendulum", "--method", "dopri5", "--tolerance", tolerance, "--dt", "0.1", "--theta0",
                               "60", "--seconds", "1", "--csv", csv});
        EXPECT_EQ(r.code, 2) << tolerance;
        EXPECT_NE(r.err.find("tolerance"), std::string::npos) << tolerance << ": " << r.err;
        EXPECT_NE(r.err.find(tolerance), std::string::npos) << "names the value: " << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(csv)) << "a refused run left a file behind";
    // A good dopri5 run writes its steps column.
    const auto good = runLab({"pendulum", "--method", "dopri5", "--tolerance", "1e-6", "--dt", "0.5", "--theta0", "60",
                              "--seconds", "1", "--csv", csv});
    ASSERT_EQ(good.code, 0) << good.err;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "t,theta,omega,energy,theta_exact,energy_error,steps");
    // long-run: a non-positive horizon, and one that asks for too many steps.
    const std::string out = (dir / "long").string();
    const auto zero = runLab({"long-run", "--out", out, "--seconds", "0"});
    EXPECT_EQ(zero.code, 2);
    EXPECT_NE(zero.err.find("--seconds"), std::string::npos) << zero.err;
    const auto huge = runLab({"long-run", "--out", out, "--seconds", "1e9"});
    EXPECT_EQ(huge.code, 2);
    EXPECT_NE(huge.err.find("1e+09"), std::string::npos) << huge.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "a refused long-run made its folder";
    // report: the timing runs are bounded.
    const auto runs = runLab({"report", "--out", (dir / "report").string(), "--timing-runs", "99"});
    EXPECT_EQ(runs.code, 2);
    EXPECT_NE(runs.err.find("--timing-runs"), std::string::npos) << runs.err;
}

} // namespace
