#!/usr/bin/env bash
# The pause menu in the real window under Xvfb, clicked and keyed by xdotool like a person: Esc goes back
# one level from every page (Worlds, Settings, Controls) to the menu's list, resumes only from the list, and
# a page never stays behind to cover the list the next time; Quit then ends the game by itself.
# Each step is checked twice: by F2 screenshots (the Quit button's blue where the list is, the scene where
# it is not) and by the result (a click on Quit that landed in the game would not end it).
set -u
game=$1
probe=${PNG_PROBE:?PNG_PROBE must name the png_probe helper}
test_name=menu
. "$(dirname "$0")/xvfb_session.sh"
start_xvfb 141 190

"$game" --settings none --world none --size 640x480 --terrain flat --seed 1 --vsync false \
  --screenshot-dir "$tmp/shots" --dump-state "$tmp/state.json" >"$tmp/game.log" 2>&1 &
game_pid=$!
win=$(timeout 20 xdotool search --sync --onlyvisible --name Minecrappy | head -n 1)
[ -n "$win" ] || fail "no game window appeared"
xdotool windowfocus --sync "$win" 2>/dev/null
sleep 2

# The pause menu's list at 640x480 (ImGui's default style): five buttons 23 px apart and the time-of-day
# slider under them, centred at x 320.
button_y() { case $1 in Resume) echo 143 ;; Worlds) echo 166 ;; Settings) echo 189 ;; Controls) echo 212 ;; Quit) echo 235 ;; esac; }
click() { xdotool mousemove --window "$win" 320 "$(button_y "$1")" click 1; sleep 0.6; }
key() { xdotool key --window "$win" "$1"; sleep 0.6; }
shots=0
# Whether the list shows, from an F2 screenshot: the Quit button's blue (or not) where the list puts it. The
# button reads 85 111 141 there; the settings page, drawn in its place, 40 58 81: blue ahead of red by 56
# against 41, so the line between them is drawn at 48, and blue must lead green by 20 (the button's 30).
is_list_blue() { [ "$3" -gt $(($1 + 48)) ] && [ "$3" -gt $(($2 + 20)) ]; }
expect_list() { # $1: yes or no, $2: the step
  key F2
  sleep 0.5
  shots=$((shots + 1))
  local shot
  shot=$(ls "$tmp"/shots/*.png 2>/dev/null | sort | tail -n 1)
  [ "$(ls "$tmp"/shots/*.png 2>/dev/null | wc -l)" -eq "$shots" ] || fail "$2: F2 wrote no screenshot"
  read -r r g b < <("$probe" "$shot" 0.5 "$(python3 -c "print($(button_y Quit) / 480)")" 3)
  if [ "$1" = yes ]; then
    is_list_blue "$r" "$g" "$b" || fail "$2: the menu's list is not shown (Quit button pixel $r $g $b)"
  else
    is_list_blue "$r" "$g" "$b" && fail "$2: the menu's list is still shown (pixel $r $g $b)"
  fi
  echo "ok: $2"
}

key Escape
expect_list yes "Esc pauses: the list"
for page in Worlds Settings Controls; do
  click "$page"
  expect_list no "$page opens in place of the list"
  key Escape
  expect_list yes "Esc from $page goes back to the list"
done
click Worlds
key Escape   # back to the list
key Escape   # resume from the list
expect_list no "Esc from the list resumes"
key Escape   # pause again: the list, with no page left over it
expect_list yes "pausing again shows the list alone"
click Quit
for _ in $(seq 50); do kill -0 "$game_pid" 2>/dev/null || break; sleep 0.1; done
kill -0 "$game_pid" 2>/dev/null && fail "Quit did not end the game"
wait "$game_pid"
code=$?
game_pid=
[ "$code" -eq 0 ] || fail "the game exited with $code after Quit"
python3 - "$tmp/state.json" <<'PY' || fail "the state on exit is not paused (a click reached the game)"
import json, sys
assert json.load(open(sys.argv[1]))["paused"]
PY
echo "menu: 1 passed, 0 failed"
