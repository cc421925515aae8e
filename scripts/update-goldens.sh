#!/usr/bin/env bash
# Regenerates the golden PNGs of the render tests on purpose, from the current renderer. Look at every
# changed image (git diff --stat tests/render/golden; open the PNGs) before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
cmake --build "$build" -j2 --target render_tests mc_data
MINECRAPPY_DATA="$PWD/$build" MINECRAPPY_UPDATE_GOLDENS=1 "$build/tests/render_tests"
git status --short tests/render/golden
