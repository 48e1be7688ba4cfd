#!/usr/bin/env bash
# Build time from scratch with and without MESHNBV_UNITY_BUILD, in one
# session (the machine is shared: the ratio comes from the same run). Each
# round configures a fresh build folder per mode -- Release, the libraries,
# the CLI, meshnbv-mpi, the tests and the benchmarks (no VTK, MeshLab or
# ParaView: their sources are not batched) -- builds it with every core and
# reads ninja's log: wall time and the CPU seconds of the compile steps per
# target. Modes alternate (off, on, on, off, ...).
# Writes bench/results/build/unity.json and unity.md.
# Usage: bench/build/unity.sh [rounds]   (WORK=... for the build folders)
set -euo pipefail
cd "$(dirname "$0")/../.."
ROUNDS=${1:-1}
WORK=${WORK:-/tmp/meshnbv_unity_bench}
OUT=bench/results/build
mkdir -p "$OUT" "$WORK"
runs=()
for round in $(seq 1 "$ROUNDS"); do
  if [ $((round % 2)) = 1 ]; then modes="OFF ON"; else modes="ON OFF"; fi
  for mode in $modes; do
    dir=$WORK/$mode
    rm -rf "$dir"
    cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_UNITY_BUILD=$mode \
      -DMESHNBV_BUILD_TESTS=ON -DMESHNBV_BUILD_BENCH=ON -DMESHNBV_BUILD_MPI=ON >/dev/null
    start=$(date +%s.%N)
    cmake --build "$dir" -j"$(nproc)" >/dev/null
    end=$(date +%s.%N)
    cp "$dir/.ninja_log" "$WORK/ninja_${mode}_$round.log"
    runs+=("$mode $round $(echo "$end - $start" | bc)")
    echo "unity $mode round $round: $(echo "$end - $start" | bc) s"
  done
done
/usr/bin/python3 - "$OUT" "$WORK" "$(nproc)" "$(git rev-parse --short HEAD)" "${runs[@]}" <<'PY'
import json, sys, collections, datetime
out, work, cores, commit = sys.argv[1:5]
rows = []
for r in sys.argv[5:]:
    mode, rnd, wall = r.split()
    per = collections.Counter()
    for line in open(f"{work}/ninja_{mode}_{rnd}.log"):
        if line.startswith("#"):
            continue
        start, end, _, target, _ = line.rstrip("\n").split("\t")
        if ".dir/" not in target:
            continue
        per[target.split(".dir/")[0].replace("CMakeFiles/", "")] += (int(end) - int(start)) / 1000
    rows.append({"unity": mode == "ON", "round": int(rnd), "wall_seconds": float(wall),
                 "compile_cpu_seconds": round(sum(per.values()), 1),
                 "per_target_cpu_seconds": {k: round(v, 1) for k, v in sorted(per.items())}})
def mean(key, unity):
    v = [r[key] for r in rows if r["unity"] == unity]
    return sum(v) / len(v)
summary = {"date": datetime.date.today().isoformat(), "commit": commit, "cores": int(cores),
           "wall_ratio_unity_to_separate": round(mean("wall_seconds", True) / mean("wall_seconds", False), 3),
           "cpu_ratio_unity_to_separate": round(mean("compile_cpu_seconds", True) / mean("compile_cpu_seconds", False), 3),
           "runs": rows}
json.dump(summary, open(f"{out}/unity.json", "w"), indent=1)
targets = sorted({t for r in rows for t in r["per_target_cpu_seconds"]},
                 key=lambda t: -max(r["per_target_cpu_seconds"].get(t, 0) for r in rows))
with open(f"{out}/unity.md", "w") as f:
    f.write(f"# Build from scratch, unity on and off\n\nWritten by bench/build/unity.sh on {summary['date']} "
            f"(commit {commit}, {cores} cores). Release; libraries, CLI, meshnbv-mpi, tests, benchmarks.\n\n")
    f.write("| | " + " | ".join(f"{'unity' if r['unity'] else 'separate'} (round {r['round']})" for r in rows) + " |\n")
    f.write("|---|" + "---|" * len(rows) + "\n")
    f.write("| wall (s) | " + " | ".join(f"{r['wall_seconds']:.0f}" for r in rows) + " |\n")
    f.write("| compile CPU (s) | " + " | ".join(f"{r['compile_cpu_seconds']:.0f}" for r in rows) + " |\n")
    for t in targets[:12]:
        f.write(f"| {t} | " + " | ".join(f"{r['per_target_cpu_seconds'].get(t, 0):.0f}" for r in rows) + " |\n")
    f.write(f"\nUnity / separate: wall {summary['wall_ratio_unity_to_separate']}, "
            f"compile CPU {summary['cpu_ratio_unity_to_separate']}.\n")
print(json.dumps({k: v for k, v in summary.items() if k != "runs"}))
PY
