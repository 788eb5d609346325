"""Helpers shared by the documentation scripts: machine/commit stamps,
CSV files with '#' provenance lines, and finishing a matplotlib figure."""
import csv
import os
import subprocess

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


def write_csv(path, rows, header_lines, fields=None):
    """Rows (dicts) as CSV, preceded by '# ' provenance lines."""
    with open(path, "w", newline="") as f:
        for line in header_lines:
            f.write(f"# {line}\n")
        writer = csv.DictWriter(f, fieldnames=fields or list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print("wrote", path)


def largest_strains(output):
    """The largest bending and membrane strains over a run's steps
    (time_history.csv, Quantities of interest/Largest strains = true)."""
    with open(os.path.join(output, "time_history.csv")) as f:
        rows = list(csv.DictReader(f))
    return [max(float(r[column]) for r in rows)
            for column in ("max_bending_strain", "max_membrane_strain")]


def finish_plot(figure, axes, xlabel, ylabel, title, path):
    axes.set_xlabel(xlabel)
    axes.set_ylabel(ylabel)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8)
    axes.set_title(title)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    figure.clf()
    print("wrote", path)
