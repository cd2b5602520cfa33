#!/usr/bin/env python3
"""Prints docs/performance.md's table of the scaling model from several runs' JSON.

Usage: scripts/scaling-model-table.py RUN.json [RUN.json ...]
Each RUN.json from `LP_NUM_THREADS=2 ./build/app/rastercmp bench --scaling --model --reps 5
--suite scenes --json RUN.json`. Per scene and N = 1, 2, 4, 8, 16, 64: the projected ms over the
runs (low-high), at 1 and 2 workers the measured wall ms in brackets, from 2 on the projected
speed-up over one worker; bold: perspective or the suite below 8x at 16 workers (the must).
"""
import json
import sys

runs = [json.load(open(path)) for path in sys.argv[1:]]
if not runs:
    sys.exit(__doc__)


def span(values, fmt):
    lo, hi = fmt % min(values), fmt % max(values)
    return lo if lo == hi else f"{lo}-{hi}"


def speedups(values, bold):
    text = span(values, "%.1f")
    if bold and min(values) < 8.0:
        lo = "%.1f" % min(values)
        text = f"**{lo}**" + text[len(lo):]
    return text + "x"


print("| scene | 1: ms (measured) | 2: ms (measured), speed-up | 4 | 8 | 16 | 64 |")
print("|---|---:|---:|---:|---:|---:|---:|")
for scene in [s["name"] for s in runs[0]["scenes"]]:
    cells = []
    for n in (1, 2, 4, 8, 16, 64):
        projected, speedup, measured = [], [], []
        for run in runs:
            (of_scene,) = [s for s in run["scenes"] if s["name"] == scene]
            (point,) = [w for w in of_scene["workers"] if w["workers"] == n]
            projected.append(point["projected_seconds"] * 1e3)
            speedup.append(point["projected_speedup"])
            if point["measured_wall_seconds"] is not None:
                measured.append(point["measured_wall_seconds"] * 1e3)
        ms = span(projected, "%.2f")
        bold = n == 16 and scene in ("perspective", "suite")
        if n == 1:
            cells.append(f"{ms} ({span(measured, '%.2f')})")
        elif n == 2:
            cells.append(f"{ms} ({span(measured, '%.2f')}), {speedups(speedup, bold)}")
        else:
            cells.append(f"{ms}, {speedups(speedup, bold)}")
    print(f"| {scene} | {' | '.join(cells)} |")
