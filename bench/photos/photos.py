#!/usr/bin/python3
"""The measurements of bench/photos/run.sh (read it first). Arguments: the
build folder, a scratch folder, the results folder."""
import json
import os
import platform
import re
import subprocess
import sys
import time
from multiprocessing import Pool

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from ply_mesh import read_ply, split_longest_edge, write_ply  # noqa: E402

BUILD, WORK, OUT = sys.argv[1:4]
MESHNBV = os.path.join(BUILD, "apps", "meshnbv")
DECODE = os.path.join(BUILD, "bench", "photo_decode")
VIEWS = 100
HALF = (2736, 1824)            # rendered
FULL = (2 * HALF[0], 2 * HALF[1])  # 5472 x 3648 = 20.0 MP, a 1" 20 MP sensor's photo
VIEW_COUNTS = (25, 50, 100)
TARGET_PEAK_MB = 4096
# Another build's meshnbv (e.g. of an earlier commit), run on the same scenes
# in the same session: its time, peak and decodes, and how far its PRI is
# from this build's.
BASELINE = os.environ.get("MESHNBV_PHOTOS_BASELINE_BIN", "")
# What the baseline is, for the tables (e.g. "commit e42ac51").
BASELINE_LABEL = os.environ.get("MESHNBV_PHOTOS_BASELINE_LABEL", BASELINE)


def run(cmd):
    t = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t
    if p.returncode != 0:
        sys.exit("bench/photos: %s failed: %s" % (" ".join(cmd), p.stderr.strip()[-2000:]))
    return wall, p.stdout, p.stderr


def to_jpeg(job):
    """A rendered photo doubled (bicubic) to 20 MP with sensor-like noise
    (Gaussian, sigma 2 levels, seeded by the view), as a quality-92 JPEG."""
    from PIL import Image
    src, dst, seed = job
    if os.path.exists(dst):
        return os.path.getsize(dst)
    im = Image.open(src).convert("RGB").resize(FULL, Image.BICUBIC)
    a = np.asarray(im, dtype=np.float32)
    a += np.random.default_rng(seed).normal(0.0, 2.0, a.shape).astype(np.float32)
    tmp = dst + ".tmp.jpg"
    Image.fromarray(np.clip(a + 0.5, 0, 255).astype(np.uint8)).save(tmp, quality=92)
    os.replace(tmp, dst)
    return os.path.getsize(dst)


def main():
    city = os.path.join(WORK, "city")
    if not os.path.exists(os.path.join(city, "scene.json")):
        run([MESHNBV, "synth", "city", "--edge-length", "0.2", "--views", str(VIEWS), "--layout", "hemisphere",
             "--size", "%dx%d" % HALF, "--samples-per-pixel", "1", "--out", city, "--overwrite", "--quiet"])
    big = os.path.join(WORK, "big.ply")
    if not os.path.exists(big):
        v, f = read_ply(os.path.join(city, "degraded.ply"))
        v2, f2 = split_longest_edge(v, f)
        write_ply(big, v2, f2, "bench/photos")
    faces = len(read_ply(big)[1])

    s = json.load(open(os.path.join(city, "scene.json")))
    jdir = os.path.join(WORK, "jpeg")
    os.makedirs(jdir, exist_ok=True)
    jobs = [(os.path.join(city, v["image"]), os.path.join(jdir, os.path.splitext(os.path.basename(v["image"]))[0] +
                                                           ".jpg"), i) for i, v in enumerate(s["views"])]
    t = time.perf_counter()
    with Pool(2) as pool:
        sizes = pool.map(to_jpeg, jobs)
    print("JPEGs: %d of %dx%d, %.1f MB each on average (%.0f s)" % (
        len(sizes), FULL[0], FULL[1], np.mean(sizes) / 1e6, time.perf_counter() - t), flush=True)

    # The cameras doubled with the photos (pixel centres at integers: u' = 2u + 0.5).
    for v, job in zip(s["views"], jobs):
        v["image"] = job[1]
        c = v["camera"]
        c["fx"], c["fy"], c["cx"], c["cy"] = 2 * c["fx"], 2 * c["fy"], 2 * c["cx"] + 0.5, 2 * c["cy"] + 0.5
        c["width"], c["height"] = FULL
    s["mesh"] = os.path.abspath(big)

    results = {"machine": {"cpus": os.cpu_count(), "platform": platform.platform()},
               "scene": {"faces": faces, "photo_size": "%dx%d" % FULL, "megapixels": FULL[0] * FULL[1] / 1e6,
                         "jpeg_mb_mean": float(np.mean(sizes)) / 1e6, "layout": "hemisphere",
                         "source": "synth city, edge 0.2 m, every triangle split in two; photos rendered at "
                                   "%dx%d, doubled (bicubic) with noise sigma 2, JPEG quality 92" % HALF},
               "target_peak_mb": TARGET_PEAK_MB, "runs": []}
    for n in VIEW_COUNTS:
        sub = dict(s)
        sub["views"] = s["views"][::VIEWS // n][:n]
        scene = os.path.join(WORK, "scene_%d.json" % n)
        json.dump(sub, open(scene, "w"))
        listing = os.path.join(WORK, "list_%d.txt" % n)
        open(listing, "w").write("\n".join(v["image"] for v in sub["views"]) + "\n")
        _, out, _ = run([DECODE, listing, "2"])
        dec = json.loads(out)
        ply, summary = os.path.join(WORK, "pri_%d.ply" % n), os.path.join(WORK, "pri_%d.json" % n)
        wall, out, err = run(["/usr/bin/time", "-f", "peak_kb %M", MESHNBV, "pri", scene, "--out", ply, "--json",
                              summary, "--overwrite", "--quiet"])
        peak = float(re.search(r"peak_kb (\d+)", err).group(1)) / 1024
        pri = json.load(open(summary))
        r = {"views": n, "decode_seconds_2_threads": dec["decode_seconds"],
             "decode_and_luminance_seconds_2_threads": dec["decode_and_luminance_seconds"],
             "pri_wall_seconds": wall, "pri_seconds": pri["seconds"], "peak_mb": peak,
             "images_decoded": pri["images_decoded"], "views_used": pri["views_used"],
             "observed_faces": pri["faces"]["observed"],
             "wall_over_decode": wall / dec["decode_seconds"],
             # The share of pri's CPU time (wall x 2 threads) that its decodes
             # and luminance conversions take, at photo_decode's cost per photo.
             "decode_cpu_share": pri["images_decoded"] * (2 * dec["decode_and_luminance_seconds"] / n) / (2 * wall)}
        if BASELINE:
            bply, bsum = os.path.join(WORK, "pri_%d_baseline.ply" % n), os.path.join(WORK, "pri_%d_baseline.json" % n)
            bwall, _, berr = run(["/usr/bin/time", "-f", "peak_kb %M", BASELINE, "pri", scene, "--out", bply,
                                  "--json", bsum, "--overwrite", "--quiet"])
            bpri = json.load(open(bsum))
            r["baseline"] = {"binary": BASELINE_LABEL, "pri_wall_seconds": bwall,
                             "peak_mb": float(re.search(r"peak_kb (\d+)", berr).group(1)) / 1024,
                             "images_decoded": bpri["images_decoded"]}
            a, b = read_ply(ply, fields=True), read_ply(bply, fields=True)
            r["baseline"]["identical_ply"] = open(ply, "rb").read() == open(bply, "rb").read()
            for name in a.dtype.names[2:]:
                x, y = a[name].astype(np.float64), b[name].astype(np.float64)
                both = np.isfinite(x) & np.isfinite(y)
                rel = np.abs(x[both] - y[both]) / np.maximum(np.abs(y[both]), 1e-12)
                r["baseline"]["max_relative_difference_" + name] = float(rel.max()) if rel.size else 0.0
                r["baseline"]["finite_mismatch_" + name] = int(np.sum(np.isfinite(x) != np.isfinite(y)))
            print("  baseline: pri %.1f s, peak %.0f MB, %d decodes" % (
                bwall, r["baseline"]["peak_mb"], bpri["images_decoded"]), flush=True)
        results["runs"].append(r)
        print("%d views: decode %.1f s (+ luminance %.1f s) on 2 threads; pri %.1f s, peak %.0f MB, %d decodes" % (
            n, dec["decode_seconds"], dec["decode_and_luminance_seconds"], wall, peak, pri["images_decoded"]),
            flush=True)

    os.makedirs(OUT, exist_ok=True)
    json.dump(results, open(os.path.join(OUT, "photos.json"), "w"), indent=2)
    sc = results["scene"]
    lines = ["%s faces; photos %s (%.1f MP), JPEG %.1f MB on average; %s." % (
                 "{:,}".format(sc["faces"]), sc["photo_size"], sc["megapixels"], sc["jpeg_mb_mean"], sc["source"]),
             "`meshnbv pri` with default settings (every view per face), 2 threads; decode: "
             "`bench/photos/photo_decode` on 2 threads, each photo once. PRI keeps one running sum per face over its "
             "views (SSD by default; no samples stored), 1 GB of them per block of faces, and decodes "
             "each photo once per block that sees it, through a 1 GB image cache; "
             "the share of its CPU time spent decoding is its decodes at photo_decode's cost per photo.", "",
             "| photos | decode (s) | decode + luminance (s) | `meshnbv pri` (s) | pri / decode | decodes in pri "
             "| their share of pri's CPU time | peak memory (MB) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in results["runs"]:
        lines.append("| %d | %.1f | %.1f | %.1f | %.2fx | %d | %.0f%% | %.0f |" % (
            r["views"], r["decode_seconds_2_threads"], r["decode_and_luminance_seconds_2_threads"],
            r["pri_wall_seconds"], r["wall_over_decode"], r["images_decoded"], 100 * r["decode_cpu_share"],
            r["peak_mb"]))
    worst = max(r["peak_mb"] for r in results["runs"])
    lines += ["", "Peak memory at most %.0f MB over %s photos: %s the %d MB target." % (
        worst, "/".join(str(n) for n in VIEW_COUNTS), "within" if worst <= TARGET_PEAK_MB else "ABOVE",
        TARGET_PEAK_MB)]
    if BASELINE:
        lines += ["", "Against the baseline build (%s), same scenes, same session:" % BASELINE_LABEL, "",
                  "| photos | pri (s) | baseline (s) | ratio | peak (MB) | baseline peak (MB) | decodes | baseline "
                  "decodes | max relative PRI difference | faces observed in one only |", "|---|---|---|---|---|---|---|---|---|---|"]
        for r in results["runs"]:
            b = r["baseline"]
            name = [k for k in b if k.startswith("max_relative_difference_")]
            rel = max((b[k] for k in name), default=0.0)
            mism = sum(b[k] for k in b if k.startswith("finite_mismatch_"))
            lines.append("| %d | %.1f | %.1f | %.2fx | %.0f | %.0f | %d | %d | %.1e | %d |" % (
                r["views"], r["pri_wall_seconds"], b["pri_wall_seconds"], r["pri_wall_seconds"] / b["pri_wall_seconds"],
                r["peak_mb"], b["peak_mb"], r["images_decoded"], b["images_decoded"], rel, mism))
    open(os.path.join(OUT, "photos.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
