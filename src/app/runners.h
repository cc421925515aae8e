// The two ways to run the game, sharing one Frontend (app/frontend.h). Both return a process exit code:
// 0 success, 1 runtime failure (no GL context, missing shader or asset), 2 bad input.
#pragma once
#include "session/options.h"
#include "session/settings.h"

namespace app {

// options.settings are the run's settings (session::mergeSettings has joined the file and the flags).
int runHeadless(const session::Options& options);
int runWindowed(const session::Options& options);

} // namespace app
