#!/usr/bin/python3
"""Measurements behind doc/performance/elements-and-assembly.md (element
kernels, assembly) and doc/performance/scaling.md (linear solvers, AMG).
Writes into doc/performance/:

  element_benchmarks.csv   Google Benchmark aggregates (mean, stddev, ...)
                           of coshell_element_benchmarks (with '#' header
                           lines naming machine and commit)
  assembly_breakdown.csv   clamped-plate assembly per element, 1 and 2
                           threads: kernel, scatter, total
  amg_near_null_space.csv  CG-AMG iterations on the Scordelis-Lo roof with
                           and without the rigid-body near-null space
  linear_solvers.csv       clamped square plate (prm/plates/
                           clamped_square_pressure.prm, one refinement level
                           per run) solved by each Linear solver/Method:
                           n_dofs, wall_time_s.{assemble,solve,total},
                           process wall time, peak RSS (/usr/bin/time -v)
  linear_solvers.png       solve time against n_dofs, log-log

  /usr/bin/python3 doc/scripts/performance_measurements.py \
      --build /tmp/final-docs-build [--levels 3 4 5 6] [--timeout 300]
      [--skip-kernels] [--skip-solvers]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from doc_common import finish_plot, machine_and_commit, write_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT = os.path.join(ROOT, "doc", "performance")
METHODS = ["cholmod", "umfpack", "amesos-klu", "amesos-mumps", "cg-amg"]
NULL_SPACES = ["rigid body", "none"]


def kernels(args, header):
    """One run of coshell_element_benchmarks in JSON (the CSV reporter aborts
    when only some benchmarks carry the us_per_element counter): the mean of
    3 repetitions per benchmark into element_benchmarks.csv, and the
    per-element split of the plate assembly (kernel, scatter = full - kernel)
    into assembly_breakdown.csv."""
    binary = os.path.join(args.build, "benchmarks", "coshell_element_benchmarks")
    result = subprocess.run([binary, "--benchmark_format=json",
                             "--benchmark_repetitions=3",
                             "--benchmark_report_aggregates_only=true"],
                            capture_output=True, text=True, check=True)
    report = json.loads(result.stdout)
    context = report["context"]
    header = header + [f"Google Benchmark: {context['num_cpus']} CPUs at "
                       f"{context['mhz_per_cpu']} MHz, library built as "
                       f"{context['library_build_type']}, {context['date']}"]
    rows = [{"name": b["run_name"], "aggregate": b["aggregate_name"],
             "real_time": f"{b['real_time']:.6g}", "cpu_time": f"{b['cpu_time']:.6g}",
             "time_unit": b["time_unit"],
             "us_per_element": f"{b['us_per_element'] * 1e6:.4g}" if "us_per_element" in b else ""}
            for b in report["benchmarks"]
            if b.get("aggregate_name") in ("mean", "median", "stddev")]
    write_csv(os.path.join(OUT, "element_benchmarks.csv"), rows, header)
    for row in rows:
        if row["aggregate"] == "mean":
            print(f"{row['name']:45s} {row['real_time']:>10s} {row['time_unit']}"
                  f" {row['us_per_element'] and row['us_per_element'] + ' us/element'}")
    per_element = {r["name"]: float(r["us_per_element"]) for r in rows
                   if r["aggregate"] == "mean" and r["us_per_element"]}
    breakdown = []
    for threads in (1, 2):
        kernel = per_element[f"plate_assembly/threads:{threads}/scatter:0/real_time"]
        total = per_element[f"plate_assembly/threads:{threads}/scatter:1/real_time"]
        breakdown.append({"threads": threads, "kernel_us_per_element": f"{kernel:.3f}",
                          "scatter_us_per_element": f"{total - kernel:.3f}",
                          "assembly_us_per_element": f"{total:.3f}"})
    write_csv(os.path.join(OUT, "assembly_breakdown.csv"), breakdown, header)
    for row in breakdown:
        print(row)


def solvers(args, header):
    coshell = os.path.join(args.build, "coshell")
    prm = os.path.join(ROOT, "prm", "plates", "clamped_square_pressure.prm")
    records = []
    for level in args.levels:
        for method in METHODS:
            output = os.path.join(args.work, f"L{level}-{method}")
            shutil.rmtree(output, ignore_errors=True)
            command = ["/usr/bin/time", "-v", coshell, prm, "--output", output,
                       "--set", f"Mesh/Refinement levels={level}",
                       "--set", f"Linear solver/Method={method}",
                       "--set", "Output/Write VTU=false"]
            start = time.perf_counter()
            try:
                result = subprocess.run(command, capture_output=True, text=True,
                                        timeout=args.timeout)
                status = "ok" if result.returncode == 0 else \
                    "failed: " + result.stderr.strip().splitlines()[0][:120]
                stderr = result.stderr
                stdout = result.stdout
            except subprocess.TimeoutExpired:
                status, stderr, stdout = f"timeout ({args.timeout:g} s)", "", ""
            wall = time.perf_counter() - start
            rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", stderr)
            record = {"level": level, "method": method, "status": status,
                      "n_dofs": "", "assemble_s": "", "solve_s": "", "total_s": "",
                      "process_wall_s": f"{wall:.3f}",
                      "max_rss_kb": rss.group(1) if rss else "",
                      "bytes_per_dof": "", "center_deflection": "",
                      "cg_iterations": ""}
            summary_path = os.path.join(output, "summary.json")
            if status == "ok" and os.path.exists(summary_path):
                with open(summary_path) as f:
                    summary = json.load(f)
                times = summary["wall_time_s"]
                record.update(n_dofs=summary["n_dofs"],
                              assemble_s=times["assemble"], solve_s=times["solve"],
                              total_s=times["total"],
                              center_deflection=summary["qoi"]["center_deflection"])
                if method == "cg-amg":
                    record["cg_iterations"] = summary["linear_solver_iterations"]
                if rss:
                    record["bytes_per_dof"] = f"{int(rss.group(1)) * 1024 / summary['n_dofs']:.0f}"
            records.append(record)
            print(" ".join(f"{k}={v}" for k, v in record.items()), flush=True)
            with open(os.path.join(output if os.path.isdir(output) else args.work,
                                   "stdout.log"), "w") as f:
                f.write(stdout)
    write_csv(os.path.join(OUT, "linear_solvers.csv"), records, header)

    figure, axes = plt.subplots(figsize=(6, 4.2))
    for index, method in enumerate(METHODS):
        mine = [r for r in records if r["method"] == method and r["status"] == "ok"]
        if mine:
            axes.loglog([r["n_dofs"] for r in mine], [r["solve_s"] for r in mine],
                        "o-", color=f"C{index}", label=method)
    finish_plot(figure, axes, "n_dofs", "wall_time_s.solve [s]",
                "clamped square plate (linear, CST+DKT, crossed)",
                os.path.join(OUT, "linear_solvers.png"))


def amg_null_space(args, header):
    """CG-AMG on a thin curved shell (Scordelis-Lo roof, h/R = 0.01) with
    and without the rigid-body near-null space: CG iterations and solve
    time per level, into amg_near_null_space.csv."""
    coshell = os.path.join(args.build, "coshell")
    prm = os.path.join(ROOT, "prm", "obstacle_course", "scordelis_lo_roof.prm")
    records = []
    for level in (2, 3, 4):
        for space in NULL_SPACES:
            output = os.path.join(args.work, f"roof-L{level}-{space.replace(' ', '_')}")
            shutil.rmtree(output, ignore_errors=True)
            subprocess.run([coshell, prm, "--output", output,
                            "--set", f"Mesh/Refinement levels={level}",
                            "--set", "Linear solver/Method=cg-amg",
                            "--set", f"Linear solver/AMG near-null space={space}",
                            "--set", "Output/Write VTU=false"],
                           capture_output=True, check=True, timeout=args.timeout)
            with open(os.path.join(output, "summary.json")) as f:
                summary = json.load(f)
            records.append({"level": level, "near_null_space": space,
                            "n_dofs": summary["n_dofs"],
                            "cg_iterations": summary["linear_solver_iterations"],
                            "solve_s": summary["wall_time_s"]["solve"],
                            "free_edge_deflection": summary["qoi"]["free_edge_deflection"]})
            print(records[-1], flush=True)
    write_csv(os.path.join(OUT, "amg_near_null_space.csv"), records, header)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--work", default="/tmp/perf-docs")
    parser.add_argument("--levels", nargs="+", type=int, default=[3, 4, 5, 6])
    parser.add_argument("--timeout", type=float, default=300)
    parser.add_argument("--skip-kernels", action="store_true")
    parser.add_argument("--skip-solvers", action="store_true")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    machine, commit = machine_and_commit()
    header = [f"machine: {machine}; commit {commit}; build {args.build} (Release)"]
    if not args.skip_kernels:
        kernels(args, header)
    if not args.skip_solvers:
        solvers(args, header)
        amg_null_space(args, header)


if __name__ == "__main__":
    main()
