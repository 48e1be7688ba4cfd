#!/usr/bin/python3
"""Reduced JPEG decoding (issue #17, PriOptions::max_image_reduction): PRI on
20 MP JPEG photos of the synthetic building at several mesh resolutions,
with photos always decoded whole (max_image_reduction 1, the default) and
at most 2 or 8 times smaller, in the same session. Per case: how many views are decoded
reduced, wall time, peak memory, decodes, and what PRI says with each:
Spearman and ROC AUC (worst decile by true error) against the true
per-face error (gt_error.csv), and Spearman between the two PRIs.

Arguments: the build folder, a scratch folder, the results folder.
Run by bench/photos/run_reduction.sh."""
import csv
import json
import os
import platform
import re
import sys
import time
from multiprocessing import Pool

import numpy as np
from scipy.stats import rankdata, spearmanr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from ply_mesh import read_ply  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from photos import run  # noqa: E402  (photos.py reads the same three arguments)

BUILD, WORK, OUT = sys.argv[1:4]
MESHNBV = os.path.join(BUILD, "apps", "meshnbv")
SIZE = (5472, 3648)  # 20.0 MP
VIEWS = 24
# (scene name, synth arguments, PRI arguments): the building on a ring at
# its default edge length (faces of a few tens of pixels in these photos)
# and coarser meshes of the same surface (a decimated mesh checked against
# full-size photos); the default lattice, and coarser lattices
# (samples_per_side) a user may set for speed.
CASES = (
    ("ring_default_edge", ["--layout", "ring"], []),
    ("ring_default_edge", ["--layout", "ring"], ["--samples-per-side", "4"]),
    ("ring_edge_1", ["--layout", "ring", "--edge-length", "1"], ["--samples-per-side", "4"]),
    ("ring_edge_2", ["--layout", "ring", "--edge-length", "2"], []),
    ("ring_edge_2", ["--layout", "ring", "--edge-length", "2"], ["--samples-per-side", "8"]),
    ("ring_edge_2", ["--layout", "ring", "--edge-length", "2"], ["--samples-per-side", "4"]),
)
REPEATS = 3  # each setting, in alternation; the median time is reported
SETTINGS = (1, 2, 8)  # max_image_reduction: whole, at most half, the most


def to_jpeg(job):
    """A rendered photo with sensor-like noise (Gaussian, sigma 2 levels,
    seeded by the view) as a quality-92 JPEG, as cameras write them."""
    from PIL import Image
    src, dst, seed = job
    if os.path.exists(dst):
        return os.path.getsize(dst)
    a = np.asarray(Image.open(src).convert("RGB"), dtype=np.float32)
    a += np.random.default_rng(seed).normal(0.0, 2.0, a.shape).astype(np.float32)
    tmp = dst + ".tmp.jpg"
    Image.fromarray(np.clip(a + 0.5, 0, 255).astype(np.uint8)).save(tmp, quality=92)
    os.replace(tmp, dst)
    return os.path.getsize(dst)


def auc_worst_decile(score, error):
    """ROC AUC of `score` separating the worst decile by true error from the
    rest (Mann-Whitney, ties averaged); faces without error never count as
    worst."""
    positive = (error >= np.quantile(error, 0.9)) & (error > 0)
    ranks = rankdata(score)
    n1, n0 = positive.sum(), (~positive).sum()
    return float((ranks[positive].sum() - n1 * (n1 + 1) / 2) / (n1 * n0))


def main():
    photos = os.path.join(WORK, "photos")
    results = {"machine": {"cpus": os.cpu_count(), "platform": platform.platform()},
               "photo_size": "%dx%d" % SIZE, "views": VIEWS, "cases": []}
    for name, synth_args, pri_args in CASES:
        d = os.path.join(WORK, name)
        if not os.path.exists(os.path.join(d, "scene.json")):
            t = time.perf_counter()
            run([MESHNBV, "synth", "building", "--views", str(VIEWS), "--size", "%dx%d" % SIZE,
                 "--samples-per-pixel", "1", "--out", d, "--overwrite", "--quiet"] + synth_args)
            print("%s: synth %.0f s" % (name, time.perf_counter() - t), flush=True)
        s = json.load(open(os.path.join(d, "scene.json")))
        os.makedirs(photos, exist_ok=True)
        jobs = [(os.path.join(d, v["image"]), os.path.join(photos, "%s_%s.jpg" % (name, i)), i)
                for i, v in enumerate(s["views"])]
        with Pool(2) as pool:
            sizes = pool.map(to_jpeg, jobs)
        for v, job in zip(s["views"], jobs):
            v["image"] = os.path.abspath(job[1])
        s["mesh"] = os.path.abspath(os.path.join(d, "degraded.ply"))
        scene = os.path.join(WORK, name + "_jpeg.json")
        json.dump(s, open(scene, "w"))
        with open(os.path.join(d, "gt_error.csv")) as f:
            rows = list(csv.reader(f))
        gt = np.array([float(r[-1]) for r in rows[1:]])
        label = " ".join([name] + pri_args)
        case = {"name": label, "scene": name, "synth_arguments": synth_args, "pri_arguments": pri_args,
                "faces": len(gt), "jpeg_mb_mean": float(np.mean(sizes)) / 1e6, "runs": {}}
        pri, walls, peaks = {}, {m: [] for m in SETTINGS}, {m: [] for m in SETTINGS}
        for rep in range(REPEATS):
            for m in (SETTINGS if rep % 2 == 0 else SETTINGS[::-1]):
                ply = os.path.join(WORK, "r%d.ply" % m)
                summary = os.path.join(WORK, "r%d.json" % m)
                wall, _, err = run(["/usr/bin/time", "-f", "peak_kb %M", MESHNBV, "pri", scene, "--out", ply,
                                    "--json", summary, "--max-image-reduction", str(m), "--overwrite", "--quiet",
                                    "--progress", "none"] + pri_args)
                walls[m].append(wall)
                peaks[m].append(float(re.search(r"peak_kb (\d+)", err).group(1)) / 1024)
                if rep == 0:
                    j = json.load(open(summary))
                    q = read_ply(ply, fields=True)["quality"].astype(np.float64)
                    ok = np.isfinite(q)
                    pri[m] = q
                    case["runs"][str(m)] = {
                        "max_image_reduction": m, "images_decoded": j["images_decoded"],
                        "views_reduced": j["views_reduced"], "observed_faces": int(ok.sum()),
                        "spearman_vs_true_error": float(spearmanr(q[ok], gt[ok]).correlation),
                        "auc_worst_decile": auc_worst_decile(q[ok], gt[ok])}
        for m in SETTINGS:
            r = case["runs"][str(m)]
            r["wall_seconds"], r["wall_seconds_all"] = float(np.median(walls[m])), walls[m]
            r["peak_mb"] = float(np.median(peaks[m]))
            print("%s, max_image_reduction %d: %.2f s, peak %.0f MB, %d of %d views reduced, Spearman %.3f" % (
                label, m, r["wall_seconds"], r["peak_mb"], r["views_reduced"], VIEWS, r["spearman_vs_true_error"]),
                flush=True)
        for m in SETTINGS[1:]:
            r = case["runs"][str(m)]
            both = np.isfinite(pri[1]) & np.isfinite(pri[m])
            r["spearman_with_whole"] = float(spearmanr(pri[1][both], pri[m][both]).correlation)
            r["observed_in_one_only"] = int(np.sum(np.isfinite(pri[1]) != np.isfinite(pri[m])))
            r["speedup"] = case["runs"]["1"]["wall_seconds"] / r["wall_seconds"]
        results["cases"].append(case)

    os.makedirs(OUT, exist_ok=True)
    json.dump(results, open(os.path.join(OUT, "reduction.json"), "w"), indent=2)
    write_table(results)


def write_table(results):
    """reduction.md from the results (also alone: reduction.py BUILD WORK OUT --table)."""
    lines = ["PRI (default settings but the case's lattice, 2 threads) on %d photos of %s (20 MP) as JPEG quality 92, of the synthetic "
             "building's degraded mesh (a ring of views; default or coarser edge lengths, default or "
             "coarser lattices); photos decoded whole (`max_image_reduction` 1, the default) and at most 2 or 8 "
             "times smaller, same session, %d runs of each in alternation (median time). Spearman and AUC (worst decile by "
             "true error) against the true per-face error. Written by bench/photos/run_reduction.sh." % (
                 VIEWS, results["photo_size"], REPEATS),
             "",
             "| case | faces observed | max_image_reduction | views reduced | time (s) | speed-up | peak (MB) "
             "| Spearman vs true error | AUC worst decile | Spearman with whole | observed in one only |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in results["cases"]:
        for m in SETTINGS:
            r = c["runs"][str(m)]
            lines.append("| %s | %d | %d | %d of %d | %.2f | %s | %.0f | %.3f | %.3f | %s | %s |" % (
                c["name"], r["observed_faces"], m, r["views_reduced"], VIEWS, r["wall_seconds"],
                "%.2fx" % r["speedup"] if m > 1 else "", r["peak_mb"], r["spearman_vs_true_error"],
                r["auc_worst_decile"], "%.3f" % r["spearman_with_whole"] if m > 1 else "",
                r["observed_in_one_only"] if m > 1 else ""))
    open(os.path.join(OUT, "reduction.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    if sys.argv[4:] == ["--table"]:
        write_table(json.load(open(os.path.join(OUT, "reduction.json"))))
    else:
        main()
