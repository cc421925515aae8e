#!/usr/bin/env bash
# Configures (once) and builds the Release tree in build/ with both cores. Used by play.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMINECRAPPY_WERROR=ON >/dev/null
fi
cmake --build "$build" -j "$(nproc)" "$@"
