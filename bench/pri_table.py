#!/usr/bin/env python3
"""Markdown table of bench/results/bench_pri.json (medians of the
repetitions) with the ratios of issue 4: compute_pri's sampling + comparison
rate over the OpenCV warping baseline and over the bilinear sampling peak,
for the same thread count and views per face. Usage:
bench/pri_table.py [bench/results/bench_pri.json]"""
import json
import re
import sys

path = sys.argv[1] if len(sys.argv) > 1 else "bench/results/bench_pri.json"
data = json.load(open(path))
med = {}
for b in data["benchmarks"]:
    if b.get("aggregate_name") == "median":
        med[b["run_name"]] = b


def args(name):
    a = dict((k, int(v)) for k, v in re.findall(r"(\w+):(\d+)", name))
    if name.startswith("BM_Pri"):
        a.setdefault("simd", 1)  # runs before the kernels' argument: the only kernels then
    return a


def find(prefix, **want):
    for name, b in med.items():
        if name.startswith(prefix + "/") and all(args(name).get(k) == v for k, v in want.items()):
            return b
    return None


def m(x):
    return f"{x / 1e6:.1f} M"


def k(x):
    return f"{x / 1e3:.0f} k"


ctx = data["context"]
print(f"date {ctx['date']}, {ctx['num_cpus']} CPUs at {ctx['mhz_per_cpu']} MHz, host {ctx['host_name']}\n")
print("| threads | views/face | spp | compute_pri: sampling+comparison | faces/s | samples/s | "
      "end to end (selection) | baseline (OpenCV warp) samples/s | x baseline | "
      "bilinear peak samples/s | % of peak |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for b in sorted((b for n, b in med.items() if n.startswith("BM_Pri/") and args(n)["simd"] == 1),
                key=lambda b: (args(b["run_name"])["spp"] == 0, args(b["run_name"])["threads"],
                               args(b["run_name"])["views"])):
    a = args(b["run_name"])
    base = find("BM_Baseline", threads=a["threads"], views=a["views"]) if a["spp"] == 8 else None
    peaks = [find("BM_BilinearPeak", threads=a["threads"], pattern=pt) for pt in (0, 1, 2)]
    peak = max((p for p in peaks if p), key=lambda p: p["samples_per_s"])
    row = [str(a["threads"]), str(a["views"]), str(a["spp"]) if a["spp"] else "auto",
           f"{b['real_time']:.0f} ms", k(b["faces_per_s"]), m(b["samples_per_s"]),
           f"{b['end_to_end_s'] * 1e3:.0f} ms ({b['select_s'] * 1e3:.0f} ms)"]
    if base:
        row += [m(base["samples_per_s"]), f"{b['samples_per_s'] / base['samples_per_s']:.1f}x"]
    else:
        row += ["-", "-"]
    row += [m(peak["samples_per_s"]), f"{100 * b['samples_per_s'] / peak['samples_per_s']:.0f}%"]
    print("| " + " | ".join(row) + " |")


def cpu_rate(b):  # samples per second of main-thread CPU time
    return b["samples_per_s"] * b["real_time"] / b["cpu_time"]


print("\n1 thread, CPU time (immune to waiting behind other load):\n")
print("| views/face | compute_pri samples/CPU-s | baseline | x baseline | bilinear peak | % of peak |")
print("|---|---|---|---|---|---|")
peak1 = max((p for p in (find("BM_BilinearPeak", threads=1, pattern=pt) for pt in (0, 1, 2)) if p),
            key=cpu_rate, default=None)
for v in (5, 10, 20):
    b = find("BM_Pri", threads=1, views=v, spp=8, simd=1)
    base = find("BM_Baseline", threads=1, views=v)
    if not (b and base and peak1):
        continue
    print(f"| {v} | {m(b['cpu_samples_per_s'])} | {m(cpu_rate(base))} | "
          f"{b['cpu_samples_per_s'] / cpu_rate(base):.1f}x | {m(cpu_rate(peak1))} | "
          f"{100 * b['cpu_samples_per_s'] / cpu_rate(peak1):.0f}% |")
cold = [b for n, b in med.items() if n.startswith("BM_PriColdCache/")]
for b in cold:
    a = args(b["run_name"])
    print(f"\ncold image cache, end to end, {a['threads']} threads, {a['views']} views, spp {a['spp']}: "
          f"{b['real_time']:.0f} ms ({k(b['faces_per_s'])} faces/s)")
for n, b in sorted(med.items()):
    if n.startswith("BM_BilinearPeak/"):
        print(f"{n}: {m(b['samples_per_s'])} samples/s, {m(cpu_rate(b))} samples/CPU-s")
    if n.startswith("BM_Baseline/"):
        print(f"{n}: {b['real_time']:.0f} ms, {k(b['faces_per_s'])} faces/s, {m(b['samples_per_s'])} samples/s, "
              f"corr with core {b['corr_with_core']:.5f}, median rel diff {b['median_rel_diff']:.4f}")
