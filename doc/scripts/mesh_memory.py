#!/usr/bin/python3
"""Benchmark (not a test): memory per MPI rank of three mesh layouts for the
clamped plate (crossed pattern, n x n squares, six DoFs per vertex), on 1
and 2 ranks: 'replicated' (CoShell's nonlinear and dynamic analyses: whole
mesh, whole sparsity pattern, full vectors on every rank; the
parallel::shared::Triangulation design), 'replicated-mesh' (CoShell's linear
statics: whole mesh, Trilinos pattern of the rank's own rows) and
'fullydistributed' (parallel::fullydistributed::Triangulation from a METIS-
partitioned description built on rank 0; locally relevant DoFs only).

Each run is its own process (build/benchmarks/coshell_mesh_memory), so its
peak resident set (VmHWM) is the layout's; the heap growth of each phase
(mallinfo2) says where the memory goes. Values are the largest over the
ranks (totals summed on each rank first). On two ranks the fully distributed
layout runs once more with a ghosted Trilinos vector
('fullydistributed+trilinos-vector'). Writes doc/performance/mesh_memory.csv
and .png.

Usage (from the repository root; builds the benchmark if needed):
  /usr/bin/python3 doc/scripts/mesh_memory.py [--sizes 144 288 576 912]
  /usr/bin/python3 doc/scripts/mesh_memory.py --plot-only   # PNG from CSV
"""
import argparse
import csv
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import ROOT, machine_and_commit, write_csv  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

BINARY = os.path.join(ROOT, "build", "benchmarks", "coshell_mesh_memory")
OUT_DIR = os.path.join(ROOT, "doc", "performance")
LAYOUTS = ["replicated", "replicated-mesh", "fullydistributed"]
MB = 1e6
PHASES = ["mesh", "dofs", "pattern", "trilinos_vector", "vector"]


def run(layout, size, ranks):
    command = [BINARY] + layout.split("+") + [str(size)]
    command = [c if c != "trilinos-vector" else "--trilinos-vector"
               for c in command]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    environment = dict(os.environ, DEAL_II_NUM_THREADS="1",
                       OMPI_ALLOW_RUN_AS_ROOT="1",
                       OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    result = subprocess.run(command, env=environment, capture_output=True,
                            text=True, check=True)
    report = json.loads(result.stdout.strip().splitlines()[-1])
    row = {"layout": layout, "ranks": ranks, "subdivisions": size,
           "n_dofs": int(report["n_dofs"]),
           "sparsity_entries": int(report["sparsity_entries"]),
           "cells_stored_per_rank": int(report["cells_stored"]),
           "cells_owned_per_rank": int(report.get("cells_owned",
                                                  report["cells_stored"]))}
    for phase in PHASES:
        if f"heap_{phase}_bytes" in report:
            row[f"heap_{phase}_MB"] = round(
                report[f"heap_{phase}_bytes"] / MB, 2)
            row[f"peak_after_{phase}_MB"] = round(
                report[f"peak_after_{phase}_bytes"] / MB, 1)
    row["kept_MB"] = round(report["kept_bytes"] / MB, 1)
    row["peak_MB"] = round(report["peak_bytes"] / MB, 1)
    row["peak_above_libraries_MB"] = round(
        report["peak_above_libraries_bytes"] / MB, 1)
    row["mesh_s"] = round(report["mesh_s"], 3)
    row["setup_s"] = round(report["setup_s"], 3)
    print(row, flush=True)
    return row


def plot_peaks(axes, rows):
    for layout, marker in zip(LAYOUTS, "osd"):
        for ranks, style in [(1, ":"), (2, "-")]:
            points = [(r["n_dofs"], r["peak_above_libraries_MB"] / 1e3)
                      for r in rows if r["layout"] == layout
                      and r["ranks"] == ranks]
            if points:
                x, y = zip(*points)
                axes.loglog(x, y, style, marker=marker,
                            label=f"{layout}, {ranks} rank(s)")
    axes.set_xlabel("DoFs")
    axes.set_ylabel("peak memory per rank above the libraries [GB]")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7)


def plot_kept_heap(axes, rows):
    """Stacked heap kept per phase, two ranks, the largest size."""
    largest = max(r["n_dofs"] for r in rows)
    kept = [r for r in rows if r["ranks"] == 2 and r["n_dofs"] == largest]
    bottom = [0.0] * len(kept)
    for phase in ["mesh", "dofs", "pattern", "vector", "trilinos_vector"]:
        heights = [r.get(f"heap_{phase}_MB", 0) / 1e3 for r in kept]
        axes.bar([r["layout"].replace("+", "\n+ ") for r in kept], heights,
                 bottom=bottom,
                 label=phase)
        bottom = [b + h for b, h in zip(bottom, heights)]
    axes.set_ylabel("heap kept per rank [GB]")
    axes.set_title(f"2 ranks, {int(largest):,} DoFs", fontsize=8)
    axes.tick_params(axis="x", labelsize=7)
    axes.legend(fontsize=7)


def plot(rows, path, stamp):
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    plot_peaks(left, rows)
    plot_kept_heap(right, rows)
    figure.suptitle("Mesh, DoFs, sparsity pattern and one DoF vector per "
                    "rank; " + stamp, fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    print("wrote", path)


def read_rows(path):
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    rows = []
    for row in csv.DictReader(lines):
        rows.append({k: (v if k == "layout" else float(v or 0))
                     for k, v in row.items()})
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+",
                        default=[144, 288, 576, 912])
    parser.add_argument("--plot-only", action="store_true",
                        help="redraw the PNG from the CSV")
    arguments = parser.parse_args()
    csv_path = os.path.join(OUT_DIR, "mesh_memory.csv")
    if arguments.plot_only:
        with open(csv_path) as f:
            stamp = ", ".join(line[2:].strip() for line in f
                              if line.startswith(("# machine:",
                                                  "# commit:")))
        plot(read_rows(csv_path), csv_path[:-3] + "png", stamp)
        return
    subprocess.run(["cmake", "--build", os.path.join(ROOT, "build"),
                    "--target", "coshell_mesh_memory"], check=True)
    rows = [run(layout, size, ranks) for size in arguments.sizes
            for ranks in (1, 2)
            for layout in LAYOUTS + (["fullydistributed+trilinos-vector"]
                                     if ranks == 2 else [])]
    fields = list(dict.fromkeys(key for row in rows for key in row))
    machine, commit = machine_and_commit()
    stamp = f"{machine}, commit {commit}"
    write_csv(csv_path, rows,
              [f"machine: {machine}", f"commit: {commit}",
               "values per rank: the largest over the ranks; heap_*: heap "
               "growth of each phase (mallinfo2); peak: VmHWM"], fields)
    plot(rows, csv_path[:-3] + "png", stamp)


if __name__ == "__main__":
    main()
