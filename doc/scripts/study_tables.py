#!/usr/bin/python3
"""Convergence table from the CSV written by scripts/study.py: for each
benchmark and element combination, the finest level's value, its error
against the published reference, the order observed from the three finest
levels alone, p = log2(d1/d2) with d1 = v[L-1] - v[L-2], d2 = v[L] - v[L-1]
(mesh size halved per level), and the Richardson-extrapolated limit
v[L] + d2 / (2^p - 1) (only when d1, d2 have the same sign, i.e. the
sequence is monotone over the last three levels), with the limit's
deviation from the reference.

  /usr/bin/python3 doc/scripts/study_tables.py [doc/study/study.csv]
Writes doc/study/convergence.csv and prints a Markdown table.
"""
import csv
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
from richardson import richardson  # noqa: E402


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "doc", "study", "study.csv")
    with open(path) as f:
        rows = list(csv.DictReader(f))
    groups = {}
    for r in rows:
        groups.setdefault((r["benchmark"], r["elements"]), []).append(r)
    out = []
    for (benchmark, elements), mine in groups.items():
        mine.sort(key=lambda r: int(r["level"]))
        v = [float(r["value"]) for r in mine]
        ref = float(mine[-1]["reference"])
        record = {"benchmark": benchmark, "elements": elements,
                  "finest_level": mine[-1]["level"], "n_dofs": mine[-1]["n_dofs"],
                  "value": f"{v[-1]:.6g}", "reference": f"{ref:g}",
                  "error": f"{(v[-1] - ref) / abs(ref):+.3e}",
                  "order": "", "richardson": "", "richardson_vs_reference": ""}
        if len(v) >= 3:
            p, limit = richardson(*v[-3:])
            if math.isnan(p):
                record["order"] = "non-monotone"
            else:
                record["order"] = f"{p:.2f}"
            if not math.isnan(limit):
                record["richardson"] = f"{limit:.6g}"
                record["richardson_vs_reference"] = f"{(limit - ref) / abs(ref):+.3e}"
        out.append(record)
    target = os.path.join(os.path.dirname(path), "convergence.csv")
    with open(target, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(out[0]))
        writer.writeheader()
        writer.writerows(out)
    print(f"wrote {target}\n")
    print("| benchmark | elements | level (DoFs) | value | error vs reference | "
          "order (3 finest) | Richardson limit | limit vs reference |")
    print("|---|---|---|---|---|---|---|---|")
    for r in out:
        print(f"| {r['benchmark']} | {r['elements']} | {r['finest_level']} ({r['n_dofs']}) | "
              f"{r['value']} | {r['error']} | {r['order']} | {r['richardson']} | "
              f"{r['richardson_vs_reference']} |")
    print("\nper level (value):")
    for (benchmark, elements), mine in groups.items():
        print(f"{benchmark} {elements}: " + ", ".join(
            f"L{r['level']}:{float(r['value']):.5g}({r['n_dofs']},{float(r['total_s']):.2f}s)"
            for r in mine))


if __name__ == "__main__":
    main()
