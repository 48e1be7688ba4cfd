#!/usr/bin/env python3
"""Tables of bench/results/simd/bench_pri_simd.json (medians of the
repetitions): PRI's sampling + comparison rate with the scalar and the
vector kernels, the 5-to-20-views ratio, and the share of the bilinear
peaks (scalar: the fastest of patterns 0-2; vectorised: of 3-4). Rates per
CPU second at 1 thread (immune to waiting behind other load), per wall
second at 2. Usage: bench/simd/table.py [json]"""
import json
import re
import sys

path = sys.argv[1] if len(sys.argv) > 1 else "bench/results/simd/bench_pri_simd.json"
data = json.load(open(path))
med = {b["run_name"]: b for b in data["benchmarks"] if b.get("aggregate_name") == "median"}
labels = {b["run_name"]: b.get("label", "") for b in data["benchmarks"] if b.get("run_type") == "iteration"}


def args(name):
    return dict((k, int(v)) for k, v in re.findall(r"(\w+):(\d+)", name))


def find(prefix, **want):
    for name, b in med.items():
        if name.startswith(prefix + "/") and all(args(name).get(k) == v for k, v in want.items()):
            return name, b
    return None, None


def rate(name, b, threads):
    if name.startswith("BM_Pri/"):
        return b["cpu_samples_per_s"] if threads == 1 else b["samples_per_s"]
    # The peaks: per CPU second of the main thread at 1 thread.
    return b["samples_per_s"] * (b["real_time"] / b["cpu_time"] if threads == 1 else 1.0)


def peak(threads, patterns):
    best = None
    for p in patterns:
        name, b = find("BM_BilinearPeak", threads=threads, pattern=p)
        if b and (best is None or rate(name, b, threads) > best[0]):
            best = (rate(name, b, threads), p, labels.get(name, ""))
    return best


ctx = data["context"]
out = [f"bench_pri of {ctx['date']}, {ctx['num_cpus']} CPUs, medians of 3 (random interleaving); "
       "city of 219k faces, 20 views of 640x480, r = 8 (45 samples per face and view). "
       "Rates in samples/s: per CPU second at 1 thread, per wall second at 2.", "",
       "| threads | views/face | scalar kernels | vector kernels | vector / scalar | "
       "% of scalar peak | % of vectorised peak |",
       "|---|---|---|---|---|---|---|"]
summary = {}
for threads in (1, 2):
    sp, vp = peak(threads, (0, 1, 2)), peak(threads, (3, 4))
    for views in (5, 20):
        ns, s = find("BM_Pri", threads=threads, views=views, spp=8, simd=0)
        nv, v = find("BM_Pri", threads=threads, views=views, spp=8, simd=1)
        if not (s and v and sp and vp):
            continue
        rs, rv = rate(ns, s, threads), rate(nv, v, threads)
        summary[(threads, views)] = rv
        out.append(f"| {threads} | {views} | {rs / 1e6:.1f} M | {rv / 1e6:.1f} M ({labels.get(nv, '')}) | "
                   f"{rv / rs:.2f}x | {100 * rv / sp[0]:.0f}% | {100 * rv / vp[0]:.0f}% |")
    if sp and vp:
        out.append(f"| {threads} | peaks | {sp[0] / 1e6:.1f} M (pattern {sp[1]}) | "
                   f"{vp[0] / 1e6:.1f} M (pattern {vp[1]}, {vp[2]}) | {vp[0] / sp[0]:.2f}x | | |")
out.append("")
for threads in (1, 2):
    if (threads, 5) in summary and (threads, 20) in summary:
        r = summary[(threads, 20)] / summary[(threads, 5)]
        out.append(f"{threads} thread{'s' if threads > 1 else ''}, vector kernels: 20 views per face at {100 * r:.0f}% of the rate at 5 "
                   f"(target: within 15%, i.e. >= 85%).")
print("\n".join(out))
