#!/usr/bin/env bash
# scripts/frame_stats.py, the way docs/ENGINE.md's frame table is measured: a short run of two
# configurations (one naming the game binary itself with game=) must print one table row each, with
# every column filled, and the machine control's line with a figure for the round; a run of another
# script must name it in the table's heading, and --stretch must sum up the frames of its ticks; a
# missing binary or script, or a stretch that is not FROM-TO, must be refused with a message and a
# non-zero exit.
# Usage: frame_stats_script.sh GAME SOURCE_DIR BENCH
set -euo pipefail
game=$1
src=$2
bench=$3
out=$(python3 "$src/../scripts/frame_stats.py" --game "$game" --bench "$bench" --rounds 1 --ticks 20 --size 160x90 \
    "--view-radius 2" "game=$game --view-radius 2 --lod false" 2>/dev/null)
echo "$out"
rows=$(grep -c '^| .*--view-radius 2' <<<"$out" || true)
[[ $rows == 2 ]] || { echo "expected 2 rows, found $rows"; exit 1; }
# Eleven columns, each with a figure: "| config | 12.3 ms (12.3-12.3) | ... | 120 MiB |".
while IFS= read -r row; do
    cells=$(awk -F'|' '{print NF - 2}' <<<"$row")
    [[ $cells == 11 ]] || { echo "row with $cells columns: $row"; exit 1; }
    grep -qE '\| [0-9]+\.[0-9]{2} \| [0-9]+ MiB \|$' <<<"$row" || { echo "no fragments per pixel or peak memory in: $row"; exit 1; }
done < <(grep '^| .*--view-radius 2' <<<"$out")
grep -qE '^machine control after each round \(the same [0-9.]+ ms .*median [0-9.]+ ms; p99 [0-9.]+ ms; slowest run held up by [0-9.]+ ms$' <<<"$out" ||
    { echo "no machine control line"; exit 1; }
# Another script: the table's heading names it. A stretch of ticks is summed up on its own.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$(python3 "$src/../scripts/frame_stats.py" --game "$game" --no-control --rounds 1 --ticks 20 --size 160x90 \
    --script "$src/e2e/valley_view.txt" --stretch 5-14 --json "$tmp/runs.json" "--view-radius 2" 2>/dev/null)
echo "$out"
line=$(grep -E '^\[--view-radius 2\] 10 frames: median [0-9.]+ ms, worst [0-9.]+ ms, over 25 ms [0-9]+, over 33 ms [0-9]+, [0-9,]+ triangles$' <<<"$out") ||
    { echo "no line for ticks 5-14"; exit 1; }
# The line's figures are those of the run's own frames of ticks 5-14 (per_frame, in the --json copy).
expected=$(python3 - "$tmp/runs.json" <<'PY'
import json, statistics, sys
run = json.load(open(sys.argv[1]))["runs"]["--view-radius 2"][0]["per_frame"]
picked = [k for k, t in enumerate(run["tick"]) if 5 <= t <= 14]
ms = [run["frame_ms"][k] for k in picked]
print(f"[--view-radius 2] {len(picked)} frames: median {statistics.median(ms):.1f} ms, worst {max(ms):.1f} ms, "
      f"over 25 ms {sum(v > 25 for v in ms)}, over 33 ms {sum(v > 33 for v in ms)}, "
      f"{statistics.median(run['triangles'][k] for k in picked):,.0f} triangles")
PY
)
[[ $line == "$expected" ]] || { echo "the stretch line says '$line', its frames '$expected'"; exit 1; }
grep -q '^1 runs each of 20 frames at 160x90 (tests/e2e/valley_view.txt)' <<<"$out" ||
    { echo "the heading does not name the script: $out"; exit 1; }
[[ $(grep -c '^| --view-radius 2 |' <<<"$out" || true) == 1 ]] || { echo "no row for the other script: $out"; exit 1; }
if err=$(python3 "$src/../scripts/frame_stats.py" --game "$game" --no-control --rounds 1 --stretch 9-5 "" 2>&1); then
    echo "a backward stretch was accepted"; exit 1
fi
grep -q -- "--stretch '9-5': expected FROM-TO" <<<"$err" || { echo "unclear message: $err"; exit 1; }
if err=$(python3 "$src/../scripts/frame_stats.py" --game "$game" --no-control --rounds 1 --script /nonexistent/view.txt "" 2>&1); then
    echo "a missing script was accepted"; exit 1
fi
grep -q -- "--script /nonexistent/view.txt: no such file" <<<"$err" || { echo "unclear message: $err"; exit 1; }
if err=$(python3 "$src/../scripts/frame_stats.py" --game "$game" --bench /nonexistent/bench --rounds 1 "" 2>&1); then
    echo "a missing benchmark binary was accepted"; exit 1
fi
grep -q "/nonexistent/bench is not an executable" <<<"$err" || { echo "unclear message: $err"; exit 1; }
if err=$(python3 "$src/../scripts/frame_stats.py" --rounds 1 "game=/nonexistent/minecrappy" 2>&1); then
    echo "a missing binary was accepted"; exit 1
fi
grep -q "/nonexistent/minecrappy is not an executable" <<<"$err" || { echo "unclear message: $err"; exit 1; }
echo "frame_stats.py ok"
