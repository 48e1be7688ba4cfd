#!/usr/bin/python3
"""The cost model of docs/scale.md, fitted to bench/results/scale/runs.json
(bench/scale/run.sh), and its prediction for a stated project and cluster.
Writes bench/results/scale/model.json and prints it.

Time. PRI's work is per (face, view that sees it): visibility rays and
view selection per face-view, lattice sampling and comparison per sample,
and decoding per pixel of each photo a process needs. One process's PRI
time (2 threads here) is fitted by least squares as
    T = t0 + a * FV + b * S + d * P
(FV face-views, S samples = sum over face-views of samples per view, P
pixels decoded) over the cost points: 8, 16 and 32 photos of 1024x768 and
16 and 32 photos of 2048x1536 (the same photos upsampled).

Memory. Each rank holds the whole mesh and its ray caster (does not shrink
with ranks), the photos its tiles need (decoded, in an LRU cache), and its
tiles' per-face results; each rank's peak is fitted as
    M = A + beta * P_r + gamma * F_r
(P_r pixels the rank decoded, F_r faces it computed) over the runs on 1, 2
and 4 ranks."""
import json
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "..", "results", "scale")


def fit(X, y):
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    pred = X @ coef
    r2 = 1 - ((y - pred) ** 2).sum() / ((y - y.mean()) ** 2).sum()
    return coef, pred, float(r2)


def main():
    runs = json.load(open(os.path.join(RESULTS, "runs.json")))
    threads = runs["machine"]["cpus"]
    points = [r for r in runs["runs"] if r["what"] == "cost point"]
    X = np.array([[1.0, r["face_views"], r["samples"], r["images_decoded"] * r["pixels"]] for r in points])
    t = np.array([r["pri_seconds"] for r in points])
    (t0, a, b, d), pred, r2 = fit(X, t)
    mpi = [r for r in runs["runs"] if r["what"] == "meshnbv-mpi pri"]
    pixels = 1024 * 768
    rows, mem = [], []
    for r in mpi:
        for k in range(r["ranks"]):
            rows.append([1.0, r["images_decoded"][k] * pixels, r["faces"][k]])
            mem.append(r["peak_mb"][k])
    (A, beta, gamma), mpred, mr2 = fit(np.array(rows), np.array(mem))
    faces = runs["scene"]["faces"]
    model = {
        "time": {
            "formula": "T = t0 + a*FV + b*S + d*P (one process, %d threads)" % threads,
            "t0_seconds": t0, "a_seconds_per_face_view": a, "b_seconds_per_sample": b,
            "d_seconds_per_pixel_decoded": d, "r2": r2,
            "points": [{"views": r["views"], "image": r["image"], "face_views": r["face_views"],
                        "samples": r["samples"], "pixels_decoded": r["images_decoded"] * r["pixels"],
                        "seconds": r["pri_seconds"], "fitted": float(p)} for r, p in zip(points, pred)]},
        "memory": {
            "formula": "M = A + beta*P_r + gamma*F_r (per rank)",
            "A_mb": A, "beta_mb_per_megapixel": beta * 1e6, "gamma_mb_per_million_faces": gamma * 1e6,
            "A_bytes_per_face_of_the_mesh": A * 2**20 / faces, "r2": mr2,
            "points": [{"pixels_decoded": x[1], "faces": x[2], "peak_mb": m, "fitted": float(p)}
                       for x, m, p in zip(rows, mem, mpred)]},
    }
    # The prediction, for a stated project and cluster (assumptions, not
    # measurements): a city survey of 1e5 photos of 20 MP and a 1e8-face
    # mesh; each face seen by 12 photos (80% forward, 60% side overlap) with
    # the bench's mean samples per face-view; each photo decoded by 2 ranks
    # (tiles at a run's border share photos); 64 nodes x 32 cores, one rank
    # per node; per-unit costs scaled from this machine's 2 threads to
    # 32 cores linearly.
    F, photos, mp, n, nodes, cores = 1e8, 1e5, 20e6, 12, 64, 32
    samples_per_face_view = float(np.sum([r["samples"] for r in points]) / np.sum([r["face_views"] for r in points]))
    core_seconds = threads * (a * F * n + b * F * n * samples_per_face_view + d * photos * 2 * mp)
    wall = core_seconds / (nodes * cores) + t0
    per_rank_pixels = photos * 2 / nodes * mp
    cache_gb = 1.0  # the image cache's bound (ImageCache: 1 GiB), photos beyond it decoded again
    model["prediction"] = {
        "faces": F, "photos": photos, "megapixels": mp / 1e6, "views_per_face": n, "nodes": nodes,
        "cores_per_node": cores, "samples_per_face_view": samples_per_face_view,
        "core_hours": core_seconds / 3600, "wall_minutes": wall / 60,
        "wall_minutes_decoding_share": threads * d * photos * 2 * mp / (nodes * cores) / 60,
        "memory_gb_per_rank": {
            "mesh_and_ray_caster": A * 2**20 / faces * F / 2**30,
            "photos_held": min(beta * per_rank_pixels / 1024, cache_gb),
            "results": gamma * F / nodes / 1024},
        "assumptions": "stated in bench/scale/model.py: 12 views per face, each photo decoded by 2 ranks, "
                       "per-unit costs of this machine's cores, the whole mesh held on every rank"}
    json.dump(model, open(os.path.join(RESULTS, "model.json"), "w"), indent=1)
    print(json.dumps(model, indent=1))


if __name__ == "__main__":
    main()
