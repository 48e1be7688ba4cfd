#!/usr/bin/python3
"""The cost model of docs/scale.md, fitted to bench/results/scale/runs.json
(bench/scale/run.sh), and its prediction for a stated project and cluster.
Writes bench/results/scale/model.json and prints it.

Time. PRI's work is per (face, view that sees it): visibility rays and
view selection per face-view, lattice sampling and comparison per sample,
and decoding per pixel of each photo a process needs. One process's PRI
time (2 threads here) is
    T = f * F + a * FV + b * S + d * P / threads
(F faces: ray-caster build, normals, tiles and assembly; FV face-views:
visibility rays and view selection; S samples = sum over face-views of
samples per view: sampling and comparison; P pixels decoded). d, the
decoding time per pixel on one thread, is measured on its own (the bench's
"decode" runs); f, a and b are fitted by least squares to T - d * P /
threads over the cost points: a quarter, half and all of the survey's
photos, half and all of them upsampled twice, and all of them on a mesh of
half the faces. Fitting d with the others, or an intercept, was
ill-conditioned (the pixels decoded grow with the samples: negative
coefficients).

Memory. Each rank holds the whole mesh and its ray caster (does not shrink
with ranks), the photos its tiles need (decoded, in an LRU cache), and its
tiles' per-face results; each rank's peak is fitted as
    M = A + beta * P_r + gamma * F_r
(P_r pixels the rank decoded) over the runs on 1, 2 and 4 ranks; A scales
with the mesh (the prediction assumes in proportion to its faces). The
faces a rank computes (F_r) add too little to be told apart from noise
here (a fitted share per face came out negative), so they are left out.

Prediction: rank 0 broadcasts the scene (the mesh: 24 bytes per vertex,
12 per face) at an assumed 1 GB/s; every rank then does the per-face part
(f * F, on its own cores: an upper bound, as view selection is in fact
shared) and shares the per face-view and per sample work with the
others."""
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
    decode = [r for r in runs["runs"] if r["what"] == "decode"]
    d = float(np.mean([r["seconds_per_megapixel"] for r in decode])) / 1e6
    X = np.array([[r["faces"], r["face_views"], r["samples"]] for r in points])
    P = np.array([r["images_decoded"] * r["pixels"] for r in points], dtype=float)
    t = np.array([r["pri_seconds"] for r in points])
    (f, a, b), pred, _ = fit(X, t - d * P / threads)
    pred = pred + d * P / threads
    r2 = float(1 - ((t - pred) ** 2).sum() / ((t - t.mean()) ** 2).sum())
    mpi = [r for r in runs["runs"] if r["what"] == "meshnbv-mpi pri"]
    pixels = runs["scene"]["pixels"]
    rows, mem = [], []
    for r in mpi:
        for k in range(r["ranks"]):
            rows.append([1.0, r["images_decoded"][k] * pixels])
            mem.append(r["peak_mb"][k])
    (A, beta), mpred, mr2 = fit(np.array(rows), np.array(mem))
    faces = runs["scene"]["faces"]
    model = {
        "time": {
            "formula": "T = f*F + a*FV + b*S + d*P/threads (one process, %d threads)" % threads,
            "f_seconds_per_face": f, "a_seconds_per_face_view": a, "b_seconds_per_sample": b,
            "d_seconds_per_megapixel_one_thread": d * 1e6, "r2": r2,
            "points": [{"faces": r["faces"], "views": r["views"], "image": r["image"], "face_views": r["face_views"],
                        "samples": r["samples"], "pixels_decoded": r["images_decoded"] * r["pixels"],
                        "seconds": r["pri_seconds"], "fitted": float(p)} for r, p in zip(points, pred)]},
        "memory": {
            "formula": "M = A + beta*P_r (per rank)",
            "A_mb": A, "beta_mb_per_megapixel": beta * 1e6,
            "A_bytes_per_face_of_the_mesh": A * 2**20 / faces, "r2": mr2,
            "points": [{"pixels_decoded": x[1], "peak_mb": m, "fitted": float(p)}
                       for x, m, p in zip(rows, mem, mpred)]},
    }
    # The prediction, for a stated project and cluster (assumptions, not
    # measurements): a city survey of 1e5 photos of 20 MP and a 1e8-face
    # mesh; each face seen by 12 photos (80% forward, 60% side overlap) with
    # the bench's mean samples per face-view; each photo decoded by 2 ranks
    # (tiles at a run's border share photos); 64 nodes x 32 cores, one rank
    # per node; per-unit costs scaled from this machine's 2 threads to
    # 32 cores linearly (set-up included: optimistic where it is serial).
    F, photos, mp, n, nodes, cores = 1e8, 1e5, 20e6, 12, 64, 32
    samples_per_face_view = float(np.sum([r["samples"] for r in points]) / np.sum([r["face_views"] for r in points]))
    decode_core_seconds = d * photos * 2 * mp
    shared_core_seconds = threads * (a * F * n + b * F * n * samples_per_face_view) + decode_core_seconds
    setup_seconds = f * F * threads / cores  # on every rank, with its own cores
    vertices = F / 2  # a closed triangle mesh has about half as many vertices as faces
    broadcast_seconds = (24 * vertices + 12 * F) / 1e9
    wall = broadcast_seconds + setup_seconds + shared_core_seconds / (nodes * cores)
    per_rank_pixels = photos * 2 / nodes * mp
    cache_gb = 1.0  # the image cache's bound (ImageCache: 1 GiB), photos beyond it decoded again
    model["prediction"] = {
        "faces": F, "photos": photos, "megapixels": mp / 1e6, "views_per_face": n, "nodes": nodes,
        "cores_per_node": cores, "samples_per_face_view": samples_per_face_view,
        "core_hours_shared": shared_core_seconds / 3600, "wall_minutes": wall / 60,
        "wall_minutes_parts": {"broadcast": broadcast_seconds / 60, "per_face_on_every_rank": setup_seconds / 60,
                               "shared_work": shared_core_seconds / (nodes * cores) / 60},
        "decoding_share_of_shared_work": decode_core_seconds / shared_core_seconds,
        "memory_gb_per_rank": {
            "mesh_and_ray_caster": A * 2**20 / faces * F / 2**30,
            "photos_held": min(beta * per_rank_pixels / 1024, cache_gb)},
        "assumptions": "stated in bench/scale/model.py: 12 views per face, each photo decoded by 2 ranks "
                       "at the bench's PNG rate, "
                       "per-unit costs of this machine's cores scaling linearly to 32, the whole mesh held "
                       "and set up on every rank, the scene broadcast at 1 GB/s"}
    json.dump(model, open(os.path.join(RESULTS, "model.json"), "w"), indent=1)
    print(json.dumps(model, indent=1))


if __name__ == "__main__":
    main()
