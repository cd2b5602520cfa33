#!/usr/bin/env python3
"""Prints a table of docs/performance.md's "Current figures" from several bench runs' JSON.

Usage: scripts/bench-figures-table.py [--halves] LABEL=RUN.json [LABEL=RUN.json ...]
Each RUN.json from `[RASTERCMP_FAST_KERNELS=avx2] LP_NUM_THREADS=2 ./build/app/rastercmp bench
--threads 2 --reps 11 --exact-reps 1 --suite scenes --json RUN.json`; LABEL names its column
("AVX-512, idle"). Each cell: lavapipe's median over the fast path's, as bench prints it, the two
medians in ms in brackets; bold where the ratio misses the scene's must (its "target" in the JSON:
kTargets in app/cmd_bench.cpp); a scene the run did not time or whose bytes differed reads so.
--halves: each cell instead the fast path's median ms over the even reps (but the first: each
follows the fast render before it) and over the odd ones (each follows lavapipe's render).
"""
import json
import statistics
import sys

args = sys.argv[1:]
halves = "--halves" in args
args = [a for a in args if a != "--halves"]
columns = []
for arg in args:
    label, _, path = arg.partition("=")
    if not path:
        sys.exit(__doc__)
    columns.append((label, {s["name"]: s for s in json.load(open(path))["scenes"]}))
if not columns:
    sys.exit(__doc__)


def cell(scene):
    if scene is None:
        return "-"
    if halves:
        samples = scene["fast"]["samples_ms"]
        even, odd = samples[2::2], samples[1::2]
        if not even or not odd:
            return "-"
        return f"{statistics.median(even):.2f} / {statistics.median(odd):.2f}"
    if not (scene["fast_equals_exact"] and scene["fast_equals_lavapipe"]):
        return "bytes differ"
    fast, lavapipe = scene["fast"]["median_ms"], scene["lavapipe"]["median_ms"]
    ratio = f"{lavapipe / fast:.1f}x"
    must = (scene.get("target") or {}).get("must")
    if must is not None and lavapipe / fast < must:
        ratio = f"**{ratio}**"
    return f"{ratio} ({fast:.2f}/{lavapipe:.2f})"


names = list(columns[0][1])
print("| scene | " + " | ".join(label for label, _ in columns) + " | must |")
print("|---|" + "---:|" * (len(columns) + 1))
for name in names:
    must = (columns[0][1][name].get("target") or {}).get("must")
    cells = [cell(runs.get(name)) for _, runs in columns]
    print(f"| {name} | " + " | ".join(cells) + f" | {f'{must:g}x' if must else 'none'} |")
