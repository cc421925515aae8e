#!/usr/bin/env python3
"""The figures of scripts/compare-commit.sh: runs two builds turn about and prints medians side by side.

Each figure is read from a build's own programs; where a benchmark was renamed, the names it had are tried
in turn. Lower is better for every figure but the hair's fraction of its limit kernel."""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

# (figure, benchmark names tried in turn, counter or None for real time in microseconds)
BENCHMARKS = [
    ("mesh a terrain chunk, greedy with occlusion (us)", ["meshBench/terrain_greedy"], None),
    ("mesh a terrain chunk, strips (us)", ["meshBench/terrain_greedy_strips"], None),
    ("mesh a terrain chunk, level of detail (us)",
     ["meshBench/terrain_greedy_flat", "meshBench/terrain_greedy_unlit"], None),
    ("64^3 region, open sky, occlusion (ns/voxel)", ["vsBaseline/greedy_ao/1/manual_time"], "ours_ns_per_voxel"),
    ("64^3 region, open sky, strips (ns/voxel)", ["vsBaseline/greedy_strips/1/manual_time"], "ours_ns_per_voxel"),
    ("64^3 region, open sky, flat (ns/voxel)",
     ["vsBaseline/greedy_flat/1/manual_time", "vsBaseline/greedy_unlit/1/manual_time"], "ours_ns_per_voxel"),
    ("64^3 region, lit, occlusion (ns/voxel)", ["vsBaseline/lit_ao/1/manual_time"], "ours_ns_per_voxel"),
    ("64^3 region, lit, strips (ns/voxel)", ["vsBaseline/lit_strips/1/manual_time"], "ours_ns_per_voxel"),
    ("light: a column from scratch (us)", ["lightRelightColumn"], None),
    ("light: an edit repaired in a kept column (us)", ["columnLight/1"], None),
    ("light: a lamp placed (us)", ["lightEditAtTheSurface/1"], None),
    ("worker job, first of a column (us a chunk)", ["workerJobBench/first_of_column"], "per_chunk"),
    ("worker job, a whole column (us a chunk)", ["workerJobBench/whole_column"], "per_chunk"),
]


def run_benchmarks(build, names):
    """Real time (us) or the named counter of each benchmark present in this build."""
    binary = os.path.join(build, "minecrappy-bench")
    listed = subprocess.run([binary, "--benchmark_list_tests"], capture_output=True, text=True, check=True)
    present = set(listed.stdout.split())
    wanted = [n for n in names if n in present]
    if not wanted:
        return {}
    pattern = "^(" + "|".join(wanted) + ")$"  # benchmark names hold no regex characters but '/' and '_' 
    out = subprocess.run([binary, "--benchmark_filter=" + pattern, "--benchmark_min_time=0.3",
                          "--benchmark_format=json"], capture_output=True, text=True, check=True)
    return {b["name"]: b for b in json.loads(out.stdout)["benchmarks"]}


def value(bench, counter):
    if counter is None:
        scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[bench.get("time_unit", "ns")]
        return bench["real_time"] * scale
    v = bench[counter]
    return v * 1e6 if counter == "per_chunk" else v  # per_chunk is seconds a chunk


def whole_view(build, radius):
    """Process wall and CPU seconds and peak MB of meshing the whole view once, and light's CPU per voxel of
    the columns meshed (None where the build's --frame-stats does not report light)."""
    with tempfile.TemporaryDirectory() as tmp:
        shot = os.path.join(tmp, "x.png")
        stats = os.path.join(tmp, "f.json")
        start = time.monotonic()
        r = subprocess.run(["/usr/bin/time", "-f", "%U %S %M", os.path.join(build, "minecrappy"), "--headless",
                            "--settings", "none", "--ticks", "1", "--size", "320x180", "--view-radius",
                            str(radius), "--screenshot", shot, "--frame-stats", stats],
                           capture_output=True, text=True, check=True)
        wall = time.monotonic() - start
        user, system, kb = r.stderr.strip().splitlines()[-1].split()
        light = json.load(open(stats)).get("light", {}).get("ns_per_column_voxel")
        return wall, float(user) + float(system), int(kb) / 1024, light


def teleport(build, source):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "f.json")
        subprocess.run([os.path.join(build, "minecrappy"), "--headless", "--settings", "none", "--ticks", "200",
                        "--size", "1280x720", "--script", os.path.join(source, "tests/e2e/teleport.txt"),
                        "--frame-stats", stats], capture_output=True, check=True)
        views = json.load(open(stats)).get("views_completed", [])
        return [v["frames"] if v.get("complete") else float("nan") for v in views]


def hair(build):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "h.json")
        subprocess.run([os.path.join(build, "minecrappy-lab"), "hair-bench", "--threads", "1", "--json", out],
                       capture_output=True, check=True)
        h = json.load(open(out))
        return h["ms_per_step"], h["fraction_of_limit"]


def measure(build, source):
    fig = {}
    names = [n for _, alts, _ in BENCHMARKS for n in alts]
    got = run_benchmarks(build, names)
    for label, alts, counter in BENCHMARKS:
        for n in alts:
            if n in got:
                fig[label] = value(got[n], counter)
                break
    for radius in (8, 16, 32):
        wall, cpu, mb, light = whole_view(build, radius)
        fig[f"whole view meshed, radius {radius}: wall (s)"] = wall
        fig[f"whole view meshed, radius {radius}: CPU (s)"] = cpu
        fig[f"whole view meshed, radius {radius}: peak memory (MB)"] = mb
        if light is not None:
            fig[f"whole view meshed, radius {radius}: light CPU a voxel of the columns meshed (ns)"] = light
    frames = teleport(build, source)
    if len(frames) >= 2:
        fig["teleport.txt r8: frames to a complete view, start"] = frames[0]
        fig["teleport.txt r8: frames to a complete view, after the jump"] = frames[1]
    ms, frac = hair(build)
    fig["hair-bench dftl 512x12, 1 thread: ms a step"] = ms
    fig["hair-bench: fraction of the limit kernel (higher is better)"] = frac
    return fig


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--rev", required=True)
    ap.add_argument("--old", required=True)
    ap.add_argument("--old-source", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--new-source", required=True)
    a = ap.parse_args()
    runs = {"old": [], "new": []}
    for r in range(a.rounds):
        print(f"round {r + 1} of {a.rounds}", file=sys.stderr)
        runs["old"].append(measure(a.old, a.old_source))
        runs["new"].append(measure(a.new, a.new_source))
    labels = []
    for run in runs["old"] + runs["new"]:
        labels += [k for k in run if k not in labels]

    def med(side, k):
        vals = [run[k] for run in runs[side] if k in run]
        return statistics.median(vals) if vals else None

    fmt = lambda v: "-" if v is None else f"{v:.3g}"
    print(f"| figure (medians of {a.rounds} rounds, turn about) | {a.rev[:10]} | current tree | current / {a.rev[:7]} |")
    print("|---|---|---|---|")
    for k in labels:
        o, n = med("old", k), med("new", k)
        ratio = f"{n / o:.2f}" if o and n is not None else "-"
        print(f"| {k} | {fmt(o)} | {fmt(n)} | {ratio} |")


if __name__ == "__main__":
    main()
