#!/usr/bin/python3
"""Sze, Liu & Lo (2004) benchmarks 3.4 (hemisphere with an 18-degree hole)
and 3.3 (slit annular plate): our load-deflection paths against the
published tables (tests/data), and the wall time of the whole path with
one or more coshell binaries, one run after another in this invocation.

  /usr/bin/python3 doc/scripts/sze_benchmarks.py --coshell BIN \
      [--baseline NAME=BIN ...] [--work /tmp/sze-docs] [--repeats 3]

Writes doc/validation/nonlinear/sze_{pinched_hemisphere,slit_annular_plate}
.csv/.png (paths of BIN with the scene's element, and of the other membrane)
and doc/performance/sze_nonlinear_timing.csv (every binary: Newton
iterations, solve seconds from summary.json, process wall seconds; the
fastest of --repeats runs, one thread, OPENBLAS_NUM_THREADS=1).
"""
import argparse
import csv
import json
import os
import subprocess
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from doc_common import finish_plot, machine_and_commit, write_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
VALIDATION = os.path.join(ROOT, "doc", "validation", "nonlinear")
PERFORMANCE = os.path.join(ROOT, "doc", "performance")
DATA = os.path.join(ROOT, "tests", "data")

# name: (prm, reference table, [(table column, qoi, sign)], the scene's
# membrane, the other membrane)
CASES = {
    "pinched_hemisphere": ("pinched_hemisphere.prm", "sze_pinched_hemisphere.csv",
                           [("pulled_radial", "pulled_ux", 1), ("pushed_radial", "pushed_uy", -1)],
                           "cst", "andes"),
    "slit_annular_plate": ("slit_annular_plate.prm", "sze_slit_annular_plate.csv",
                           [("w_A", "w_A", 1), ("w_B", "w_B", 1)], "andes", "cst"),
}


def read_table(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def run(binary, prm, output, extra=()):
    command = [binary, os.path.join(ROOT, "prm", "benchmarks", prm), "--output", output,
               "--set", "Output/Write VTU=false", "--set", "Parallel/Threads=1", *extra]
    environment = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, env=environment)
    wall = time.perf_counter() - start
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(output, "load_displacement.csv")) as f:
        path = list(csv.DictReader(f))
    return wall, summary, path


def accuracy(args, header, name):
    prm, table, columns, membrane, other = CASES[name]
    reference = read_table(os.path.join(DATA, table))
    runs = {f"{membrane}+dkt": run(args.coshell, prm, os.path.join(args.work, name))[2],
            f"{other}+dkt": run(args.coshell, prm, os.path.join(args.work, name + "_" + other),
                                     ["--set", f"Element/Membrane element={other}"])[2]}
    rows = []
    for label, path in runs.items():
        by_factor = {round(float(r["load_factor"]), 6): r for r in path}
        for ref in reference:
            factor = round(float(ref["load_factor"]), 6)
            if factor == 0 or factor not in by_factor:
                continue
            row = {"variant": label, "load_factor": factor}
            for column, qoi, sign in columns:
                ours = sign * float(by_factor[factor][qoi])
                row[f"{column}_ours"] = f"{ours:.6g}"
                row[f"{column}_reference"] = ref[column]
                row[f"{column}_error"] = f"{ours / float(ref[column]) - 1:.4g}"
            rows.append(row)
    write_csv(os.path.join(VALIDATION, f"sze_{name}.csv"), rows, header)
    figure, axes = plt.subplots(figsize=(6, 4.2))
    for column, qoi, sign in columns:
        axes.plot([float(r[column]) for r in reference], [float(r["load_factor"]) for r in reference],
                  "ko", markersize=3, label=f"{column}, Sze et al. 2004" if column == columns[0][0] else None)
        for label, path in runs.items():
            axes.plot([sign * float(r[qoi]) for r in path], [float(r["load_factor"]) for r in path],
                      "-" if label.startswith(membrane) else "--", label=f"{column}, {label}")
    finish_plot(figure, axes, "deflection", "load factor P / P_max", name.replace("_", " "),
                os.path.join(VALIDATION, f"sze_{name}.png"))


def timing(args, header):
    binaries = [("current", args.coshell)] + [tuple(b.split("=", 1)) for b in args.baseline]
    rows = []
    for name, (prm, *_rest) in CASES.items():
        for label, binary in binaries:
            best = None
            for repeat in range(args.repeats):
                wall, summary, _ = run(binary, prm, os.path.join(args.work, f"time_{name}_{label}"))
                solve = summary["wall_time_s"]["solve"]
                if best is None or solve < best["solve_s"]:
                    best = {"case": name, "binary": label, "dofs": summary["n_dofs"],
                            "newton_iterations": summary["newton_iterations"],
                            "solve_s": solve, "process_wall_s": wall}
            best["ms_per_iteration"] = 1e3 * best["solve_s"] / best["newton_iterations"]
            rows.append({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in best.items()})
            print(rows[-1])
    write_csv(os.path.join(PERFORMANCE, "sze_nonlinear_timing.csv"), rows, header)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--baseline", nargs="*", default=[], help="NAME=BINARY to time as well")
    parser.add_argument("--work", default="/tmp/sze-docs")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--skip-accuracy", action="store_true")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    machine, commit = machine_and_commit()
    header = [f"machine: {machine}; commit {commit}; binary {args.coshell}"]
    if not args.skip_accuracy:
        for name in CASES:
            accuracy(args, header, name)
    timing(args, header)


if __name__ == "__main__":
    main()
