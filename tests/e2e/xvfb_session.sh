# Sourced by the tests of the real window (window_test.sh, menu_test.sh, timeline_test.sh): a temporary folder
# removed on exit with the game and Xvfb, fail() for the test named by $test_name, start_xvfb FIRST LAST, which
# starts Xvfb on the first display number in FIRST..LAST with no lock file and exports DISPLAY once it answers,
# and shot NAME (below).
# The tests take disjoint ranges, so CTest can run them side by side.
tmp=$(mktemp -d)
xvfb_pid= game_pid=
cleanup() {
  [ -n "$game_pid" ] && kill "$game_pid" 2>/dev/null
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  [ -f "$tmp/game.log" ] && sed 's/^/  game: /' "$tmp/game.log"
  echo "$test_name: 0 passed, 1 failed"
  exit 1
}
start_xvfb() {
  local n display=
  for n in $(seq "$1" "$2"); do [ -e "/tmp/.X$n-lock" ] || { display=":$n"; break; }; done
  [ -n "$display" ] || fail "no free X display in :$1 to :$2"
  Xvfb "$display" -screen 0 800x600x24 -nolisten tcp >"$tmp/xvfb.log" 2>&1 &
  xvfb_pid=$!
  export DISPLAY=$display
  for _ in $(seq 300); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.1; done
  xdotool getmouselocation >/dev/null 2>&1 || fail "Xvfb did not start"
}
# F2 in the game window $win, then the wait for its screenshot in $tmp/shots, moved to $tmp/$1.png: the game has
# read every input sent before the F2 (it is handled at a tick or a frame, after the events before it). No step
# waits for a time.
shot() {
  xdotool key --window "$win" F2
  for _ in $(seq 600); do [ "$(ls "$tmp"/shots/*.png 2>/dev/null | wc -l)" -gt 0 ] && break; sleep 0.1; done
  local f
  f=$(ls "$tmp"/shots/*.png 2>/dev/null | head -n 1)
  [ -n "$f" ] || fail "F2 wrote no screenshot in 60 s (before '$1')"
  mv "$f" "$tmp/$1.png"
}
