"""Summary of bench/mesher/run.sh: per (scene, threads) the median over
rounds of the mesher's seconds for the baseline and this tree, their ratio,
this tree's phases, and whether both made the same surface (faces,
tetrahedra and the vertex checksum). Writes summary.json and table.md.
Usage: table.py OUT BASE_COMMIT NEW_COMMIT"""
import json
import os
import statistics
import sys

out, base_commit, new_commit = sys.argv[1:4]
runs = [json.loads(line) for line in open(os.path.join(out, "runs.jsonl")) if line.strip()]
keys = sorted({(r["scene"], r["threads"]) for r in runs})
rows = []
for scene, threads in keys:
    sel = {w: [r for r in runs if r["scene"] == scene and r["threads"] == threads and r["build"] == w]
           for w in ("base", "new")}
    med = {w: statistics.median(r["seconds"] for r in sel[w]) for w in sel}
    phases = {p: statistics.median(r[p] for r in sel["new"])
              for p in ("seconds_delaunay", "seconds_visibility", "seconds_labelling")}
    same = all(sel["base"][0][k] == r[k] for r in sel["base"] + sel["new"]
               for k in ("faces", "tetrahedra", "rays", "vertex_checksum"))
    # Each build on its own: the same surface on every thread count and round.
    stable = all(all(sel[w][0][k] == r[k] for r in sel[w] for k in ("faces", "vertex_checksum"))
                 for w in sel)
    rows.append({"scene": scene, "threads": threads, "points": sel["new"][0]["points"],
                 "rounds": len(sel["new"]), "base_seconds": med["base"], "new_seconds": med["new"],
                 "speedup": med["base"] / med["new"], "new_phases": phases, "same_surface": same,
                 "same_within_each_build": stable, "base_faces": sel["base"][0]["faces"],
                 "faces": sel["new"][0]["faces"], "tetrahedra": sel["new"][0]["tetrahedra"]})
json.dump({"base_commit": base_commit, "new_commit": new_commit, "rows": rows},
          open(os.path.join(out, "summary.json"), "w"), indent=1)
with open(os.path.join(out, "table.md"), "w") as f:
    f.write("# Delaunay visibility mesher: this tree against %s\n\n" % base_commit)
    f.write("bench/mesher/run.sh at %s; medians of %d alternating rounds, one session. "
            "Points like the dense backend's fused ones, 4 views each.\n\n" % (new_commit, rows[0]["rounds"]))
    f.write("| scene | points | threads | tetrahedra | faces | %s s | this tree s | speed-up | "
            "Delaunay / rays / graph cut s | %s faces | same surface in each build |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|\n" % (base_commit, base_commit))
    for r in rows:
        p = r["new_phases"]
        f.write("| %s | %d | %d | %d | %d | %.2f | %.2f | %.2fx | %.2f / %.2f / %.2f | %d | %s |\n" % (
            r["scene"], r["points"], r["threads"], r["tetrahedra"], r["faces"], r["base_seconds"],
            r["new_seconds"], r["speedup"], p["seconds_delaunay"], p["seconds_visibility"],
            p["seconds_labelling"], r["base_faces"], "yes" if r["same_within_each_build"] else "no"))
print(open(os.path.join(out, "table.md")).read())
