#!/usr/bin/env bash
# Seeded random scripts through the real game (the game-state fuzzer's twin with drawing): each seed writes a
# script of any command with extreme values (teleports past the border, huge mouse motion, every key and pad
# button, placing, breaking, carrying), runs it headless drawing every frame (--frame-stats), saves the world
# and takes a screenshot, then reopens the world. It must exit 0, keep every number finite and every position
# inside the border, and the reopened world must hash like the one saved.
#   random_scripts.sh GAME [SEEDS]     SEEDS: how many (default 6, about 10 s each here; RANDOM_SCRIPTS=200 for
#                                      a longer run); RANDOM_SCRIPT_SEED: the first seed
set -uo pipefail
game=$1
seeds=${2:-${RANDOM_SCRIPTS:-6}}
first=${RANDOM_SCRIPT_SEED:-1}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

for ((seed = first; seed < first + seeds; ++seed)); do
  python3 - "$seed" >"$tmp/s.txt" <<'PY'
import random, sys
r = random.Random(int(sys.argv[1]))
keys = "W A S D SPACE LEFT_SHIFT LEFT_CONTROL F E Q 1 2 7 8 9 F1 F3 ESCAPE".split()
axes = "left_x left_y right_x right_y".split()
buttons = "a b x y left_bumper right_bumper back start left_thumb right_thumb dpad_up dpad_down".split()
extremes = [0, 1, -1, 1e-30, 1e30, -1e30, 3.4e38, -3.4e38, 8192, 8193, -8192.5, 1e9, 127.9, -64, 90, 360]
def big():
    return r.choice(extremes) if r.random() < 0.5 else r.uniform(-300, 300)
for _ in range(r.randint(50, 300)):
    t = r.randint(0, 599)
    c = r.randrange(9)
    if c == 0: print(t, "key", r.choice(keys), r.choice(["down", "up"]))
    elif c == 1: print(t, "mouse_move", "%.9g" % big(), "%.9g" % big())
    elif c == 2: print(t, "mouse_button", r.choice(["left", "right", "middle"]), r.choice(["down", "up"]))
    elif c == 3: print(t, "scroll", "%.9g" % big())
    elif c == 4: print(t, "gamepad_axis", r.choice(axes), "%.6g" % r.uniform(-1, 1))
    elif c == 5: print(t, "gamepad_axis", r.choice(["left_trigger", "right_trigger"]), "%.6g" % r.random())
    elif c == 6: print(t, "gamepad_button", r.choice(buttons), r.choice(["down", "up"]))
    elif c == 7: print(t, "teleport", "%.9g" % big(), "%.9g" % r.choice([big(), r.uniform(30, 80)]), "%.9g" % big())
    else: print(t, "look", "%.9g" % big(), "%.6g" % r.uniform(-90, 90))
PY
  world="$tmp/w$seed.mcworld"
  if ! "$game" --headless --settings none --ticks 600 --size 160x90 --seed "$seed" --script "$tmp/s.txt" \
    --world "$world" --save --screenshot "$tmp/s.png" --dump-state "$tmp/d.json" --frame-stats "$tmp/f.json" \
    >"$tmp/out.txt" 2>&1; then
    echo "FAIL: seed $seed: the run failed (script kept as random-script-$seed.txt)"
    cp "$tmp/s.txt" "random-script-$seed.txt"
    tail -5 "$tmp/out.txt"
    failed=$((failed + 1))
    continue
  fi
  if ! "$game" --headless --settings none --ticks 0 --world "$world" --dump-state "$tmp/r.json" >/dev/null 2>&1; then
    echo "FAIL: seed $seed: the saved world does not reopen"
    failed=$((failed + 1))
    continue
  fi
  if python3 - "$tmp/d.json" "$tmp/r.json" "$world" <<'PY'; then
import json, math, sqlite3, sys
dump, reopened = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
def finite(v):
    if isinstance(v, dict): return all(finite(x) for x in v.values())
    if isinstance(v, list): return all(finite(x) for x in v)
    if v is None: return False
    return not isinstance(v, float) or math.isfinite(v)
assert finite(dump["player"]) and finite(dump["hair_balls"]), "a non-finite number in the dump"
x, y, z = dump["player"]["position"]
assert abs(x) <= 8192 and abs(z) <= 8192 and 0 <= y <= 384, ("outside the border", x, y, z)
for b in dump["hair_balls"]:
    bx, by, bz = b["position"]
    assert abs(bx) <= 8192 and abs(bz) <= 8192, ("a ball outside the border", b["position"])
saved = sqlite3.connect(sys.argv[3]).execute("SELECT value FROM meta WHERE key = 'state_hash'").fetchone()[0]
assert reopened["state_hash"] == saved, ("reopened hash", reopened["state_hash"], "saved", saved)
PY
    passed=$((passed + 1))
  else
    echo "FAIL: seed $seed: the checks above (script kept as random-script-$seed.txt)"
    cp "$tmp/s.txt" "random-script-$seed.txt"
    failed=$((failed + 1))
  fi
done

echo "random scripts: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
