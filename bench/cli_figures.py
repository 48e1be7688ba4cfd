#!/usr/bin/python3
"""Figures of docs/evaluation.md and docs/robustness.md about the test suite
and the CLI's limits, measured into bench/results/cli_figures.json:

- the wall time of the tests whose duration the docs quote (ctest's own
  timing, from its JUnit output);
- cli/extreme_options: how many runs it makes and how many succeed (its
  outcomes.tsv: label, exit code, milliseconds, message);
- `meshnbv synth city` at the smallest edge length its check allows (a
  quarter of the default) against the default, in the same run: faces,
  peak memory (max RSS) and wall time.

usage: bench/cli_figures.py [BUILD_DIR] [OUT.json]
       (default build, bench/results/cli_figures.json)

BUILD_DIR: a Release build with tests (MESHNBV_BUILD_TESTS=ON); the loop
tests need colmap. Standard library only. About 4 minutes on 2 cores.
"""
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

TESTS = ["core/EvalLoop.TinySyntheticLoopEndToEnd", "cli/loop", "cli/extreme_options"]


def ctest_times(build):
    """Runs TESTS with ctest; returns {name: {"status", "seconds"}}."""
    with tempfile.TemporaryDirectory() as tmp:
        junit = os.path.join(tmp, "junit.xml")
        regex = "^(" + "|".join(re.escape(t) for t in TESTS) + ")$"
        subprocess.run(["ctest", "--test-dir", build, "-R", regex, "--output-junit", junit],
                       check=False, stdout=subprocess.DEVNULL)
        out = {}
        for case in ET.parse(junit).getroot().iter("testcase"):
            out[case.get("name")] = {"status": case.get("status"), "seconds": float(case.get("time"))}
    return out


def extreme_outcomes(build):
    path = os.path.join(build, "tests", "cli_tmp", "extreme_options", "outcomes.tsv")
    rows = [line.rstrip("\n").split("\t") for line in open(path, encoding="utf-8", errors="replace")]
    codes = {}
    for r in rows:
        codes[r[1]] = codes.get(r[1], 0) + 1
    ms = sorted(int(r[2]) for r in rows)
    by_command = {}  # the first word of the label is the subcommand
    for r in rows:
        c = by_command.setdefault(r[0].split(" ")[0], {"runs": 0, "ms": 0})
        c["runs"] += 1
        c["ms"] += int(r[2])
    return {"runs": len(rows), "exit_codes": codes, "succeeded": codes.get("0", 0),
            "slowest_run_ms": ms[-1], "sum_of_run_ms": sum(ms), "by_command": by_command}


def synth_city(meshnbv, edge_length):
    """One `meshnbv synth city` run as a child process: faces, max RSS, time."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "city")
        cmd = [meshnbv, "synth", "city", "--out", out, "--views", "2", "--size", "64x48", "--quiet"]
        if edge_length:
            cmd += ["--edge-length", str(edge_length)]
        # Max RSS of this child alone: run it through a fresh Python so that
        # RUSAGE_CHILDREN holds nothing else.
        probe = ("import resource,subprocess,sys,time;t=time.monotonic();"
                 "subprocess.run(sys.argv[1:],check=True,stdout=subprocess.DEVNULL);"
                 "print(time.monotonic()-t, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
        r = subprocess.run([sys.executable, "-c", probe] + cmd, check=True, capture_output=True, text=True)
        seconds, rss_kb = r.stdout.split()
        faces = None
        with open(os.path.join(out, "truth.ply"), "rb") as f:
            for raw in f:
                m = re.match(rb"element face (\d+)", raw)
                if m:
                    faces = int(m.group(1))
                if raw.strip() == b"end_header":
                    break
    return {"command": " ".join(["meshnbv"] + cmd[1:3] + cmd[5:]), "faces": faces,
            "max_rss_mb": int(rss_kb) / 1024.0, "seconds": float(seconds)}


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    out_path = sys.argv[2] if len(sys.argv) > 2 else "bench/results/cli_figures.json"
    meshnbv = os.path.join(build, "apps", "meshnbv")
    start = time.monotonic()
    result = {
        "written_by": "bench/cli_figures.py",
        "date": time.strftime("%Y-%m-%dT%H:%M:%S+00:00", time.gmtime()),
        "host": platform.node(),
        "cpus": os.cpu_count(),
        "load_average_at_start": os.getloadavg(),
        "colmap": shutil.which("colmap") is not None,
    }
    result["tests"] = ctest_times(build)
    result["extreme_options"] = extreme_outcomes(build)
    default = synth_city(meshnbv, 0)
    smallest = synth_city(meshnbv, 0.2)  # the city's default edge 0.8 m / 4
    result["synth_city"] = {"default_edge": default, "edge_0.2": smallest,
                            "faces_ratio": smallest["faces"] / default["faces"]}
    result["seconds"] = time.monotonic() - start
    with open(out_path, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
