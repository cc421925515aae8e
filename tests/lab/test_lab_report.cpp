// docs/LAB.md's pendulum figures are the lab's: the block between the lab-report markers must be exactly what
// `minecrappy-lab report` writes as its first section (errors, orders, limits and the agreement with the 50-digit
// reference are the same bits on every run of a build; timings are never in it). When the physics changes on
// purpose, regenerate the block with
//   build/minecrappy-lab report --out /tmp/report && sed -n '/lab-report:begin/,/lab-report:end/p'
//   /tmp/report/report.md
// and paste it over docs/LAB.md's.
#include "lab/exact_reference.h"
#include "lab/lab_report.h"
#include "physics/pendulum.h"

#include <gtest/gtest.h>

#include "lab_run.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace {

TEST(LabReport, TheDocsQuoteTheLabsPendulumFiguresExactly) {
    // Precondition: the report has its tables, with a row for the methods the prose names.
    lab_test::expectDocsQuote(
        "LAB.md", "lab-report", [] { return lab::pendulumReportMarkdown(); },
        {"| rk4 |", "| symplectic-euler |", "| rotating |"},
        "docs/LAB.md's pendulum figures differ from `minecrappy-lab report`; regenerate them");
}

TEST(LabReport, TheClosedFormIsAsAccurateAsItsHeaderSays) {
    // physics/pendulum.h: within 6e-14 rad over the first minute and 1e-13 rad at 300 s for swings; for rotation
    // the ulp of theta (which keeps growing) sets the floor: held here to 2 ulp. Against every reference value.
    const physics::PendulumParams params{1.0, 9.81, 1.0, 0.0};
    int rows = 0;
    for (const lab::ExactReferenceValue& v : lab::exactReferenceValues()) {
        const double reference = std::strtod(v.theta, nullptr);
        ASSERT_TRUE(std::isfinite(reference)) << v.theta;
        const double ulp =
            std::nextafter(std::abs(reference), std::numeric_limits<double>::infinity()) - std::abs(reference);
        const physics::ExactPendulum exact(params, {v.theta0, v.omega0});
        const bool swinging = exact.regime() == physics::ExactPendulum::Regime::Swinging;
        const double bound = swinging ? (v.t <= 60.0 ? 6e-14 : 1e-13) : 2.0 * ulp;
        EXPECT_LE(std::abs(exact.at(v.t).theta - reference), bound)
            << "theta0 " << v.theta0 << ", omega0 " << v.omega0 << ", t " << v.t;
        EXPECT_NEAR(exact.at(v.t).omega, std::strtod(v.omega, nullptr), 1e-11)
            << "theta0 " << v.theta0 << ", omega0 " << v.omega0 << ", t " << v.t;
        ++rows;
    }
    EXPECT_EQ(rows, 20); // five starts x four times: the whole table was read
}

} // namespace
