#!/usr/bin/python3
"""Figures of docs/results.md that are not in the tables: timings, the
views each run added, the spread of the random seeds, the references' sizes.

usage: summary.py [RESULTS_DIR]      (default bench/results/eval)

Reads RESULTS_DIR/<dataset>/<run>/loop.json (bench/eval/run.sh writes them)
and RESULTS_DIR/<dataset>/reference.ply; writes RESULTS_DIR/summary.json.
Standard library only; runs in well under a second.
"""
import json
import os
import re
import statistics
import sys


def ply_counts(path):
    """Element counts from a PLY header: {"vertex": n, "face": m}."""
    counts = {}
    with open(path, "rb") as f:
        for raw in f:
            line = raw.decode("ascii", "replace").strip()
            m = re.match(r"element (\w+) (\d+)", line)
            if m:
                counts[m.group(1)] = int(m.group(2))
            if line == "end_header":
                break
    return counts


def spread(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values)} if values else None


def view_number(name):
    m = re.search(r"(\d+)\D*$", name)
    return int(m.group(1)) if m else None


def run_summary(loop):
    steps = loop["steps"]
    later = steps[1:]  # step 0 is the bootstrap: nothing chosen
    out = {
        "strategy": loop["strategy"],
        "seconds": loop["seconds"],
        "steps": len(steps),
        "views": [steps[0]["num_views"], steps[-1]["num_views"]],
        "bootstrap": steps[0]["views"],
        "added": [s["added"] for s in later],
        "added_numbers_sorted": sorted(n for n in (view_number(s["added"]) for s in later) if n is not None),
        "chosen_by": sorted(set(s["chosen_by"] for s in later)),
    }
    if later:
        kinds = sorted(later[0]["seconds"])
        out["step_seconds"] = {k: spread([s["seconds"][k] for s in later]) for k in kinds}
        out["step_seconds"]["total"] = spread([sum(s["seconds"].values()) for s in later])
    # The first view count whose mesh differs from the bootstrap's (faces).
    changed = [s["num_views"] for s in steps if s["faces"] != steps[0]["faces"]]
    out["first_views_with_a_changed_mesh"] = changed[0] if changed else None
    out["points"] = [steps[0]["points"], steps[-1]["points"]]
    out["faces"] = [steps[0]["faces"], steps[-1]["faces"]]
    return out


def seed_spread(loops):
    """Per completeness threshold: the range (max - min) over the seeds, in
    percentage points, at each view count every seed reached after the
    bootstrap (identical for all seeds); median and largest over those."""
    result = {}
    for key in loops[0]["steps"][0]["completeness"]:
        by_views = {}
        for loop in loops:
            for s in loop["steps"][1:]:
                v = s["completeness"].get(key)
                if v is not None:
                    by_views.setdefault(s["num_views"], []).append(v)
        ranges = [100 * (max(v) - min(v)) for n, v in sorted(by_views.items()) if len(v) == len(loops)]
        result[key] = {"view_counts": len(ranges), "median_points": statistics.median(ranges),
                       "max_points": max(ranges)}
    return result


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "bench/results/eval"
    out = {"written_by": "bench/eval/summary.py", "from": "loop.json and reference.ply beside it",
           "datasets": {}}
    for dataset in sorted(os.listdir(root)):
        ddir = os.path.join(root, dataset)
        if not os.path.isdir(ddir):
            continue
        runs = {}
        for name in sorted(os.listdir(ddir)):
            f = os.path.join(ddir, name, "loop.json")
            if os.path.isfile(f):
                runs[name] = json.load(open(f))
        if not runs:
            continue
        first = next(iter(runs.values()))
        d = {
            "synthetic": first["synthetic"],
            "reference": first["reference"],
            "thresholds": first["thresholds"],
            "percentiles": first["percentiles"],
            "loop_seconds_total": sum(r["seconds"] for r in runs.values()),
            "runs": {name: run_summary(loop) for name, loop in runs.items()},
        }
        if first["synthetic"]:
            # bench/eval/run.sh's synthetic thresholds: 0.5%, 1%, 2% of the diagonal.
            d["diagonal"] = first["thresholds"][1] / 0.01
        ref = os.path.join(ddir, "reference.ply")
        if os.path.isfile(ref):
            c = ply_counts(ref)
            d["reference_ply"] = {"vertices": c.get("vertex"), "faces": c.get("face")}
        seeds = [loop for name, loop in runs.items() if re.match(r"random_seed\d+$", name)]
        if len(seeds) > 1:
            d["random_seed_spread"] = seed_spread(seeds)
        out["datasets"][dataset] = d
    path = os.path.join(root, "summary.json")
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print("summary: " + path)


if __name__ == "__main__":
    main()
