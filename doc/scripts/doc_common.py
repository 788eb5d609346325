"""Helpers shared by the documentation scripts: machine/commit stamps,
CSV files with '#' provenance lines, and finishing a matplotlib figure."""
import csv
import json
import os
import re
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def machine_and_commit():
    """CPU model and core count, and the short commit (marked when source/
    or include/ differ from it, since then the numbers are not of that
    commit)."""
    model, cores = "unknown", str(os.cpu_count())
    try:
        for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
            if line.startswith("CPU(s):"):
                cores = line.split(":", 1)[1].strip()
    except OSError:
        pass
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "source", "include"],
                           capture_output=True, text=True).stdout.strip()
    return f"{model}, {cores} cores", commit + (" (+ uncommitted source changes)" if dirty else "")


def run_with_peak_memory(command, environment):
    """Runs 'command' under /usr/bin/time -v: (the completed process, its
    wall time in s, the peak resident set of its largest process in kB;
    under mpirun that is one rank)."""
    start = time.time()
    result = subprocess.run(["/usr/bin/time", "-v"] + command, env=environment,
                            capture_output=True, text=True)
    wall = time.time() - start
    found = re.search(r"Maximum resident set size \(kbytes\): (\d+)",
                      result.stderr)
    return result, wall, int(found.group(1)) if found else 0


def run_scene_measured(command, ranks, threads, output):
    """Runs a coshell command line on 'ranks' MPI ranks (mpirun when more
    than one) with 'threads' threads each, writing into 'output': (its
    summary.json, the process wall time in s, the peak resident set of the
    largest process in kB), or None (printing the end of its output) if it
    failed."""
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    environment = dict(os.environ, DEAL_II_NUM_THREADS=str(threads),
                       OMPI_ALLOW_RUN_AS_ROOT="1",
                       OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    result, wall, peak_kb = run_with_peak_memory(command, environment)
    if result.returncode != 0:
        print(result.stdout[-2000:], result.stderr[-2000:])
        return None
    with open(os.path.join(output, "summary.json")) as f:
        return json.load(f), wall, peak_kb


def write_csv(path, rows, header_lines, fields=None):
    """Rows (dicts) as CSV, preceded by '# ' provenance lines."""
    with open(path, "w", newline="") as f:
        for line in header_lines:
            f.write(f"# {line}\n")
        writer = csv.DictWriter(f, fieldnames=fields or list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print("wrote", path)


def read_csv(path):
    """The rows (dicts of strings) of a CSV file that write_csv wrote,
    after its '#' provenance lines."""
    with open(path) as f:
        return list(csv.DictReader(line for line in f
                                   if not line.startswith("#")))


def largest_strains(output):
    """The largest bending and membrane strains over a run's steps
    (time_history.csv, Quantities of interest/Largest strains = true)."""
    with open(os.path.join(output, "time_history.csv")) as f:
        rows = list(csv.DictReader(f))
    return [max(float(r[column]) for r in rows)
            for column in ("max_bending_strain", "max_membrane_strain")]


def finish_plot(figure, axes, xlabel, ylabel, title, path,
                legend_below=False):
    """Labels, grid, legend (below the axes if 'legend_below', for plots
    whose data fill every corner), title; saves and clears."""
    axes.set_xlabel(xlabel)
    axes.set_ylabel(ylabel)
    axes.grid(True, which="both", alpha=0.3)
    if legend_below:
        axes.legend(fontsize=8, loc="upper center", ncol=2,
                    bbox_to_anchor=(0.5, -0.14))
    else:
        axes.legend(fontsize=8)
    axes.set_title(title)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    figure.clf()
    print("wrote", path)
