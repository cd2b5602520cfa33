#!/usr/bin/env python3
"""Prints docs/experiments.md's table of a `rastercmp sweep zfight` run from its zfight.json.

Usage: scripts/zfight-table.py OUT/zfight.json
"""
import json
import sys

report = json.load(open(sys.argv[1]))


def number(value):
    return "none" if value is None else f"{value:.3g}"


gap_lo, gap_hi = report["calibrated_gap_interval"] or (None, None)
print(f"far {report['far']:.6g}, target distance {report['target_distance']:.6g}, "
      f"{report['jitters']} jitters, calibrated gap {number(gap_lo)} to {number(gap_hi)}")
print()
print("| series | measured onset: above, at most | predicted onset interval | agrees |")
print("|---|---|---|---|")
for s in report["series"]:
    lo, hi = s["predicted_onset_interval"]
    predicted = "none in the range" if lo is None else f"[{number(lo)}, {number(hi)}]"
    calibration = " (calibration)" if s["calibration"] else ""
    print(f"| {s['format']}, {s['mapping']} | {number(s['measured_onset_above'])}, "
          f"{number(s['measured_onset_at_most'])} | {predicted}{calibration} | {'yes' if s['agrees'] else 'no'} |")
