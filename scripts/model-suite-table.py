#!/usr/bin/env python3
"""Prints docs/suite.md's table of the real-model suite from the imported scenes.

Usage: scripts/model-suite-table.py [build/suite/models]
Each row: the case, the model file (from the description), the framebuffer, depth format and
samples, and the counts `rastercmp import` wrote into the description.
"""
import json
import pathlib
import sys

folder = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build/suite/models")
print("| case | model | size | depth | samples | draws, primitives, vertices |")
print("|---|---|---|---|---|---|")
for path in sorted(folder.glob("*.json")):
    scene = json.loads(path.read_text())
    description = scene["description"]
    source, counts = description.removeprefix("imported from ").split(": ", 1)
    print(f"| `{scene['name']}` | {source} | {scene.get('width', 64)}x{scene.get('height', 64)} | "
          f"{scene.get('depth_format', 'd32_sfloat')} | {scene.get('samples', 1)} | {counts} |")
