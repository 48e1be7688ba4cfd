"""Markdown table of bench/results/quality/quality.json (bench/quality/run.sh).

One row per case, one column per predictor: Spearman / AUC / precision at
10, over the faces that every PRI predictor observes. The best value of
each metric in a row is in bold.
Usage: table.py quality.json > table.md
"""
import json
import sys

PREDICTORS = ["paper_ssd", "paper_ncc", "default_ssd", "default_ncc", "offset",
              "views", "max_angle", "reconstructability"]
METRICS = ["spearman", "auc", "precision_at_10"]


def main():
    data = json.load(open(sys.argv[1]))
    print(f"Run of {data['date']} ({data['seconds']:.0f} s, {data['threads']} threads), "
          f"{data['program']}. Each cell: Spearman / ROC AUC of the worst decile / precision of the 10 worst.")
    print()
    print("| case | faces | error p50 / p90 (px) | " + " | ".join(PREDICTORS) + " |")
    print("|---|---|---|" + "---|" * len(PREDICTORS))
    for case in data["cases"]:
        p = case["predictors"]
        best = {m: max(p[k][m] for k in PREDICTORS) for m in METRICS}
        cells = []
        for k in PREDICTORS:
            parts = []
            for m in METRICS:
                text = f"{p[k][m]:.2f}" if m != "precision_at_10" else f"{p[k][m]:.1f}"
                parts.append(f"**{text}**" if p[k][m] == best[m] else text)
            cells.append(" / ".join(parts))
        e = case.get("error_px", {})
        err = f"{e.get('p50', float('nan')):.2f} / {e.get('p90', float('nan')):.2f}"
        print(f"| {case['name']} | {case['observed_faces']} | {err} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
