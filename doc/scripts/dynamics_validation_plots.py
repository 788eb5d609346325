#!/usr/bin/python3
"""Conservation and order plots of the dynamics validation
(doc/validation/dynamics.md, "Integrators, conservation, order and
restart"): runs the free-flying plate
with each integrator and the time-step study, and writes to
doc/validation/dynamics/
  free_flying_conservation.csv/.png  relative drift of the total energy and
                                     of |L| against time, per scheme
  time_order.csv/.png                final-position error against dt
                                     (generalized alpha, implicit Euler)
stamped with machine and commit.

  /usr/bin/python3 doc/scripts/dynamics_validation_plots.py --coshell build/coshell
"""
import argparse
import csv
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

OUT = os.path.join(ROOT, "doc", "validation", "dynamics")
PRM = os.path.join(ROOT, "prm", "dynamics", "free_flying_plate.prm")
METHODS = ["generalized alpha", "implicit euler", "linearized implicit euler"]
QOIS = ["corner_x", "corner_z", "far_x", "far_y", "far_z"]


def run(coshell, output, sets):
    command = [coshell, PRM, "--output", output]
    for assignment in sets:
        command += ["--set", assignment]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(output, "time_history.csv")) as f:
        return list(csv.DictReader(f))


def norm3(row, prefix):
    return math.sqrt(sum(float(row[f"{prefix}_{c}"]) ** 2 for c in "xyz"))


def conservation(coshell, work):
    rows, figure = [], plt.figure(figsize=(7, 4))
    axes = figure.add_subplot(111)
    for method in METHODS:
        history = run(coshell, os.path.join(work, method.replace(" ", "_")),
                      [f"Time integration/Method={method}"])
        e0, l0 = float(history[0]["total_energy"]), norm3(history[0], "angular_momentum")
        t = [float(r["time"]) for r in history]
        energy = [float(r["total_energy"]) / e0 - 1 for r in history]
        momentum = [norm3(r, "angular_momentum") / l0 - 1 for r in history]
        axes.plot(t, energy, label=f"{method}: energy")
        axes.plot(t, momentum, "--", label=f"{method}: |L|")
        rows.append({"method": method, "steps": len(history),
                     "final_energy_drift": energy[-1],
                     "final_angular_momentum_drift": momentum[-1],
                     "max_linear_momentum": max(norm3(r, "linear_momentum") for r in history)})
    axes.set_yscale("symlog", linthresh=1e-4)
    return rows, figure, axes


def order(coshell, work):
    dts = [0.1, 0.05, 0.025, 0.0125]
    rows, figure = [], plt.figure(figsize=(6, 4))
    axes = figure.add_subplot(111)
    for method in METHODS[:2]:
        def final(dt):
            history = run(coshell, os.path.join(work, f"order_{method}_{dt}".replace(" ", "_")),
                          [f"Time integration/Method={method}",
                           f"Time integration/Time step={dt!r}",
                           f"Time integration/Maximum time step={dt!r}",
                           "Time integration/End time=1",
                           "Nonlinear solver/Residual tolerance=1e-10"])
            return [float(history[-1][q]) for q in QOIS]
        reference = final(0.0015625)
        errors = [max(abs(a - b) for a, b in zip(final(dt), reference)) for dt in dts]
        axes.loglog(dts, errors, "o-", label=method)
        rows += [{"method": method, "dt": dt, "error": e} for dt, e in zip(dts, errors)]
    axes.loglog(dts, [2e-1 * dt ** 2 for dt in dts], "k:", label="slope 2")
    axes.loglog(dts, [3e-1 * dt for dt in dts], "k-.", label="slope 1")
    return rows, figure, axes


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    args = parser.parse_args()
    coshell = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    os.makedirs(OUT, exist_ok=True)
    stamp = [f"machine: {machine}; commit {commit}", "prm/dynamics/free_flying_plate.prm"]
    with tempfile.TemporaryDirectory() as work:
        rows, figure, axes = conservation(coshell, work)
        write_csv(os.path.join(OUT, "free_flying_conservation.csv"), rows, stamp)
        finish_plot(figure, axes, "time (s)", "relative drift",
                    f"Free-flying plate, 1000 steps of 0.02 s ({commit})",
                    os.path.join(OUT, "free_flying_conservation.png"))
        rows, figure, axes = order(coshell, work)
        write_csv(os.path.join(OUT, "time_order.csv"), rows, stamp)
        finish_plot(figure, axes, "dt (s)", "error of the final positions",
                    f"Order in dt, free-flying plate, 1 s ({commit})",
                    os.path.join(OUT, "time_order.png"))


if __name__ == "__main__":
    main()
