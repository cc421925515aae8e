// minecrappy-lab's hair commands, in-process on tiny inputs: the JSON keys the acceptance checks read, the
// physics figures hair-check reports, and exit code 2 naming the flag for bad values.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lab/hair_study.h"
#include "lab_run.h"

namespace {

using Result = lab_test::LabRun;
using lab_test::runLab;

std::string readFile(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(HairStudy, BenchWritesTheKeysAndFiguresAreSane) {
    const auto dir = std::filesystem::temp_directory_path() / "mc_hair_bench_test";
    std::filesystem::create_directories(dir);
    const auto json = dir / "bench.json";
    const Result r = runLab(
        {"hair-bench", "--strands", "64", "--nodes", "6", "--steps", "5", "--threads", "2", "--json", json.string()});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("solver / naive"), std::string::npos);
    const std::string text = readFile(json);
    for (const char* key : {"\"node_steps_per_s\"", "\"naive_node_steps_per_s\"", "\"limit_node_steps_per_s\"",
                            "\"ms_per_step\"", "\"threads\": 2"})
        EXPECT_NE(text.find(key), std::string::npos) << key;
    std::filesystem::remove_all(dir);
}

TEST(HairStudy, CheckStaysInsideItsBoundsOnAShortRun) {
    lab::HairCheckOptions o;
    o.seconds = 0.5;
    const lab::HairCheckResult r = lab::runHairCheck(o);
    EXPECT_FALSE(r.nan);
    EXPECT_LT(r.maxPenetration, 1e-5);
    // Measured: segment error 6.2e-6 (float rounding of dftl's exact lengths), settled after 2.45 s (3.217 s
    // while the host's spin and drop were integrated by the tick; the run is chaotic, see HAIR.md). Held to 5
    // times the error and 25 % either side of the settle time: a solver that let segments stretch by a tenth of
    // a millimetre in a metre, or one whose damping halved or doubled, fails (the bound was 0.5 before, 80,000
    // times the measured value, and "settled at all").
    EXPECT_LT(r.maxSegmentError, 3e-5);
    EXPECT_GT(r.settleSeconds, 2.45 / 1.25);
    EXPECT_LT(r.settleSeconds, 2.45 * 1.25);
    std::ostringstream s;
    lab::writeHairCheckJson(r, s);
    for (const char* key : {"\"max_segment_error\"", "\"max_penetration\"", "\"nan\": false", "\"settle_seconds\""})
        EXPECT_NE(s.str().find(key), std::string::npos) << key;
}

TEST(HairStudy, CheckCommandPrintsJson) {
    const Result r = runLab({"hair-check", "--seconds", "0.2", "--dt", "0.02"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("\"max_penetration\""), std::string::npos);
}

TEST(HairStudy, BadValuesExitTwoNamingTheFlag) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"hair-bench", "--strands", "0"}, "--strands"},
        {{"hair-bench", "--strands", "1000000000"}, "--strands"},
        {{"hair-bench", "--nodes", "1"}, "--nodes"},
        {{"hair-bench", "--iterations", "-3"}, "--iterations"},
        {{"hair-bench", "--steps", "0"}, "--steps"},
        {{"hair-bench", "--threads", "0"}, "--threads"},
        {{"hair-bench", "--strands", "many"}, "--strands"},
        {{"hair-bench", "--strands", "1048576", "--nodes", "256"}, "--strands"},
        {{"hair-check", "--dt", "0"}, "--dt"},
        {{"hair-check", "--dt", "-0.01"}, "--dt"},
        {{"hair-check", "--dt", "nan"}, "--dt"},
        {{"hair-check", "--dt", "inf"}, "--dt"},
        {{"hair-check", "--dt", "5"}, "--dt"},
        {{"hair-check", "--seconds", "0"}, "--seconds"},
        {{"hair-check", "--seconds", "1e9"}, "--seconds"},
    };
    for (const auto& [args, flag] : cases) {
        const Result r = runLab(args);
        EXPECT_EQ(r.code, 2) << args[1] << " " << args[2];
        EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
    }
}

} // namespace
