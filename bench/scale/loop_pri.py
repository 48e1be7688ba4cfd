#!/usr/bin/python3
"""Incremental PRI in the paper's loop (docs/scale.md, issue #22): the same
`meshnbv loop --strategy nbv` run with and without --incremental-pri on the
synthetic building and, when ../shared/data holds it, Middlebury
templeRing; per step the PRI time and the faces recomputed; both runs must
choose the same views (incremental PRI equals a full computation).
Arguments: the folder holding meshnbv, a scratch folder, the results folder.
Writes loop_pri.json and loop_pri.md there."""
import json
import os
import subprocess
import sys

BIN, WORK, OUT = sys.argv[1:4]
MESHNBV = os.path.join(BIN, "meshnbv")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TEMPLE = os.path.join(os.environ.get("MESHNBV_SHARED_DATA", os.path.join(ROOT, "..", "shared", "data")),
                      "middlebury", "templeRing")


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("bench/scale/loop_pri: %s failed: %s" % (" ".join(cmd), p.stderr.strip()[-2000:]))


def main():
    datasets = []
    building = os.path.join(WORK, "loop", "building")
    if not os.path.exists(os.path.join(building, "scene.json")):
        run([MESHNBV, "synth", "building", "--out", building, "--views", "24", "--size", "1024x768",
             "--layout", "ring", "--quiet", "--overwrite"])
    datasets.append(("building", building, ["--view-budget", "12", "--facet-support", "edges"]))
    if os.path.exists(os.path.join(TEMPLE, "templeR_par.txt")):
        datasets.append(("templeRing", TEMPLE, ["--view-budget", "23"]))
    else:
        print("loop_pri: templeRing not found at %s: synthetic building only" % TEMPLE)
    results = {"datasets": []}
    for name, path, extra in datasets:
        cache = os.path.join(WORK, "loop", "cache_" + name)
        runs = {}
        # The first run fills COLMAP's cache (features, matches): run it once
        # before either measured run so that both find it filled.
        for label, flag in (("warm-up", "--incremental-pri"), ("full", "--no-incremental-pri"),
                            ("incremental", "--incremental-pri")):
            out = os.path.join(WORK, "loop", name + "_" + label)
            run([MESHNBV, "loop", path, "--strategy", "nbv", "--cache", cache, "--out", out, "--overwrite",
                 "--save-meshes", "none", "--quiet", flag] + extra)
            runs[label] = json.load(open(os.path.join(out, "loop.json")))
        full, inc = runs["full"]["steps"], runs["incremental"]["steps"]
        same = [s["views"] for s in full] == [s["views"] for s in inc]
        steps = []
        for a, b in zip(full, inc):
            if a["step"] == 0:
                continue  # no PRI before the first choice
            steps.append({"step": a["step"], "faces": b["faces"], "full_pri_seconds": a["seconds"]["pri"],
                          "incremental_pri_seconds": b["seconds"]["pri"],
                          "recomputed": b["pri_faces"]["recomputed"], "pri_faces": b["pri_faces"]["total"]})
        results["datasets"].append({"dataset": name, "same_views_chosen": same, "steps": steps})
        print("%s: same views chosen %s; PRI %.2f s full, %.2f s incremental" % (
            name, same, sum(s["full_pri_seconds"] for s in steps), sum(s["incremental_pri_seconds"] for s in steps)),
            flush=True)
    json.dump(results, open(os.path.join(OUT, "loop_pri.json"), "w"), indent=1)
    lines = []
    for d in results["datasets"]:
        st = d["steps"]
        rec = sum(s["recomputed"] for s in st)
        tot = sum(s["pri_faces"] for s in st)
        lines += ["%s (`meshnbv loop --strategy nbv`): same views chosen with and without incremental PRI: %s." % (
                      d["dataset"], "yes" if d["same_views_chosen"] else "NO"), "",
                  "| step | faces | recomputed | full PRI s | incremental PRI s |", "|---|---|---|---|---|"]
        for s in st:
            lines.append("| %d | %d | %d (%.0f%%) | %.3f | %.3f |" % (
                s["step"], s["pri_faces"], s["recomputed"], 100.0 * s["recomputed"] / max(1, s["pri_faces"]),
                s["full_pri_seconds"], s["incremental_pri_seconds"]))
        lines.append("| all | %d | %d (%.0f%%) | %.2f | %.2f |" % (
            tot, rec, 100.0 * rec / max(1, tot), sum(s["full_pri_seconds"] for s in st),
            sum(s["incremental_pri_seconds"] for s in st)))
        lines.append("")
    open(os.path.join(OUT, "loop_pri.md"), "w").write("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
