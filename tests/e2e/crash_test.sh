#!/usr/bin/env bash
# Crash safety: the headless game autosaves a world every few ticks while the pendulums swing, the
# hair hangs and the player walks, and is killed with SIGKILL at random moments, again and again.
# After every kill the world must open (nothing half-written) and hold a completed save: its tick is
# on the autosave schedule, and it never goes back in time. KILLS (default 30) sets how many; the
# docs/WORLDS.md gives the longer run.
set -u
game=$1
kills=${KILLS:-30}
every=7   # autosave every 7 ticks: saves follow each other as fast as the disk allows
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
world="$tmp/crash.mcworld"
fail() { echo "FAIL: $*"; echo "crash: 0 passed, 1 failed"; exit 1; }

last=0
for i in $(seq 1 "$kills"); do
  # The last run is killed only once it has stepped 70 ticks past where it opened (its frame of that tick
  # captured; ten autosaves asked for), so that a completed save is there to find however busy the machine:
  # the random moments alone may all fall before the first save on a loaded one.
  # The walk starts at the tick the world opens at: a script's ticks are the world's own, and one before it is
  # refused (the runs after the first save would end at once).
  printf '%d key W down\n%d look 45 -10\n' "$last" "$last" >"$tmp/walk.txt"
  capture=()
  [ "$i" -eq "$kills" ] && capture=(--size 160x90 --capture-every 1 --capture-dir "$tmp/frames")
  "$game" --settings none --headless --world "$world" --autosave-ticks "$every" --ticks 100000000 --script "$tmp/walk.txt" \
    "${capture[@]}" >"$tmp/run.log" 2>&1 &
  pid=$!
  if [ "$i" -eq "$kills" ]; then
    frame=$(printf '%s/frames/frame-%06d.png' "$tmp" $((last + 70)))
    for _ in $(seq 3000); do [ -s "$frame" ] && break; sleep 0.1; done
    [ -s "$frame" ] || { kill -KILL "$pid"; fail "the last run did not reach tick $((last + 70)) in 300 s"; }
  else
    # A random moment between 0.3 and 1.5 s: during start-up, a save, or between saves.
    sleep "$(awk -v s="$RANDOM" 'BEGIN { srand(s); printf "%.3f", 0.3 + rand() * 1.2 }')"
  fi
  kill -KILL "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  "$game" --settings none --headless --world "$world" --ticks 0 --dump-state "$tmp/state.json" >"$tmp/open.log" 2>&1 ||
    { cat "$tmp/open.log"; fail "kill $i: the world does not open"; }
  tick=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["tick"])' "$tmp/state.json")
  [ $((tick % every)) -eq 0 ] || fail "kill $i: tick $tick is not a completed autosave"
  [ "$tick" -ge "$last" ] || fail "kill $i: the world went back from tick $last to $tick"
  last=$tick
done
[ "$last" -gt 0 ] || fail "no save ever completed"
echo "crash: $kills kills, the world always opened, last saved tick $last"
echo "crash: 1 passed, 0 failed"
