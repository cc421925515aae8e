#!/usr/bin/env python3
"""Frame figures that hold up on a noisy machine: runs the headless walking benchmark for each
configuration several times, in turn (A B C A B C ...), so that a slow minute of the machine falls on
every configuration alike, and prints for each the median over the runs of each run's figures, with
the spread of the per-run medians.

    scripts/frame_stats.py "--view-radius 8" "--view-radius 8 --lod false" --rounds 3

Each configuration is a string of extra arguments for build/minecrappy (or for another build of the
game named first with `game=PATH`, to compare two builds: "game=/tmp/old/minecrappy --view-radius 8");
every run is
    minecrappy --headless --settings none --ticks T --size WxH --script SCRIPT
               --frame-stats FILE CONFIG
where SCRIPT is tests/e2e/walk.txt unless --script names another (tests/e2e/valley_view.txt holds
still the walk's view with the most triangles).
After each round it times the machine itself (`minecrappy-bench --benchmark_filter=machineStalls`: a
fixed 8-9 ms of arithmetic, 300 times, with the other core busy) and prints how long the slowest run was
held up: a frame can be held up as long, whatever the game does (--no-control leaves it out).
--stretch FROM-TO sums up a stretch of ticks of each run on its own (the walk's view over the valley,
304-363, or the player standing in a tree crown, 420-599, where nothing in view changes), from the
per_frame figures of --frame-stats.
How the figures are defined: docs/ENGINE.md ("Speed").
"""
import argparse
import json
import os
import re
import shlex
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def split_config(game, config):
    """The binary and the extra arguments of a configuration."""
    words = shlex.split(config)
    if words and words[0].startswith("game="):
        return words[0][len("game="):], words[1:]
    return game, words


def run_once(game, config, args, out):
    game, extra = split_config(game, config)
    cmd = [game, "--headless", "--settings", "none", "--ticks", str(args.ticks), "--size", args.size,
           "--script", args.script, "--frame-stats", out]
    cmd += extra
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"frame_stats: configuration {config!r} failed (exit {done.returncode}):\n{done.stderr}")
    with open(out) as f:
        return json.load(f)


def machine_stalls(bench):
    """The machine control's counters (fastest_ms, median_ms, p99_ms, worst_ms, worst_stall_ms, ...)."""
    done = subprocess.run([bench, "--benchmark_filter=^machineStalls", "--benchmark_format=json"],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"frame_stats: {bench} failed (exit {done.returncode}):\n{done.stderr}")
    found = [b for b in json.loads(done.stdout)["benchmarks"] if b["name"].startswith("machineStalls")]
    if not found:
        sys.exit(f"frame_stats: {bench} has no machineStalls benchmark")
    return found[0]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("configs", nargs="+", help="extra arguments of one configuration, quoted")
    p.add_argument("--rounds", type=int, default=3, help="runs of each configuration (default 3)")
    p.add_argument("--ticks", type=int, default=600, help="frames per run (default 600)")
    p.add_argument("--size", default="1280x720", help="frame size (default 1280x720)")
    p.add_argument("--script", default=os.path.join(ROOT, "tests", "e2e", "walk.txt"),
                   help="the input script (default tests/e2e/walk.txt, the walk over chunk borders)")
    p.add_argument("--stretch", metavar="FROM-TO", action="append", default=[],
                   help="also sum up the frames of ticks FROM to TO (inclusive) of each run on their own: "
                        "median, worst, frames over 25 and over 33 ms (the frame aims), triangles; may be repeated")
    p.add_argument("--game", default=os.path.join(ROOT, "build", "minecrappy"), help="the game binary")
    p.add_argument("--json", help="also write every run's figures here")
    p.add_argument("--bench", default=os.path.join(ROOT, "build", "minecrappy-bench"),
                   help="the benchmark binary that times the machine itself after each round")
    p.add_argument("--no-control", action="store_true", help="do not time the machine itself")
    args = p.parse_args()
    if args.rounds < 1 or args.ticks < 1:
        sys.exit("frame_stats: --rounds and --ticks must be at least 1")
    if not os.path.isfile(args.script):
        sys.exit(f"frame_stats: --script {args.script}: no such file")
    stretches = []
    for text in args.stretch:
        m = re.fullmatch(r"(\d+)-(\d+)", text)
        if not m or int(m.group(1)) > int(m.group(2)):
            sys.exit(f"frame_stats: --stretch {text!r}: expected FROM-TO, two ticks with FROM <= TO")
        stretches.append((int(m.group(1)), int(m.group(2))))
    for c in args.configs:
        game = split_config(args.game, c)[0]
        if not os.access(game, os.X_OK):
            sys.exit(f"frame_stats: {game} is not an executable (build first: scripts/build.sh)")
    if not args.no_control and not os.access(args.bench, os.X_OK):
        sys.exit(f"frame_stats: {args.bench} is not an executable (build first, or --no-control)")

    runs = {c: [] for c in args.configs}
    control = []
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(args.rounds):
            for i, c in enumerate(args.configs):
                j = run_once(args.game, c, args, os.path.join(tmp, f"{r}-{i}.json"))
                runs[c].append(j)
                print(f"round {r + 1}/{args.rounds} [{c}]: median {j['median_ms']:.1f} ms, "
                      f"p99 {j['p99_ms']:.1f}, worst {j['worst_ms']:.1f}", file=sys.stderr)
            if not args.no_control:
                control.append(machine_stalls(args.bench))

    def med(c, f):
        return statistics.median(f(j) for j in runs[c])

    def overdraw(c):  # builds from before the figure existed leave it out
        if any("fragments_per_pixel" not in j for j in runs[c]):
            return "-"
        return f"{med(c, lambda j: j['fragments_per_pixel']['median']):.2f}"

    # The columns of docs/ENGINE.md's frame table, so that a row can be pasted as it is.
    print(f"{args.rounds} runs each of {args.ticks} frames at {args.size} ({os.path.relpath(args.script, ROOT)}), "
          "medians over the runs:")
    print("| configuration | median (range of runs) | 99th percentile | worst | after loading: p99, worst "
          "| triangles (median) | draw calls (median) | meshing (median, worst) | GPU wait (median) "
          "| fragments per pixel (median) | peak memory |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for c in args.configs:
        meds = sorted(j["median_ms"] for j in runs[c])
        print(f"| {c} | {med(c, lambda j: j['median_ms']):.1f} ms ({meds[0]:.1f}-{meds[-1]:.1f}) "
              f"| {med(c, lambda j: j['p99_ms']):.1f} ms | {med(c, lambda j: j['worst_ms']):.1f} ms "
              f"| {med(c, lambda j: j['after_load']['p99_ms']):.1f}, "
              f"{med(c, lambda j: j['after_load']['worst_ms']):.1f} ms "
              f"| {med(c, lambda j: j['triangles']['median']):,.0f} "
              f"| {med(c, lambda j: j['draw_calls']['median']):.0f} "
              f"| {med(c, lambda j: j['mesh_ms']['median']):.2f} ms, {med(c, lambda j: j['mesh_ms']['worst']):.1f} ms "
              f"| {med(c, lambda j: j['gpu_wait_ms']['median']):.1f} ms "
              f"| {overdraw(c)} "
              f"| {med(c, lambda j: j['peak_rss_mib']):.0f} MiB |")
    for lo, hi in stretches:
        print(f"ticks {lo}-{hi} of each run on their own (medians over the runs; frames over 25 and 33 ms: "
              "each run's count):")
        for c in args.configs:
            per = []
            for j in runs[c]:
                each = j.get("per_frame")
                if each is None:
                    sys.exit(f"frame_stats: [{c}] wrote no per_frame figures (a build from before they existed)")
                picked = [k for k, t in enumerate(each["tick"]) if lo <= t <= hi]
                if not picked:
                    sys.exit(f"frame_stats: [{c}] drew no frame in ticks {lo}-{hi}")
                ms = [each["frame_ms"][k] for k in picked]
                per.append({"frames": len(picked), "median": statistics.median(ms), "worst": max(ms),
                            "over25": sum(v > 25.0 for v in ms), "over33": sum(v > 33.0 for v in ms),
                            "triangles": statistics.median(each["triangles"][k] for k in picked)})

            def mid(key):
                return statistics.median(r[key] for r in per)
            print(f"[{c}] {per[0]['frames']} frames: median {mid('median'):.1f} ms, worst {mid('worst'):.1f} ms, "
                  f"over 25 ms {', '.join(str(r['over25']) for r in per)}, "
                  f"over 33 ms {', '.join(str(r['over33']) for r in per)}, {mid('triangles'):,.0f} triangles")
    if control:
        # Every run of the control does the same work: time beyond its fastest run is the machine's.
        print(f"machine control after each round (the same {control[0]['fastest_ms']:.1f} ms of arithmetic, "
              f"300 times, other core busy): median " + ", ".join(f"{c['median_ms']:.1f}" for c in control) +
              " ms; p99 " + ", ".join(f"{c['p99_ms']:.1f}" for c in control) +
              " ms; slowest run held up by " + ", ".join(f"{c['worst_stall_ms']:.1f}" for c in control) + " ms")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"runs": runs, "machine_control": control}, f, indent=1)


if __name__ == "__main__":
    main()
