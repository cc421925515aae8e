#!/usr/bin/env bash
# End-to-end checks of the two programs' command lines and the headless contract:
# exit codes, messages naming what was wrong, determinism of state hash and PNG bytes.
set -u
game_bin=$1 lab=$2 src=$3
game() { "$game_bin" --settings none "$@"; }  # never read or write the user's settings in tests
source "$(dirname "$0")/checks.sh" # tmp, check(), passes, failures
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
# The time of day: --time-of-day sets it, the clock runs on (600 ticks of a 20-minute day: 0.2 h), and the frame
# size, which the simulation never sees, leaves the hash alone.
dusk() {
  game --headless --ticks 600 --size "$2" --seed 7 --script "$src/e2e/walk.txt" --time-of-day 18.5 \
    --dump-state "$tmp/$1.json" >/dev/null
}
check "dusk at 320x180" dusk dusk_small 320x180
check "dusk at 640x360" dusk dusk_large 640x360
check "two frame sizes, same state hash" test "$(hash "$tmp/dusk_small.json")" = "$(hash "$tmp/dusk_large.json")"
check "the time of day is in the hash" test "$(hash "$tmp/dusk_small.json")" != "$(hash "$tmp/a.json")"
check "the clock ran on from 18.5" python3 - "$tmp/dusk_small.json" "$tmp/a.json" <<'PY'
import json, sys
d, a = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert abs(d["time_of_day"] - 18.7) < 1e-9, d["time_of_day"]
assert abs(a["time_of_day"] - 12.2) < 1e-9, a["time_of_day"]  # the default noon, run on
assert d["day_length"] == 20 and d["day_stopped"] is False, d
PY
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
# --frame-stats: every quantity summed up per frame, and each frame really drew something.
check "frame stats report triangles, draw calls, meshing, GPU wait and overdraw" python3 - "$game_bin" "$tmp" <<'PY'
import json, subprocess, sys
game, tmp = sys.argv[1], sys.argv[2]
# 300 frames: the view loads in about 28 on an idle machine (each column's light is computed as it streams in;
# meshing has a wall-clock budget a frame, so a busy machine takes more frames), then the rest.
N = 300
subprocess.run([game, "--settings", "none", "--headless", "--ticks", str(N), "--size", "320x180",
                "--frame-stats", tmp + "/frames.json"], check=True, stdout=subprocess.DEVNULL)
j = json.load(open(tmp + "/frames.json"))
assert j["frames"] == N, j["frames"]
for key in ("triangles", "draw_calls", "mesh_ms", "gpu_wait_ms", "fragments_per_pixel"):
    s = j[key]
    assert 0 <= s["median"] <= s["p99"] <= s["worst"], (key, s)
assert j["triangles"]["median"] > 1000, j["triangles"]
# At least a chunk per drawn chunk, plus the sky and the UI.
assert j["draw_calls"]["median"] >= j["mean_chunks_drawn"] + 2, (j["draw_calls"], j["mean_chunks_drawn"])
assert j["mesh_ms"]["worst"] > 0, j["mesh_ms"]  # the first frame meshes what is in view
# Every pixel is shaded at least once: by the terrain, or else by the sky drawn where nothing is.
assert j["fragments_per_pixel"]["frames"] >= 1, j["fragments_per_pixel"]  # precondition: a frame counted
assert j["fragments_per_pixel"]["median"] >= 1.0, j["fragments_per_pixel"]
# The loading at the start is left out of after_load; the slowest frames are listed, slowest first.
a, slow = j["after_load"], j["slowest"]
assert j["views_completed"][0]["complete"], j["views_completed"]  # precondition: the view loaded
assert a["frames"] == N - j["views_completed"][0]["frames"], (a, j["views_completed"])
assert 0 < a["median_ms"] <= a["p99_ms"] <= a["worst_ms"] <= j["worst_ms"], a
assert len(slow) == 10 and slow[0]["frame_ms"] == j["worst_ms"], slow
assert all(x["frame_ms"] >= y["frame_ms"] for x, y in zip(slow, slow[1:])), slow
# A frame's fragments are read once the frame after it is handed on, or after the last frame.
subprocess.run([game, "--settings", "none", "--headless", "--ticks", "1", "--size", "320x180",
                "--frame-stats", tmp + "/one.json"], check=True, stdout=subprocess.DEVNULL)
one = json.load(open(tmp + "/one.json"))
assert one["frames"] == 1 and one["fragments_per_pixel"]["frames"] == 1, one["fragments_per_pixel"]
assert one["fragments_per_pixel"]["median"] >= 1.0, one["fragments_per_pixel"]
PY
# After a teleport to terrain nothing has generated, the view completes (tests/e2e/teleport.txt).
check "the view completes after a teleport" python3 - "$game_bin" "$tmp" "$src" <<'PY'
import json, subprocess, sys
game, tmp, src = sys.argv[1:4]
subprocess.run([game, "--settings", "none", "--headless", "--ticks", "300", "--size", "320x180",
                "--script", src + "/e2e/teleport.txt", "--frame-stats", tmp + "/tp.json"],
               check=True, stdout=subprocess.DEVNULL)
views = json.load(open(tmp + "/tp.json"))["views_completed"]
after = [v for v in views if v["from_tick"] >= 121]
assert views and views[0]["from_tick"] <= 2 and views[0]["complete"], views  # the start
assert after and after[0]["from_tick"] == 121 and after[0]["complete"], views  # the frame after the jump
PY
# A recorded run replays to the same hash and the same PNG bytes; a tampered one stops with exit 3.
record() {
  game --headless --ticks 600 --size 320x180 --seed 7 --script "$src/e2e/walk.txt" --record "$tmp/walk.mcscript" \
    --keyframe-file-interval 200 --screenshot "$tmp/rec.png" --dump-state "$tmp/rec.json" >/dev/null 2>&1
}
replay() { game --headless --size 320x180 --script "$tmp/walk.mcscript" --screenshot "$tmp/replay.png" --dump-state "$tmp/replay.json" >/dev/null 2>&1; }
check "record a run" record
check "recording leaves the run's hash alone" test "$(hash "$tmp/rec.json")" = "$(hash "$tmp/a.json")"
check "replay the recording" replay
check "replay reaches the recorded hash" test "$(hash "$tmp/replay.json")" = "$(hash "$tmp/rec.json")"
check "replay draws the same PNG bytes" cmp -s "$tmp/rec.png" "$tmp/replay.png"
# --seek: a replay brought to tick 300 (from the keyframe file's tick 200) and run on 300 ticks ends where the
# straight replay does (hash and PNG bytes), and stopped at 300 dumps the state a 300-tick replay dumps; a tick
# past the end names the last one. With a keyframe damaged, the seek warns and goes from the start, to the same end.
seek_then() { # seek, ticks, name
  game --headless --size 320x180 --replay "$tmp/walk.mcscript" --seek "$1" --ticks "$2" --screenshot "$tmp/$3.png" \
    --dump-state "$tmp/$3.json" >"$tmp/$3.out" 2>"$tmp/$3.err"
}
check "the recording's keyframe file" test -s "$tmp/walk.mcscript.keys"
check "seek to 300, run 300 more" seek_then 300 300 seek300
check "the seek restored the file's keyframe" grep -q "restored tick 200 from the keyframe file" "$tmp/seek300.out"
cp "$tmp/walk.mcscript.keys" "$tmp/keys.bak"
python3 - "$tmp/walk.mcscript.keys" <<'PY'
import struct, sys
b = bytearray(open(sys.argv[1], "rb").read())
tick, _, length, _ = struct.unpack_from("<QQQQ", b, 24)
assert tick == 200, tick
b[24 + 32 + length // 2] ^= 0x40
open(sys.argv[1], "wb").write(b)
PY
check "seek past a damaged keyframe" seek_then 300 300 damaged
check "the damaged keyframe is named" grep -q "the keyframe at tick 200 is damaged" "$tmp/damaged.err"
check "and the seek stepped from the start" grep -qx "at tick 300" "$tmp/damaged.out"
check "to the replay's hash" test "$(hash "$tmp/damaged.json")" = "$(hash "$tmp/replay.json")"
mv "$tmp/keys.bak" "$tmp/walk.mcscript.keys"
check "a keyframe interval of 0 is refused naming it" expect_exit 2 "--keyframe-interval: out of range 1..100000, got '0'" \
  game --headless --replay "$tmp/walk.mcscript" --keyframe-interval 0
check "a keyframe budget of 0 is refused naming it" expect_exit 2 "--keyframe-budget: out of range 1..65536, got '0'" \
  game --headless --replay "$tmp/walk.mcscript" --keyframe-budget 0
check "the seek ends at the replay's hash" test "$(hash "$tmp/seek300.json")" = "$(hash "$tmp/replay.json")"
check "the seek draws the replay's PNG bytes" cmp -s "$tmp/seek300.png" "$tmp/replay.png"
check "seek to 300 and stop" seek_then 300 0 at300
check "a 300-tick replay" game --headless --size 320x180 --replay "$tmp/walk.mcscript" --ticks 300 \
  --dump-state "$tmp/ran300.json"
check "stopped at 300 it is the 300-tick replay's state" test "$(hash "$tmp/at300.json")" = "$(hash "$tmp/ran300.json")"
check "precondition: tick 300 is not the end" test "$(hash "$tmp/at300.json")" != "$(hash "$tmp/replay.json")"
check "a seek past the end names the last tick" expect_exit 2 "--seek 601: tick 601 is past the last tick of .*walk.mcscript, 600" \
  game --headless --replay "$tmp/walk.mcscript" --seek 601
check "a negative seek is refused naming it" expect_exit 2 "--seek: expected a non-negative whole number, got '-1'" \
  game --headless --replay "$tmp/walk.mcscript" --seek -1
check "--replay refuses a script that is no recording" expect_exit 2 "walk.txt: not a recording" \
  game --headless --replay "$src/e2e/walk.txt"
check "--seek needs --headless" expect_exit 2 "--seek 3 needs --headless" game --replay "$tmp/walk.mcscript" --seek 3
sed 's/^300 act move=\([^ ]*\)/300 act move=\1 yaw=20/' "$tmp/walk.mcscript" >"$tmp/tampered.mcscript"
cp "$tmp/walk.mcscript.start.mcworld" "$tmp/tampered.mcscript.start.mcworld"
check "the tampered tick differs" bash -c "! cmp -s '$tmp/walk.mcscript' '$tmp/tampered.mcscript'"
check "a tampered recording stops at the next hash with exit 3" expect_exit 3 "at tick 310" \
  game --headless --script "$tmp/tampered.mcscript"
# Header values: one outside what the game writes is refused before the first tick, naming the line; one the
# game could write but this run did not use changes the hair, and the hash (which covers every hair node)
# stops the replay at the next hash line.
header_tamper() { # from, to, name
  sed "s/^# $1\$/# $2/" "$tmp/walk.mcscript" >"$tmp/$3.mcscript"
  cp "$tmp/walk.mcscript.start.mcworld" "$tmp/$3.mcscript.start.mcworld"
  ! cmp -s "$tmp/walk.mcscript" "$tmp/$3.mcscript"
}
check "hair_budget 1 is written in" header_tamper "hair_budget 1000" "hair_budget 1" budget1
check "a hair budget of 1 is refused naming the line" expect_exit 2 "budget1.mcscript:6: hair_budget 1: out of range" \
  game --headless --script "$tmp/budget1.mcscript"
check "version banana is written in" header_tamper "version 0.1.0" "version banana" banana
check "an unknown version is refused naming the line" expect_exit 2 "banana.mcscript:2: version 'banana'" \
  game --headless --script "$tmp/banana.mcscript"
check "hair_detail 1 (half the strands) is written in" header_tamper "hair_detail 2" "hair_detail 1" half
check "half the hair stops the replay at the first hash line with exit 3" expect_exit 3 "at tick 10," \
  game --headless --script "$tmp/half.mcscript"
# A replay takes its world from the recording: a different --seed or --terrain is refused, not ignored.
check "a replay refuses another --seed" expect_exit 2 "recorded with seed 7; this run asks for --seed 2" \
  game --headless --script "$tmp/walk.mcscript" --seed 2
check "a replay refuses another --terrain" expect_exit 2 "this run asks for --terrain flat" \
  game --headless --script "$tmp/walk.mcscript" --terrain flat
check "a replay takes the recorded --seed" expect_exit 0 "" game --headless --ticks 20 --script "$tmp/walk.mcscript" --seed 7
# A script's ticks are the world's own: in a world saved at tick 300, an event at tick 8 is refused by line.
check "a world saved at tick 300" game --headless --ticks 300 --seed 3 --world "$tmp/w300.mcworld" --save
printf '0 look 0 0\n8 key W down\n' >"$tmp/early.txt"
check "events before the world's tick are refused naming the line" \
  expect_exit 2 "early.txt:1: tick 0 is before the world's tick 300" \
  game --headless --ticks 10 --world "$tmp/w300.mcworld" --script "$tmp/early.txt"
printf '300 look 0 0\n308 key W down\n' >"$tmp/late.txt"
check "events from the world's tick on are taken" \
  game --headless --ticks 10 --world "$tmp/w300.mcworld" --script "$tmp/late.txt" --dump-state "$tmp/late.json"
# A teleport into stone lifts the body out (the column's nearest height where it fits), never leaves it stuck.
printf '0 teleport 0.5 20 0.5\n' >"$tmp/stone.txt"
check "a teleport into stone" game --headless --ticks 2 --seed 7 --script "$tmp/stone.txt" --dump-state "$tmp/stone.json"
check "ends with the body out of the stone" python3 - "$tmp/stone.json" <<'PY'
import json, sys
y = json.load(open(sys.argv[1]))["player"]["position"][1]
assert y != 20 and y == int(y), y
PY
head -c 2000 "$tmp/walk.mcscript" >"$tmp/cut.mcscript"
cp "$tmp/walk.mcscript.start.mcworld" "$tmp/cut.mcscript.start.mcworld"
check "a recording cut mid-line is refused" expect_exit 2 "cut short" game --headless --script "$tmp/cut.mcscript"
check "a PNG is not a recording" expect_exit 2 "rec.png:1" game --headless --ticks 1 --script "$tmp/rec.png"
check "a recording into a missing folder is refused" expect_exit 2 "--record" \
  game --headless --ticks 1 --record "$tmp/missing/x.mcscript"
check "a recording onto a folder is refused" expect_exit 2 "--record" game --headless --ticks 1 --record "$tmp"
# A session killed (SIGKILL) while recording over an older recording leaves the older one replayable: the new
# start world takes a name of its own (k.mcscript.start.2.mcworld) and the older one goes only when the new
# recording is in place. The test waits for that file (the recording has begun), never for a fixed time.
killed_over_older() {
  cp "$tmp/walk.mcscript" "$tmp/k.mcscript" && cp "$tmp/walk.mcscript.start.mcworld" "$tmp/k.mcscript.start.mcworld" ||
    return 1
  # The binary itself in the background (not the `game` function, whose subshell $! would name: killing that
  # left the game running its 10^8 ticks after the test, on a core the rest of the suite needed).
  "$game_bin" --settings none --headless --ticks 100000000 --size 160x90 --seed 2 --world none \
    --record "$tmp/k.mcscript" >/dev/null 2>&1 &
  local pid=$! n=0
  until [ -s "$tmp/k.mcscript.start.2.mcworld" ]; do
    kill -0 "$pid" 2>/dev/null || { echo "the recording session ended before its start world appeared"; return 1; }
    n=$((n + 1))
    [ "$n" -lt 6000 ] || { kill -9 "$pid"; echo "no start world after 300 s"; return 1; }
    sleep 0.05
  done
  kill -9 "$pid"
  wait "$pid" 2>/dev/null
  game --headless --size 320x180 --script "$tmp/k.mcscript" --dump-state "$tmp/k.json" >/dev/null 2>"$tmp/err" ||
    { cat "$tmp/err"; return 1; }
  test "$(hash "$tmp/k.json")" = "$(hash "$tmp/rec.json")"
}
check "a recording killed over an older one leaves the older one replayable" killed_over_older
# A recording needs a folder for its start world: a device or a pipe is refused before the first tick.
check "a recording onto a device is refused" expect_exit 2 "a recording is a file with its start world beside it" \
  game --headless --ticks 1 --world none --record /dev/null
check "and leaves nothing beside the device" test ! -e /dev/null.start.mcworld
mkfifo "$tmp/rec.fifo"
check "a recording onto a pipe is refused" expect_exit 2 "a recording is a file with its start world beside it" \
  game --headless --ticks 1 --world none --record "$tmp/rec.fifo"

# A frame sequence: one PNG every 5 ticks, named by tick, each a different picture of the walk.
capture() { game --headless --ticks 300 --size 160x90 --seed 7 --script "$src/e2e/walk.txt" --capture-every 5 --capture-dir "$tmp/clip" >/dev/null; }
check "capture a clip" capture
check "60 frames, numbered by tick" test "$(ls "$tmp/clip" | head -1)-$(ls "$tmp/clip" | tail -1)-$(ls "$tmp/clip" | wc -l)" = "frame-000005.png-frame-000300.png-60"
check "60 distinct frames" test "$(md5sum "$tmp"/clip/*.png | cut -d' ' -f1 | sort -u | wc -l)" = 60
touch "$tmp/afile"
check "a capture folder that is a file is refused" expect_exit 2 "--capture-dir" game --headless --ticks 1 --capture-every 1 --capture-dir "$tmp/afile"
check "capturing every 0 ticks is refused" expect_exit 2 "--capture-every" game --headless --ticks 1 --capture-every 0 --capture-dir "$tmp/c0"
check "a capture folder needs a period" expect_exit 2 "--capture-dir needs --capture-every" game --headless --ticks 1 --capture-dir "$tmp/c1"
check "capturing needs --headless" expect_exit 2 "needs --headless" game --capture-every 1 --capture-dir "$tmp/c2"
check "nothing was made for a refused capture" test ! -e "$tmp/c0" -a ! -e "$tmp/c1" -a ! -e "$tmp/c2"

# Off-screen GL without OSMesa: a library that cannot load stands in for a missing one (LD_LIBRARY_PATH).
mkdir -p "$tmp/no-osmesa" "$tmp/no-gl"
: >"$tmp/no-osmesa/libOSMesa.so.8"
: >"$tmp/no-gl/libOSMesa.so.8"
: >"$tmp/no-gl/libEGL.so.1"
game --headless --ticks 30 --size 160x90 --gl-backend osmesa --screenshot "$tmp/osmesa.png" >/dev/null
check "auto falls back to EGL without OSMesa" env LD_LIBRARY_PATH="$tmp/no-osmesa" LIBGL_ALWAYS_SOFTWARE=1 "$game_bin" --settings none --headless \
  --ticks 30 --size 160x90 --gl-backend auto --screenshot "$tmp/fallback.png"
check "EGL draws what OSMesa draws" cmp -s "$tmp/osmesa.png" "$tmp/fallback.png"
check "without either, the message names both and what to install" expect_exit 1 "OSMesa: .*EGL: .*Install either" \
  env LD_LIBRARY_PATH="$tmp/no-gl" "$game_bin" --settings none --headless --ticks 1 --gl-backend auto --screenshot "$tmp/x.png"
check "a bad backend name is refused" expect_exit 2 "--gl-backend" game --headless --ticks 1 --gl-backend vulkan

# A 4x screenshot is the 1x picture drawn larger: 5120x2880 from 1280x720 (two tiles of at most 4096 across),
# and averaged over matching boxes on a 7x5 grid it matches the 1x one (HUD and labels included).
shot() { game --headless --ticks 90 --size 1280x720 --seed 7 --script "$src/e2e/walk.txt" --screenshot "$tmp/$1" "${@:2}" >/dev/null 2>&1; }
check "a 1x screenshot" shot s1.png
check "a 4x screenshot" shot s4.png --screenshot-scale 4
check "the 4x screenshot is 5120x2880" python3 -c "
import struct, sys
d = open('$tmp/s4.png', 'rb').read(24)
assert struct.unpack('>II', d[16:24]) == (5120, 2880), struct.unpack('>II', d[16:24])"
same_picture() {
  local worst=0 x y a b
  for x in 0.1 0.23 0.36 0.5 0.63 0.76 0.9; do
    for y in 0.1 0.3 0.5 0.7 0.9; do
      read -r -a a < <("$PNG_PROBE" "$tmp/s1.png" "$x" "$y" 8)
      read -r -a b < <("$PNG_PROBE" "$tmp/s4.png" "$x" "$y" 32)
      for c in 0 1 2; do
        local d=$((a[c] - b[c])); d=${d#-}
        [ "$d" -gt "$worst" ] && worst=$d
      done
    done
  done
  echo "4x against 1x: largest box difference $worst of 255"
  [ "$worst" -le 8 ]
}
check "the 4x screenshot downsampled matches the 1x one" same_picture
check "a scale of 0 is refused" expect_exit 2 "--screenshot-scale" game --headless --ticks 1 --screenshot-scale 0 --screenshot "$tmp/z.png"
check "a scale of 100 is refused" expect_exit 2 "--screenshot-scale" game --headless --ticks 1 --screenshot-scale 100 --screenshot "$tmp/z.png"
check "nothing written for a refused scale" test ! -e "$tmp/z.png"

printf '0 look 0 0\n' >"$tmp/other.txt"
game --headless --ticks 600 --size 320x180 --seed 7 --script "$tmp/other.txt" --dump-state "$tmp/c.json" >/dev/null
check "different input, different hash" test "$(hash "$tmp/a.json")" != "$(hash "$tmp/c.json")"
printf x >"$tmp/garbage.txt"
# Output paths are tried before the first tick (a run of 10^8 ticks must still end at once), exit 2
# with the system's reason, and nothing is left behind.
check "dump into a missing folder: exit 2 before the run" expect_exit 2 \
  "--dump-state: cannot write '$tmp/no/such/dir/s.json': the folder '$tmp/no/such/dir' does not exist" \
  timeout 20 "$game_bin" --settings none --headless --ticks 100000000 --dump-state "$tmp/no/such/dir/s.json"
check "a refused dump leaves no file or folder" test ! -e "$tmp/no"
check "dump onto a folder: exit 2" expect_exit 2 "cannot write '$tmp': it is a folder" game --headless --ticks 1 --dump-state "$tmp"
check "screenshot under /sys: exit 2 with the reason" expect_exit 2 "--screenshot: cannot write '/sys/x.png': [A-Z]" \
  game --headless --ticks 1 --screenshot /sys/x.png
check "frame stats under a file: exit 2" expect_exit 2 "--frame-stats: cannot write '.*': '.*garbage.txt' is not a folder" \
  game --headless --ticks 1 --frame-stats "$tmp/garbage.txt/f.json"

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
game --headless --ticks 0 --dump-state "$tmp/demo.json" >/dev/null
check "the dump names each hair ball's solver" python3 - "$tmp/demo.json" <<'PY'
import json, sys
balls = json.load(open(sys.argv[1]))["hair_balls"]
assert balls and all(b["solver"] in ("ftl", "dftl", "pbd", "xpbd-substeps", "shake") for b in balls), balls
assert len({b["solver"] for b in balls}) >= 2, [b["solver"] for b in balls]  # the demo shows two side by side
PY
# A hair ball whose solver this build lacks (a world from a newer build): the load is refused, exit 2 naming
# the file, the row and the name, and the file is not written (not even by --save).
game --headless --world "$tmp/future.mcworld" --ticks 1 --save >/dev/null
python3 -c 'import sqlite3, sys; c = sqlite3.connect(sys.argv[1]); c.execute("UPDATE hair_balls SET solver = ? WHERE id = 0", ("warp-9",)); c.commit(); c.close()' "$tmp/future.mcworld"
cp "$tmp/future.mcworld" "$tmp/future.orig"
check "unknown solver: exit 2 naming the file and the name" expect_exit 2 "future.mcworld: table hair_balls, row 0: solver 'warp-9'" \
  game --headless --world "$tmp/future.mcworld" --ticks 5 --save
check "unknown solver: file unchanged" cmp -s "$tmp/future.mcworld" "$tmp/future.orig"

# Issue 9: limits on input, checked before the run.
check "/dev/zero as a script: exit 2 at once with bounded memory" python3 - "$game_bin" <<'PY'
import resource, subprocess, sys, time
r = subprocess.run([sys.argv[1], "--settings", "none", "--headless", "--ticks", "3", "--script", "/dev/zero"],
                   capture_output=True, text=True, timeout=60)
use = resource.getrusage(resource.RUSAGE_CHILDREN)
cpu = use.ru_utime + use.ru_stime  # the child's own time: a busy machine does not move it
peak_mib = use.ru_maxrss / 1024
assert r.returncode == 2, (r.returncode, r.stderr)
assert "/dev/zero: larger than 16 MiB" in r.stderr, r.stderr
assert cpu < 15, cpu
assert peak_mib < 400, peak_mib  # reading it whole grew past 1.2 GB in 5 s
PY
head -c 5000 /dev/zero | tr '\0' ' ' >"$tmp/longline.txt"
check "a line over 4096 bytes: exit 2 naming file and line" expect_exit 2 "longline.txt:1: line of 5000 bytes" \
  game --headless --ticks 1 --script "$tmp/longline.txt"
check "seed above 2^64-1: exit 2, not saturated" expect_exit 2 "--seed: .* is above 2^64-1" \
  game --headless --ticks 0 --seed 18446744073709551616
check "ticks above 2^64-1: exit 2" expect_exit 2 "--ticks: .* is above 2^64-1" game --headless --ticks 99999999999999999999999
check "a .jpg screenshot name: exit 2" expect_exit 2 "writes PNG" game --headless --ticks 1 --screenshot "$tmp/x.jpg"
check "no .jpg written" test ! -e "$tmp/x.jpg"
mkdir -p "$tmp/nonedir"
(cd "$tmp/nonedir" && "$game_bin" --settings none --headless --ticks 1 --world none >/dev/null 2>&1)
check "headless --world none writes no file" test -z "$(ls -A "$tmp/nonedir")"
# A frame over half the available memory is refused; where this machine has room for the largest
# size, that size is not run here (5.8 GB), only the small side of the rule.
avail_kb=$(awk '/^MemAvailable:/ { print $2 }' /proc/meminfo)
if [ -n "$avail_kb" ] && [ $((avail_kb * 1024 / 2)) -lt $((21 * 16384 * 16384 + 170 * 1048576)) ]; then
  check "a 16384x16384 frame over half the memory: exit 2" expect_exit 2 "--size 16384x16384: .* needs about" \
    game --headless --ticks 1 --size 16384x16384
fi

# Script triggers take travel 0..1: a pull, a release to 0 and a second pull step the hotbar twice
# (with -1..1 values, 0 read as half pulled and never re-armed the trigger).
printf '0 gamepad_axis right_trigger 1\n2 gamepad_axis right_trigger 0\n4 gamepad_axis right_trigger 1\n' >"$tmp/trigger.txt"
game --headless --ticks 6 --script "$tmp/trigger.txt" --dump-state "$tmp/trigger.json" >/dev/null
check "two trigger pulls in a script step the hotbar twice" python3 -c '
import json, sys
p = json.load(open(sys.argv[1]))["player"]
assert p["selected_slot"] == 2, p["selected_slot"]' "$tmp/trigger.json"
printf '0 gamepad_axis right_trigger -1\n' >"$tmp/trigger_bad.txt"
check "trigger travel outside 0..1: exit 2" expect_exit 2 "trigger_bad.txt:1: .* outside 0..1" \
  game --headless --ticks 1 --script "$tmp/trigger_bad.txt"

# F2 on a script line of tick 120 names the screenshot after tick 120.
printf '120 key F2 down\n121 key F2 up\n' >"$tmp/f2.txt"
game --headless --ticks 125 --size 320x180 --script "$tmp/f2.txt" --screenshot-dir "$tmp/shots" >/dev/null
check "F2 at tick 120 writes minecrappy-tick-000120.png" test -f "$tmp/shots/minecrappy-tick-000120.png"
check "and no other screenshot" test "$(ls "$tmp/shots" | wc -l)" -eq 1

# Warnings: script events a run never reaches, and two actions on one key.
printf '0 key W down\n70 key W up\n65 key S down\n' >"$tmp/late.txt"
check "script events past --ticks warn" expect_exit 0 \
  "warning: .*late.txt: 2 events at tick >= 60 will not run (--ticks 60); the first is line 2" \
  game --headless --ticks 60 --script "$tmp/late.txt"
printf '[keys]\nsprint = "SPACE"\n' >"$tmp/shared.toml"
check "two actions on one key warn" expect_exit 0 "shared.toml:2: actions 'jump' and 'sprint' share key SPACE" \
  "$game_bin" --settings "$tmp/shared.toml" --headless --ticks 0

# SIGTERM ends a headless run at a tick boundary as if it had ended: the world is saved, the dump
# written, the exit code 128 + 15; the saved world opens at the tick the dump shows.
# Started directly, not through game(): $! of a backgrounded shell function is a subshell, and the
# signal would end that shell and leave the game running.
# The test waits for the state it needs, tick 2 done (its captured frame written), never for a fixed time: on a
# busy machine a second may not reach tick 1.
"$game_bin" --settings none --headless --ticks 100000000 --world "$tmp/sig.mcworld" --dump-state "$tmp/sig.json" \
  --size 160x90 --capture-every 2 --capture-dir "$tmp/sig_frames" >"$tmp/sig.out" 2>"$tmp/sig.err" &
sig_pid=$!
for _ in $(seq 3000); do [ -s "$tmp/sig_frames/frame-000002.png" ] && break; sleep 0.1; done
kill -TERM "$sig_pid"
# A game that ignored the signal would run for hours: give it 30 s to finish, then end it (exit 137).
for _ in $(seq 300); do kill -0 "$sig_pid" 2>/dev/null || break; sleep 0.1; done
kill -KILL "$sig_pid" 2>/dev/null
wait "$sig_pid"
sig_rc=$?
check "SIGTERM: exit 143" test "$sig_rc" -eq 143
check "SIGTERM: says so" grep -q "interrupted by SIGTERM at tick [1-9][0-9]* of 100000000" "$tmp/sig.err"
check "SIGTERM: dump written" test -s "$tmp/sig.json"
game --headless --world "$tmp/sig.mcworld" --ticks 0 --dump-state "$tmp/sig_reopened.json" >/dev/null
check "SIGTERM: the saved world reopens at the dumped state" test "$(hash "$tmp/sig.json")" = "$(hash "$tmp/sig_reopened.json")"

# The hair lab: the check runs spin, carry, a drop onto blocks and a frame spike at the game's default
# solver, at every tick the game's settings offer from 1/240 to 1/30 s: lengths exact to float rounding
# (measured 6e-6; the bar set for it was 1 %), no penetration, no NaN, the hair comes to rest, and a new ball
# on the blocks comes to rest in nearly the same time at every rate (below).
for dt in 0.0041666667 0.0069444444 0.0166666667 0.0333333333; do
  check "hair-check --dt $dt" "$lab" hair-check --dt "$dt" --json "$tmp/hc_$dt.json"
done
check "hair-check results" python3 - "$tmp" <<'PY'
import json, sys
rest = {}
for dt in ("0.0041666667", "0.0069444444", "0.0166666667", "0.0333333333"):
    r = json.load(open(f"{sys.argv[1]}/hc_{dt}.json"))
    assert r["solver"] == "dftl", r
    assert r["nan"] is False, r
    assert r["max_penetration"] < 1e-5, r
    assert r["max_segment_error"] < 1e-4, r
    assert 0 < r["settle_seconds"] < 30, r
    rest[dt] = r["rest_settle_seconds"]
    assert rest[dt] > 0, r
# hair-check steps the hair on the game's clock (substeps of 1/60 s at every tick, docs/HAIR.md,
# "Frame-rate independence"): measured 3 s at 30, 60, 144 and 240 Hz, held to the issue's 15 %.
rates = [rest["0.0333333333"], rest["0.0041666667"], rest["0.0069444444"], rest["0.0166666667"]]
assert max(rates) <= 1.15 * min(rates), rest
PY
check "hair-check: an unknown solver is refused" expect_exit 2 "--solver 'verlet' is not a hair solver" "$lab" hair-check --solver verlet
check "hair-chain: no links is refused" expect_exit 2 "--links" "$lab" hair-chain --links 0 --csv "$tmp/chain.csv"
check "hair-chain: a negative step is refused" expect_exit 2 "--dt" "$lab" hair-chain --dt -0.01 --csv "$tmp/chain.csv"
check "hair-chain: the reference" "$lab" hair-chain --solver reference --seconds 0.5 --csv "$tmp/chain.csv"
check "hair-chain: CSV header" grep -qx "t,tip_x,tip_y,ref_tip_x,ref_tip_y,tip_error,max_segment_error,energy_error" "$tmp/chain.csv"
check "hair-bench" "$lab" hair-bench --strands 256 --nodes 8 --steps 20 --json "$tmp/hb.json"
check "hair-bench keys" python3 - "$tmp/hb.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
for k in ("node_steps_per_s", "naive_node_steps_per_s", "limit_node_steps_per_s", "ms_per_step", "threads"):
    assert k in r and r[k] > 0, k
assert r["solver"] == "dftl", r
PY
check "hair-bench --solver shake" "$lab" hair-bench --solver shake --strands 256 --nodes 8 --steps 20
check "hair-bench rejects a billion strands" expect_exit 2 "--strands" "$lab" hair-bench --strands 1000000000

# Every output follows one rule (docs/SCRIPTS.md, "Output files"): checked through the game's own flags.
out1() { game --headless --ticks 1 --size 160x90 --world none "$@" >/dev/null 2>"$tmp/err"; }
symlink_kept() {
  echo old >"$tmp/real.json" && ln -s real.json "$tmp/l.json" &&
    out1 --dump-state "$tmp/l.json" && [ -L "$tmp/l.json" ] && grep -q state_hash "$tmp/real.json"
}
check "outputs: a symlink is followed and kept" symlink_kept
dangling_refused() {
  ln -s nowhere.json "$tmp/d.json" &&
    expect_exit 2 "which does not exist" game --headless --ticks 1 --size 160x90 --world none --dump-state "$tmp/d.json" &&
    [ -L "$tmp/d.json" ] && [ ! -e "$tmp/nowhere.json" ]
}
check "outputs: a dangling symlink is refused and left" dangling_refused
# A folder the game or the lab makes, given as a link to nothing: refused before the first tick, the link named
# (creating through it failed with a bare "File exists", exit 1, or at the first F2).
dangling_folders() {
  ln -s gone_dir "$tmp/dlink" || return 1
  expect_exit 2 "'$tmp/dlink' is a symbolic link to 'gone_dir', which does not exist" \
    game --headless --ticks 1 --size 160x90 --world none --capture-every 1 --capture-dir "$tmp/dlink" || return 1
  expect_exit 2 "--screenshot-dir: cannot make the folder: '$tmp/dlink' is a symbolic link" \
    game --headless --ticks 1 --size 160x90 --world none --screenshot-dir "$tmp/dlink/shots" || return 1
  expect_exit 2 "'$tmp/dlink' is a symbolic link to 'gone_dir', which does not exist" \
    "$lab" seed-figures --out "$tmp/dlink" || return 1
  [ -L "$tmp/dlink" ] && [ ! -e "$tmp/gone_dir" ]
}
check "outputs: a folder flag on a dangling link is refused, naming it" dangling_folders
fifo_without_reader() {
  mkfifo "$tmp/f.json" || return 1
  timeout 60 "$game_bin" --settings none --headless --ticks 1 --size 160x90 --world none --dump-state "$tmp/f.json" \
    >/dev/null 2>"$tmp/err"
  local rc=$?
  [ "$rc" = 2 ] && grep -q "a FIFO that no process reads" "$tmp/err" && [ -p "$tmp/f.json" ]
}
check "outputs: a FIFO without a reader is refused, not waited on" fifo_without_reader
fifo_with_reader() {
  mkfifo "$tmp/g.json" || return 1
  timeout 60 cat "$tmp/g.json" >"$tmp/from_fifo" &
  local reader=$!
  out1 --dump-state "$tmp/g.json" && wait "$reader" && grep -q state_hash "$tmp/from_fifo" && [ -p "$tmp/g.json" ]
}
check "outputs: a FIFO with a reader gets the dump and stays a FIFO" fifo_with_reader
device_kept() {
  if ! mknod "$tmp/n.json" c 1 3 2>/dev/null; then cp -a /dev/null "$tmp/n.json" 2>/dev/null || return 0; fi
  out1 --dump-state "$tmp/n.json" && [ -c "$tmp/n.json" ]
}
check "outputs: a device node is written in place, not replaced" device_kept
check "outputs: /dev/full is a full disk: exit 2 with the reason" \
  expect_exit 2 "No space left on device" game --headless --ticks 1 --size 160x90 --world none --dump-state /dev/full
check "outputs: /dev/full stays a device" test -c /dev/full
missing_folder() {
  expect_exit 2 "does not exist" game --headless --ticks 1 --size 160x90 --world none --screenshot "$tmp/nofolder/x.png" &&
    [ ! -e "$tmp/nofolder" ]
}
check "outputs: a missing folder is refused, not made" missing_folder
check "outputs: the lab's full disk is exit 2 too" \
  expect_exit 2 "No space left on device" "$lab" hair-chain --solver reference --seconds 0.1 --csv /dev/full
# A real full file system where this machine lets a test mount one (root in a container usually can).
full_disk() {
  mkdir -p "$tmp/full"
  if ! mount -t tmpfs -o size=256k tmpfs "$tmp/full" 2>/dev/null; then
    echo "(outputs: no tmpfs could be mounted here; the full disk is covered by the fault tests and /dev/full)"
    return 0
  fi
  echo previous >"$tmp/full/s.json" && echo previous >"$tmp/full/s.png"
  dd if=/dev/zero of="$tmp/full/filler" bs=4k 2>/dev/null # until the disk is full
  game --headless --ticks 1 --size 320x180 --world none --screenshot "$tmp/full/s.png" \
    --dump-state "$tmp/full/s.json" >/dev/null 2>"$tmp/err"
  local rc=$? ok=0
  { [ "$rc" = 2 ] && grep -q "No space left on device" "$tmp/err" && [ "$(cat "$tmp/full/s.json")" = previous ] &&
    [ "$(cat "$tmp/full/s.png")" = previous ] && [ "$(ls -A "$tmp/full" | wc -l)" = 3 ]; } || ok=1
  [ "$ok" = 0 ] || { echo "exit $rc"; cat "$tmp/err"; ls -la "$tmp/full"; }
  umount "$tmp/full"
  return "$ok"
}
check "outputs: a full disk keeps the previous files and leaves no temporary" full_disk
# A world save that fails on a full disk is a write that failed: exit 2, the previous save kept.
full_disk_world() {
  game --headless --ticks 5 --size 160x90 --seed 4 --world "$tmp/fw.mcworld" --save >/dev/null 2>&1 || return 1
  mkdir -p "$tmp/fullw"
  if ! mount -t tmpfs -o size=4m tmpfs "$tmp/fullw" 2>/dev/null; then
    echo "(outputs: no tmpfs could be mounted here; a failed save's exit code is not checked on a full disk)"
    return 0
  fi
  cp "$tmp/fw.mcworld" "$tmp/fullw/w.mcworld"
  dd if=/dev/zero of="$tmp/fullw/filler" bs=4k 2>/dev/null # until the disk is full
  printf '5 key W down\n7 key SPACE down\n' >"$tmp/fw.txt" # the world's ticks: it was saved at 5
  game --headless --ticks 40 --size 160x90 --world "$tmp/fullw/w.mcworld" --script "$tmp/fw.txt" --save \
    >/dev/null 2>"$tmp/err"
  local rc=$? ok=0
  { [ "$rc" = 2 ] && grep -q "save failed" "$tmp/err" && cmp -s "$tmp/fw.mcworld" "$tmp/fullw/w.mcworld"; } || ok=1
  [ "$ok" = 0 ] || { echo "exit $rc"; cat "$tmp/err"; ls -la "$tmp/fullw"; }
  umount "$tmp/fullw"
  return "$ok"
}
check "outputs: a world save on a full disk is exit 2 and keeps the previous save" full_disk_world

# The README's picture command (its line under the picture) still runs and places its two coloured lamps:
# taken from the README, at 320x180 and with the screenshot written here, from the source folder.
readme_picture() {
  local line
  line=$(grep -o 'build/minecrappy --settings none --headless[^`]*readme-demo.png' "$src/../README.md") || { echo "no picture command in README"; return 1; }
  line=${line#build/minecrappy --settings none } # game() gives --settings none
  line=${line/--size 960x540/--size 320x180}
  line=${line/--screenshot assets\/readme-demo.png/--screenshot $tmp/readme.png}
  [[ $line == *"$tmp/readme.png"* && $line == *"320x180"* ]] || { echo "the picture command changed shape: $line"; return 1; }
  # shellcheck disable=SC2086 # the README's words, split as a shell would
  (cd "$src/.." && game $line --dump-state "$tmp/readme.json" >/dev/null) || return 1
  python3 - "$tmp/readme.json" <<'PY'
import json, sys
blocks = sorted(e["block"] for e in json.load(open(sys.argv[1]))["edits"])
sys.exit(0 if blocks == ["blue_lamp", "red_lamp"] else f"the picture's edits: {blocks}, wanted a red and a blue lamp")
PY
}
check "the README's picture command places its red and blue lamps" readme_picture

echo "cli: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
