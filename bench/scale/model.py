#!/usr/bin/python3
"""The cost model of docs/scale.md, fitted to bench/results/scale/runs.json
(bench/scale/run.sh), and its prediction for a stated project and cluster.
Writes bench/results/scale/model.json and prints it.

Time: PRI's work is per (face, view that sees it) -- visibility rays,
sampling, comparison -- so one process's PRI time is fitted as
    T = t0 + c * F * n
(F faces, n mean views per face, c core-independent seconds per face-view
at this machine's thread count), over the runs at 8, 16 and 32 views.
Memory per rank: each rank holds the whole mesh and its ray caster (a part
that does not shrink with ranks) and one tile's samples and its images
(a part that does), fitted as
    M(R) = A + B / R
over the runs on R = 1, 2, 4 ranks."""
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "..", "results", "scale")


def main():
    runs = json.load(open(os.path.join(RESULTS, "runs.json")))
    points = [r for r in runs["runs"] if r["what"] == "cost point"]
    fn = np.array([r["faces"] * r["mean_views"] for r in points])
    t = np.array([r["pri_seconds"] for r in points])
    c, t0 = np.polyfit(fn, t, 1)
    pred = t0 + c * fn
    r2 = 1 - ((t - pred) ** 2).sum() / ((t - t.mean()) ** 2).sum()
    mpi = [r for r in runs["runs"] if r["what"] == "meshnbv-mpi pri"]
    R = np.array([r["ranks"] for r in mpi], dtype=float)
    M = np.array([max(r["peak_mb"]) for r in mpi])
    B, A = np.polyfit(1.0 / R, M, 1)
    faces = runs["scene"]["faces"]
    threads = runs["machine"]["cpus"]
    model = {
        "time": {"t0_seconds": t0, "seconds_per_face_view": c, "threads": threads,
                 "core_seconds_per_face_view": c * threads, "r2": r2,
                 "points": [{"views": r["views"], "face_views": f, "seconds": s}
                            for r, f, s in zip(points, fn.tolist(), t.tolist())],
                 "mean_samples_per_face": float(np.mean([r["mean_samples"] for r in points]))},
        "memory": {"A_mb": A, "B_mb": B, "faces": faces, "A_bytes_per_face": A * 2**20 / faces,
                   "points": [{"ranks": int(r), "peak_mb": m} for r, m in zip(R.tolist(), M.tolist())]},
    }
    # The prediction: a city survey of 1e5 photos and a 1e8-face mesh, each
    # face seen by 30 photos (stated, not measured), faces sampled as
    # finely as in the bench; 64 nodes x 32 cores, one rank per node.
    F, n, nodes, cores = 1e8, 30, 64, 32
    core_seconds = c * threads * F * n
    wall = core_seconds / (nodes * cores)
    replicated_gb = model["memory"]["A_bytes_per_face"] * F / 2**30
    model["prediction"] = {
        "faces": F, "photos": 1e5, "views_per_face": n, "nodes": nodes, "cores_per_node": cores,
        "core_hours": core_seconds / 3600, "wall_hours_if_perfectly_parallel": wall / 3600,
        "replicated_gb_per_rank": replicated_gb,
        "assumptions": "the bench's per face-view cost (its lattice size and 1024x768 photos) scales to "
                       "1e8 faces; decoding excluded (each rank decodes the photos its tiles see); the "
                       "mesh and its ray caster are held whole on every rank (A per face scaled)"}
    json.dump(model, open(os.path.join(RESULTS, "model.json"), "w"), indent=1)
    print(json.dumps(model, indent=1))


if __name__ == "__main__":
    main()
