#!/usr/bin/env bash
# The longer fuzzing run: configures a clang tree in build-fuzz/ (-DMINECRAPPY_FUZZ=ON), builds the five
# libFuzzer targets, and runs each for SECONDS (default 600) in turn, growing a scratch corpus in
# build-fuzz/fuzz/corpus-<target>/ that starts from the committed seeds in tests/fuzz/corpus/<target>/
# (never modified here). Any crash, leak, timeout or out-of-memory input is copied into
# tests/fuzz/crashes/<target>/ for a person to reproduce (build-fuzz/fuzz/fuzz_<target> FILE), fix, and
# then add to tests/fuzz/corpus/<target>/ as a regression input.
#   scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 600, scripts/fuzz.sh 60 world cli
# Environment: FUZZ_JOBS (parallel fuzzing jobs per target, default 1), CXX (default clang++, else clang++-14).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(script settings world cli game)
build=${BUILD_DIR:-build-fuzz}
cxx=${CXX:-$(command -v clang++ || command -v clang++-14)}

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
        -DMINECRAPPY_FUZZ=ON -DMINECRAPPY_NATIVE_HAIR=OFF >/dev/null
fi
cmake --build "$build" -j "$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

status=0
parallel=()
if [ "${FUZZ_JOBS:-1}" -gt 1 ]; then parallel=(-jobs="$FUZZ_JOBS" -workers="$FUZZ_JOBS"); fi
for t in "${targets[@]}"; do
  corpus=$build/fuzz/corpus-$t
  artifacts=$build/fuzz/artifacts-$t
  mkdir -p "$corpus" "$artifacts"
  cp -R "tests/fuzz/corpus/$t/." "$corpus/"
  echo "== fuzz_$t: ${seconds}s, corpus $corpus ($(ls "$corpus" | wc -l) inputs)"
  set +e
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$build/fuzz/fuzz_$t" "$corpus" -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 \
      -error_exitcode=77 -timeout_exitcode=78 -detect_leaks=1 -print_final_stats=1 \
      "${parallel[@]}" $([ "$t" = game ] && echo -max_len=2048 -len_control=0) -artifact_prefix="$artifacts/" 2>&1 | tail -n 40
  rc=${PIPESTATUS[0]}
  set -e
  found=$(find "$artifacts" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  if [ "$found" -gt 0 ]; then
    mkdir -p "tests/fuzz/crashes/$t"
    find "$artifacts" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) \
      -exec cp {} "tests/fuzz/crashes/$t/" \;
    echo "!! fuzz_$t: $found failing input(s) copied to tests/fuzz/crashes/$t/ (reproduce: $build/fuzz/fuzz_$t FILE)"
    status=1
  elif [ "$rc" -ne 0 ]; then
    echo "!! fuzz_$t exited with $rc"
    status=1
  fi
done
cd "$root"
exit $status
