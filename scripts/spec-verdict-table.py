#!/usr/bin/env python3
"""Prints the verdict of every case of a conformance run as a Markdown table (docs/spec-profile.md).

Usage: scripts/spec-verdict-table.py OUT/summary.json [--totals]

Each row: the scene, its verdict and the reason condensed from the case's counts and message.
--totals prints one line of verdict counts instead.
"""
import json
import sys


def reason(case):
    verdict = case["verdict"]
    message = case.get("message") or verdict
    if verdict == "ResourceError" and "render.json" in message:
        return "no capture of this scene"
    if verdict in ("NotSupported", "ResourceError", "InternalError", "Crash", "Timeout"):
        return message
    allowed_owner = case.get("allowed_owner", 0)
    owners = f"; {allowed_owner} allowed owners" if allowed_owner else ""
    if verdict == "Pass":
        return "every Must and MustNot kept; every stored depth inside its interval" + owners
    if verdict == "QualityWarning":
        wrong = case.get("wrong_owner", 0)
        return f"Must/MustNot all kept, every depth inside its interval; {wrong} wrong owner(s){owners}"
    return case.get("message") or verdict


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        summary = json.load(f)
    if "--totals" in sys.argv[2:]:
        print(", ".join(f"{count} {verdict}" for verdict, count in summary["verdicts"].items() if count))
        return
    print("| scene | verdict | reason |")
    print("|---|---|---|")
    for case in summary["cases"]:
        print(f"| `{case['scene']}` | {case['verdict']} | {reason(case)} |")


if __name__ == "__main__":
    main()
