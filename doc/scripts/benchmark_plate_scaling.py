#!/usr/bin/python3
"""Benchmark (not a test): wall time of the phases of a linear solve against
the number of DoFs, for the clamped square plate under uniform pressure
(prm/plates/clamped_square_pressure.prm: crossed pattern, CST + DKT), one
refinement level per run with Subdivisions x = y = n and no VTU output, for
one or more Linear solver/Method values.

Writes doc/performance/plate_scaling.csv ('#' lines naming machine, cores,
the commit of the coshell binary and of the checkout, and the solvers; one
row per run with the phase times and thread count from summary.json, the
process wall time, peak resident memory and bytes per DoF from
/usr/bin/time -v, and the load just before the run) and
doc/performance/plate_scaling.png (log-log: assembly, solve per method,
total; exponents b of t = a N^b fitted over N >= --fit-from in the legend).
With --speedup-size n it also runs that size with DEAL_II_NUM_THREADS = 1
and 2 into doc/performance/plate_threads.csv (2-thread assembly speedup).

Every run holds --lock (flock, shared with the other measurements on this
machine), and waits until other processes use less than --max-busy cores.

Usage (from the repository root; /usr/bin/python3 has matplotlib); the
measurements of doc/performance/scaling.md:

  /usr/bin/python3 doc/scripts/benchmark_plate_scaling.py \
      --coshell /tmp/coshell-stable2/coshell --commit a21ba22 \
      --methods cholmod umfpack:2.1e6 --speedup-size 362

  options: [--sizes 8 16 32 ...] [--repeats 3] [--large-repeats 1]
           [--fit-from 1e5] [--plot-only] [--merge]

Runs where other processes used CPU anyway (busy_cores_others_during > 0.2)
should be re-measured with --merge --sizes ....

A method is written METHOD or METHOD:MAX_DOFS (sizes above MAX_DOFS are
skipped for it).
"""

import argparse
import csv
import fcntl
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import machine_and_commit, write_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRM = os.path.join(ROOT, "prm", "plates", "clamped_square_pressure.prm")
OUT_DIR = os.path.join(ROOT, "doc", "performance")
CSV_PATH = os.path.join(OUT_DIR, "plate_scaling.csv")
PNG_PATH = os.path.join(OUT_DIR, "plate_scaling.png")
THREADS_CSV_PATH = os.path.join(OUT_DIR, "plate_threads.csv")
PHASES = ["setup", "assemble", "solve", "output", "total"]
FIELDS = (["method", "subdivisions", "repeat", "threads", "n_cells", "n_dofs",
           "center_deflection", "relative_error"] + [f"{p}_s" for p in PHASES] +
          ["process_wall_s", "process_cpu_s", "peak_rss_mb", "bytes_per_dof",
           "load_1min_before", "busy_cores_before", "busy_cores_others_during",
           "commit"])


def cpu_seconds():
    """(busy, total) CPU time of all processes so far, from /proc/stat."""
    with open("/proc/stat") as f:
        values = [int(v) for v in f.readline().split()[1:]]
    ticks = os.sysconf("SC_CLK_TCK")
    return (sum(values) - values[3] - values[4]) / ticks, sum(values) / ticks


def busy_cores(seconds=3.0):
    """CPU cores in use by all processes over a short interval, measured
    between runs, i.e. by other users."""
    busy0, total0 = cpu_seconds()
    time.sleep(seconds)
    busy1, total1 = cpu_seconds()
    return (busy1 - busy0) / max(1e-9, total1 - total0) * os.cpu_count()


def wait_until_quiet(max_busy, timeout):
    """Waits until other processes use less than max_busy cores."""
    deadline = time.monotonic() + timeout
    busy = busy_cores()
    while busy >= max_busy and time.monotonic() < deadline:
        print(f"  machine busy ({busy:.2f} cores in use by others): waiting",
              flush=True)
        time.sleep(20)
        busy = busy_cores()
    return busy


def run(coshell, method, n, repeat, args, threads=None):
    """One coshell run under the measurement lock; returns the CSV row.
    threads: value of DEAL_II_NUM_THREADS (None: all cores)."""
    output = os.path.join(args.work, f"{method}-n{n}-r{repeat}")
    if os.path.isdir(output):
        shutil.rmtree(output)
    command = ["/usr/bin/time", "-v", coshell, PRM, "--output", output,
               "--set", "Mesh/Triangle pattern=crossed",
               "--set", "Element/Membrane element=cst",
               "--set", "Element/Bending element=dkt",
               "--set", "Mesh/Refinement levels=0",
               "--set", f"Mesh/Subdivisions x={n}",
               "--set", f"Mesh/Subdivisions y={n}",
               "--set", f"Linear solver/Method={method}",
               "--set", "Output/Write VTU=false"]
    environment = dict(os.environ)
    environment.pop("DEAL_II_NUM_THREADS", None)
    if threads is not None:
        environment["DEAL_II_NUM_THREADS"] = str(threads)
    with open(args.lock, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        others = wait_until_quiet(args.max_busy, args.quiet_timeout)
        load = os.getloadavg()[0]
        busy_start, _ = cpu_seconds()
        start = time.monotonic()
        process = subprocess.run(command, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.PIPE, text=True, env=environment)
        wall = time.monotonic() - start
        busy_during = cpu_seconds()[0] - busy_start
    if process.returncode != 0:
        sys.exit(f"coshell failed for {method}, n = {n}:\n{process.stderr[-2000:]}")
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    shutil.rmtree(output)

    def time_v(label):
        return float(re.search(re.escape(label) + r": ([0-9.]+)", process.stderr).group(1))
    rss_kb = time_v("Maximum resident set size (kbytes)")
    cpu = time_v("User time (seconds)") + time_v("System time (seconds)")
    row = dict(method=method, subdivisions=n, repeat=repeat,
               threads=summary.get("threads", ""), n_cells=summary["n_cells"],
               n_dofs=summary["n_dofs"],
               center_deflection=summary["qoi"]["center_deflection"],
               relative_error=summary["relative_error"]["center_deflection"],
               process_wall_s=wall,
               process_cpu_s=cpu,
               peak_rss_mb=rss_kb / 1024.0,
               bytes_per_dof=round(rss_kb * 1024 / summary["n_dofs"]),
               load_1min_before=load, busy_cores_before=others,
               busy_cores_others_during=max(0.0, busy_during - cpu) / wall,
               commit=args.commit or summary.get("commit", "unknown"))
    for phase in PHASES:
        row[f"{phase}_s"] = summary["wall_time_s"][phase]
    print(f"{method:8s} n = {n:4d}  N = {row['n_dofs']:8d}  threads {row['threads']}  " +
          "  ".join(f"{p} {row[p + '_s']:8.3f}" for p in PHASES) +
          f"  cpu/wall {row['process_cpu_s'] / wall:4.2f}"
          f"  rss {row['peak_rss_mb']:7.0f} MB ({row['bytes_per_dof']} B/DoF)"
          f"  others {others:.2f} cores before,"
          f" {row['busy_cores_others_during']:.2f} during", flush=True)
    return row


def best_of(rows):
    """Per method and size, the repeat with the smallest total time."""
    best = {}
    for row in rows:
        key = (row["method"], int(row["n_dofs"]))
        if key not in best or float(row["total_s"]) < float(best[key]["total_s"]):
            best[key] = row
    return [best[key] for key in sorted(best)]


def fit(xs, ys):
    """Least-squares fit of log y = log a + b log x; returns (a, b)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    b = sum((u - mx) * (v - my) for u, v in zip(lx, ly)) / sum(
        (u - mx) ** 2 for u in lx)
    return math.exp(my - b * mx), b


def plot(rows, fit_from, title):
    """Assembly and total of the first method, solve of every method;
    returns {curve: fitted exponent}."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = best_of(rows)
    methods = list(dict.fromkeys(r["method"] for r in rows))
    curves = [(f"assemble ({methods[0]})", methods[0], "assemble", "tab:blue", "o")]
    curves += [(f"solve ({m})", m, "solve", colour, marker)
               for m, colour, marker in zip(methods, ["tab:red", "tab:orange", "tab:purple"],
                                            ["s", "^", "v"])]
    curves += [(f"total ({methods[0]})", methods[0], "total", "black", "D")]
    fig, ax = plt.subplots(figsize=(7.5, 6))
    exponents = {}
    for label, method, phase, colour, marker in curves:
        mine = [r for r in rows if r["method"] == method]
        xs = [float(r["n_dofs"]) for r in mine]
        ys = [float(r[f"{phase}_s"]) for r in mine]
        fx = [x for x in xs if x >= fit_from]
        fy = [y for x, y in zip(xs, ys) if x >= fit_from]
        if len(fx) >= 2:
            a, b = fit(fx, fy)
            exponents[label] = b
            label = f"{label}: t ~ N^{b:.2f}"
            ax.loglog(fx, [a * x ** b for x in fx], "-", color=colour, linewidth=0.8)
        ax.loglog(xs, ys, marker, color=colour, markersize=4, label=label)
    ax.set_xlabel("number of DoFs N")
    ax.set_ylabel("wall time [s] (summary.json, best of repeats)")
    ax.set_title(f"{title}\nfits over N >= {fit_from:g}", fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(PNG_PATH, dpi=110)
    plt.close(fig)
    return exponents


def provenance(rows):
    """'#' lines of the CSV files: machine, commits, solvers, threads."""
    machine, checkout = machine_and_commit()
    memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2 ** 30
    binary = ", ".join(sorted({str(r["commit"]) for r in rows}))
    return [f"machine: {machine}, {memory:.0f} GiB",
            f"coshell commit (summary.json): {binary}; checkout: {checkout}",
            "solvers: " + ", ".join(dict.fromkeys(r["method"] for r in rows)) +
            "; threads: " + ", ".join(sorted({str(r["threads"]) for r in rows}))]


def write_rows(path, rows):
    formatted = [{k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()}
                 for row in rows]
    write_csv(path, formatted, provenance(rows), FIELDS)


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def parse_method(text):
    name, _, limit = text.partition(":")
    return name, float(limit) if limit else math.inf


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--coshell", default=os.path.join(ROOT, "build", "coshell"))
    parser.add_argument("--methods", nargs="+", type=parse_method,
                        default=[("cholmod", math.inf)],
                        help="METHOD or METHOD:MAX_DOFS; the first gives the "
                             "assembly and total curves")
    parser.add_argument("--sizes", type=int, nargs="*",
                        default=[8, 16, 32, 45, 64, 90, 128, 181, 256, 300, 362,
                                 408, 450, 500])
    parser.add_argument("--repeats", type=int, default=3,
                        help="repeats for runs below 2e5 DoFs")
    parser.add_argument("--large-repeats", type=int, default=1,
                        help="repeats for runs from 2e5 DoFs on")
    parser.add_argument("--speedup-size", type=int,
                        help="also run this size with DEAL_II_NUM_THREADS = 1 "
                             "and 2 (3 repeats each) into plate_threads.csv")
    parser.add_argument("--commit",
                        help="commit of the coshell binary, recorded instead of "
                             "summary.json's (which is stamped when cmake is "
                             "configured, so stale in a build dir reused "
                             "across commits)")
    parser.add_argument("--fit-from", type=float, default=1e5)
    parser.add_argument("--work", default="/tmp/coshell-benchmark")
    parser.add_argument("--lock", default="/tmp/coshell-measure.lock")
    parser.add_argument("--plot-only", action="store_true")
    parser.add_argument("--merge", action="store_true",
                        help="keep the rows of the existing CSV for (method, "
                             "size) pairs not measured now (to re-measure a "
                             "few sizes)")
    parser.add_argument("--max-busy", type=float, default=0.3,
                        help="before each run, wait (up to --quiet-timeout s) "
                             "until other processes use fewer cores than this")
    parser.add_argument("--quiet-timeout", type=float, default=600)
    args = parser.parse_args()

    os.makedirs(OUT_DIR, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    if args.plot_only:
        rows = read_rows(CSV_PATH)
    else:
        coshell = os.path.abspath(args.coshell)
        rows = []
        for method, max_dofs in args.methods:
            for n in args.sizes:
                expected_dofs = 6 * ((n + 1) ** 2 + n ** 2)
                if expected_dofs > max_dofs:
                    continue
                repeats = args.repeats if expected_dofs < 2e5 else args.large_repeats
                for repeat in range(repeats):
                    rows.append(run(coshell, method, n, repeat, args))
        if args.merge and os.path.exists(CSV_PATH):
            measured = {(r["method"], str(r["subdivisions"])) for r in rows}
            rows = sorted([r for r in read_rows(CSV_PATH)
                           if (r["method"], r["subdivisions"]) not in measured] + rows,
                          key=lambda r: (r["method"] != args.methods[0][0], r["method"],
                                         int(r["subdivisions"]), int(r["repeat"])))
        write_rows(CSV_PATH, rows)
        if args.speedup_size:
            speedup = [run(coshell, args.methods[0][0], args.speedup_size, repeat,
                           args, threads)
                       for threads in (1, 2) for repeat in range(3)]
            write_rows(THREADS_CSV_PATH, speedup)
    if os.path.exists(THREADS_CSV_PATH):
        speedup = read_rows(THREADS_CSV_PATH)
        best = {t: min(float(r["assemble_s"]) for r in speedup if r["threads"] == t)
                for t in ("1", "2")}
        print(f"assembly at N = {speedup[0]['n_dofs']}: 1 thread {best['1']:.3f} s, "
              f"2 threads {best['2']:.3f} s, speedup {best['1'] / best['2']:.2f}")
    header = provenance(rows)
    exponents = plot(rows, args.fit_from,
                     "\n".join(["clamped square plate, crossed, CST+DKT"] + header))
    print("\n".join(header))
    print("fitted exponents (N >= %g):" % args.fit_from,
          ", ".join(f"{p} {b:.2f}" for p, b in exponents.items()))


if __name__ == "__main__":
    main()
