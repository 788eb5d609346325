#!/usr/bin/python3
"""Benchmark (not a test): memory per rank and time per Newton iteration of a
co-rotational static solve on 1 and 2 MPI ranks, for two coshell binaries
(the one before the distributed Newton tangent and the one after).

The clamped square plate under pressure (prm/plates/clamped_square_pressure
.prm: crossed pattern, CST + DKT) made co-rotational (Analysis/Type =
nonlinear static), n x n squares with n = --size (144: 250 086 DoFs; 288:
998 790), --load-steps load steps, Linear solver/Method = --method, no VTU,
one thread per rank. Each binary runs on 2 ranks, --rounds times,
alternating with the other; the new binary also runs once on one rank. Per
run: the peak resident memory of the largest process (/usr/bin/time -v
reports the largest child: one rank of mpirun), the whole process's wall
time, the load path's time from summary.json (wall_time_s.solve) and, where
the binary writes it, its split (load_stepping_s: assembly, linear solver),
Newton iterations and the centre deflection (both runs must agree).

Writes doc/performance/mpi_newton_memory_METHOD.csv and .png.

Usage (from the repository root):
  /usr/bin/python3 doc/scripts/mpi_newton_memory.py --old OLD/coshell \\
      --new build/coshell --size 144
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


def scene_arguments(args, output):
    return [PRM, "--output", output,
            "--set", f"Mesh/Subdivisions x={args.size}",
            "--set", f"Mesh/Subdivisions y={args.size}",
            "--set", "Mesh/Refinement levels=0",
            "--set", "Element/Formulation=corotational",
            "--set", "Analysis/Type=nonlinear static",
            "--set", f"Nonlinear solver/Load steps={args.load_steps}",
            "--set", "Output/Write VTU=false",
            "--set", f"Linear solver/Method={args.method}"]


def run(args, label, binary, ranks):
    output = os.path.join(args.scratch, f"{label}-{ranks}")
    shutil.rmtree(output, ignore_errors=True)
    command = [binary] + scene_arguments(args, output)
    measured = run_scene_measured(command, ranks, 1, output)
    if measured is None:
        return None
    summary, wall, peak_kb = measured
    iterations = summary["newton_iterations"]
    path = summary.get("load_stepping_s", {})
    row = {"binary": label, "ranks": ranks, "n_dofs": summary["n_dofs"],
           "newton_iterations": iterations,
           "center_deflection": summary["qoi"]["center_deflection"],
           "peak_rss_mb_largest_process": round(peak_kb / 1024, 1),
           "process_wall_s": round(wall, 2),
           "load_path_s": round(summary["wall_time_s"]["solve"], 3),
           "load_path_s_per_iteration":
               round(summary["wall_time_s"]["solve"] / iterations, 3),
           "assembly_s_per_iteration":
               round(path["assembly"] / iterations, 3) if path else "",
           "linear_solver_s_per_iteration":
               round(path["linear_solver"] / iterations, 3) if path else ""}
    print(row, flush=True)
    shutil.rmtree(output, ignore_errors=True)
    return row


def plot(rows, path, stamp):
    figure, (memory, seconds) = plt.subplots(1, 2, figsize=(9, 4))
    labels = [r["binary"].replace(" ", "\n") + f"\n{r['ranks']} rank(s)"
              for r in rows]
    memory.bar(range(len(rows)), [r["peak_rss_mb_largest_process"]
                                  for r in rows], color="tab:blue")
    memory.set_xticks(range(len(rows)), labels, fontsize=7)
    memory.set_ylabel("peak resident memory of one rank, MB")
    seconds.bar(range(len(rows)), [r["load_path_s_per_iteration"]
                                   for r in rows], color="tab:orange")
    seconds.set_xticks(range(len(rows)), labels, fontsize=7)
    seconds.set_ylabel("load path per Newton iteration, s")
    figure.suptitle(f"co-rotational clamped plate, {rows[0]['n_dofs']} DoFs; "
                    + stamp, fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    print("wrote", path)


def redraw(name):
    with open(name + ".csv") as f:
        lines = f.readlines()
    stamp = "; ".join(l[2:].strip() for l in lines[:2] if l.startswith("#"))
    rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
    for row in rows:
        for key in ("peak_rss_mb_largest_process", "load_path_s_per_iteration"):
            row[key] = float(row[key])
    plot(rows, name + ".png", stamp)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--old", required=True, help="binary before")
    parser.add_argument("--new", required=True, help="binary after")
    parser.add_argument("--old-label", default="replicated tangent")
    parser.add_argument("--new-label", default="distributed tangent")
    parser.add_argument("--size", type=int, default=144)
    parser.add_argument("--load-steps", type=int, default=2)
    parser.add_argument("--method", default="amesos-mumps")
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--scratch", default="/tmp/coshell_mpi_newton_memory")
    parser.add_argument("--plot-only", action="store_true",
                        help="redraw the PNG from the CSV")
    args = parser.parse_args()
    name = os.path.join(OUT_DIR, f"mpi_newton_memory_{args.method}")
    if args.plot_only:
        redraw(name)
        return
    machine, commit = machine_and_commit()
    rows = [run(args, args.new_label, args.new, 1)]
    for _ in range(args.rounds):
        rows.append(run(args, args.old_label, args.old, 2))
        rows.append(run(args, args.new_label, args.new, 2))
    rows = [r for r in rows if r]
    header = [f"machine: {machine}", f"commit: {commit} (the new binary)",
              f"co-rotational clamped square plate, crossed, CST+DKT, "
              f"{args.size} x {args.size}, {args.load_steps} load steps, "
              f"{args.method}, one thread per rank"]
    write_csv(name + ".csv", rows, header)
    plot(rows, name + ".png", f"{args.method}; {machine}; commit {commit}")


if __name__ == "__main__":
    main()
