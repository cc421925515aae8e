#!/usr/bin/env bash
# The pause menu in the real window under Xvfb, clicked and keyed by xdotool like a person: Esc goes back
# one level from every page (Blocks, Worlds, Settings, Controls) to the menu's list, resumes only from the list, and
# a page never stays behind to cover the list the next time; inside a pop-up (the "Delete world?" question, a
# drop-down, the time slider's typed hour) Esc closes or cancels only that; Quit then ends the game by itself.
# Each step is checked twice: by F2 screenshots (the Quit button's blue where the list is, the scene where
# it is not), taken until the step shows or 30 s pass (no fixed wait decides), and by the result (a click on
# Quit that landed in the game would not end it; the hour typed and confirmed is the state's, the one
# cancelled is not).
set -u
game=$1
probe=${PNG_PROBE:?PNG_PROBE must name the png_probe helper}
test_name=menu
. "$(dirname "$0")/xvfb_session.sh"
start_xvfb 141 190

# One saved world in the Worlds list, for its "Delete world?" question.
mkdir -p "$tmp/xdg/minecrappy/worlds"
"$game" --settings none --headless --ticks 1 --size 160x90 --world "$tmp/xdg/minecrappy/worlds/keep.mcworld" \
  >/dev/null 2>&1 || fail "the headless run that makes a world failed"
XDG_DATA_HOME=$tmp/xdg "$game" --settings none --world none --size 640x480 --terrain flat --seed 1 --vsync false \
  --time-of-day 12 --day-cycle false --screenshot-dir "$tmp/shots" --dump-state "$tmp/state.json" \
  >"$tmp/game.log" 2>&1 &
game_pid=$!
win=$(timeout 120 xdotool search --sync --onlyvisible --name Minecrappy | head -n 1)
[ -n "$win" ] || fail "no game window appeared"
xdotool windowfocus --sync "$win" 2>/dev/null
sleep 2

# The pause menu's list at 640x480 (ImGui's default style): six buttons 23 px apart and the time-of-day
# slider under them, centred at x 320.
button_y() {
  case $1 in Resume) echo 132 ;; Blocks) echo 155 ;; Worlds) echo 178 ;; Settings) echo 201 ;; Controls) echo 224 ;;
  Quit) echo 247 ;; esac
}
click() { xdotool mousemove --window "$win" 320 "$(button_y "$1")" click 1; sleep 0.6; }
key() { xdotool key --window "$win" "$1"; sleep 0.6; }
shots=0
# F2, then the wait for its screenshot: the game has read every input sent before it (F2 is handled at a tick,
# after the events before it).
sync() {
  key F2
  shots=$((shots + 1))
  for _ in $(seq 600); do [ "$(ls "$tmp"/shots/*.png 2>/dev/null | wc -l)" -ge "$shots" ] && return 0; sleep 0.1; done
  fail "F2 wrote no screenshot in 60 s"
}
# Takes F2 screenshots until `$2 R G B` (the colour around pixel $3,$4 of the 640x480 window) holds, or fails
# after 30 s naming the step $1. Each shot is waited for (F2 writes it at the end of a frame).
shot_until() {
  local step=$1 check=$2 x=$3 y=$4 shot r g b
  for _ in $(seq 30); do
    key F2
    shots=$((shots + 1))
    for _ in $(seq 600); do [ "$(ls "$tmp"/shots/*.png 2>/dev/null | wc -l)" -ge "$shots" ] && break; sleep 0.1; done
    [ "$(ls "$tmp"/shots/*.png 2>/dev/null | wc -l)" -ge "$shots" ] || fail "$step: F2 wrote no screenshot"
    shot=$(ls -t "$tmp"/shots/*.png | head -n 1)
    read -r r g b < <("$probe" "$shot" "$(python3 -c "print($x / 640)")" "$(python3 -c "print($y / 480)")" 3)
    "$check" "$r" "$g" "$b" && { echo "ok: $step"; return 0; }
  done
  fail "$step: not shown after 30 screenshots (last pixel $r $g $b at $x,$y)"
}
# Whether the list shows: the Quit button's blue (or not) where the list puts it. The button reads 85 111 141
# there; the settings page, drawn in its place, 40 58 81: blue ahead of red by 56 against 41, so the line
# between them is drawn at 48, and blue must lead green by 20 (the button's 30).
is_list_blue() { [ "$3" -gt $(($1 + 48)) ] && [ "$3" -gt $(($2 + 20)) ]; }
not_list_blue() { ! is_list_blue "$@"; }
expect_list() { # $1: yes or no, $2: the step
  if [ "$1" = yes ]; then shot_until "$2" is_list_blue 320 "$(button_y Quit)"; else shot_until "$2" not_list_blue 320 "$(button_y Quit)"; fi
}
# The "Delete world?" question's title bar at 320,213 reads 67 96 138; the Worlds page under it 39 42 36.
is_title_blue() { [ "$3" -gt $(($1 + 40)) ]; }
# The hair-detail drop-down, open, covers 340,240 with its dark grey (20 20 21); closed, the hair budget
# slider is there, blue-ish (24 34 41).
is_dark_grey() { [ "$3" -lt $(($1 + 10)) ] && [ "$1" -lt 60 ]; }
is_slider_blue() { [ "$3" -gt $(($1 + 10)) ]; }
worlds_without_question() { ! is_title_blue "$@"; }
ctrl_click_time() {
  xdotool keydown --window "$win" ctrl
  sync
  xdotool mousemove --window "$win" 320 270 click 1
  sync
  xdotool keyup --window "$win" ctrl
  sync
}

key Escape
expect_list yes "Esc pauses: the list"
for page in Blocks Worlds Settings Controls; do
  click "$page"
  expect_list no "$page opens in place of the list"
  key Escape
  expect_list yes "Esc from $page goes back to the list"
done
click Worlds
expect_list no "Worlds opens"
key Escape   # back to the list
expect_list yes "back on the list"
key Escape   # resume from the list
expect_list no "Esc from the list resumes"
key Escape   # pause again: the list, with no page left over it
expect_list yes "pausing again shows the list alone"
# The Blocks page puts the block clicked into the selected slot (slot 1, grass): the red lamp, third in its
# third row (at 296,246 while slot 1 holds grass); the slot's red shows in the hotbar (the icon's top-left pane at
# 152,444 reads 226 59 42 with the red lamp, 106 103 56 with grass: red ahead of green and blue by 80).
click Blocks
expect_list no "Blocks opens"
xdotool mousemove --window "$win" 296 246 click 1
sync
xdotool mousemove --window "$win" 620 470
is_red() { [ "$1" -gt $(($2 + 80)) ] && [ "$1" -gt $(($3 + 80)) ]; }
shot_until "the red lamp is in slot 1" is_red 152 444
key Escape
expect_list yes "Esc from Blocks goes back to the list"
# Esc in the "Delete world?" question keeps the world and stays on Worlds (it went back to the list).
click Worlds
expect_list no "Worlds opens again"
xdotool mousemove --window "$win" 408 245 click 1   # the world's Delete
shot_until "Delete asks first" is_title_blue 320 213
key Escape
shot_until "Esc in the question closes only the question" worlds_without_question 320 213
expect_list no "... and Worlds stays"
[ -f "$tmp/xdg/minecrappy/worlds/keep.mcworld" ] || fail "Esc in the question deleted the world"
key Escape
expect_list yes "Esc from Worlds goes back to the list"
# Esc with the hair-detail drop-down open closes the drop-down and stays on Settings.
click Settings
expect_list no "Settings opens again"
xdotool mousemove --window "$win" 230 207 click 1
sync
xdotool mousemove --window "$win" 620 470   # away from the drop-down: no tooltip over the probe
shot_until "the hair-detail drop-down opens" is_dark_grey 340 240
key Escape
shot_until "Esc closes the drop-down" is_slider_blue 340 240
expect_list no "... and Settings stays"
key Escape
expect_list yes "Esc from Settings goes back to the list"
# The time slider, Ctrl+clicked: a typed hour is kept by Return and cancelled by Esc, which leaves the menu.
ctrl_click_time
key 9
key Return
expect_list yes "Return keeps the typed hour and the menu"
ctrl_click_time
key 1
key 5
key Escape
expect_list yes "Esc cancels the typed hour and keeps the menu"
key Escape
expect_list no "the next Esc resumes: the text edit was closed"
key Escape
expect_list yes "and pauses again"
click Quit
for _ in $(seq 1200); do kill -0 "$game_pid" 2>/dev/null || break; sleep 0.1; done
kill -0 "$game_pid" 2>/dev/null && fail "Quit did not end the game"
wait "$game_pid"
code=$?
game_pid=
[ "$code" -eq 0 ] || fail "the game exited with $code after Quit"
python3 - "$tmp/state.json" <<'PY' || fail "the state on exit is not paused (a click reached the game)"
import json, sys
assert json.load(open(sys.argv[1]))["paused"]
PY
python3 - "$tmp/state.json" <<'PY' || fail "slot 1 does not hold the red lamp picked on the Blocks page"
import json, sys
hotbar = json.load(open(sys.argv[1]))["player"]["hotbar"]
assert hotbar[0] == "red_lamp", hotbar
PY
python3 - "$tmp/state.json" <<'PY' || fail "the time is not the hour typed and confirmed (9), or the cancelled one (15) was kept"
import json, sys
t = json.load(open(sys.argv[1]))["time_of_day"]
assert t == 9.0, t
PY

# Worlds > Recordings > Play: a recording in the worlds folder replays in the window as a timeline; End, then the
# state on exit is the headless replay's end (tick and hash).
"$game" --settings none --headless --world none --ticks 120 --size 160x90 --script "$(dirname "$0")/walk.txt" \
  --record "$tmp/xdg/minecrappy/worlds/walk.mcscript" >/dev/null 2>&1 || fail "the headless recording failed"
"$game" --settings none --headless --replay "$tmp/xdg/minecrappy/worlds/walk.mcscript" --dump-state "$tmp/replayed.json" \
  >/dev/null 2>&1 || fail "the headless replay failed"
XDG_DATA_HOME=$tmp/xdg "$game" --settings none --world none --size 640x480 --terrain flat --seed 1 --vsync false \
  --screenshot-dir "$tmp/shots" --dump-state "$tmp/state.json" >"$tmp/game.log" 2>&1 &
game_pid=$!
win=$(timeout 120 xdotool search --sync --onlyvisible --name Minecrappy | head -n 1)
[ -n "$win" ] || fail "no game window appeared"
xdotool windowfocus --sync "$win" 2>/dev/null
key Escape
expect_list yes "Esc pauses (the second session)"
click Worlds
# Each page is waited for by its colour where the next click goes (a window is laid out in its first frame and
# shown in the next): "Create and play" reads 60 92 125 at 140,338; the first recording's Play 73 103 133 at
# 397,178; the timeline's bar 38 38 38 at 500,40 (the sky there is 99 137 196).
is_button_blue() { [ "$3" -gt $(($1 + 40)) ] && [ "$3" -gt 100 ]; }
is_bar_grey() { [ "$3" -lt 60 ] && [ "$1" -lt 60 ]; }
shot_until "Worlds opens (the second session)" is_button_blue 140 338
xdotool mousemove --window "$win" 258 338 click 1 # Recordings..., beside Create and play
shot_until "Recordings opens and lists the recording" is_button_blue 397 178
xdotool mousemove --window "$win" 397 178 click 1 # the first recording's Play
shot_until "Play shows the timeline" is_bar_grey 500 40
key End
sync
kill -TERM "$game_pid"
wait "$game_pid" || fail "the game exited with $? on SIGTERM"
game_pid=
python3 - "$tmp/state.json" "$tmp/replayed.json" <<'PY' || fail "the replay opened from Recordings did not end at the recording's end"
import json, sys
window, headless = (json.load(open(p)) for p in sys.argv[1:3])
assert window["tick"] == 120 and window["state_hash"] == headless["state_hash"], (window["tick"], window["state_hash"], headless["state_hash"])
PY
echo "ok: Recordings > Play replays the recording to its end"
echo "menu: 1 passed, 0 failed"
