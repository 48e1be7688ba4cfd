#!/usr/bin/python3
"""New poses below the base (issue #16, docs/nbv.md): for every run of an
experiment folder (experiment.sh's layout) the views the loop added
(`added_camera` in each starting set's loop.json) whose centre lies below
the dataset's reference mesh (the synthetic scenes stand on z = 0, +z up),
and the lowest of them. Writes below_base.md and below_base.json there.

  bench/eval/below_base.py RESULTS_DIR"""
import glob
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from ply_mesh import read_ply  # noqa: E402


def main():
    root = sys.argv[1]
    rows = []
    for dataset in sorted(os.listdir(root)):
        ref = os.path.join(root, dataset, "reference.ply")
        if not os.path.isfile(ref):
            continue
        base = float(read_ply(ref)[0][:, 2].min())
        for run in sorted(os.listdir(os.path.join(root, dataset))):
            heights = []
            for f in sorted(glob.glob(os.path.join(root, dataset, run, "bootstrap_*", "loop.json"))):
                for step in json.load(open(f))["steps"]:
                    if "added_camera" in step:
                        heights.append(step["added_camera"]["center"][2])
            if heights:
                below = [h for h in heights if h < base]
                rows.append({"dataset": dataset, "run": run, "base_z": base, "added": len(heights),
                             "below_base": len(below), "lowest_z": min(heights)})
    json.dump(rows, open(os.path.join(root, "below_base.json"), "w"), indent=1)
    lines = ["Added views below the reference mesh's lowest point (bench/eval/below_base.py).", "",
             "| dataset | run | base z | added views | below the base | lowest z |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %s | %.2f | %d | %d | %.2f |" % (r["dataset"], r["run"], r["base_z"], r["added"],
                                                         r["below_base"], r["lowest_z"]))
    open(os.path.join(root, "below_base.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
