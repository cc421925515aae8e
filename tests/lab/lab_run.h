// Runs minecrappy-lab in-process, the way a shell would: argv[0] plus the given arguments, with its
// exit code and both output streams captured. Shared by the lab's command-line tests.
#pragma once

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "lab/lab_cli.h"

namespace lab_test {

struct LabRun {
    int code = -1;
    std::string out, err;
};

inline LabRun runLab(std::vector<std::string> args, std::string_view version = {}) {
    args.insert(args.begin(), "minecrappy-lab");
    std::vector<const char*> argv;
    argv.reserve(args.size());
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    LabRun r;
    r.code = lab::runLab(static_cast<int>(argv.size()), argv.data(), out, err, version);
    r.out = out.str();
    r.err = err.str();
    return r;
}

} // namespace lab_test
