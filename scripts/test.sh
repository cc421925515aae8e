#!/usr/bin/env bash
# Sets up, builds and runs every test through CTest, in three passes:
#  1. the Release build (g++, warnings are errors): unit, render, end-to-end, crash and soak tests, then the
#     speed gate alone (label gate: same-process speed ratios against measured ceilings);
#  2. a clang 14 build with AddressSanitizer and UndefinedBehaviorSanitizer (warnings are errors):
#     unit and render tests under the sanitizers, any report fails; then the e2e scripts' states and a
#     recording compared between the two builds (tests/e2e/cross_build.sh);
#  3. clang-format and clang-tidy over the tree (scripts/check-style.sh).
# Fuzzing joins pass 2 when the fuzz targets are built (label fuzz). Arguments go to every ctest run.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs=$(nproc)

echo "== 1/3: Release build (g++) and every test"
BUILD_DIR=build scripts/build.sh
(cd build && ctest --output-on-failure -j "$jobs" -LE gate "$@")
echo "== the speed gate, alone, after the other tests"
(cd build && ctest --output-on-failure -L gate "$@")

echo "== 2/3: clang 14 with AddressSanitizer and UndefinedBehaviorSanitizer"
# Line tables are all a sanitizer report needs (file and line of each frame); full debug information made this
# build about a quarter slower. Only what this pass runs is built (not the benchmarks or the lab program).
if [ ! -f build-sanitize/CMakeCache.txt ]; then
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DMINECRAPPY_SANITIZE=ON -DMINECRAPPY_FUZZ=ON -DMINECRAPPY_WERROR=ON -DMINECRAPPY_NATIVE_HAIR=OFF >/dev/null
fi
cmake --build build-sanitize -j "$jobs" --target unit_tests render_tests minecrappy png_probe fuzz_targets
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0
# The docs-figure tests of the lab reports recompute every study (about a minute in the Release build, ten
# times that under the sanitizers); the code it runs is covered here by the smaller lab tests. The render tests
# run on OSMesa, and on EGL only the goldens (context, drawing and read-back through the EGL platform code): the
# Release pass runs every render test on both backends, and our code is otherwise the same on either.
(cd build-sanitize && ctest --output-on-failure -j "$jobs" -L 'unit|render|fuzz' \
  -E '^(LabReport|HairReport)\.TheDocs|\.egl$' "$@")
(cd build-sanitize && ctest --output-on-failure --no-tests=error -j "$jobs" \
  -R '^RenderTest\.(FlatScene|DefaultTerrain)MatchesGolden\.egl$' "$@")

echo "== cross-build determinism: the Release and sanitizer builds reach the same states"
bash tests/e2e/cross_build.sh build/minecrappy build-sanitize/minecrappy tests

echo "== 3/3: clang-format and clang-tidy"
scripts/check-style.sh
