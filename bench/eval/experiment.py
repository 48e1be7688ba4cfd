#!/usr/bin/python3
"""The paired analysis of bench/eval/experiment.sh: per dataset and view
count the mean and 95% interval of each strategy over the starting sets,
and each strategy's paired difference to the best baseline.

usage: experiment.py RESULTS_DIR      (bench/results/eval/experiment/<backend>)

Reads RESULTS_DIR/<dataset>/<run>/bootstraps.json and bootstrap_<b>/loop.json
(`meshnbv loop --bootstraps B`); runs are named <strategy> or
<strategy>_seed<N>. A random run per starting set is the mean over its
seeds at each view count, so every strategy has one value per starting set
and differences pair them. A run that changes one option of another
(VARIANT_OF: nbv_recon_m45 of nbv_recon, ...) is also paired with that
run, in a row of its own. The primary metric is completeness at the
middle threshold (1.25 mm on templeRing, 1% of the diagonal on synthetic
scenes); its area is the mean over the view counts from the bootstrap to
the budget, in points. Baselines: uniform, random, coverage; the best is
the one with the largest mean area. Intervals: Student t over the starting
sets, with the critical values `meshnbv loop` wrote (bootstraps.json).
Accuracies (distances) and their ratios are summarised by the geometric
mean and the interval of the mean log: their spread is multiplicative
(one failed start can be 20x worse), and a distance's interval must stay
above zero.

Writes RESULTS_DIR/<dataset>/{curves.png, paired.png, table.md} and
RESULTS_DIR/{summary.json, results.md}.
"""
import json
import math
import os
import re
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

BASELINES = ["uniform", "random", "coverage"]
ORDER = BASELINES + ["nbv", "nbv_recon", "nbv_recon_m45", "nbv_recon_nohull", "nbv_recon_sampled",
                     "nbv_recon_sampled_m45", "nbv_recon_sampled_ground", "nbv_recon_sampled_level"]
LABELS = {"uniform": "Uniform", "random": "Random (mean of seeds)", "coverage": "Coverage",
          "nbv": "NBV (paper's energy)", "nbv_recon": "NBV (whole-mesh energy)",
          "nbv_recon_nohull": "NBV (whole-mesh, no hull)",
          "nbv_recon_m45": "NBV (whole-mesh, match angle 45°)",
          "nbv_recon_sampled": "NBV (whole-mesh energy, new poses, whole hemisphere)",
          "nbv_recon_sampled_m45": "NBV (whole-mesh, new poses, match angle 45°)",
          "nbv_recon_sampled_ground": "NBV (whole-mesh, new poses above the ground)",
          "nbv_recon_sampled_level": "NBV (whole-mesh, new poses above the ground, level)"}
# Variants paired with the run they change one option of (a row of their own).
VARIANT_OF = {"nbv_recon_m45": "nbv_recon", "nbv_recon_sampled_m45": "nbv_recon_sampled",
              "nbv_recon_sampled_ground": "nbv_recon_sampled",
              "nbv_recon_sampled_level": "nbv_recon_sampled_ground",
              "nbv_recon_nohull": "nbv_recon"}
COLOURS = {"uniform": "tab:blue", "random": "tab:orange", "coverage": "tab:green", "nbv": "tab:red",
           "nbv_recon": "tab:purple", "nbv_recon_nohull": "tab:pink", "nbv_recon_sampled": "tab:brown",
           "nbv_recon_m45": "tab:gray", "nbv_recon_sampled_m45": "tab:olive",
           "nbv_recon_sampled_ground": "tab:cyan", "nbv_recon_sampled_level": "black"}


def load_runs(dataset_dir):
    """{strategy: {"bootstraps": [...], "t": {n: t}, "curves": [[{views: step}] per seed] per bootstrap}}"""
    out = {}
    for name in sorted(os.listdir(dataset_dir)):
        f = os.path.join(dataset_dir, name, "bootstraps.json")
        if not os.path.isfile(f):
            continue
        summary = json.load(open(f))
        strategy = re.sub(r"_seed\d+$", "", name)
        entry = out.setdefault(strategy, {"sets": None, "t": {}, "seeds": [], "seconds": []})
        sets = [r["bootstrap_views"] for r in summary["runs"]]
        if entry["sets"] is None:
            entry["sets"] = sets
        elif entry["sets"] != sets:
            raise SystemExit("%s: starting sets differ between the runs of %s" % (name, strategy))
        entry["t"].update({int(n): t for n, t in summary["t_critical"].items()})
        per_set = []
        for r in summary["runs"]:
            loop_file = os.path.join(dataset_dir, name, r["folder"], "loop.json")
            if not r["done"] or not os.path.isfile(loop_file):
                per_set.append(None)
                continue
            loop = json.load(open(loop_file))
            entry["seconds"].append(loop["seconds"])
            per_set.append({s["num_views"]: s for s in loop["steps"]})
        entry["seeds"].append(per_set)
    return out


def value(step, kind, key):
    v = step[kind].get(key)
    return float("nan") if v is None else float(v)


def per_set_curves(entry, kind, key):
    """One curve per starting set {views: value}, the mean over seeds (views every seed reached)."""
    curves = []
    for b in range(len(entry["sets"])):
        runs = [seed[b] for seed in entry["seeds"] if b < len(seed) and seed[b] is not None]
        if len(runs) != len(entry["seeds"]):
            curves.append(None)
            continue
        views = sorted(set.intersection(*(set(r) for r in runs)))
        curves.append({v: statistics.fmean([value(r[v], kind, key) for r in runs]) for v in views})
    return curves


def interval(values, t_table):
    """(n, mean, low, high) of the finite values; one value: zero width."""
    x = [v for v in values if v is not None and math.isfinite(v)]
    if not x:
        return (0, float("nan"), float("nan"), float("nan"))
    m = statistics.fmean(x)
    if len(x) < 2:
        return (1, m, m, m)
    half = t_table[len(x)] * statistics.stdev(x) / math.sqrt(len(x))
    return (len(x), m, m - half, m + half)


def log_interval(values, t_table):
    """interval() of the logs, back as (n, geometric mean, low, high): for
    distances and ratios, whose spread is multiplicative."""
    logs = [math.log(v) if v is not None and math.isfinite(v) and v > 0 else None for v in values]
    n, m, lo, hi = interval(logs, t_table)
    return (n, math.exp(m), math.exp(lo), math.exp(hi)) if n else (0, float("nan"), float("nan"), float("nan"))


def area(curve, views):
    return statistics.fmean([curve[v] for v in views]) if all(v in curve for v in views) else float("nan")


def analyse(dataset, ddir, runs):
    any_entry = next(iter(runs.values()))
    first = next(s for seed in any_entry["seeds"] for s in seed if s)
    step0 = first[min(first)]
    loop_json = json.load(open(os.path.join(ddir, next(n for n in sorted(os.listdir(ddir))
                                                        if os.path.isfile(os.path.join(ddir, n, "bootstraps.json"))),
                                            "bootstrap_1", "loop.json")))
    real = not loop_json["synthetic"]
    tkeys = list(step0["completeness"].keys())
    pkeys = list(step0["accuracy"].keys())
    primary = tkeys[1] if len(tkeys) > 1 else tkeys[0]
    acc90 = "90" if "90" in pkeys else pkeys[len(pkeys) // 2]
    t_table = {}
    for e in runs.values():
        t_table.update(e["t"])
    strategies = [s for s in ORDER if s in runs] + sorted(s for s in runs if s not in ORDER)
    comp = {s: per_set_curves(runs[s], "completeness", primary) for s in strategies}
    acc = {s: per_set_curves(runs[s], "accuracy", acc90) for s in strategies}
    # View counts every run of every strategy reached.
    common = None
    for s in strategies:
        for c in comp[s]:
            if c is not None:
                common = set(c) if common is None else common & set(c)
    views = sorted(common or [])
    last = views[-1]
    n_sets = len(any_entry["sets"])

    result = {"dataset": dataset, "real": real, "starting_sets": any_entry["sets"], "views": views,
              "primary_metric": "completeness_" + primary, "accuracy_metric": "accuracy_" + acc90,
              "seeds": {s: len(runs[s]["seeds"]) for s in strategies},
              "loop_seconds_total": {s: sum(runs[s]["seconds"]) for s in strategies},
              "strategies": {}}
    for s in strategies:
        areas = [area(c, views) if c else None for c in comp[s]]
        result["strategies"][s] = {
            "area": interval([100 * a if a is not None else None for a in areas], t_table),
            "area_per_set": [100 * a if a is not None else None for a in areas],
            "final_completeness": interval([100 * c[last] if c else None for c in comp[s]], t_table),
            "final_accuracy": log_interval([a[last] if a else None for a in acc[s]], t_table),
            "curve": {v: interval([100 * c[v] if c and v in c else None for c in comp[s]], t_table) for v in views},
            "accuracy_curve": {v: log_interval([a[v] if a and v in a else None for a in acc[s]], t_table)
                               for v in views},
        }
    # Views a strategy needs to reach uniform's final completeness from the
    # same starting set, as a share of uniform's views (issue #16's new-pose
    # criterion); None where it never does within the budget.
    if "uniform" in strategies:
        for s in strategies:
            shares = []
            for c, u in zip(comp[s], comp["uniform"]):
                if not c or not u:
                    shares.append(None)
                    continue
                goal = u[last]
                reach = [v for v in sorted(c) if c[v] >= goal]
                shares.append(100.0 * reach[0] / last if reach else None)
            result["strategies"][s]["views_to_uniform_final"] = {
                "share_per_set": shares, "reached": sum(x is not None for x in shares),
                "interval": interval(shares, t_table)}
    baselines = [s for s in BASELINES if s in strategies]
    best = max(baselines, key=lambda s: result["strategies"][s]["area"][1]) if baselines else None
    result["best_baseline"] = best
    paired = {}
    if best:
        for s in strategies:
            if s == best:
                continue
            d_area = [None if (a is None or b is None) else 100 * (area(a, views) - area(b, views))
                      for a, b in zip(comp[s], comp[best])]
            d_final = [None if (a is None or b is None) else 100 * (a[last] - b[last])
                       for a, b in zip(comp[s], comp[best])]
            r_acc = [None if (a is None or b is None or not (a[last] > 0 and b[last] > 0))
                     else a[last] / b[last] for a, b in zip(acc[s], acc[best])]
            d_curve = {v: interval([None if (a is None or b is None) else 100 * (a[v] - b[v])
                                    for a, b in zip(comp[s], comp[best])], t_table) for v in views}
            paired[s] = {"area_difference": interval(d_area, t_table),
                         "final_completeness_difference": interval(d_final, t_table),
                         "final_accuracy_ratio": log_interval(r_acc, t_table),
                         "curve_difference": d_curve}
    result["paired_to_best_baseline"] = paired
    variants = {}
    for s, base in VARIANT_OF.items():
        if s in strategies and base in strategies:
            d_area = [None if (a is None or b is None) else 100 * (area(a, views) - area(b, views))
                      for a, b in zip(comp[s], comp[base])]
            d_final = [None if (a is None or b is None) else 100 * (a[last] - b[last])
                       for a, b in zip(comp[s], comp[base])]
            variants[s] = {"base": base, "area_difference": interval(d_area, t_table),
                           "final_completeness_difference": interval(d_final, t_table)}
    result["paired_to_variant_base"] = variants

    unit, scale = ("mm", 1000.0) if real else ("m", 1.0)
    # Curves with bands.
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for s in strategies:
        c = result["strategies"][s]["curve"]
        a = result["strategies"][s]["accuracy_curve"]
        col = COLOURS.get(s)
        axes[0].plot(views, [c[v][1] for v in views], label=LABELS.get(s, s), color=col)
        axes[0].fill_between(views, [c[v][2] for v in views], [c[v][3] for v in views], alpha=0.18, color=col)
        axes[1].plot(views, [scale * a[v][1] for v in views], label=LABELS.get(s, s), color=col)
        axes[1].fill_between(views, [scale * a[v][2] for v in views], [scale * a[v][3] for v in views],
                             alpha=0.18, color=col)
    thr = float(primary)
    axes[1].set_title("90%% accuracy (%s; geometric mean, 95%% interval; lower is better)" % unit, fontsize=9)
    axes[0].set_title("completeness at %s %s (mean, 95%% interval over %d starting sets)"
                      % (("%.2f" % (thr * scale)), unit, n_sets), fontsize=9)
    axes[0].set_ylabel("%")
    axes[1].set_yscale("log")
    for ax in axes:
        ax.set_xlabel("views")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(dataset)
    fig.tight_layout()
    fig.savefig(os.path.join(ddir, "curves.png"), dpi=110)
    plt.close(fig)
    # Paired differences to the best baseline.
    if paired:
        fig, ax = plt.subplots(figsize=(6.5, 4.2))
        for s, p in paired.items():
            d = p["curve_difference"]
            col = COLOURS.get(s)
            ax.plot(views, [d[v][1] for v in views], label=LABELS.get(s, s), color=col)
            ax.fill_between(views, [d[v][2] for v in views], [d[v][3] for v in views], alpha=0.18, color=col)
        ax.axhline(0, color="black", lw=0.8)
        ax.set_xlabel("views")
        ax.set_ylabel("points of completeness")
        ax.set_title("%s: paired difference to %s (95%% interval)" % (dataset, LABELS.get(best, best)), fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(ddir, "paired.png"), dpi=110)
        plt.close(fig)

    # The paper's table (its Table 3) at the last view count, mean [95% interval].
    def cell(iv, mult=1.0, digits=1):
        n, m, lo, hi = iv
        if n == 0:
            return "—"
        f = "%." + str(digits) + "f"
        return (f + " [" + f + ", " + f + "]") % (m * mult, lo * mult, hi * mult)

    per_last = {}
    for s in strategies:
        rows = {}
        for kind, keys in (("accuracy", pkeys), ("completeness", tkeys)):
            for k in keys:
                curves = per_set_curves(runs[s], kind, k)
                f = log_interval if kind == "accuracy" else interval
                rows[(kind, k)] = f([c[last] if c and last in c else None for c in curves], t_table)
        per_last[s] = rows
    digits = 2 if real else 3
    lines = ["| | Thresholds | " + " | ".join(LABELS.get(s, s) for s in strategies) + " |",
             "|---|---|" + "---|" * len(strategies),
             "| Num. frames | - | " + " | ".join(str(last) for _ in strategies) + " |"]
    for i, k in enumerate(pkeys):
        lines.append("| %s | %s%% | " % ("Error (%s)" % unit if i == 0 else "", k) +
                     " | ".join(cell(per_last[s][("accuracy", k)], scale, digits) for s in strategies) + " |")
    for i, k in enumerate(tkeys):
        lines.append("| %s | %s %s | " % ("Completeness (%)" if i == 0 else "", "%.3g" % (float(k) * scale), unit) +
                     " | ".join(cell(per_last[s][("completeness", k)], 100.0) for s in strategies) + " |")
    lines.append("| Area, %d–%d views | completeness %s %s (points) | " % (views[0], last, "%.3g" % (thr * scale), unit) +
                 " | ".join(cell(result["strategies"][s]["area"]) for s in strategies) + " |")
    if paired:
        lines.append("| Paired, to %s | area difference (points) | " % LABELS.get(best, best) +
                     " | ".join("—" if s == best else cell(paired[s]["area_difference"]) for s in strategies) + " |")
        lines.append("| | final completeness difference (points) | " +
                     " | ".join("—" if s == best else cell(paired[s]["final_completeness_difference"])
                                for s in strategies) + " |")
        lines.append("| | final 90% accuracy ratio | " +
                     " | ".join("—" if s == best else cell(paired[s]["final_accuracy_ratio"], 1.0, 2)
                                for s in strategies) + " |")
    if variants:
        lines.append("| Paired, to the run it varies | area difference (points) | " +
                     " | ".join(cell(variants[s]["area_difference"]) + " to " + variants[s]["base"]
                                if s in variants else "—" for s in strategies) + " |")
        lines.append("| | final completeness difference (points) | " +
                     " | ".join(cell(variants[s]["final_completeness_difference"]) if s in variants else "—"
                                for s in strategies) + " |")
    if "uniform" in strategies:
        lines.append("| Views to reach Uniform's final | %% of Uniform's %d (sets reaching it) | " % last +
                     " | ".join("%s (%d/%d)" % (cell(result["strategies"][s]["views_to_uniform_final"]["interval"], 1.0, 0),
                                                result["strategies"][s]["views_to_uniform_final"]["reached"], n_sets)
                                for s in strategies) + " |")
    table = "\n".join(lines) + "\n"
    with open(os.path.join(ddir, "table.md"), "w") as f:
        f.write(table)
    result["table"] = table
    return result


def jsonable(x):
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "bench/results/eval/experiment/sparse"
    results = []
    for dataset in sorted(os.listdir(root)):
        ddir = os.path.join(root, dataset)
        if os.path.isdir(ddir):
            runs = load_runs(ddir)
            if runs:
                results.append(analyse(dataset, ddir, runs))
    md = ["# The paired experiment", "",
          "Written by bench/eval/experiment.py from the runs of bench/eval/experiment.sh beside it. "
          "Cells: mean [95% interval] over the starting sets (accuracies and their ratios: geometric mean "
          "and the interval of the mean log); random is the mean of its seeds per set.", ""]
    for r in results:
        md += ["## %s" % r["dataset"], "",
               "Starting sets: %s. Best baseline (largest mean area): %s." %
               (", ".join("{" + ",".join(map(str, s)) + "}" for s in r["starting_sets"]), r["best_baseline"]), "",
               r["table"], "![curves](%s/curves.png)" % r["dataset"], ""]
        if r["paired_to_best_baseline"]:
            md += ["![paired differences](%s/paired.png)" % r["dataset"], ""]
        r.pop("table")
    with open(os.path.join(root, "results.md"), "w") as f:
        f.write("\n".join(md))
    with open(os.path.join(root, "summary.json"), "w") as f:
        json.dump(jsonable(results), f, indent=1)
    print("wrote %s/results.md and summary.json (%d datasets)" % (root, len(results)))


if __name__ == "__main__":
    main()
