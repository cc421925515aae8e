// The two ways to run the game. Both return a process exit code: 0 success, 1 runtime failure
// (no GL context, missing shader or asset), 2 bad input.
#pragma once
#include "app/options.h"
#include "app/settings.h"

namespace app {

int runHeadless(const Options& options, const Settings& settings);
int runWindowed(const Options& options, const Settings& settings);

} // namespace app
