// The hair figures docs/HAIR.md quotes, made by the lab: `minecrappy-lab hair-report` prints them as Markdown,
// and tests/lab/test_hair_report.cpp fails when the docs' copy (between the hair-report markers) differs.
// Only deterministic figures (errors, orders, settle times: the same bits on every run of this build), never
// timings. It must never touch a terminal or exit.
#pragma once

#include <string>

namespace lab {

// The Markdown block: every hair method on the 11-link chain against its exact solution (tip error as the
// step halves, the observed order, energy error), and hair-check's figures for the game's default at 30, 60
// and 144 Hz. Takes about 5 s.
std::string hairReportMarkdown();

} // namespace lab
