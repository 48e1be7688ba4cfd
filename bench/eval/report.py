#!/usr/bin/python3
"""Curves and tables of `meshnbv loop` runs (bench/eval/run.sh writes them).

usage: report.py RESULTS_DIR

RESULTS_DIR/<dataset>/<run>/loop.json, one folder per run; runs named
<strategy> or <strategy>_seed<N> (random: the mean over seeds is reported).
Writes, per dataset: curves.png (accuracy at 90% and completeness at the
middle threshold against the number of views, one curve per strategy),
table.md (the layout of the paper's Table 3, at the last common view count),
and RESULTS_DIR/results.md with every table.
"""
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ORDER = ["uniform", "random", "coverage", "nbv", "nbv_sampled", "nbv_refined"]
LABELS = {"uniform": "Uniform", "random": "Random (mean of seeds)", "coverage": "Coverage",
          "nbv": "NBV (given views)", "nbv_sampled": "NBV (sampled poses)",
          "nbv_refined": "NBV (refined poses)"}


def load(dataset_dir):
    runs = defaultdict(list)
    for name in sorted(os.listdir(dataset_dir)):
        f = os.path.join(dataset_dir, name, "loop.json")
        if not os.path.isfile(f):
            continue
        key = name.split("_seed")[0]
        runs[key].append(json.load(open(f)))
    return runs


def series(loops, kind, key):
    """Mean over runs of metric `kind` ("accuracy"/"completeness") at `key`, by view count."""
    by_views = defaultdict(list)
    for loop in loops:
        for s in loop["steps"]:
            v = s[kind].get(key)
            by_views[s["num_views"]].append(float("nan") if v is None else v)
    xs = sorted(by_views)
    # Only counts every run reached.
    xs = [x for x in xs if len(by_views[x]) == len(loops)]
    return xs, [sum(by_views[x]) / len(by_views[x]) for x in xs]


def fmt(v, scale, digits):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "—"
    return ("%." + str(digits) + "f") % (v * scale)


def main():
    root = sys.argv[1]
    out_md = ["# Results of the incremental view-selection loop", "",
              "Written by bench/eval/report.py from the loop.json files beside it.", ""]
    for dataset in sorted(os.listdir(root)):
        ddir = os.path.join(root, dataset)
        if not os.path.isdir(ddir):
            continue
        runs = load(ddir)
        if not runs:
            continue
        any_loop = next(iter(runs.values()))[0]
        thresholds = any_loop["thresholds"]
        tkeys = list(any_loop["steps"][0]["completeness"].keys())
        pkeys = list(any_loop["steps"][0]["accuracy"].keys())
        real = not any_loop["synthetic"]
        unit, scale, digits = ("mm", 1000.0, 2) if real else ("m", 1.0, 3)
        strategies = [s for s in ORDER if s in runs] + [s for s in runs if s not in ORDER]

        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        for s in strategies:
            xs, acc = series(runs[s], "accuracy", pkeys[1])
            axes[0].plot(xs, [a * scale for a in acc], marker="o", ms=3, label=LABELS.get(s, s))
            xs, comp = series(runs[s], "completeness", tkeys[1])
            axes[1].plot(xs, [100 * c for c in comp], marker="o", ms=3, label=LABELS.get(s, s))
        axes[0].set_title("accuracy: %s%% of the reconstruction within" % pkeys[1])
        axes[0].set_ylabel(unit)
        axes[1].set_title("completeness within %s %s" % (fmt(thresholds[1], scale, 2 if real else 3), unit))
        axes[1].set_ylabel("% of the reference")
        for ax in axes:
            ax.set_xlabel("views")
            ax.grid(alpha=0.3)
        axes[1].legend(fontsize=8)
        fig.suptitle("%s: reference = %s" % (dataset, any_loop["reference"].split(" (")[0].split(",")[0]), fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(ddir, "curves.png"), dpi=110)
        plt.close(fig)

        # Table at the largest view count every strategy reached.
        common = min(max(s["num_views"] for s in loops[0]["steps"]) for loops in runs.values())
        rows = ["| | Thresholds | " + " | ".join(LABELS.get(s, s) for s in strategies) + " |",
                "|---|---|" + "---|" * len(strategies),
                "| Num. frames | - | " + " | ".join(str(common) for _ in strategies) + " |"]

        def at(s, kind, key):
            vals = []
            for loop in runs[s]:
                for st in loop["steps"]:
                    if st["num_views"] == common:
                        v = st[kind].get(key)
                        vals.append(float("nan") if v is None else v)
            return sum(vals) / len(vals) if vals else None

        for i, p in enumerate(pkeys):
            head = "Error (%s)" % unit if i == 0 else ""
            rows.append("| %s | %s%% | " % (head, p) +
                        " | ".join(fmt(at(s, "accuracy", p), scale, digits) for s in strategies) + " |")
        for i, t in enumerate(tkeys):
            head = "Completeness (%)" if i == 0 else ""
            rows.append("| %s | %s %s | " % (head, fmt(float(t), scale, 2 if real else 3), unit) +
                        " | ".join(fmt(at(s, "completeness", t), 100.0, 1) for s in strategies) + " |")
        # The whole curve in one number: means over the steps every run reached.
        first = max(min(s["num_views"] for s in loops[0]["steps"]) for loops in runs.values())

        def mean_over_steps(s, kind, key):
            vals = []
            for loop in runs[s]:
                for st in loop["steps"]:
                    if first <= st["num_views"] <= common:
                        v = st[kind].get(key)
                        vals.append(float("nan") if v is None else v)
            return sum(vals) / len(vals) if vals else None

        rows.append("| Mean over %d–%d views | accuracy %s%% (%s) | " % (first, common, pkeys[1], unit) +
                    " | ".join(fmt(mean_over_steps(s, "accuracy", pkeys[1]), scale, digits) for s in strategies) + " |")
        rows.append("| | completeness %s %s (%%) | " % (fmt(float(tkeys[1]), scale, 2 if real else 3), unit) +
                    " | ".join(fmt(mean_over_steps(s, "completeness", tkeys[1]), 100.0, 1) for s in strategies) + " |")
        seeds = {s: len(runs[s]) for s in strategies if len(runs[s]) > 1}
        note = ["", "Reference: %s." % any_loop["reference"]]
        if seeds:
            note.append("Means over seeds: " + ", ".join("%s %d runs" % (k, v) for k, v in seeds.items()) + ".")
        table = "\n".join(rows + note) + "\n"
        open(os.path.join(ddir, "table.md"), "w").write(table)
        out_md += ["## " + dataset, "", table, "![curves](%s/curves.png)" % dataset, ""]
    open(os.path.join(root, "results.md"), "w").write("\n".join(out_md))
    print("report: " + os.path.join(root, "results.md"))


if __name__ == "__main__":
    main()
