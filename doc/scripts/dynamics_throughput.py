#!/usr/bin/python3
"""Dynamics throughput benchmark: the flapping plate (prm/dynamics/
flapping_plate.prm, 484 triangles, 1590 DoFs) with each time integrator,
one assembly thread. Writes doc/performance/dynamics_throughput.csv (steps
per second, real-time factor, per-step breakdown: assembly, linear solver,
other) and dynamics_throughput.png, stamped with machine and commit. All
runs are made in one invocation so their ratios are comparable.

  /usr/bin/python3 doc/scripts/dynamics_throughput.py --coshell build/coshell
"""
import argparse
import json
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
CASES = [
    ("generalized alpha", "consistent"),
    ("generalized alpha", "paper"),
    ("implicit euler", "consistent"),
    ("linearized implicit euler", "consistent"),
]


def run(coshell, method, tangent, work):
    output = os.path.join(work, f"{method}-{tangent}".replace(" ", "_"))
    command = [coshell, os.path.join(ROOT, "prm", "dynamics", "flapping_plate.prm"),
               "--output", output, "--set", f"Time integration/Method={method}",
               "--set", f"Nonlinear solver/Tangent={tangent}",
               "--set", "Parallel/Threads=1"]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    steps, seconds = summary["steps"], summary["time_stepping_s"]
    return {"method": method, "tangent": tangent, "steps": steps,
            "newton_iterations": summary["newton_iterations"],
            "simulated_time_s": summary["simulated_time_s"],
            "wall_time_s": round(seconds["total"], 4),
            "steps_per_second": round(steps / seconds["total"], 2),
            "real_time_factor": round(summary["real_time_factor"], 5),
            "assembly_ms_per_step": round(1e3 * seconds["assembly"] / steps, 3),
            "linear_solver_ms_per_step": round(1e3 * seconds["linear_solver"] / steps, 3),
            "other_ms_per_step": round(1e3 * seconds["other"] / steps, 3),
            "final_tip_w": summary["qoi"]["tip_w"]}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    args = parser.parse_args()
    machine, commit = machine_and_commit()
    with tempfile.TemporaryDirectory() as work:
        rows = [run(os.path.abspath(args.coshell), m, t, work) for m, t in CASES]
    os.makedirs(OUT, exist_ok=True)
    write_csv(os.path.join(OUT, "dynamics_throughput.csv"), rows,
              [f"machine: {machine}; commit {commit}",
               "prm/dynamics/flapping_plate.prm, 0.2 s simulated, dt = 2 ms, Parallel/Threads = 1"])
    figure, axes = plt.subplots(figsize=(7, 4))
    labels = [f"{r['method']}\n({r['tangent']})" for r in rows]
    bottom = [0.0] * len(rows)
    for part in ("assembly", "linear_solver", "other"):
        values = [r[f"{part}_ms_per_step"] for r in rows]
        axes.bar(labels, values, bottom=bottom, label=part.replace("_", " "))
        bottom = [b + v for b, v in zip(bottom, values)]
    for x, r in enumerate(rows):
        axes.text(x, bottom[x], f"RTF {r['real_time_factor']:.3f}", ha="center",
                  va="bottom", fontsize=8)
    axes.tick_params(axis="x", labelsize=7)
    finish_plot(figure, axes, "", "wall time per step (ms)",
                f"Flapping plate, 484 triangles ({commit})",
                os.path.join(OUT, "dynamics_throughput.png"))


if __name__ == "__main__":
    main()
