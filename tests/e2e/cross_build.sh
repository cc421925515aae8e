#!/usr/bin/env bash
# Determinism across builds: the e2e scripts reach the same state in the Release build (g++, the hair kernels
# with the machine's vectors) and the sanitizer build (clang 14, x86-64 baseline vectors), so a hash that
# lies in one of them shows. Compared: the dump's state_hash (every hair node included, docs/WORLDS.md,
# "The state hash") and each ball's hair_hash; and a recording made by one build replays in the other.
# Usage: cross_build.sh RELEASE_GAME SANITIZER_GAME SOURCE_TESTS_DIR. Run by scripts/test.sh after both passes.
set -u
a=$1 b=$2 src=$3
source "$(dirname "$0")/checks.sh" # tmp, check(), passes, failures
same_state() { # two dumps: the same state hash and the same hair, ball by ball (and at least one ball)
  python3 - "$1" "$2" <<'PY'
import json, sys
x, y = (json.load(open(p)) for p in sys.argv[1:3])
assert x["state_hash"] == y["state_hash"], (x["state_hash"], y["state_hash"])
hx, hy = [b["hair_hash"] for b in x["hair_balls"]], [b["hair_hash"] for b in y["hair_balls"]]
assert hx and hx == hy, (hx, hy)
PY
}
run() { # build, name, ticks, script, extra flags...
  local bin=$1 name=$2 ticks=$3 script=$4; shift 4
  "$bin" --settings none --headless --ticks "$ticks" --size 160x90 --seed 7 --script "$script" \
    --dump-state "$tmp/$name.json" "$@" >/dev/null 2>"$tmp/$name.err" || { cat "$tmp/$name.err"; return 1; }
}
for case in "walk 600 $src/e2e/walk.txt" "four_balls 300 $src/e2e/four_balls.txt" "teleport 120 $src/e2e/teleport.txt"; do
  set -- $case
  check "$1: release build runs" run "$a" "$1.a" "$2" "$3"
  check "$1: sanitizer build runs" run "$b" "$1.b" "$2" "$3"
  check "$1: the same state and hair in both builds" same_state "$tmp/$1.a.json" "$tmp/$1.b.json"
done
# A recording made by the Release build replays in the sanitizer build to every recorded hash (exit 3 if not).
check "record (release)" run "$a" rec 300 "$src/e2e/four_balls.txt" --record "$tmp/four.mcscript"
replay() { "$b" --settings none --headless --size 160x90 --script "$tmp/four.mcscript" --dump-state "$tmp/replay.json" >/dev/null; }
check "replay (sanitizer)" replay
check "the replay ends in the recorded state" same_state "$tmp/rec.json" "$tmp/replay.json"
echo "cross_build: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
