#!/usr/bin/python3
"""Tables of bench/eval/dense.sh: dense against sparse with every view, and
the time split of the dense templeRing loop.

    dense_summary.py WORK/dense_bench RESULTS_DIR
"""
import json
import os
import sys


def last_step(path):
    j = json.load(open(path))
    return j, j["steps"][-1]


def quality(bench):
    rows = []
    for scene in ("building", "fortress", "temple"):
        for backend in ("sparse", "dense"):
            f = os.path.join(bench, scene, backend, "loop.json")
            if not os.path.exists(f):
                continue
            j, s = last_step(f)
            thresholds = sorted(s["completeness"], key=float)
            rows.append({
                "scene": scene,
                "backend": backend,
                "synthetic": j["synthetic"],
                "reference": j["reference"],
                "views": s["num_views"],
                "points": s["points"],
                "faces": s["faces"],
                "surface_samples": s["samples"]["reconstruction"],
                "accuracy": s["accuracy"],
                "completeness": {t: s["completeness"][t] for t in thresholds},
                "seconds": s["seconds"],
                "dense": s.get("dense"),
                "failure": s.get("failure"),
            })
    return rows


def fmt(x, digits=4):
    return "n/a" if x is None else ("%.*g" % (digits, x))


def main():
    bench, results = sys.argv[1], sys.argv[2]
    os.makedirs(results, exist_ok=True)
    rows = quality(bench)
    out = {"quality": rows}
    md = ["# Dense backend against sparse, every view", "",
          "bench/eval/dense.sh; the last step of a loop holding every view of the dataset (uniform, "
          "bootstrap n-1). Synthetic: the truth, thresholds 0.5%, 1%, 2% of its diagonal; templeRing: "
          "the reconstruction from all 47 views with the same backend, thresholds in metres.", "",
          "| scene | backend | views | points | faces | surface samples | 90% accuracy | completeness | reconstruct s (sparse / dense / mesh) |",
          "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        comp = ", ".join("%s: %.1f%%" % (fmt(float(t)), 100 * v) for t, v in r["completeness"].items())
        t = r["seconds"]
        md.append("| %s | %s | %d | %d | %d | %d | %s | %s | %.1f (%.1f / %.1f / %.1f) |" % (
            r["scene"], r["backend"], r["views"], r["points"], r["faces"], r["surface_samples"],
            fmt(r["accuracy"].get("90")), comp, t["reconstruct"], t.get("sparse", 0), t.get("dense", 0),
            t.get("mesh", 0)))
    by = {(r["scene"], r["backend"]): r for r in rows}
    md += ["", "templeRing's reference is the reconstruction from all 47 views with the same backend, so "
           "its every-view row measures the backend against itself (zero distance, 100%): only its "
           "points count there."]
    md.append("")
    for scene in ("building", "fortress", "temple"):
        if (scene, "sparse") in by and (scene, "dense") in by:
            s, d = by[(scene, "sparse")], by[(scene, "dense")]
            raw = (d.get("dense") or {}).get("raw_points", 0)
            md.append("- %s: dense/sparse points handed to the mesher %.1fx (depth samples before the voxel "
                      "merge: %.1fx), metric surface samples (area) %.1fx." % (
                scene, d["points"] / max(1, s["points"]), raw / max(1, s["points"]),
                d["surface_samples"] / max(1, s["surface_samples"])))
    loop_file = os.path.join(results, "loop_temple", "loop.json")
    if os.path.exists(loop_file):
        j = json.load(open(loop_file))
        steps = j["steps"]
        keys = ("sparse", "dense", "mesh", "pri", "choose", "evaluate")
        total = {k: sum(s["seconds"].get(k, 0) for s in steps) for k in keys}
        out["loop"] = {"steps": len(steps), "views": steps[-1]["num_views"], "seconds": j["seconds"],
                       "split": total}
        md += ["", "## A 23-view nbv loop on templeRing, dense backend", "",
               "%d steps up to %d views in %.0f s (%.1f min; features and matches cached, depth maps "
               "computed as views arrive)." % (len(steps), steps[-1]["num_views"], j["seconds"],
                                               j["seconds"] / 60), "",
               "| step | views | points | faces | pairs (matched now) | sparse | dense | mesh | PRI | choose | evaluate |",
               "|---|---|---|---|---|---|---|---|---|---|---|"]
        for s in steps:
            t = s["seconds"]
            d = s.get("dense", {})
            md.append("| %d | %d | %d | %d | %s (%s) | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |" % (
                s["step"], s["num_views"], s["points"], s["faces"], d.get("pairs", 0),
                d.get("pairs_computed", 0), t.get("sparse", 0), t.get("dense", 0), t.get("mesh", 0),
                t["pri"], t["choose"], t["evaluate"]))
        md.append("| all | | | | | %s |" % " | ".join("%.0f" % total[k] for k in keys))
    json.dump(out, open(os.path.join(results, "quality.json"), "w"), indent=2)
    open(os.path.join(results, "summary.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
