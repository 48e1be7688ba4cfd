"""Summary of bench/against_baseline/run.sh: per (threads, views) the median
over rounds of BM_Pri's samples/s (wall) and cpu_samples_per_s for the
baseline and this tree, their ratio, and the ratio of 20 to 5 views per face
within each build; BM_CandidateEvaluations' evaluations/s likewise. Writes
summary.json and table.md.
Usage: table.py OUT BASE_COMMIT NEW_COMMIT"""
import glob
import json
import os
import re
import statistics
import sys

out, base_commit, new_commit = sys.argv[1:4]
runs = {"base": {}, "new": {}}
context = None
nbv = {"base": {}, "new": {}}
for path in sorted(glob.glob(os.path.join(out, "bench_nbv_*_*.json"))):
    which = re.match(r"bench_nbv_(base|new)_\d+\.json", os.path.basename(path)).group(1)
    for b in json.load(open(path))["benchmarks"]:
        m = re.match(r"BM_CandidateEvaluations/(\d+)", b["name"])
        if m:
            nbv[which].setdefault(int(m.group(1)), []).append(b["evaluations_per_s"])
for path in sorted(glob.glob(os.path.join(out, "bench_pri_*_*.json"))):
    which = re.match(r"bench_pri_(base|new)_\d+\.json", os.path.basename(path)).group(1)
    doc = json.load(open(path))
    context = context or doc["context"]
    for b in doc["benchmarks"]:
        m = re.match(r"BM_Pri/threads:(\d+)/views:(\d+)/spp:8", b["name"])
        if not m:
            continue
        key = (int(m.group(1)), int(m.group(2)))
        runs[which].setdefault(key, []).append((b["samples_per_s"], b["cpu_samples_per_s"]))

rows = []
for key in sorted(runs["new"]):
    med = {w: (statistics.median(x[0] for x in runs[w][key]), statistics.median(x[1] for x in runs[w][key]))
           for w in ("base", "new") if key in runs[w]}
    rows.append({"threads": key[0], "views_per_face": key[1], "rounds": len(runs["new"][key]),
                 "base_samples_per_s": med["base"][0], "new_samples_per_s": med["new"][0],
                 "base_cpu_samples_per_s": med["base"][1], "new_cpu_samples_per_s": med["new"][1],
                 "speedup_wall": med["new"][0] / med["base"][0], "speedup_cpu": med["new"][1] / med["base"][1]})


def per_views(which, threads, views, field):
    return next(r[f"{which}_{field}"] for r in rows if r["threads"] == threads and r["views_per_face"] == views)


ratios = []
for t in sorted({r["threads"] for r in rows}):
    for which in ("base", "new"):
        ratios.append({"threads": t, "build": which,
                       "20_over_5_wall": per_views(which, t, 20, "samples_per_s") / per_views(which, t, 5, "samples_per_s"),
                       "20_over_5_cpu": per_views(which, t, 20, "cpu_samples_per_s") / per_views(which, t, 5, "cpu_samples_per_s")})
energy = [{"threads": t, "base_evaluations_per_s": statistics.median(nbv["base"][t]),
           "new_evaluations_per_s": statistics.median(nbv["new"][t]),
           "speedup": statistics.median(nbv["new"][t]) / statistics.median(nbv["base"][t])}
          for t in sorted(nbv["new"]) if t in nbv["base"]]
summary = {"base_commit": base_commit, "new_commit": new_commit, "machine": {
    k: context.get(k) for k in ("host_name", "num_cpus", "mhz_per_cpu", "date")}, "rows": rows, "ratios": ratios, "energy": energy}
json.dump(summary, open(os.path.join(out, "summary.json"), "w"), indent=2)
with open(os.path.join(out, "table.md"), "w") as f:
    f.write(f"PRI sampling + comparison (BM_Pri), city of > 200k faces, 20 views 640x480, r = 8; baseline {base_commit} "
            f"against {new_commit}; medians of {rows[0]['rounds']} alternating "
            "rounds (bench/against_baseline/run.sh).\n\n")
    f.write("| threads | views per face | baseline M samples/s | new M samples/s | speed-up (wall) | speed-up (CPU) |\n")
    f.write("|---|---|---|---|---|---|\n")
    for r in rows:
        f.write(f"| {r['threads']} | {r['views_per_face']} | {r['base_samples_per_s'] / 1e6:.1f} | "
                f"{r['new_samples_per_s'] / 1e6:.1f} | {r['speedup_wall']:.2f} | {r['speedup_cpu']:.2f} |\n")
    f.write("\n| threads | build | samples/s at 20 views over 5 (wall) | (CPU) |\n|---|---|---|---|\n")
    for q in ratios:
        f.write(f"| {q['threads']} | {q['build']} | {q['20_over_5_wall']:.2f} | {q['20_over_5_cpu']:.2f} |\n")
    f.write("\n| threads | baseline k evaluations/s | new k evaluations/s | speed-up |\n|---|---|---|---|\n")
    for q in energy:
        f.write(f"| {q['threads']} | {q['base_evaluations_per_s'] / 1e3:.0f} | {q['new_evaluations_per_s'] / 1e3:.0f} | "
                f"{q['speedup']:.2f} |\n")
print(open(os.path.join(out, "table.md")).read())
