#!/usr/bin/python3
"""Measurements behind doc/performance.md (sections on element kernels,
linear solvers and memory). Writes into doc/performance/:

  element_benchmarks.csv   raw Google Benchmark CSV of
                           coshell_element_benchmarks (with '#' header lines
                           naming machine and commit)
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
import csv
import io
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
METHODS = ["cholmod", "umfpack", "amesos-klu", "cg-amg"]


def kernels(args, header):
    binary = os.path.join(args.build, "benchmarks", "coshell_element_benchmarks")
    # Google Benchmark's CSV reporter aborts when only some benchmarks
    # define a user counter (us_per_element), so the kernels and the
    # assembly are run as two filtered invocations and concatenated.
    parts = []
    for pattern in ("kernel", "linear_assembly"):
        result = subprocess.run([binary, "--benchmark_format=csv",
                                 f"--benchmark_filter={pattern}",
                                 "--benchmark_repetitions=3",
                                 "--benchmark_report_aggregates_only=true"],
                                capture_output=True, text=True, check=True)
        parts.append(result.stdout[result.stdout.index("name,"):])
    # two CSV blocks, each with its own header line
    text = parts[0].rstrip("\n") + "\n" + parts[1]
    path = os.path.join(OUT, "element_benchmarks.csv")
    with open(path, "w") as f:
        for line in header:
            f.write(f"# {line}\n")
        f.write(text)
    print("wrote", path)
    for row in (r for part in parts for r in csv.DictReader(io.StringIO(part))):
        extra = f" us_per_element={float(row['us_per_element']) * 1e6:.3f}" \
            if row.get("us_per_element") else ""
        print(f"{row['name']:45s} real {float(row['real_time']):10.3f} {row['time_unit']}"
              f" cpu {float(row['cpu_time']):10.3f}{extra}")


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
            its = re.search(r"(\d+) (?:CG )?iterations", stdout)
            if its and method == "cg-amg":
                record["cg_iterations"] = its.group(1)
            summary_path = os.path.join(output, "summary.json")
            if status == "ok" and os.path.exists(summary_path):
                with open(summary_path) as f:
                    summary = json.load(f)
                times = summary["wall_time_s"]
                record.update(n_dofs=summary["n_dofs"],
                              assemble_s=times["assemble"], solve_s=times["solve"],
                              total_s=times["total"],
                              center_deflection=summary["qoi"]["center_deflection"])
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


if __name__ == "__main__":
    main()
