#!/usr/bin/python3
"""Speed of the IOL fold stage (prm/iol/injection.prm, stage 1 only, the
coarse lens of ctest iol.injection.fold: 203 triangles, 900 DoFs), one
thread, OpenBLAS on one thread. Each configuration is a coshell binary
and --set overrides; with --baseline an older binary (e.g. one built
from an earlier commit) runs the same scene first, so that the ratios
come from one invocation. Writes doc/performance/iol_fold_speed.csv
(Newton iterations, steps, wall time split into contact detection,
collision filter, pair terms, the rest of the assembly, linear solver
and other; ms per Newton iteration; the folded shape's width and strain
energy, which show whether the runs folded alike) and
iol_fold_speed.png, stamped with machine and commit.

  /usr/bin/python3 doc/scripts/iol_fold_speed.py --coshell build/coshell \\
      [--baseline OLD/coshell --baseline-label "8f02875"]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import ROOT, finish_plot, machine_and_commit, write_csv  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
FOLD_ONLY = ["Mesh/Gmsh parameters=optic_mesh_size = 0.9, haptic_mesh_size = 0.35",
             "Stage 2/Analysis type=none", "Stage 3/Analysis type=none",
             "Stage 4/Analysis type=none",
             "Parallel/Threads=1"]
PARTS = ("detection", "filter", "pair_terms", "elements", "linear_solver", "other")


def folded_width(row):
    """Distance between the optic's rim points y = +-3 mm (6 mm flat)."""
    def point(name, y):
        return (float(row[name + "_ux"]), y + float(row[name + "_uy"]),
                float(row[name + "_uz"]))
    return math.dist(point("rim_yp", 3), point("rim_ym", -3))


def run(label, coshell, prm, assignments, work):
    output = os.path.join(work, label.replace(" ", "_").replace(",", ""))
    command = [coshell, prm, "--output", output]
    for assignment in FOLD_ONLY + assignments:
        command += ["--set", assignment]
    environment = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL,
                   env=environment)
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(output, "time_history.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    seconds, contact = summary["time_stepping_s"], summary["contact"]
    # The contact's detection and pair terms run inside the assembly, its
    # filter outside (in "other").
    parts = {"detection": contact["detection_s"],
             "filter": contact["collision_filter_s"],
             "pair_terms": contact["pair_terms_s"],
             "elements": seconds["assembly"] - contact["detection_s"]
             - contact["pair_terms_s"],
             "linear_solver": seconds["linear_solver"],
             "other": seconds["other"] - contact["collision_filter_s"]}
    iterations = summary["newton_iterations"]
    row = {"configuration": label, "steps": summary["steps"],
           "newton_iterations": iterations,
           "wall_time_s": round(seconds["total"], 3),
           "ms_per_iteration": round(1e3 * seconds["total"] / iterations, 2),
           "real_time_factor": round(summary["real_time_factor"], 5)}
    row.update({f"{p}_s": round(v, 3) for p, v in parts.items()})
    row["folded_width_mm"] = round(folded_width(last), 4)
    row["strain_energy_n_mm"] = float(last["strain_energy"])
    row["smallest_gap_mm"] = contact["smallest_gap"]
    return row


def scene(source):
    return os.path.join(os.path.abspath(source), "prm", "iol", "injection.prm")


def plot(rows, commit):
    figure, axes = plt.subplots(figsize=(7.5, 4.2))
    labels = [r["configuration"].replace(", ", ",\n") for r in rows]
    bottom = [0.0] * len(rows)
    for part in PARTS:
        values = [r[f"{part}_s"] for r in rows]
        axes.bar(labels, values, bottom=bottom, label=part.replace("_", " "))
        bottom = [b + v for b, v in zip(bottom, values)]
    for x, r in enumerate(rows):
        axes.text(x, bottom[x], f"{r['newton_iterations']} it.\n"
                  f"{r['ms_per_iteration']:.1f} ms/it.", ha="center",
                  va="bottom", fontsize=7)
    axes.set_ylim(0, 1.2 * max(bottom))
    axes.tick_params(axis="x", labelsize=7)
    finish_plot(figure, axes, "", "wall time of the fold stage (s)",
                f"IOL fold, 1.3 s simulated, 203 triangles, 1 thread ({commit})",
                os.path.join(OUT, "iol_fold_speed.png"))


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--baseline", help="an older coshell binary")
    parser.add_argument("--baseline-source",
                        help="its source tree (its prm/iol/injection.prm "
                        "and meshes); default: this one")
    parser.add_argument("--baseline-label", default="baseline")
    args = parser.parse_args()
    machine, commit = machine_and_commit()
    configurations = []
    if args.baseline:
        source = args.baseline_source or ROOT
        configurations.append((f"{args.baseline_label}, residual test",
                               args.baseline, scene(source), []))
    configurations += [
        (f"{commit}, residual test", args.coshell, scene(ROOT),
         ["Nonlinear solver/Correction tolerance=0"]),
        (f"{commit}, correction 1e-5 mm", args.coshell, scene(ROOT), [])]
    with tempfile.TemporaryDirectory() as work:
        rows = [run(label, os.path.abspath(binary), prm, sets, work)
                for label, binary, prm, sets in configurations]
    for r in rows:
        print(r)
    os.makedirs(OUT, exist_ok=True)
    write_csv(os.path.join(OUT, "iol_fold_speed.csv"), rows,
              [f"machine: {machine}; commit {commit}",
               "prm/iol/injection.prm stage 1 (fold, 1.3 s), coarse lens "
               "(203 triangles, 900 DoFs), Parallel/Threads = 1, "
               "OPENBLAS_NUM_THREADS = 1; runs one after another"])
    plot(rows, commit)


if __name__ == "__main__":
    main()
