#!/usr/bin/env bash
# Times the project's binary greedy baseline (tests/bench/binary_greedy_baseline.cpp) against the published
# binary greedy mesher it stands for, on the same blocks in one process (scripts/anchor_compare.cpp).
# Not part of CI. The published mesher.h is read from a clone of cgerikj/binary-greedy-meshing at the pinned
# commit into a temporary folder and deleted afterwards; nothing of it is committed.
#
#   scripts/compare-anchor.sh [CLONE] [ROUNDS]
#
# CLONE: an existing clone (or mirror) of https://github.com/cgerikj/binary-greedy-meshing; without it the
# script clones one (network needed). Needs the Release build in build/ (scripts/build.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pin=af8c688ed3af63e98f9631c05774f30e1350a021
clone=${1:-}
rounds=${2:-2000}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [[ -z $clone ]]; then
    git clone --quiet https://github.com/cgerikj/binary-greedy-meshing "$tmp/clone"
    clone=$tmp/clone
fi
git -C "$clone" show "$pin:src/mesher.h" > "$tmp/mesher.h"
printf '#define BM_IMPLEMENTATION\n#define BM_VECTOR std::vector\n#include <vector>\n#include "mesher.h"\n' > "$tmp/published.cpp"
read -r -a extra <<< "${ANCHOR_FLAGS:-}" # more flags for both, e.g. ANCHOR_FLAGS=-march=native
flags=(-std=c++20 -O3 -DNDEBUG "${extra[@]}")
layers=$root/build/src-layers
${CXX:-g++} "${flags[@]}" -I"$tmp" -c "$tmp/published.cpp" -o "$tmp/published.o"
${CXX:-g++} "${flags[@]}" -I"$tmp" -I"$root/tests/bench" -I"$layers/mc_world" -I"$layers/mc_core" \
    "$root/scripts/anchor_compare.cpp" "$root/tests/bench/binary_greedy_baseline.cpp" "$tmp/published.o" \
    "$root/build/src/libmc_world.a" "$root/build/src/libmc_core.a" -lstb -lpthread -o "$tmp/anchor_compare"
echo "published mesher: cgerikj/binary-greedy-meshing at $pin; both built with ${flags[*]}"
"$tmp/anchor_compare" "$rounds"
