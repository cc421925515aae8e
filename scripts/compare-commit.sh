#!/usr/bin/env bash
# Builds another commit beside the current tree and prints the engine's speed figures of both, run turn
# about in one sitting, so that a speed claim names what it was compared with (docs/ENGINE.md, "Speed").
#
#   scripts/compare-commit.sh REV [ROUNDS]
#
# REV: any commit (a hash, a tag, HEAD~3). It is built, Release, in a git worktree under
# build-compare/<hash>/ (kept for the next run; delete the folder to rebuild it). The current tree is built
# with scripts/build.sh. ROUNDS (default 3): each round runs every figure once with REV and once with the
# current tree, in turn; the table shows medians over the rounds and current / REV.
#
# Figures: meshing one terrain chunk (meshBench) and a 64^3 region (vsBaseline, our time per voxel);
# light (a column from scratch, an edit repaired, a lamp placed); a worker job (first of a column, a whole
# column); streaming (the whole view meshed at radius 8, 16 and 32: process wall and CPU seconds and peak memory
# of `--ticks 1 --screenshot`; frames to a complete view after the start and after the teleport of
# tests/e2e/teleport.txt at radius 8); hair (`minecrappy-lab hair-bench --threads 1`: ms a step and the
# fraction of its limit kernel). A figure a commit does not have prints as "-". Not part of CI.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
if [[ $# -lt 1 || $# -gt 2 ]]; then
    echo "usage: scripts/compare-commit.sh REV [ROUNDS]" >&2
    exit 2
fi
rev=$(git rev-parse --verify --quiet "$1^{commit}") || { echo "compare-commit: '$1' names no commit" >&2; exit 2; }
rounds=${2:-3}
if ! [[ $rounds =~ ^[1-9][0-9]*$ ]]; then
    echo "compare-commit: ROUNDS must be a whole number from 1, not '$rounds'" >&2
    exit 2
fi
scripts/setup.sh
scripts/build.sh >/dev/null
old=$root/build-compare/$rev
if [[ ! -d $old/src ]]; then
    mkdir -p "$root/build-compare"
    git worktree add --force --detach "$old/src" "$rev" >/dev/null
fi
if [[ ! -f $old/build/CMakeCache.txt ]]; then
    cmake -S "$old/src" -B "$old/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
echo "compare-commit: building $rev in $old/build"
cmake --build "$old/build" -j "$(nproc)" --target minecrappy minecrappy-bench minecrappy-lab >/dev/null
exec python3 "$root/scripts/compare_commit.py" --rounds "$rounds" --rev "$rev" \
    --old "$old/build" --old-source "$old/src" --new "$root/build" --new-source "$root"
