#!/usr/bin/python3
"""Benchmark (not a test): wall time of the phases of a linear solve against
the number of DoFs, for the clamped square plate under uniform pressure
(prm/plates/clamped_square_pressure.prm: crossed pattern, CST + DKT, UMFPACK),
one refinement level per run with Subdivisions x = y = n and no VTU output.

Writes doc/performance/plate_scaling.csv (one row per run, with the phase
times from summary.json, the peak resident memory of the coshell process and
the 1-minute load average and the cores used by other processes just before
the run) and doc/performance/plate_scaling.png
(log-log, with the exponents b of t = a N^b fitted over N >= --fit-from).

Usage (from the repository root; /usr/bin/python3 has matplotlib):

  /usr/bin/python3 doc/scripts/benchmark_plate_scaling.py --coshell build/coshell
      [--sizes 8 16 32 ...] [--repeats 3] [--fit-from 1e5] [--plot-only]

Run it on a quiet machine (uptime load < 1) and a Release build; the script
waits for the load to drop before starting and, before every run, until
other processes use less than --max-busy cores.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRM = os.path.join(ROOT, "prm", "plates", "clamped_square_pressure.prm")
OUT_DIR = os.path.join(ROOT, "doc", "performance")
CSV_PATH = os.path.join(OUT_DIR, "plate_scaling.csv")
PNG_PATH = os.path.join(OUT_DIR, "plate_scaling.png")
PHASES = ["setup", "assemble", "solve", "output", "total"]
FIELDS = (["subdivisions", "repeat", "n_cells", "n_dofs", "center_deflection",
           "relative_error"] + [f"{p}_s" for p in PHASES] +
          ["process_wall_s", "process_cpu_s", "peak_rss_mb", "load_1min_before",
           "busy_cores_before", "commit"])


def busy_cores(seconds=3.0):
    """CPU cores in use by all processes over a short interval (from
    /proc/stat), measured between runs, i.e. by other users."""
    def sample():
        with open("/proc/stat") as f:
            values = [int(v) for v in f.readline().split()[1:]]
        idle = values[3] + values[4]
        return sum(values) - idle, sum(values)
    busy0, total0 = sample()
    time.sleep(seconds)
    busy1, total1 = sample()
    return (busy1 - busy0) / max(1, total1 - total0) * os.cpu_count()


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


def run(coshell, n, repeat, work, max_busy, timeout):
    output = os.path.join(work, f"n{n}-r{repeat}")
    if os.path.isdir(output):
        shutil.rmtree(output)
    command = [coshell, PRM, "--output", output,
               "--set", "Mesh/Triangle pattern=crossed",
               "--set", "Element/Membrane element=cst",
               "--set", "Element/Bending element=dkt",
               "--set", "Mesh/Refinement levels=0",
               "--set", f"Mesh/Subdivisions x={n}",
               "--set", f"Mesh/Subdivisions y={n}",
               "--set", "Output/Write VTU=false"]
    others = wait_until_quiet(max_busy, timeout)
    load = os.getloadavg()[0]
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - start
    if status != 0:
        sys.exit(f"coshell failed for n = {n} (status {status})")
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    shutil.rmtree(output)
    row = dict(subdivisions=n, repeat=repeat, n_cells=summary["n_cells"],
               n_dofs=summary["n_dofs"],
               center_deflection=summary["qoi"]["center_deflection"],
               relative_error=summary["relative_error"]["center_deflection"],
               process_wall_s=wall,
               process_cpu_s=usage.ru_utime + usage.ru_stime,
               peak_rss_mb=usage.ru_maxrss / 1024.0,
               load_1min_before=load, busy_cores_before=others,
               commit=summary.get("commit", "unknown"))
    for phase in PHASES:
        row[f"{phase}_s"] = summary["wall_time_s"][phase]
    print(f"n = {n:4d}  N = {row['n_dofs']:8d}  " +
          "  ".join(f"{p} {row[p + '_s']:8.3f}" for p in PHASES) +
          f"  cpu/wall {row['process_cpu_s'] / wall:4.2f}"
          f"  rss {row['peak_rss_mb']:7.0f} MB  load {load:.2f}"
          f"  others {others:.2f} cores", flush=True)
    return row


def best_of(rows):
    """Per size, the repeat with the smallest total time."""
    best = {}
    for row in rows:
        n = int(row["n_dofs"])
        if n not in best or float(row["total_s"]) < float(best[n]["total_s"]):
            best[n] = row
    return [best[n] for n in sorted(best)]


def fit(xs, ys):
    """Least-squares fit of log y = log a + b log x; returns (a, b)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    b = sum((u - mx) * (v - my) for u, v in zip(lx, ly)) / sum(
        (u - mx) ** 2 for u in lx)
    return math.exp(my - b * mx), b


def plot(rows, fit_from, machine):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = best_of(rows)
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    colours = {"setup": "tab:gray", "assemble": "tab:blue",
               "solve": "tab:red", "output": "tab:green", "total": "black"}
    exponents = {}
    for phase in ["setup", "assemble", "solve", "total"]:
        xs = [float(r["n_dofs"]) for r in rows]
        ys = [float(r[f"{phase}_s"]) for r in rows]
        ax.loglog(xs, ys, "o", color=colours[phase], markersize=4)
        fx = [x for x in xs if x >= fit_from]
        fy = [y for x, y in zip(xs, ys) if x >= fit_from]
        if len(fx) >= 2:
            a, b = fit(fx, fy)
            exponents[phase] = b
            ax.loglog(fx, [a * x ** b for x in fx], "-", color=colours[phase],
                      label=f"{phase}: t ~ N^{b:.2f}")
    xs = [float(r["n_dofs"]) for r in rows]
    x0, y0 = xs[-1], float(rows[-1]["total_s"])
    ax.loglog([xs[0], x0], [y0 * xs[0] / x0 / 3, y0 / 3], ":", color="gray",
              label="O(N) guide")
    ax.set_xlabel("number of DoFs N")
    ax.set_ylabel("wall time [s] (best of repeats)")
    ax.set_title("Clamped square plate, crossed pattern, CST+DKT, UMFPACK, "
                 f"commit {rows[-1]['commit']}\n{machine}; fits over "
                 f"N >= {fit_from:g}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(PNG_PATH, dpi=110)
    plt.close(fig)
    return exponents


def machine_name():
    model, cores = "unknown CPU", os.cpu_count()
    try:
        for line in subprocess.run(["lscpu"], capture_output=True,
                                   text=True).stdout.splitlines():
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
    except OSError:
        pass
    memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2 ** 30
    return f"{model}, {cores} cores, {memory:.0f} GiB"


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--coshell", default=os.path.join(ROOT, "build", "coshell"))
    parser.add_argument("--sizes", type=int, nargs="*",
                        default=[8, 16, 32, 45, 64, 90, 128, 181, 256, 300, 330, 362, 384, 408])
    parser.add_argument("--repeats", type=int, default=3,
                        help="repeats for runs below 2e5 DoFs")
    parser.add_argument("--large-repeats", type=int, default=1,
                        help="repeats for runs from 2e5 DoFs on")
    parser.add_argument("--fit-from", type=float, default=1e5)
    parser.add_argument("--work", default="/tmp/coshell-benchmark")
    parser.add_argument("--plot-only", action="store_true")
    parser.add_argument("--max-load", type=float, default=1.0,
                        help="wait (up to 30 min) until the 1-minute load "
                             "average is below this before starting")
    parser.add_argument("--max-busy", type=float, default=0.1,
                        help="before each run, wait (up to --quiet-timeout s) "
                             "until other processes use fewer cores than this")
    parser.add_argument("--quiet-timeout", type=float, default=1800)
    parser.add_argument("--merge", action="store_true",
                        help="keep the rows of the existing CSV for sizes "
                             "not in --sizes (to re-measure a few sizes)")
    args = parser.parse_args()

    os.makedirs(OUT_DIR, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    if args.plot_only:
        with open(CSV_PATH) as f:
            rows = list(csv.DictReader(f))
    else:
        coshell = os.path.abspath(args.coshell)
        deadline = time.monotonic() + 1800
        while os.getloadavg()[0] >= args.max_load and time.monotonic() < deadline:
            print(f"load {os.getloadavg()[0]:.2f} >= {args.max_load}: waiting",
                  flush=True)
            time.sleep(30)
        rows = []
        for n in args.sizes:
            expected_dofs = 6 * ((n + 1) ** 2 + n ** 2)
            repeats = args.repeats if expected_dofs < 2e5 else args.large_repeats
            for repeat in range(repeats):
                rows.append(run(coshell, n, repeat, args.work,
                                args.max_busy, args.quiet_timeout))
        if args.merge and os.path.exists(CSV_PATH):
            with open(CSV_PATH) as f:
                kept = [r for r in csv.DictReader(f)
                        if int(r["subdivisions"]) not in args.sizes]
            rows = sorted(kept + rows, key=lambda r: (int(r["subdivisions"]),
                                                      int(r["repeat"])))
        with open(CSV_PATH, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=FIELDS)
            writer.writeheader()
            for row in rows:
                writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                                 for k, v in row.items()})
    machine = machine_name()
    exponents = plot(rows, args.fit_from, machine)
    print("machine:", machine)
    print("fitted exponents (N >= %g):" % args.fit_from,
          ", ".join(f"{p} {b:.2f}" for p, b in exponents.items()))


if __name__ == "__main__":
    main()
