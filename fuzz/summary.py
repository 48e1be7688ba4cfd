#!/usr/bin/env python3
"""Sums up libFuzzer logs (fuzz/run.sh): per target the executions, speed,
coverage (edges, features) at start and end, when coverage last grew, and
any finding. Usage: summary.py LOG_DIR [target...]; prints a Markdown table."""
import os
import re
import sys

LINE = re.compile(r"^#(\d+)\s+(\w+)\s+cov: (\d+) ft: (\d+) corp: (\d+)/")


def summarize(path):
    first = last = None
    last_cov_growth = 0
    cov = -1
    stats = {}
    findings = []
    for raw in open(path, errors="replace"):
        m = LINE.match(raw)
        if m:
            execs, kind, c, ft, corp = int(m[1]), m[2], int(m[3]), int(m[4]), int(m[5])
            if first is None and kind == "INITED":
                first = (c, ft, corp)
            if c > cov:
                if cov >= 0:
                    last_cov_growth = execs
                cov = c
            last = (execs, c, ft, corp)
        elif raw.startswith("stat::"):
            key, _, value = raw[len("stat::"):].partition(":")
            stats[key.strip(": ")] = value.strip()
        elif ("ERROR: AddressSanitizer" in raw or "ERROR: LeakSanitizer" in raw
              or "runtime error:" in raw or "ERROR: libFuzzer" in raw
              or "fuzz: check failed" in raw or "terminate called" in raw):
            findings.append(raw.strip())
    return first, last, last_cov_growth, stats, findings


def main():
    log_dir = sys.argv[1]
    targets = sys.argv[2:] or sorted(f[:-4] for f in os.listdir(log_dir) if f.endswith(".log"))
    print("| target | execs | exec/s | cov start → end | ft end | corpus | cov last grew at | findings |")
    print("|---|---|---|---|---|---|---|---|")
    for t in targets:
        path = os.path.join(log_dir, t + ".log")
        if not os.path.exists(path):
            print("| %s | no log | | | | | | |" % t)
            continue
        first, last, grew, stats, findings = summarize(path)
        execs = int(stats.get("number_of_executed_units", last[0] if last else 0))
        speed = stats.get("average_exec_per_sec", "?")
        start = "%d" % first[0] if first else "?"
        end = "%d" % last[1] if last else "?"
        share = "exec %d (%.0f%% of the run)" % (grew, 100.0 * grew / execs) if execs else "?"
        print("| %s | %d | %s | %s → %s | %s | %s | %s | %s |" % (
            t, execs, speed, start, end, last[2] if last else "?", last[3] if last else "?",
            share, "; ".join(findings[:2]) or "none"))


if __name__ == "__main__":
    main()
