// The figures docs/LAB.md quotes, made by the lab: `minecrappy-lab report --out DIR` writes them
// as Markdown (report.md), each table with the command that makes its full version, and
// tests/lab/test_lab_report.cpp fails when the docs' copy (between the lab-report markers) differs from
// pendulumReportMarkdown(). Deterministic figures (errors, orders, limits, agreement with the 50-digit
// reference: the same bits on every run of a build) go in that block; timings never do: they go in
// timingReportMarkdown(), with the machine and the spread of several runs, and are quoted, not asserted.
// It must never touch a terminal or exit.
#pragma once

#include <string>

namespace lab {

// The deterministic block: each method's angle and energy error at 1 ms and at about one game tick, its
// observed order, the ratios the prose quotes, the linear and 60-second stability limits, the adaptive
// method by tolerance, the long-horizon drift, and the closed form against 50-digit reference values.
// Takes a few seconds.
std::string pendulumReportMarkdown();

// Nanoseconds per step of each method at about one game tick: the median and the range of `runs` runs, with
// the CPU it ran on. Not reproducible bit for bit; never compared by a test.
std::string timingReportMarkdown(int runs);

} // namespace lab
