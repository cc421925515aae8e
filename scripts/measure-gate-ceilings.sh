#!/usr/bin/env bash
# Measures the speed gate's ceilings (docs/TESTING.md, "The speed gate"): runs `minecrappy-bench --gate
# --print` RUNS times (default 30) while two busy loops load both cores, then a third as many times idle, and
# prints, per ratio, the worst of all runs, the median of the loaded ones and the ceiling they give: 1.25 times
# the worst, which must be below 1.8 times that median (otherwise the ratio is too noisy to catch a change that
# doubles it, and the script says so and exits 1). Paste the printed lines into
# tests/bench/speed_gate_ceilings.txt. Not part of CI.
#
#   scripts/measure-gate-ceilings.sh [RUNS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-30}
if ! [[ $runs =~ ^[1-9][0-9]*$ ]]; then
    echo "measure-gate-ceilings: RUNS must be a whole number from 1, not '$runs'" >&2
    exit 2
fi
"$root/scripts/build.sh" --target minecrappy-bench >/dev/null
out=$(mktemp)
loads=()
trap 'kill "${loads[@]}" 2>/dev/null || true; rm -f "$out"' EXIT
for _ in 1 2; do
    (while :; do :; done) &
    loads+=($!)
done
for ((i = 1; i <= runs; ++i)); do
    "$root/build/minecrappy-bench" --gate --print | awk 'NR > 1 && $1 !~ /^\(/ { print "loaded", $1, $2 }' >> "$out"
done
kill "${loads[@]}" 2>/dev/null || true
# And a third as many on an idle machine: a ratio can read differently there (the ceiling must hold both ways).
for ((i = 1; i <= (runs + 2) / 3; ++i)); do
    "$root/build/minecrappy-bench" --gate --print | awk 'NR > 1 && $1 !~ /^\(/ { print "idle", $1, $2 }' >> "$out"
done
python3 - "$out" "$runs" "$(git -C "$root" rev-parse --short HEAD)" <<'EOF'
import collections, statistics, sys
runs = collections.defaultdict(lambda: collections.defaultdict(list))
for line in open(sys.argv[1]):
    load, name, ratio = line.split()
    runs[name][load].append(float(ratio))
bad = 0
for name, r in runs.items():
    loaded, idle = r["loaded"], r["idle"]
    worst, median = max(loaded + idle), statistics.median(loaded)
    ceiling = 1.25 * worst
    ok = ceiling < 1.8 * median
    bad += not ok
    print(f"{name} {ceiling:.3g}  # at {sys.argv[3]}: {len(loaded)} loaded runs worst {max(loaded):.3g}, median "
          f"{median:.3g}; {len(idle)} idle worst {max(idle):.3g}"
          + ("" if ok else "; TOO NOISY: 1.25 x worst is not below 1.8 x the loaded median"))
sys.exit(1 if bad else 0)
EOF
