// The command line of minecrappy-lab: parses the subcommands (pendulum, work-precision, stability,
// seed-figures), validates every value before any work starts, runs the study and says where its files
// went. Exit codes: 0 done (or --help), 2 bad usage or input (the message names the flag), 1 a runtime
// failure such as a file that cannot be written. It must never call exit() or touch std::cout/std::cerr
// except through the streams it is given, so tests can run it in-process.
#pragma once
#include <ostream>
#include <string_view>

namespace lab {

// `version`: when not empty, --version prints "minecrappy-lab <version>" (main() passes MC_VERSION; the
// lab library itself does not know the project version).
int runLab(int argc, const char* const* argv, std::ostream& out, std::ostream& err, std::string_view version = {});
// The same on std::cout and std::cerr.
int runLab(int argc, char** argv, std::string_view version = {});

} // namespace lab
