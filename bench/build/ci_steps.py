#!/usr/bin/python3
"""Where a run of scripts/test.sh (the README's test command, CI's job) spent
its time: the step lines it prints (`== scripts/test.sh: <step> done at N s`),
each ctest's total, and the longest tests of each ctest, from its log.

Usage: bench/build/ci_steps.py LOG OUT.json [--label TEXT]
"""
import json
import re
import sys


def main():
    args = sys.argv[1:]
    label = ""
    if "--label" in args:
        i = args.index("--label")
        label = args[i + 1]
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    log, out = args
    steps, ctests, current = [], [], None
    for line in open(log, errors="replace"):
        m = re.match(r"== scripts/test\.sh: (.+) done at (\d+) s", line)
        if m:
            steps.append({"step": m.group(1), "done_at_seconds": int(m.group(2))})
            continue
        m = re.match(r"\s*\d+/\d+ Test +#\d+: (\S+)(?:  \# .*?)? \.*\s*(\*\*\*Failed|Passed)\s+([\d.]+) sec", line)
        if m:
            if current is None:
                current = {"tests": []}
                ctests.append(current)
            current["tests"].append({"name": m.group(1), "passed": m.group(2) == "Passed",
                                     "seconds": float(m.group(3))})
            continue
        m = re.match(r"Total Test time \(real\) =\s*([\d.]+) sec", line)
        if m and current is not None:
            current["wall_seconds"] = float(m.group(1))
            current = None
    if not steps:
        sys.exit(f"{log}: no '== scripts/test.sh: ... done at N s' line (not a scripts/test.sh log)")
    previous = 0
    for s in steps:
        s["seconds"] = s["done_at_seconds"] - previous
        previous = s["done_at_seconds"]
    summary = {"label": label, "total_seconds": steps[-1]["done_at_seconds"], "steps": steps, "ctest_runs": []}
    for c in ctests:
        tests = sorted(c["tests"], key=lambda t: -t["seconds"])
        summary["ctest_runs"].append({
            "tests": len(tests), "failed": sum(not t["passed"] for t in tests),
            "wall_seconds": c.get("wall_seconds"),
            "test_seconds": round(sum(t["seconds"] for t in tests), 1),
            "longest": tests[:12]})
    json.dump(summary, open(out, "w"), indent=1)
    print(f"{out}: {summary['total_seconds']} s in all; " +
          "; ".join(f"{s['step']} {s['seconds']} s" for s in steps))


if __name__ == "__main__":
    main()
