#!/usr/bin/python3
"""Newton iterations and time with the exact local forces in the
co-rotational tangent's geometric terms and with the forces extrapolated
from the previous iterate (Nonlinear solver/Geometric stiffness;
doc/theory/corotational.md, section 13.4), on every nonlinear benchmark of prm/benchmarks and on
three dynamic scenes, one binary, one run after another in one invocation.

  /usr/bin/python3 doc/scripts/geometric_stiffness.py --coshell BIN \
      [--work /tmp/geometric-stiffness] [--repeats 3] [--quick]

Writes doc/performance/geometric_stiffness.csv (per case and variant:
Newton corrections with failed attempts, load or time steps, the solve
phase's seconds, fastest of --repeats runs for runs under 10 s, and the
largest relative difference of the quantities of interest between the
variants) and geometric_stiffness.png. One thread, OPENBLAS_NUM_THREADS=1.
--quick skips the IOL fold (40 s a run).
"""
import argparse
import json
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from doc_common import finish_plot, machine_and_commit, write_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PERFORMANCE = os.path.join(ROOT, "doc", "performance")
VARIANTS = {"current": "current forces", "extrapolated": "extrapolated forces"}

# name: (prm relative to prm/, extra --set entries). The two Sze scenes
# take the symmetric tangent with CHOLMOD; they are measured with the
# consistent tangent as well, like every other benchmark.
CONSISTENT = ["Nonlinear solver/Tangent=consistent"]
CASES = {
    "slit annular plate 12x60": ("benchmarks/slit_annular_plate.prm", CONSISTENT),
    "slit annular plate 12x60, 5 load steps": (
        "benchmarks/slit_annular_plate.prm", CONSISTENT + ["Nonlinear solver/Load steps=5"]),
    "slit annular plate 12x60, symmetric tangent, CHOLMOD (the scene's)": (
        "benchmarks/slit_annular_plate.prm", []),
    "pinched hemisphere 16x16": ("benchmarks/pinched_hemisphere.prm", CONSISTENT),
    "pinched hemisphere 16x16, symmetric tangent, CHOLMOD (the scene's)": (
        "benchmarks/pinched_hemisphere.prm", []),
    "cantilever end moment": ("benchmarks/cantilever_end_moment.prm", []),
    "cantilever end shear": ("benchmarks/cantilever_end_shear.prm", []),
    "clamped circular plate": ("benchmarks/clamped_circular_plate_large_deflection.prm", []),
    "clamped square plate": ("benchmarks/clamped_square_plate_large_deflection.prm", []),
    "hinged cylindrical roof (arc length)": ("benchmarks/hinged_cylindrical_roof.prm", []),
    "flapping plate (dynamics)": ("dynamics/flapping_plate.prm", []),
    "ISO compression of the lens (dynamics, contact)": ("iol/compression_iso11979.prm", []),
    "IOL fold stage (dynamics, contact)": (
        "iol/injection.prm", ["Stage 2/Analysis type=none", "Stage 3/Analysis type=none",
                               "Stage 4/Analysis type=none"]),
}


def run(binary, prm, output, extra):
    command = [binary, os.path.join(ROOT, "prm", prm), "--output", output,
               "--set", "Output/Write VTU=false", "--set", "Parallel/Threads=1"]
    for entry in extra:
        command += ["--set", entry]
    environment = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    subprocess.run(command, check=True, capture_output=True, env=environment)
    with open(os.path.join(output, "summary.json")) as f:
        return json.load(f)


def iterations(summary, output):
    """Newton corrections; arc length does not count them in the summary,
    so they are the rows of newton_history.csv with a correction."""
    if summary.get("newton_corrections"):
        return summary["newton_corrections"]
    with open(os.path.join(output, "newton_history.csv")) as f:
        return sum(1 for _ in f) - 1


def measure(binary, work, name, prm, extra, variant, repeats):
    output = os.path.join(work, "".join(c if c.isalnum() else "_" for c in name)
                          + "_" + variant)
    entries = extra + [f"Nonlinear solver/Geometric stiffness={VARIANTS[variant]}"]
    best = None
    for attempt in range(repeats):
        summary = run(binary, prm, output, entries)
        solve = summary["wall_time_s"]["solve"]
        best = solve if best is None else min(best, solve)
        if solve > 10:
            break
    return {"case": name, "variant": variant, "corrections": iterations(summary, output),
            "steps": summary.get("load_steps", summary.get("steps", "")),
            "solve_s": round(best, 4)}, summary.get("qoi", {})


def largest_difference(a, b):
    worst = 0.0
    for key, value in a.items():
        if isinstance(value, (int, float)) and key in b:
            worst = max(worst, abs(value - b[key]) / max(abs(value), 1e-30))
    return worst


def plot(rows, path):
    names = list(dict.fromkeys(row["case"] for row in rows))
    by = {(row["case"], row["variant"]): row for row in rows}
    figure, axes = plt.subplots(figsize=(8, 5))
    ratios = [by[(n, "current")]["corrections"] / by[(n, "extrapolated")]["corrections"]
              for n in names]
    speed = [by[(n, "current")]["solve_s"] / by[(n, "extrapolated")]["solve_s"] for n in names]
    y = range(len(names))
    axes.barh([v + 0.2 for v in y], ratios, height=0.4, label="Newton corrections, current / extrapolated")
    axes.barh([v - 0.2 for v in y], speed, height=0.4, label="solve time, current / extrapolated")
    axes.axvline(1, color="k", lw=0.8)
    axes.set_yticks(list(y))
    axes.set_yticklabels(names, fontsize=7)
    finish_plot(figure, axes, "ratio (> 1: extrapolated forces better)", "",
                "Extrapolated forces in the geometric stiffness", path)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--work", default="/tmp/geometric-stiffness")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rows = []
    for name, (prm, extra) in CASES.items():
        if args.quick and "fold" in name:
            continue
        qois = {}
        for variant in VARIANTS:
            row, qois[variant] = measure(args.coshell, args.work, name, prm, extra, variant,
                                         args.repeats)
            rows.append(row)
            print(row, flush=True)
        rows[-1]["qoi_difference"] = rows[-2]["qoi_difference"] = \
            f"{largest_difference(qois['current'], qois['extrapolated']):.1e}"
    machine, commit = machine_and_commit()
    write_csv(os.path.join(PERFORMANCE, "geometric_stiffness.csv"), rows,
              [f"machine: {machine}", f"commit: {commit}",
               "one thread; solve_s: fastest of the repeats (one run above 10 s)"],
              ["case", "variant", "steps", "corrections", "solve_s", "qoi_difference"])
    plot(rows, os.path.join(PERFORMANCE, "geometric_stiffness.png"))


if __name__ == "__main__":
    main()
