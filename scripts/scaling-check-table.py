#!/usr/bin/env python3
"""Prints docs/performance.md's "Checked on 16 cores" table: the scaling model's projection at N
workers against the wall time measured on N cores, and the projection two of the cores make.

Usage: scripts/scaling-check-table.py N ALL.json [ALL.json ...] --two TWO.json [TWO.json ...]
Each ALL.json from `LP_NUM_THREADS=2 ./build/app/rastercmp bench --scaling --model --reps 11
--suite scenes --json ALL.json` on a host of at least N usable CPUs; each TWO.json from the same
command under `taskset -c 0,1` on that host (the projection a two-core host makes). Per scene of
the first ALL run, the low-high over the runs of: the measured wall ms at one worker, the
projected and the measured ms at N, the measured speed-up (one worker's wall time over N's, run
by run), the projected speed-up at N of the ALL runs and of the TWO runs ("-" where no TWO run
has the scene).
"""
import json
import sys

args = sys.argv[1:]
if len(args) < 4 or "--two" not in args:
    sys.exit(__doc__)
n = int(args[0])
split = args.index("--two")
every = [json.load(open(path)) for path in args[1:split]]
two = [json.load(open(path)) for path in args[split + 1:]]
if not every or not two:
    sys.exit(__doc__)


def point(run, scene, workers):
    """The run's point of `scene` at `workers`, or None where the run has no such scene."""
    for s in run["scenes"]:
        if s["name"] == scene:
            (p,) = [w for w in s["workers"] if w["workers"] == workers]
            return p
    return None


def span(values, fmt, suffix=""):
    if not values:
        return "-"
    lo, hi = fmt % min(values), fmt % max(values)
    return (lo if lo == hi else f"{lo}-{hi}") + suffix


for run in every:
    if run.get("usable_cpus", run["hardware_threads"]) < n:
        sys.exit(f"a run on {run.get('usable_cpus', run['hardware_threads'])} CPUs cannot measure {n} workers")
print(f"| scene | 1 worker: measured ms | {n}: projected ms | {n}: measured ms | {n}: speed-up measured "
      f"| {n}: projected on {n} cores | {n}: projected from 2 cores |")
print("|---|---:|---:|---:|---:|---:|---:|")
for scene in [s["name"] for s in every[0]["scenes"]]:
    ones = [point(r, scene, 1) for r in every]
    ats = [point(r, scene, n) for r in every]
    twos = [p for p in (point(r, scene, n) for r in two) if p is not None]
    cells = [
        span([p["measured_wall_seconds"] * 1e3 for p in ones], "%.2f"),
        span([p["projected_seconds"] * 1e3 for p in ats], "%.2f"),
        span([p["measured_wall_seconds"] * 1e3 for p in ats], "%.2f"),
        span([o["measured_wall_seconds"] / p["measured_wall_seconds"] for o, p in zip(ones, ats)], "%.1f", "x"),
        span([p["projected_speedup"] for p in ats], "%.1f", "x"),
        span([p["projected_speedup"] for p in twos], "%.1f", "x"),
    ]
    print(f"| {scene} | {' | '.join(cells)} |")
