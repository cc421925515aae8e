// Small pieces every lab study and command shares: number formatting for CSV and chart labels, timing, the
// CSV writer and the --out folder. Kept here once (they had been written three times over).
#pragma once

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace lab {

// Appends the shortest text that reads back as the same double (full precision without %.17g's noise).
void appendNumber(std::string& line, double v);
// v through one printf conversion for a double ("%.3g", "%+.3g", "%.2f"...): labels, tables, messages.
std::string formatNumber(const char* printfFormat, double v);
// %.4g: for labels and messages.
std::string formatShort(double v);
double secondsSince(std::chrono::steady_clock::time_point start);

// Writes `path` whole through a temporary file and a rename (lab/atomic_file.h), or throws naming it.
std::filesystem::path writeCsvFile(const std::filesystem::path& path, const std::function<void(std::ostream&)>& body);

// Creates `dir` and its parents for --out; a folder that cannot be made is bad input: says so on `err`,
// naming the command and the folder, and returns false (the caller exits 2).
bool prepareOutDir(const std::string& dir, const std::string& command, std::ostream& err);
// "COMMAND: wrote PATH", a line each.
void reportWritten(std::ostream& out, const std::string& command, const std::vector<std::filesystem::path>& paths);

// Runs `step` in batches until `steps` are done; returns the best seconds per step among the batches, so one
// batch undisturbed by the rest of the (shared) machine is enough.
template <typename F>
double bestSecondsPerStep(int steps, F&& step) {
    const int batches = std::clamp(steps / 20, 1, 10);
    const int perBatch = std::max(1, steps / batches);
    double best = 1e30;
    for (int b = 0; b < batches; ++b) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < perBatch; ++i) step();
        best = std::min(best, secondsSince(t0) / perBatch);
    }
    return best;
}

} // namespace lab
