#!/usr/bin/python3
"""The measurements of bench/scale/run.sh (read it first). Arguments: the
folder holding meshnbv and meshnbv-mpi, a scratch folder, the results folder."""
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from ply_mesh import read_ply, split_longest_edge, write_ply  # noqa: E402

BIN, WORK, OUT = sys.argv[1:4]
MESHNBV = os.path.join(BIN, "meshnbv")
MPI = os.path.join(BIN, "meshnbv-mpi")
# The survey: 128 nadir photos of 512x384 (an 11 x 12 grid), so that each
# photo sees a small part of the city and a rank's tiles need part of them.
VIEWS, SIZE = 128, (512, 384)


def run(cmd, **kw):
    t = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    wall = time.perf_counter() - t
    if p.returncode != 0:
        sys.exit("bench/scale: %s failed: %s" % (" ".join(cmd), p.stderr.strip()[-2000:]))
    return wall, p.stdout, p.stderr


def same(a, b):
    return open(a, "rb").read() == open(b, "rb").read()


def scene_with(src_json, dst_json, mesh, views=None, stride=1, scale=1):
    """The scene of `src_json` on `mesh`: its first `views` views, or every
    `stride`-th; with `scale` 2, the photos upsampled twice (upscaled()) and
    the intrinsics with them (pixel centres at integers: u' = 2u + 0.5)."""
    s = json.load(open(src_json))
    base = os.path.dirname(os.path.abspath(src_json))
    s["mesh"] = os.path.abspath(mesh)
    for v in s["views"]:
        v["image"] = os.path.join(base, v["image"])
        if scale == 2:
            v["image"] = upscaled(v["image"])
            c = v["camera"]
            c["fx"], c["fy"], c["cx"], c["cy"] = 2 * c["fx"], 2 * c["fy"], 2 * c["cx"] + 0.5, 2 * c["cy"] + 0.5
            c["width"], c["height"] = 2 * c["width"], 2 * c["height"]
    if views is not None:
        s["views"] = s["views"][:views]
    s["views"] = s["views"][::stride]
    json.dump(s, open(dst_json, "w"))


def upscaled(path):
    """`path` upsampled twice (bicubic), cached beside it."""
    from PIL import Image
    out = os.path.join(os.path.dirname(path), "up2_" + os.path.basename(path))
    if not os.path.exists(out):
        im = Image.open(path)
        im.resize((2 * im.width, 2 * im.height), Image.BICUBIC).save(out)
    return out


def main():
    results = {"machine": {"cpus": os.cpu_count(), "platform": platform.platform()}, "runs": []}
    city = os.path.join(WORK, "city_survey")
    if not os.path.exists(os.path.join(city, "scene.json")):
        shutil.rmtree(city, ignore_errors=True)
        run([MESHNBV, "synth", "city", "--edge-length", "0.2", "--views", str(VIEWS), "--size", "%dx%d" % SIZE,
             "--layout", "grid", "--out", city, "--quiet"])
    big = os.path.join(WORK, "big.ply")
    if not os.path.exists(big):
        v, f = read_ply(os.path.join(city, "degraded.ply"))
        v2, f2 = split_longest_edge(v, f)
        write_ply(big, v2, f2, "bench/scale")
    scene = os.path.join(WORK, "big.json")
    scene_with(os.path.join(city, "scene.json"), scene, big)
    faces = len(read_ply(big)[1])
    results["scene"] = {"faces": faces, "views": VIEWS, "image": "%dx%d" % SIZE, "pixels": SIZE[0] * SIZE[1], "from": "synthetic city, edge 0.2 m, "
                        "each triangle split in two along its longest edge; a survey flight of nadir photos "
                        "(synth --layout grid)"}
    print("scene: %d faces, %d views" % (faces, VIEWS), flush=True)

    # 1. One process against 1, 2, 4 ranks.
    one = os.path.join(WORK, "one.ply")
    wall, out, err = run(["/usr/bin/time", "-f", "peak_kb %M", MESHNBV, "pri", scene, "--out", one,
                          "--overwrite", "--quiet"])
    peak = float(re.search(r"peak_kb (\d+)", err).group(1)) / 1024
    results["runs"].append({"what": "meshnbv pri", "ranks": 0, "seconds": wall, "peak_mb": [peak]})
    print("meshnbv: %.1f s, %.0f MB" % (wall, peak), flush=True)
    # Each rank with every core (TBB threads), then each rank with one
    # thread: the speed-up over ranks that this 2-core machine can show.
    for n, threads in ((1, 0), (2, 0), (4, 0), (1, 1), (2, 1)):
        path = os.path.join(WORK, "np%d.ply" % n)
        # --bind-to none: Open MPI binds each rank to one core by default
        # (np <= 2), which would leave TBB one thread.
        wall, out, err = run(["mpirun", "-q", "--oversubscribe", "--bind-to", "none", "-np", str(n), MPI, "pri",
                              scene, "--out", path, "--overwrite", "--progress", "json"] +
                             (["--threads", str(threads)] if threads else []))
        ranks = re.findall(r"rank (\d+) ([\d.]+) tiles, ([\d.]+) faces, ([\d.]+) images decoded, ([\d.]+) s, "
                           r"peak (\d+) MB, (\d+) threads", err)
        if len(ranks) != n:
            sys.exit("bench/scale: no per-rank line for %d ranks in: %s" % (n, err[-2000:]))
        results["runs"].append({
            "what": "meshnbv-mpi pri" if not threads else "meshnbv-mpi pri, 1 thread per rank",
            "ranks": n, "seconds": wall, "identical": same(one, path),
            "tiles": [float(r[1]) for r in ranks], "faces": [float(r[2]) for r in ranks],
            "images_decoded": [float(r[3]) for r in ranks], "rank_seconds": [float(r[4]) for r in ranks],
            "peak_mb": [float(r[5]) for r in ranks], "threads": [int(r[6]) for r in ranks]})
        print("np %d (%s threads): %.1f s, peaks %s MB, images %s, identical %s" % (
            n, threads or "all", wall, [r[5] for r in ranks], [r[3] for r in ranks], same(one, path)), flush=True)

    # 2. Incremental: a local edit and an added view.
    v, f = read_ply(big)
    # A dent of radius 4 m around the surface point nearest to a point
    # above the centre, inside the bounding box (which then stays the same).
    lo, hi = v.min(axis=0), v.max(axis=0)
    aim = 0.5 * (lo + hi) + np.array([0, 0, 0.2 * (hi[2] - lo[2])])
    centre = v[np.argmin(np.linalg.norm(v - aim, axis=1))]
    near = np.linalg.norm(v - centre, axis=1) < 4.0
    edited = v.copy()
    edited[near, 2] -= 0.3
    assert (edited.min(axis=0) == lo).all() and (edited.max(axis=0) == hi).all(), "the dent moved the bounding box"
    edited_ply = os.path.join(WORK, "edited.ply")
    write_ply(edited_ply, edited, f, "bench/scale")
    edited_scene = os.path.join(WORK, "edited.json")
    scene_with(os.path.join(city, "scene.json"), edited_scene, edited_ply)
    fewer = os.path.join(WORK, "fewer.json")
    scene_with(os.path.join(city, "scene.json"), fewer, big, views=VIEWS - 1)
    fewer_ply = os.path.join(WORK, "fewer.ply")
    run([MESHNBV, "pri", fewer, "--out", fewer_ply, "--overwrite", "--quiet"])
    for name, target, previous in (("local edit", edited_scene, one), ("one view added", scene, fewer_ply)):
        full = os.path.join(WORK, "full.ply")
        inc = os.path.join(WORK, "inc.ply")
        t_full, _, _ = run([MESHNBV, "pri", target, "--out", full, "--overwrite", "--quiet"])
        t_inc, out, _ = run([MESHNBV, "pri", target, "--previous", previous, "--out", inc, "--overwrite",
                             "--quiet"])
        m = re.search(r"recomputed (\d+) of (\d+) faces", out)
        sel = re.search(r"views selected again for (\d+) faces", out)
        results["runs"].append({"what": "incremental: " + name, "full_seconds": t_full,
                                "incremental_seconds": t_inc, "recomputed": int(m.group(1)),
                                "reselected": int(sel.group(1)),
                                "faces": int(m.group(2)), "identical": same(full, inc),
                                "edited_vertices": int(near.sum()) if name == "local edit" else 0})
        print("%s: full %.1f s, incremental %.1f s, recomputed %s of %s, identical %s" % (
            name, t_full, t_inc, m.group(1), m.group(2), same(full, inc)), flush=True)

    # 3. Cost-model points (one process, 2 threads): every 4th, 2nd and
    # every photo at their size, every 2nd and every photo upsampled twice.
    # And every photo on the city's own mesh (half the faces: the split
    # undone), for the part of the time that grows with the faces alone.
    base = os.path.join(city, "degraded.ply")
    for stride, scale, mesh in ((4, 1, big), (2, 1, big), (1, 1, big), (2, 2, big), (1, 2, big), (1, 1, base)):
        sub = os.path.join(WORK, "cost_%d_%d_%s.json" % (stride, scale, os.path.basename(mesh)))
        scene_with(os.path.join(city, "scene.json"), sub, mesh, stride=stride, scale=scale)
        faces = len(read_ply(mesh)[1])
        views = len(json.load(open(sub))["views"])
        summary = os.path.join(WORK, "cost_summary.json")
        ply = os.path.join(WORK, "views.ply")
        t, _, err = run(["/usr/bin/time", "-f", "peak_kb %M", MESHNBV, "pri", sub, "--out", ply, "--json", summary,
                         "--overwrite", "--quiet"])
        s = json.load(open(summary))
        per_face = read_ply(ply, fields=True)
        seen = per_face["pri_views"] >= 2
        pixels = SIZE[0] * SIZE[1] * scale * scale
        results["runs"].append({"what": "cost point", "views": views, "faces": faces, "seconds": t,
                                "image": "%dx%d" % (SIZE[0] * scale, SIZE[1] * scale), "pixels": pixels,
                                "peak_mb": float(re.search(r"peak_kb (\d+)", err).group(1)) / 1024,
                                "observed": s["faces"]["observed"], "pri_seconds": s["seconds"],
                                "images_decoded": s["images_decoded"],
                                "face_views": float(per_face["pri_views"].sum()),
                                "samples": float((per_face["pri_views"] * per_face["pri_samples"]).sum()),
                                "mean_views": float(per_face["pri_views"].mean()),
                                "mean_samples": float(per_face["pri_samples"][seen].mean())})
        print("cost point: %d faces, %d views of %dx%d, %.1f s" % (faces, views, SIZE[0] * scale, SIZE[1] * scale, t),
              flush=True)
    # Decoding alone, on one thread: the photos at both sizes read with
    # PIL (Debian's libpng, the library OpenCV decodes PNG with).
    from PIL import Image
    for scale in (1, 2):
        paths = [v["image"] for v in json.load(open(os.path.join(WORK, "cost_1_%d_big.ply.json" % scale)))["views"]][:32]
        t = time.perf_counter()
        for path in paths:
            Image.open(path).load()
        seconds = time.perf_counter() - t
        pixels = len(paths) * SIZE[0] * SIZE[1] * scale * scale
        results["runs"].append({"what": "decode", "image": "%dx%d" % (SIZE[0] * scale, SIZE[1] * scale),
                                "photos": len(paths), "seconds": seconds, "pixels": pixels,
                                "seconds_per_megapixel": seconds / pixels * 1e6})
        print("decode: %d photos of %dx%d, %.2f s" % (len(paths), SIZE[0] * scale, SIZE[1] * scale, seconds),
              flush=True)
    json.dump(results, open(os.path.join(OUT, "runs.json"), "w"), indent=1)
    table(results)
    subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(os.path.abspath(__file__)), "model.py")],
                   check=True)


def table(results):
    rows = ["| run | ranks | wall s | peak MB per rank | images decoded per rank | faces per rank | identical |",
            "|---|---|---|---|---|---|---|"]
    for r in results["runs"]:
        if r["what"].startswith("meshnbv"):
            rows.append("| %s | %s | %.1f | %s | %s | %s | %s |" % (
                r["what"], r["ranks"] or "-", r["seconds"], ", ".join("%.0f" % x for x in r["peak_mb"]),
                ", ".join("%.0f" % x for x in r.get("images_decoded", [])) or "-",
                ", ".join("%.0f" % x for x in r.get("faces", [])) or "-",
                {True: "yes", False: "NO"}.get(r.get("identical"), "reference")))
    rows += ["", "| incremental | full s | incremental s | recomputed faces | views selected again | of | identical |",
             "|---|---|---|---|---|---|---|"]
    for r in results["runs"]:
        if r["what"].startswith("incremental"):
            rows.append("| %s | %.1f | %.1f | %d (%.1f%%) | %d (%.1f%%) | %d | %s |" % (
                r["what"][13:], r["full_seconds"], r["incremental_seconds"], r["recomputed"],
                100.0 * r["recomputed"] / r["faces"], r["reselected"], 100.0 * r["reselected"] / r["faces"],
                r["faces"], "yes" if r["identical"] else "NO"))
    rows += ["", "| cost point: views | image | faces | mean views per face | mean samples per face-view | "
             "images decoded | wall s | PRI s | peak MB |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in results["runs"]:
        if r["what"] == "cost point":
            rows.append("| %d | %s | %d | %.2f | %.1f | %d | %.1f | %.1f | %.0f |" % (
                r["views"], r["image"], r["faces"], r["mean_views"], r["mean_samples"], r["images_decoded"],
                r["seconds"], r["pri_seconds"], r["peak_mb"]))
    s = results["scene"]
    text = ("Scene: %d faces (%s), %d views of %s. Machine: %d cores.\n\n" % (
        s["faces"], s["from"], s["views"], s["image"], results["machine"]["cpus"])) + "\n".join(rows) + "\n"
    open(os.path.join(OUT, "table.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main()
