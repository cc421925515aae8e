// docs/HAIR.md's hair figures are the lab's: the block between the hair-report markers must be exactly what
// `minecrappy-lab hair-report` prints (errors, orders and settle times are the same bits on every run of a
// build; timings are never in it). When the physics changes on purpose, regenerate the block with
//   build/minecrappy-lab hair-report
// and paste it between the markers.
#include "lab/hair_report.h"

#include <gtest/gtest.h>

#include "lab_run.h"

#include <fstream>
#include <sstream>
#include <string>

namespace {

TEST(HairReport, TheDocsQuoteTheLabsFiguresExactly) {
    std::string why;
    const std::string quoted = lab_test::docsBlock("HAIR.md", "hair-report", why);
    ASSERT_TRUE(why.empty()) << why;
    const std::string made = lab::hairReportMarkdown();
    // Precondition: the report has its two tables, one row per method and per tick.
    ASSERT_NE(made.find("| shake |"), std::string::npos);
    ASSERT_NE(made.find("| 1/144 s |"), std::string::npos);
    EXPECT_EQ(quoted, made) << "docs/HAIR.md's hair figures differ from `minecrappy-lab hair-report`; regenerate them";
}

} // namespace
