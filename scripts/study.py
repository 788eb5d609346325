#!/usr/bin/python3
"""Speed-against-error study: runs coshell over benchmarks x element
combinations x refinement levels, collects every level's summary.json into
one CSV, draws per benchmark the relative error against wall time and
against n_dofs (log-log, one curve per element combination), and prints,
for each benchmark and error target, the fastest run that reaches it.

  scripts/study.py [--coshell build/coshell] [--output study]
                   [--benchmarks plates/clamped_square_pressure ...]
                   [--elements cst+dkt andes+dkt ...] [--levels 0,1,2,3,4]
                   [--targets 0.005 0.001] [--plots doc/study]
                   [--calculix doc/calculix/calculix_comparison.csv]

Benchmarks are prm files under prm/ (without .prm); each must define one
quantity of interest with a reference value. Element combinations are
MEMBRANE+BENDING with MEMBRANE in cst|andes|off and BENDING in
dkt|przemieniecki|off. --calculix overlays, dashed, the CalculiX curves
of scripts/calculix_compare.py (their time is whole-process wall time,
ours the in-process total).
"""
import argparse
import csv
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "doc", "scripts"))
from doc_common import machine_and_commit  # noqa: E402
DEFAULT_BENCHMARKS = ["plates/clamped_square_pressure",
                      "obstacle_course/scordelis_lo_roof",
                      "obstacle_course/pinched_cylinder",
                      "obstacle_course/pinched_hemisphere"]
FIELDS = ["benchmark", "elements", "level", "h", "n_cells", "n_dofs", "qoi",
          "value", "reference", "relative_error", "setup_s", "assemble_s",
          "solve_s", "output_s", "total_s"]


def run_case(args, benchmark, elements):
    membrane, bending = elements.split("+")
    output = os.path.join(args.output, benchmark.replace("/", "_"), elements)
    command = [args.coshell, os.path.join(ROOT, "prm", benchmark + ".prm"),
               "--output", output,
               "--set", f"Mesh/Refinement levels={args.levels}",
               "--set", f"Element/Membrane element={membrane}",
               "--set", f"Element/Bending element={bending}",
               "--set", "Output/Write VTU=false"]
    result = subprocess.run(command, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        print(f"  {benchmark} {elements}: failed: {result.stderr.strip()}")
        return []
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    return [row_of(benchmark, elements, level)
            for level in summary.get("levels", [summary])]


def row_of(benchmark, elements, level):
    name, value = next(iter(level["qoi"].items()))
    times = level["wall_time_s"]
    return {"benchmark": benchmark, "elements": elements,
            "level": level["refinement_level"], "h": level["h"],
            "n_cells": level["n_cells"], "n_dofs": level["n_dofs"],
            "qoi": name, "value": value,
            "reference": level.get("reference", {}).get(name, ""),
            "relative_error": level.get("relative_error", {}).get(name, ""),
            "setup_s": times["setup"], "assemble_s": times["assemble"],
            "solve_s": times["solve"], "output_s": times["output"],
            "total_s": times["total"]}


def read_calculix(path):
    """CalculiX rows of a calculix_compare.py CSV ('#' lines skipped)."""
    if not path:
        return []
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return [r for r in rows if r["code"] == "calculix"]


def plot_calculix(by_time, by_dofs, calculix_rows, benchmark, first_color):
    mine = [r for r in calculix_rows if r["benchmark"] == benchmark]
    for index, element in enumerate(sorted({r["element"] for r in mine})):
        curve = [r for r in mine if r["element"] == element]
        errors = [max(float(r["relative_error"]), 1e-16) for r in curve]
        style = dict(marker="s", linestyle="--", color=f"C{(first_color + index) % 10}",
                     label=f"CalculiX {element} (process)")
        by_time.loglog([float(r["process_wall_s"]) for r in curve], errors, **style)
        by_dofs.loglog([int(r["n_dofs"]) for r in curve], errors, **style)


def plot_benchmark(rows, benchmark, directory, calculix_rows=()):
    figure, (by_time, by_dofs) = plt.subplots(1, 2, figsize=(10, 4))
    for index, elements in enumerate(sorted({r["elements"] for r in rows})):
        mine = [r for r in rows if r["elements"] == elements and r["relative_error"] != ""]
        errors = [max(float(r["relative_error"]), 1e-16) for r in mine]
        style = dict(marker="o", color=f"C{index}", label=elements)
        by_time.loglog([float(r["total_s"]) for r in mine], errors, **style)
        by_dofs.loglog([int(r["n_dofs"]) for r in mine], errors, **style)
    plot_calculix(by_time, by_dofs, calculix_rows, benchmark,
                  len({r["elements"] for r in rows}))
    by_time.set_xlabel("wall time per run [s]")
    by_dofs.set_xlabel("n_dofs")
    for axes in (by_time, by_dofs):
        axes.set_ylabel("relative error")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize=8)
    figure.suptitle(benchmark)
    figure.tight_layout()
    path = os.path.join(directory, benchmark.replace("/", "_") + ".png")
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def fastest_to_target(rows, target):
    reached = [r for r in rows if r["relative_error"] != "" and
               float(r["relative_error"]) <= target]
    return min(reached, key=lambda r: float(r["total_s"])) if reached else None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", default=os.path.join(ROOT, "build", "coshell"))
    parser.add_argument("--output", default="study")
    parser.add_argument("--benchmarks", nargs="+", default=DEFAULT_BENCHMARKS)
    parser.add_argument("--elements", nargs="+",
                        default=["cst+dkt", "andes+dkt", "cst+przemieniecki",
                                 "andes+przemieniecki"])
    parser.add_argument("--levels", default="0,1,2,3,4")
    parser.add_argument("--targets", nargs="+", type=float, default=[0.005, 0.001])
    parser.add_argument("--plots", default=os.path.join(ROOT, "doc", "study"))
    parser.add_argument("--calculix", help="CSV of scripts/calculix_compare.py to overlay")
    args = parser.parse_args()

    rows = []
    for benchmark in args.benchmarks:
        for elements in args.elements:
            print(f"running {benchmark} with {elements}", flush=True)
            rows += run_case(args, benchmark, elements)
    if not rows:
        sys.exit("no run succeeded")
    os.makedirs(args.plots, exist_ok=True)
    table = os.path.join(args.plots, "study.csv")
    with open(table, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    machine, commit = machine_and_commit()
    print(f"\nmachine: {machine}; commit {commit}; table {table}")
    calculix_rows = read_calculix(args.calculix)
    for benchmark in args.benchmarks:
        mine = [r for r in rows if r["benchmark"] == benchmark]
        if not mine:
            continue
        path = plot_benchmark(mine, benchmark, args.plots, calculix_rows)
        print(f"{benchmark}: plot {path}")
        for target in args.targets:
            best = fastest_to_target(mine, target)
            if best:
                print(f"  fastest to {target:.2%}: {best['elements']} level "
                      f"{best['level']} ({best['n_dofs']} dofs) in "
                      f"{float(best['total_s']):.3g} s")
            else:
                print(f"  no run reached {target:.2%}")


if __name__ == "__main__":
    main()
