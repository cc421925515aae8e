// The README's hair figures are the lab's: the block between the hair-report markers must be exactly what
// `minecrappy-lab hair-report` prints (errors, orders and settle times are the same bits on every run of a
// build; timings are never in it). When the physics changes on purpose, regenerate the block with
//   build/minecrappy-lab hair-report
// and paste it between the markers.
#include "lab/hair_report.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace {

std::string readme() {
    std::ifstream in(std::string(MC_TEST_DATA) + "/../README.md");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(HairReport, TheReadmeQuotesTheLabsFiguresExactly) {
    const std::string text = readme();
    ASSERT_FALSE(text.empty()) << "README.md not found next to tests/";
    const std::string begin = "<!-- hair-report:begin -->\n", end = "<!-- hair-report:end -->";
    const auto a = text.find(begin), b = text.find(end);
    ASSERT_NE(a, std::string::npos) << "no hair-report:begin marker in README.md";
    ASSERT_NE(b, std::string::npos) << "no hair-report:end marker in README.md";
    ASSERT_LT(a, b);
    const std::string quoted = text.substr(a + begin.size(), b - a - begin.size());
    const std::string made = lab::hairReportMarkdown();
    // Precondition: the report has its two tables, one row per method and per tick.
    ASSERT_NE(made.find("| shake |"), std::string::npos);
    ASSERT_NE(made.find("| 1/144 s |"), std::string::npos);
    EXPECT_EQ(quoted, made) << "README.md's hair figures differ from `minecrappy-lab hair-report`; regenerate them";
}

} // namespace
