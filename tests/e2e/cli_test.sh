#!/usr/bin/env bash
# End-to-end checks of the two programs' command lines and the headless contract:
# exit codes, messages naming what was wrong, determinism of state hash and PNG bytes.
set -u
game_bin=$1 lab=$2 src=$3
game() { "$game_bin" --settings none "$@"; }  # never read or write the user's settings in tests
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0 passes=0
check() { # description, then a command that must succeed
  local what=$1; shift
  if "$@"; then passes=$((passes + 1)); else echo "FAIL: $what"; failures=$((failures + 1)); fi
}
expect_exit() { # code, stderr pattern, command...
  local code=$1 pattern=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"
  local got=$?
  if [ "$got" != "$code" ]; then echo "exit $got, wanted $code: $*"; cat "$tmp/err"; return 1; fi
  if [ -n "$pattern" ] && ! grep -q -- "$pattern" "$tmp/err" "$tmp/out"; then
    echo "no '$pattern' in output of: $*"; cat "$tmp/err"; return 1
  fi
}

check "game --help" expect_exit 0 "--dump-state" game --help
check "game --version" expect_exit 0 "minecrappy" game --version
check "lab --help" expect_exit 0 "minecrappy-lab" "$lab" --help
check "lab --version" expect_exit 0 "minecrappy-lab" "$lab" --version
check "lab unknown" expect_exit 2 "bogus" "$lab" bogus
check "unknown flag" expect_exit 2 "--frobnicate" game --frobnicate
check "bad ticks" expect_exit 2 "--ticks" game --headless --ticks x
check "bad size" expect_exit 2 "--size" game --headless --ticks 1 --size 12
check "bad terrain" expect_exit 2 "--terrain" game --headless --ticks 1 --terrain lava
check "missing script" expect_exit 2 "--script" game --headless --ticks 1 --script "$tmp/none.txt"
printf '0 look 0 0\n# fine\n5 key SPCE down\n' >"$tmp/bad.txt"
check "bad script line names file and line" expect_exit 2 "bad.txt:3" game --headless --ticks 1 --script "$tmp/bad.txt"
check "no display" expect_exit 1 "--headless" env -u DISPLAY -u WAYLAND_DISPLAY "$game_bin" --settings none --world none
check "missing data is a runtime failure" expect_exit 1 "chunk.vert" \
  env MINECRAPPY_DATA="$tmp/nowhere" "$game_bin" --settings none --headless --ticks 1 --screenshot "$tmp/x.png"

# The same seed and script give the same state hash and the same PNG bytes.
run() {
  game --headless --ticks 600 --size 320x180 --seed 7 --script "$src/e2e/walk.txt" \
    --screenshot "$tmp/$1.png" --dump-state "$tmp/$1.json" >/dev/null
}
check "headless run 1" run a
check "headless run 2" run b
hash() { grep -o '"state_hash": "[0-9a-f]*"' "$1"; }
check "same state hash" test "$(hash "$tmp/a.json")" = "$(hash "$tmp/b.json")"
check "same PNG bytes" cmp -s "$tmp/a.png" "$tmp/b.png"
check "dump has the contract" grep -q '"selected_block": "brick"' "$tmp/a.json"
check "the walk placed a brick" grep -q '"block": "brick"' "$tmp/a.json"
check "the walk broke a block" grep -q '"block": "air"' "$tmp/a.json"
check "the walk crossed chunk borders" python3 - "$tmp/a.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
x, y, z = s["player"]["position"]
assert s["tick"] == 600, s["tick"]
assert abs(x) > 40 and abs(z) > 40, (x, z)
PY
printf '0 look 0 0\n' >"$tmp/other.txt"
game --headless --ticks 600 --size 320x180 --seed 7 --script "$tmp/other.txt" --dump-state "$tmp/c.json" >/dev/null
check "different input, different hash" test "$(hash "$tmp/a.json")" != "$(hash "$tmp/c.json")"
check "a failed dump leaves no partial file" expect_exit 1 "cannot write" game --headless --ticks 1 --dump-state "$tmp/no/such/dir/s.json"

# The pendulum set in the world and the lab compute the same numbers for the same angle, step and time.
game --headless --ticks 120 --dump-state "$tmp/p.json" >/dev/null
for m in exact euler midpoint trapezoid; do
  "$lab" pendulum --method "$m" --dt 0.016666666666666666 --theta0 60 --seconds 2 --csv "$tmp/$m.csv" >/dev/null
done
check "in-world pendulums match the lab" python3 - "$tmp" <<'PY'
import csv, json, os, sys
tmp = sys.argv[1]
s = json.load(open(os.path.join(tmp, "p.json")))
slots = s["pendulums"][0]["slots"]
assert abs(s["pendulums"][0]["time"] - 2.0) < 1e-12
for slot in slots:
    rows = list(csv.DictReader(open(os.path.join(tmp, slot["method"] + ".csv"))))
    last = rows[-1]
    assert abs(float(last["t"]) - 2.0) < 1e-12, last["t"]
    for key in ("theta", "omega"):
        assert abs(float(last[key]) - slot[key]) <= 1e-12, (slot["method"], key, last[key], slot[key])
PY

# Worlds: a file that is not a world is refused with exit 2 and left as it was; a saved world
# reloads to the same state hash; --ticks 0 loads, dumps and exits.
head -c 5000 /dev/urandom >"$tmp/garbage.mcworld"
cp "$tmp/garbage.mcworld" "$tmp/garbage.orig"
check "not a world: exit 2 naming the file" expect_exit 2 "garbage.mcworld" game --headless --world "$tmp/garbage.mcworld" --ticks 5
check "not a world: file unchanged" cmp -s "$tmp/garbage.mcworld" "$tmp/garbage.orig"
game --headless --world "$tmp/w.mcworld" --ticks 200 --script "$src/e2e/walk.txt" --save --dump-state "$tmp/saved.json" >/dev/null
game --headless --world "$tmp/w.mcworld" --ticks 0 --dump-state "$tmp/loaded.json" >/dev/null
check "a saved world loads to the same state hash" test "$(hash "$tmp/saved.json")" = "$(hash "$tmp/loaded.json")"

# The hair lab: the check runs spin, carry, a drop onto blocks and a frame spike without NaN or
# penetration; the bench reports every key the acceptance checks read.
check "hair-check" "$lab" hair-check --json "$tmp/hc.json"
check "hair-check results" python3 - "$tmp/hc.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["nan"] is False, r
assert r["max_penetration"] < 1e-4, r
assert r["max_segment_error"] < 0.3, r
assert 0 < r["settle_seconds"] < 15, r
PY
check "hair-bench" "$lab" hair-bench --strands 256 --nodes 8 --steps 20 --json "$tmp/hb.json"
check "hair-bench keys" python3 - "$tmp/hb.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
for k in ("node_steps_per_s", "naive_node_steps_per_s", "limit_node_steps_per_s", "ms_per_step", "threads"):
    assert k in r and r[k] > 0, k
PY
check "hair-bench rejects a billion strands" expect_exit 2 "--strands" "$lab" hair-bench --strands 1000000000

echo "cli: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
