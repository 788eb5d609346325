#!/usr/bin/python3
"""Runs the co-rotational benchmarks of prm/benchmarks with the consistent
and with the paper's tangent, and the stability cases of
tests/nonlinear_tests.cmake, and writes the tables and plots used by
doc/validation/corotational.md and
doc/performance/nonlinear.md (section "Consistent against paper tangent:
wall time").

  /usr/bin/python3 doc/scripts/nonlinear_benchmarks.py \
      --coshell /tmp/final-docs-build/coshell [--work /tmp/nonlinear-docs] \
      [--timeout 120] [--only NAME ...] [--symmetric-only]

Writes into doc/validation/nonlinear/:
  iterations.csv        one row per benchmark and tangent: status, load
                        steps, Newton iterations, wall time, final load
                        factor and QoIs, observed Newton orders
  reference_points.csv  consistent-tangent value, reference and error at
                        every reference point
  stability.csv         the hard cases (very thin strip, aspect ratio 20,
                        one-step roll-up, arc length snap-through, ANDES
                        membrane)
  <name>.csv / .png     load-displacement path (consistent tangent)
  <name>_newton_history.csv
  symmetric_tangent.csv every benchmark and stability case with the
                        consistent tangent and with its symmetric part
                        (Tangent = symmetric, CHOLMOD): iterations, wall
                        time, final QoIs (--symmetric-only writes just
                        this file)
Machine (lscpu) and commit (git rev-parse --short HEAD) are written as
'#' comment lines at the top of each CSV.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from doc_common import finish_plot, machine_and_commit, write_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT = os.path.join(ROOT, "doc", "validation", "nonlinear")
NO_VTU = "Output/Write VTU=false"
MAX_IT = "Nonlinear solver/Maximum iterations=100"

# name, prm, extra --set assignments, reference points (qoi, lambda, value),
# length scale for the error (error = |v - ref| / max(|ref|, length))
BENCHMARKS = [
    ("cantilever_end_moment", "cantilever_end_moment",
     ["Mesh/Subdivisions x=48"],
     [("tip_u", 0.25, -4.360571), ("tip_w", 0.25, 7.639437),
      ("tip_u", 0.5, -12.0), ("tip_w", 0.5, 7.639437),
      ("tip_u", 0.75, -14.546479), ("tip_w", 0.75, 2.546479),
      ("tip_u", 1.0, -12.0), ("tip_w", 1.0, 0.0)], 1.2),
    ("cantilever_end_shear", "cantilever_end_shear", [],
     [("tip_u", 0.25, -0.563), ("tip_w", 0.25, 3.015),
      ("tip_u", 0.5, -1.604), ("tip_w", 0.5, 4.933),
      ("tip_u", 0.75, -2.541), ("tip_w", 0.75, 6.031),
      ("tip_u", 1.0, -3.286), ("tip_w", 1.0, 6.698)], 0.0),
    ("clamped_circular_plate_large_deflection",
     "clamped_circular_plate_large_deflection", [],
     [("center_deflection", 0.01, 0.01680), ("center_deflection", 0.02, 0.03228),
      ("center_deflection", 0.05, 0.06796), ("center_deflection", 0.1, 0.10520),
      ("center_deflection", 0.2, 0.14938), ("center_deflection", 0.5, 0.21980),
      ("center_deflection", 1.0, 0.28557)], 0.0),
    ("clamped_square_plate_large_deflection",
     "clamped_square_plate_large_deflection", [], [], 0.0),
    ("hinged_cylindrical_roof", "hinged_cylindrical_roof", [], [], 0.0),
]

THIN = ["Material/Thickness=0.0012", "Material/Young's modulus=694444444444.4445"]
# name, prm, extra sets, reference points, length
STABILITY = [
    ("very_thin_end_moment_48", "cantilever_end_moment",
     ["Mesh/Subdivisions x=48"] + THIN, BENCHMARKS[0][3], 1.2),
    ("very_thin_end_moment_96", "cantilever_end_moment",
     ["Mesh/Subdivisions x=96"] + THIN, BENCHMARKS[0][3], 1.2),
    ("aspect_ratio_20_end_shear", "cantilever_end_shear",
     ["Mesh/Subdivisions x=200", "Mesh/Subdivisions y=1",
      "Mesh/Triangle pattern=same-diagonal"], BENCHMARKS[1][3], 0.0),
    ("full_roll_up_one_step", "cantilever_end_moment",
     ["Mesh/Subdivisions x=48", "Nonlinear solver/Load steps=1",
      "Quantities of interest/Reference curves="],
     [("tip_u", 1.0, -12.0), ("tip_w", 1.0, 0.0)], 1.2),
    ("andes_end_moment", "cantilever_end_moment",
     ["Mesh/Subdivisions x=48", "Element/Membrane element=andes"],
     BENCHMARKS[0][3], 1.2),
    ("andes_end_shear", "cantilever_end_shear",
     ["Element/Membrane element=andes"], BENCHMARKS[1][3], 0.0),
    ("andes_circular_plate", "clamped_circular_plate_large_deflection",
     ["Element/Membrane element=andes"], BENCHMARKS[2][3], 0.0),
    ("andes_square_plate", "clamped_square_plate_large_deflection",
     ["Element/Membrane element=andes"], [], 0.0),
    ("andes_hinged_roof", "hinged_cylindrical_roof",
     ["Element/Membrane element=andes"], [], 0.0),
]


def read_rows(path):
    for candidate in (path, path + ".partial"):
        if os.path.exists(candidate):
            with open(candidate) as f:
                return list(csv.DictReader(f))
    return []


def newton_orders(history):
    """As tests/scripts/check_nonlinear.py: p = log(r2/r1)/log(r1/r0) for
    consecutive relative residuals with r0 < 1e-2, decreasing, r2 > 1e-13."""
    steps = {}
    for row in history:
        # a run killed by the timeout may leave a truncated last row
        if row.get("relative_residual") not in (None, ""):
            steps.setdefault(row["step"], []).append(float(row["relative_residual"]))
    orders = []
    for residuals in steps.values():
        for r0, r1, r2 in zip(residuals, residuals[1:], residuals[2:]):
            if r0 < 1e-2 and r2 < r1 < r0 and r2 > 1e-13:
                orders.append(math.log(r2 / r1) / math.log(r1 / r0))
    return orders


PLOT_SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                           "..", "..", "scripts", "plot_load_displacement.py")


def run(args, name, prm, sets, tangent):
    output = os.path.join(args.work, f"{name}-{tangent}")
    if os.path.isdir(output):
        shutil.rmtree(output)
    command = [args.coshell, os.path.join(ROOT, "prm", "benchmarks", prm + ".prm"),
               "--output", output, "--set", f"Nonlinear solver/Tangent={tangent}",
               "--set", MAX_IT, "--set", NO_VTU]
    for s in sets:
        command += ["--set", s]
    start = time.perf_counter()
    try:
        result = subprocess.run(command, capture_output=True, text=True,
                                timeout=args.timeout)
        wall = time.perf_counter() - start
        if result.returncode == 0:
            status = "converged"
        else:
            lines = [l for l in result.stderr.strip().splitlines() if l.strip()]
            status = "failed: " + (lines[-1] if lines else f"exit {result.returncode}")
    except subprocess.TimeoutExpired:
        wall = time.perf_counter() - start
        status = f"timeout ({args.timeout:g} s)"
    rows = read_rows(os.path.join(output, "load_displacement.csv"))
    history = read_rows(os.path.join(output, "newton_history.csv"))
    summary = {}
    if os.path.exists(os.path.join(output, "summary.json")):
        with open(os.path.join(output, "summary.json")) as f:
            summary = json.load(f)
    orders = newton_orders(history)
    record = {
        "benchmark": name, "tangent": tangent, "status": status,
        "load_steps": len(rows),
        "newton_iterations": sum(int(r["iterations"]) for r in rows),
        "max_iterations_per_step": max((int(r["iterations"]) for r in rows), default=0),
        "newton_solves_incl_failed": len(history),
        "wall_time_s": f"{wall:.3f}",
        "solve_time_s": summary.get("wall_time_s", {}).get("solve", ""),
        "n_dofs": summary.get("n_dofs", ""),
        "final_load_factor": rows[-1]["load_factor"] if rows else "",
        "final_qoi": "; ".join(f"{k}={float(v):.6g}" for k, v in rows[-1].items()
                               if k not in ("step", "load_factor", "iterations"))
        if rows else "",
        "max_order": f"{max(orders):.2f}" if orders else "",
        "median_order": f"{sorted(orders)[len(orders) // 2]:.2f}" if orders else "",
        "n_orders": len(orders),
    }
    print(f"{name:45s} {tangent:10s} {status[:60]:60s} steps {record['load_steps']:3d} "
          f"its {record['newton_iterations']:4d} {wall:7.2f} s "
          f"order max {record['max_order']} median {record['median_order']}", flush=True)
    return record, output, rows, history


def reference_errors(name, tangent, rows, points, length):
    out = []
    for qoi, factor, reference in points:
        row = next((r for r in rows if abs(float(r["load_factor"]) - factor) < 1e-9), None)
        value = float(row[qoi]) if row else float("nan")
        scale = max(abs(reference), length)
        out.append({"benchmark": name, "tangent": tangent, "qoi": qoi,
                    "load_factor": factor,
                    "value": f"{value:.6g}" if row else "not reached",
                    "reference": reference,
                    "error": f"{(value - reference) / scale:+.3e}" if row else "",
                    "error_scale": f"{scale:g}"})
    return out


def plot_square(rows, path):
    h = 0.1
    w = [float(r["center_deflection"]) / h for r in rows]
    q = [100 * float(r["load_factor"]) for r in rows]
    figure, axes = plt.subplots(figsize=(6, 4.2))
    axes.plot([0] + w, [0] + q, "o-", label="co-rotational (CST+DKT, 8x8 crossed)")
    wl = [0, max(w)]
    axes.plot(wl, [x * h / 0.126532 for x in wl], "k--",
              label="linear Kirchhoff, w = 0.126532 q")
    axes.set_ylim(0, 105)
    finish_plot(figure, axes, "centre deflection w / h", "pressure q",
                "clamped square plate, large deflection", path)


def plot_roof(rows, path):
    d = [-float(r["apex_deflection"]) for r in rows]
    p = [3000 * float(r["load_factor"]) for r in rows]
    peaks = [i for i in range(1, len(p) - 1) if p[i - 1] < p[i] > p[i + 1]]
    figure, axes = plt.subplots(figsize=(6, 4.2))
    axes.plot([0] + d, [0] + p, "o-", ms=3, label="co-rotational, arc length")
    for i in peaks:
        axes.plot(d[i], p[i], "r*", ms=12,
                  label=f"limit point P = {p[i]:.0f} at w = {d[i]:.2f}")
    finish_plot(figure, axes, "apex deflection (downwards)", "load P = 3000 lambda",
                "hinged cylindrical roof, h = 12.7", path)
    return [(p[i], d[i], rows[i]["step"]) for i in peaks]


def compare_symmetric(args, header):
    """The consistent tangent against its symmetric part on every case,
    one run each, in this one invocation."""
    records = []
    for name, prm, sets, _, _ in BENCHMARKS + STABILITY:
        for tangent in ("consistent", "symmetric"):
            record, output, _, _ = run(args, name, prm, sets, tangent)
            summary_path = os.path.join(output, "summary.json")
            fallbacks = 0
            if os.path.exists(summary_path):
                with open(summary_path) as f:
                    summary = json.load(f)
                level = summary.get("levels", [summary])[-1]
                fallbacks = level.get("cholmod_fallbacks", 0)
            records.append({k: record[k] for k in (
                "benchmark", "tangent", "status", "load_steps",
                "newton_iterations", "wall_time_s", "solve_time_s",
                "final_load_factor", "final_qoi")} |
                {"cholmod_fallbacks": fallbacks})
    write_csv(os.path.join(OUT, "symmetric_tangent.csv"), records, header)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--work", default="/tmp/nonlinear-docs")
    parser.add_argument("--timeout", type=float, default=120)
    parser.add_argument("--skip-stability", action="store_true")
    parser.add_argument("--symmetric-only", action="store_true")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    machine, commit = machine_and_commit()
    header = [f"machine: {machine}; commit {commit}; coshell {args.coshell}",
              f"every run: --set '{MAX_IT}' --set '{NO_VTU}', timeout {args.timeout:g} s"]
    compare_symmetric(args, header)
    if args.symmetric_only:
        return

    records, references = [], []
    for name, prm, sets, points, length in BENCHMARKS:
        for tangent in ("consistent", "paper"):
            record, output, rows, _ = run(args, name, prm, sets, tangent)
            records.append(record)
            references += reference_errors(name, tangent, rows, points, length)
            if tangent != "consistent":
                continue
            # coshell writes CSVs only; the plot is drawn here.
            subprocess.run(["/usr/bin/python3", PLOT_SCRIPT, output],
                           capture_output=True)
            for src, dst in (("load_displacement.csv", f"{name}.csv"),
                             ("newton_history.csv", f"{name}_newton_history.csv"),
                             ("load_displacement.png", f"{name}.png")):
                if os.path.exists(os.path.join(output, src)):
                    shutil.copy(os.path.join(output, src), os.path.join(OUT, dst))
            if name == "clamped_square_plate_large_deflection" and rows:
                plot_square(rows, os.path.join(OUT, f"{name}.png"))
            if name == "hinged_cylindrical_roof" and rows:
                for P, w, step in plot_roof(rows, os.path.join(OUT, f"{name}.png")):
                    print(f"roof limit point: P = {P:.1f}, apex deflection {w:.3f}, step {step}")
    write_csv(os.path.join(OUT, "iterations.csv"), records, header)
    write_csv(os.path.join(OUT, "reference_points.csv"), references, header)

    if args.skip_stability:
        return
    stability, stability_refs = [], []
    for name, prm, sets, points, length in STABILITY:
        record, output, rows, _ = run(args, name, prm, sets, "consistent")
        stability.append(record)
        stability_refs += reference_errors(name, "consistent", rows, points, length)
        if name == "andes_hinged_roof" and rows:
            factors = [float(r["load_factor"]) for r in rows]
            for i in range(1, len(rows) - 1):
                if factors[i - 1] < factors[i] > factors[i + 1]:
                    print(f"andes roof limit point: P = {3000 * factors[i]:.1f} at "
                          f"apex {float(rows[i]['apex_deflection']):.3f}")
    write_csv(os.path.join(OUT, "stability.csv"), stability, header)
    write_csv(os.path.join(OUT, "stability_reference_points.csv"), stability_refs, header)


if __name__ == "__main__":
    main()
