#!/usr/bin/python3
"""Benchmark (not a test): strong scaling of a linear solve over 1 and 2 MPI
ranks, and the largest linear problem this machine holds with AMG.

The clamped square plate under pressure (prm/plates/clamped_square_pressure
.prm: crossed pattern, CST + DKT, one level, no VTU), n x n squares with n =
--size (288: 1 000 830 DoFs). Each Linear solver/Method of --methods runs as
1 rank x 1 thread, 1 rank x 2 threads and 2 ranks x 1 thread
(DEAL_II_NUM_THREADS), so that every run uses at most the 2 cores. Per run:
the phases of summary.json (rank 0's clock: setup, assemble, solve, output),
the process wall time, and the peak resident memory of the largest process
(/usr/bin/time -v reports the largest child: one rank of mpirun).

Writes doc/performance/mpi_scaling.csv and .png (phase times per
configuration, one panel per method). With --largest N1 N2 ... it instead
runs cg-amg at those sizes (one rank with 2 threads, or --largest-ranks
ranks with one thread each) and appends to doc/performance/mpi_largest.csv
(DoFs, wall time, peak memory, bytes per DoF), stopping at the first size
that fails.

Usage (from the repository root):
  /usr/bin/python3 doc/scripts/mpi_scaling.py --coshell build/coshell
  /usr/bin/python3 doc/scripts/mpi_scaling.py --coshell build/coshell \\
      --largest 500 700 912
"""
import argparse
import csv
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import (ROOT, machine_and_commit,  # noqa: E402
                        run_scene_measured, write_csv)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRM = os.path.join(ROOT, "prm", "plates", "clamped_square_pressure.prm")
OUT_DIR = os.path.join(ROOT, "doc", "performance")
PHASES = ["setup", "assemble", "solve", "output"]
CONFIGURATIONS = [(1, 1), (1, 2), (2, 1)]  # (ranks, threads per rank)


def run(coshell, size, method, ranks, threads, scratch):
    output = os.path.join(scratch, f"{method}-{ranks}x{threads}-{size}")
    shutil.rmtree(output, ignore_errors=True)
    command = [coshell, PRM, "--output", output,
               "--set", f"Mesh/Subdivisions x={size}",
               "--set", f"Mesh/Subdivisions y={size}",
               "--set", "Mesh/Refinement levels=0",
               "--set", "Output/Write VTU=false",
               "--set", f"Linear solver/Method={method}"]
    measured = run_scene_measured(command, ranks, threads, output)
    if measured is None:
        return None
    summary, wall, peak_kb = measured
    row = {"method": method, "ranks": ranks, "threads_per_rank": threads,
           "subdivisions": size, "n_dofs": summary["n_dofs"],
           "iterations": summary.get("linear_solver_iterations", 1),
           "center_deflection": summary["qoi"]["center_deflection"]}
    for phase in PHASES:
        row[f"{phase}_s"] = round(summary["wall_time_s"][phase], 3)
    row["process_wall_s"] = round(wall, 2)
    row["peak_rss_mb_largest_process"] = round(peak_kb / 1024, 1)
    row["bytes_per_dof_largest_process"] = round(peak_kb * 1024 /
                                                 summary["n_dofs"])
    print(row, flush=True)
    shutil.rmtree(output, ignore_errors=True)
    return row


def plot(rows, methods, path, stamp):
    figure, axes = plt.subplots(1, len(methods), figsize=(4.5 * len(methods), 4),
                                squeeze=False)
    for axis, method in zip(axes[0], methods):
        mine = [r for r in rows if r["method"] == method]
        labels = [f"{r['ranks']} rank x {r['threads_per_rank']} thr"
                  for r in mine]
        bottom = [0.0] * len(mine)
        for phase in PHASES:
            heights = [r[f"{phase}_s"] for r in mine]
            axis.bar(labels, heights, bottom=bottom, label=phase)
            bottom = [b + h for b, h in zip(bottom, heights)]
        for x, r in enumerate(mine):
            axis.text(x, bottom[x], f"{r['peak_rss_mb_largest_process']:.0f} MB",
                      ha="center", va="bottom", fontsize=8)
        axis.set_title(f"{method}, {mine[0]['n_dofs']} DoFs" if mine else method)
        axis.set_ylabel("wall time of rank 0, s")
        axis.legend(fontsize=8, loc="upper right", ncol=2, framealpha=0.9)
        axis.set_ylim(0, 1.45 * max(bottom))
    figure.suptitle(stamp, fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    print("wrote", path)


def redraw(methods):
    path = os.path.join(OUT_DIR, "mpi_scaling.csv")
    with open(path) as f:
        lines = f.readlines()
    stamp = "; ".join(l[2:].strip() for l in lines[:2] if l.startswith("#"))
    rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
    for row in rows:
        for key in row:
            if key.endswith("_s") or key.startswith("peak") or key in (
                    "ranks", "threads_per_rank", "n_dofs"):
                row[key] = float(row[key])
        row["ranks"], row["threads_per_rank"] = (int(row["ranks"]),
                                                 int(row["threads_per_rank"]))
        row["n_dofs"] = int(row["n_dofs"])
    plot(rows, methods, os.path.join(OUT_DIR, "mpi_scaling.png"), stamp)


def earlier_rows(path):
    """The rows of an earlier mpi_largest.csv, each with the commit of the
    binary that ran it (older files name one commit in their header)."""
    with open(path) as f:
        lines = f.readlines()
    named = [l.split(":", 1)[1].strip() for l in lines
             if l.startswith("# commit:")]
    rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
    for row in rows:
        if not row.get("commit"):
            row["commit"] = named[0] if named else "unknown"
    return rows


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--size", type=int, default=288)
    parser.add_argument("--methods", nargs="+",
                        default=["amesos-mumps", "cg-amg"])
    parser.add_argument("--largest", type=int, nargs="*")
    parser.add_argument("--largest-ranks", type=int, default=1,
                        help="ranks of the --largest runs (1: one rank with "
                        "2 threads; more: 1 thread each)")
    parser.add_argument("--scratch", default="/tmp/coshell_mpi_scaling")
    parser.add_argument("--plot-only", action="store_true",
                        help="redraw the PNG from the CSV")
    args = parser.parse_args()
    if args.plot_only:
        redraw(args.methods)
        return
    machine, commit = machine_and_commit()
    header = [f"machine: {machine}", f"commit: {commit}",
              "clamped square plate, crossed, CST+DKT, linear static"]
    if args.largest:
        rows = []
        for size in args.largest:
            ranks, threads = (args.largest_ranks, 1) if args.largest_ranks > 1 \
                else (1, 2)
            row = run(args.coshell, size, "cg-amg", ranks, threads,
                      args.scratch)
            if row is None:
                break
            rows.append(dict(row, commit=commit))
        path = os.path.join(OUT_DIR, "mpi_largest.csv")
        if os.path.exists(path):  # append to the earlier runs
            rows = earlier_rows(path) + rows
        header[1] = "commit: see the commit column"
        write_csv(path, rows, header)
        return
    rows = [run(args.coshell, args.size, method, ranks, threads, args.scratch)
            for method in args.methods for ranks, threads in CONFIGURATIONS]
    rows = [r for r in rows if r]
    write_csv(os.path.join(OUT_DIR, "mpi_scaling.csv"), rows, header)
    plot(rows, args.methods, os.path.join(OUT_DIR, "mpi_scaling.png"),
         f"{machine}; commit {commit}")


if __name__ == "__main__":
    main()
