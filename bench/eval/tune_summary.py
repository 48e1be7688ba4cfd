#!/usr/bin/python3
"""Table of bench/eval/tune_gain.sh's grid: per dataset and setting, the mean
area under the completeness curve (the experiment's primary threshold, all
view counts) and the final completeness, means over the starting sets; the
setting kept is the one of largest area averaged over the datasets.

    bench/eval/tune_summary.py bench/results/eval/tune_gain
"""
import json
import os
import statistics
import sys


def curve(loop, key):
    return {s["num_views"]: s["completeness"][key] for s in loop["steps"]}


def main():
    root = sys.argv[1]
    table = {}
    for dataset in sorted(os.listdir(root)):
        ddir = os.path.join(root, dataset)
        if not os.path.isdir(ddir):
            continue
        for name in sorted(os.listdir(ddir)):
            f = os.path.join(ddir, name, "bootstraps.json")
            if not os.path.isfile(f):
                continue
            runs = json.load(open(f))["runs"]
            areas, finals = [], []
            for r in runs:
                loop = json.load(open(os.path.join(ddir, name, r["folder"], "loop.json")))
                keys = list(loop["steps"][0]["completeness"].keys())
                key = keys[1] if len(keys) > 1 else keys[0]
                c = curve(loop, key)
                areas.append(100 * statistics.fmean(c.values()))
                finals.append(100 * c[max(c)])
            table.setdefault(name, {})[dataset] = {"area": statistics.fmean(areas),
                                                   "final": statistics.fmean(finals), "sets": len(runs)}
    datasets = sorted({d for v in table.values() for d in v})
    full = {n: v for n, v in table.items() if all(d in v for d in datasets)}
    best = max(full, key=lambda n: statistics.fmean(full[n][d]["area"] for d in datasets)) if full else None
    lines = ["# Tuning of the whole-mesh energy", "",
             "Written by bench/eval/tune_summary.py from bench/eval/tune_gain.sh. Cells: mean area under the "
             "completeness curve / mean final completeness (points), over the starting sets. "
             "Kept: the largest area averaged over the datasets: **%s**." % best, "",
             "| setting | " + " | ".join(datasets) + " | mean area |", "|---|" + "---|" * (len(datasets) + 1)]
    for n in sorted(table):
        cells = ["%.1f / %.1f" % (table[n][d]["area"], table[n][d]["final"]) if d in table[n] else "—"
                 for d in datasets]
        mean = "%.1f" % statistics.fmean(table[n][d]["area"] for d in datasets) if n in full else "—"
        lines.append("| %s | %s | %s |" % (n, " | ".join(cells), mean))
    open(os.path.join(root, "summary.md"), "w").write("\n".join(lines) + "\n")
    json.dump({"best": best, "table": table}, open(os.path.join(root, "summary.json"), "w"), indent=1)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
