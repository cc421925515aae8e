// libFuzzer target: the command line (app/options.h). The input is split on NUL or newline into
// argv[1..]; parseOptions() must never crash, throw, exit or print (it returns what main() prints).
// Options it accepts must hold values within the ranges that --help documents.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "session/options.h"

namespace {

bool g_inside = false; // inside parseOptions(): an exit() from there is a bug

void exitHook() {
    if (g_inside) {
        // Raise through abort so that libFuzzer records the input as a crash.
        std::abort();
    }
}

void check(bool ok) {
    if (!ok) std::abort();
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    std::atexit(exitHook);
    std::at_quick_exit(exitHook);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args{"minecrappy"};
    std::string current;
    for (std::size_t i = 0; i < size; ++i) {
        const char c = static_cast<char>(data[i]);
        if (c == '\0' || c == '\n') {
            args.push_back(current);
            current.clear();
        } else {
            current += c;
        }
    }
    if (!current.empty()) args.push_back(current);
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    argv.push_back(nullptr);

    // Anything written to the standard streams from inside the parser is a bug (it must only return text).
    std::ostringstream captured;
    std::streambuf* const oldOut = std::cout.rdbuf(captured.rdbuf());
    std::streambuf* const oldErr = std::cerr.rdbuf(captured.rdbuf());
    std::streambuf* const oldLog = std::clog.rdbuf(captured.rdbuf());
    session::ParseOutcome outcome;
    g_inside = true;
    try {
        outcome = session::parseOptions(static_cast<int>(args.size()), argv.data());
    } catch (...) {
        std::abort(); // must never throw
    }
    g_inside = false;
    std::cout.rdbuf(oldOut);
    std::cerr.rdbuf(oldErr);
    std::clog.rdbuf(oldLog);
    check(captured.str().empty());

    if (outcome.options) {
        const session::Options& o = *outcome.options;
        check(outcome.exitCode == 0);
        const session::Settings& s = o.settings;
        check(s.size.width >= 16 && s.size.width <= 16384 && s.size.height >= 16 && s.size.height <= 16384);
        check(s.tickRate >= 10 && s.tickRate <= 1000);
        check(s.viewRadius >= 2 && s.viewRadius <= 32);
        check(std::isfinite(s.fov) && s.fov >= 30.0f && s.fov <= 120.0f);
        check(s.hairDetail >= 0 && s.hairDetail <= 2);
        check(s.hairBudgetThousands >= 100 && s.hairBudgetThousands <= 100000);
        check(o.autosaveTicks >= 1 && o.autosaveTicks <= 1000000);
    } else {
        check(outcome.exitCode == 0 || outcome.exitCode == 2);
        check(!outcome.output.empty());
    }
    return 0;
}
