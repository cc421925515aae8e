#!/usr/bin/env bash
# A replay played in the real window as a timeline (minecrappy --replay), driven by xdotool under Xvfb: End, three
# ticks back, take over (T), walk; and a click in the middle of the bar, a tick back, take over. Each step is
# waited for through an F2 screenshot and the pictures must change; each take-over with --record starts a new
# recording at the tick the timeline was at, whose start hash is the straight replay's at that tick and which
# replays headless to the window's final state. Then a replay facing a hair ball: E opens its panel read only, clicks
# on its sliders change nothing (the take-over a tick later starts at the straight replay's state).
set -u
game=$1 src=$2
test_name=timeline
. "$(dirname "$0")/xvfb_session.sh"
start_xvfb 191 230

"$game" --settings none --headless --world none --ticks 600 --size 320x180 --script "$src/e2e/walk.txt" \
  --record "$tmp/walk.mcscript" >/dev/null 2>&1 || fail "the headless recording failed"

hash_of() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["state_hash"])' "$1"; }
# The hash the straight replay has at a tick.
replay_hash_at() {
  "$game" --settings none --headless --replay "$tmp/walk.mcscript" --seek "$1" --dump-state "$tmp/at$1.json" \
    >/dev/null 2>&1 || fail "the headless seek to $1 failed"
  hash_of "$tmp/at$1.json"
}

# One window session: $1 the name; the rest of the steps come from the caller between open_window and close_window.
open_window() {
  rm -rf "$tmp/shots"
  # No --world: a replay plays its recording's start world, and the worlds folder stays empty.
  "$game" --settings none --worlds-dir "$tmp/worlds" --replay "$tmp/walk.mcscript" --size 800x500 --vsync false \
    --screenshot-dir "$tmp/shots" --dump-state "$tmp/$1.json" --record "$tmp/$1.mcscript" >"$tmp/game.log" 2>&1 &
  game_pid=$!
  win=$(timeout 120 xdotool search --sync --onlyvisible --name Minecrappy | head -n 1)
  [ -n "$win" ] || fail "no game window appeared"
  xdotool windowactivate --sync "$win" 2>/dev/null || xdotool windowfocus --sync "$win"
}
close_window() { # SIGTERM ends the game as closing the window does: the recording and the dump are written
  kill -TERM "$game_pid"
  wait "$game_pid" || fail "the game exited with $? on SIGTERM"
  game_pid=
}
# The recording a take-over started: its start tick, its start hash the straight replay's there, and a headless
# replay of it reaching the window's final state.
check_taken() { # name, lowest start tick, highest
  local rec=$tmp/$1.mcscript
  [ -f "$rec" ] || fail "$1: the take-over wrote no recording"
  local start
  start=$(sed -n 's/^# start_tick \([0-9]*\)$/\1/p' "$rec")
  [ -n "$start" ] && [ "$start" -ge "$2" ] && [ "$start" -le "$3" ] || fail "$1: it starts at tick '$start', not in $2..$3"
  local recorded
  recorded=$(sed -n "s/^# hash $start \([0-9a-f]*\)$/\1/p" "$rec")
  [ "$recorded" = "$(replay_hash_at "$start")" ] || fail "$1: the state taken over at $start is not the replay's"
  "$game" --settings none --headless --replay "$rec" --dump-state "$tmp/$1.replayed.json" >"$tmp/replay.log" 2>&1 ||
    fail "$1: its replay failed: $(cat "$tmp/replay.log")"
  [ "$(hash_of "$tmp/$1.replayed.json")" = "$(hash_of "$tmp/$1.json")" ] || fail "$1: the replay ends elsewhere than the window"
}

open_window ended
shot start
xdotool key --window "$win" End Left Left Left
shot near_end
cmp -s "$tmp/start.png" "$tmp/near_end.png" && fail "End and three ticks back changed nothing on screen"
xdotool key --window "$win" t
xdotool keydown --window "$win" w
shot taken
xdotool keyup --window "$win" w
shot walked
close_window
check_taken ended 597 597
[ -z "$(ls -A "$tmp/worlds" 2>/dev/null)" ] || fail "the replay wrote a world: $(ls "$tmp/worlds")"

open_window dragged
shot start
xdotool mousemove --window "$win" 400 40 click 1 # the middle of the bar: about tick 300
shot clicked
cmp -s "$tmp/start.png" "$tmp/clicked.png" && fail "the click on the bar changed nothing on screen"
xdotool key --window "$win" Left
shot back
xdotool key --window "$win" t
shot taken
close_window
check_taken dragged 250 350

# A recording that stands 2.5 m south of the first hair ball, facing it (its place from a headless run).
"$game" --settings none --headless --world none --ticks 1 --dump-state "$tmp/balls.json" >/dev/null 2>&1 ||
  fail "the headless run that finds the hair ball failed"
python3 - "$tmp/balls.json" >"$tmp/face.txt" <<'PY' || fail "no hair ball in the demo scene"
import json, sys
x, y, z = json.load(open(sys.argv[1]))["hair_balls"][0]["position"]
print(f"0 teleport {x} {y - 1.55} {z + 2.5}")
print("0 look 0 0")
PY
"$game" --settings none --headless --world none --ticks 120 --size 320x180 --script "$tmp/face.txt" \
  --record "$tmp/walk.mcscript" >/dev/null 2>&1 || fail "the recording facing the ball failed"
open_window panel
xdotool key --window "$win" End
xdotool key --window "$win" --repeat 30 --delay 20 Left # tick 90
shot before_panel
xdotool key --window "$win" e
shot panel_open
shot panel_shown # a new window is laid out in its first frame, shown in the next
cmp -s "$tmp/before_panel.png" "$tmp/panel_shown.png" && fail "E showed no panel in the replay"
for y in $(seq 120 20 420); do xdotool mousemove --window "$win" 500 "$y" click 1; done # across its sliders
shot clicked_panel
xdotool key --window "$win" Right # a command queued by a click would be applied in this tick
shot stepped
xdotool key --window "$win" t
shot taken
close_window
check_taken panel 91 91
echo "timeline: 1 passed, 0 failed"
