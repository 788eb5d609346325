#!/usr/bin/python3
"""Newton corrections per time step on the push of the IOL injection
(prm/iol/injection.prm, default lens, stages 1 and 2; the push is stage 2,
t = 1.3 to 5.68 s), for the old scheme and the pieces of IPC's Newton on
the incremental potential (issue #70's stop rule: more than 5 corrections
a step at dt >= 5 ms ends the potential-Newton route). Each configuration
is a set of --set overrides and a Maximum time step. Counted from
newton_history.csv (one row per iteration; a failed attempt is a run of
rows whose iteration counter starts again) and time_history.csv (stage and
dt of each accepted step): corrections in the accepted attempts, and all
corrections, failed attempts included, per accepted step. With the
plunger's work over the push (the integral of its force over its travel)
and the optic's position at the push's end beside them, which show what a
looser stopping test gives up. Writes
doc/performance/iol_newton_corrections.csv and .png, stamped with machine
and commit. Runs take 1.5 to 6 min each; --runs DIR keeps them (and
reuses any already there).

  /usr/bin/python3 doc/scripts/iol_newton_corrections.py \\
      --coshell build/coshell [--runs /tmp/newton_corrections]
"""
import argparse
import csv
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import ROOT, finish_plot, machine_and_commit, write_csv  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
PUSH_ONLY = ["Stage 3/Analysis type=none", "Stage 4/Analysis type=none",
             "Parallel/Threads=1"]
ARMIJO = ["Nonlinear solver/Line search rule=armijo"]


def velocity_test(tolerance):
    return [f"Nonlinear solver/Velocity tolerance={tolerance}",
            "Nonlinear solver/Correction tolerance=0"]


# (name, label, Maximum time step in s, overrides)
CONFIGURATIONS = [
    ("old_5ms", "energy-slope search,\n1e-5 mm test", 0.005, []),
    ("armijo_5ms", "Armijo", 0.005, ARMIJO),
    ("armijo_projected_5ms", "Armijo,\nprojected Hessians", 0.005,
     ARMIJO + ["Contact/Projected tangent=true"]),
    ("armijo_v1e-2_5ms", "Armijo,\n1e-2 mm/s test", 0.005,
     ARMIJO + velocity_test(0.01)),
    ("armijo_v1e-1_5ms", "Armijo,\n1e-1 mm/s test", 0.005,
     ARMIJO + velocity_test(0.1)),
    ("armijo_v1e-2_kappa_0.1x_5ms", "Armijo,\n1e-2 mm/s,\nkappa / 10", 0.005,
     ARMIJO + velocity_test(0.01) + ["Contact/Barrier stiffness=0.0295"]),
    ("armijo_v1e-2_kappa_10x_5ms", "Armijo,\n1e-2 mm/s,\nkappa x 10", 0.005,
     ARMIJO + velocity_test(0.01) + ["Contact/Barrier stiffness=2.95"]),
    ("old_20ms", "energy-slope search,\n1e-5 mm test", 0.02, []),
    ("armijo_v1e-1_20ms", "Armijo,\n1e-1 mm/s test", 0.02,
     ARMIJO + velocity_test(0.1)),
]
PUSH_STAGE = 2


def run(coshell, name, maximum_step, overrides, runs):
    output = os.path.join(runs, name)
    if os.path.exists(os.path.join(output, "summary.json")):
        return output
    command = [coshell, os.path.join(ROOT, "prm", "iol", "injection.prm"),
               "--output", output]
    for assignment in PUSH_ONLY + overrides + [
            f"Time integration/Maximum time step={maximum_step}"]:
        command += ["--set", assignment]
    environment = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL,
                   env=environment)
    return output


def attempts_by_step(output):
    """For each step, its attempts: lists of the iterations' correction
    norms (0 on the evaluation that ends a converged attempt)."""
    attempts, previous = {}, None
    with open(os.path.join(output, "newton_history.csv")) as f:
        for row in csv.DictReader(f):
            step, iteration = int(row["step"]), int(row["iteration"])
            if previous is None or previous[0] != step or iteration <= previous[1]:
                attempts.setdefault(step, []).append([])
            attempts[step][-1].append(float(row["correction_norm"]))
            previous = (step, iteration)
    return attempts


def push_work(output):
    """The plunger's work over the push, N mm (trapezoid rule)."""
    with open(os.path.join(output, "plunger_force.csv")) as f:
        rows = [(float(r["plunger_displacement"]), float(r["force_n"]))
                for r in csv.DictReader(f)]
    return sum(0.5 * (f0 + f1) * (x1 - x0)
               for (x0, f0), (x1, f1) in zip(rows, rows[1:]))


def count(output, maximum_step):
    with open(os.path.join(output, "time_history.csv")) as f:
        history = list(csv.DictReader(f))
    push = [r for r in history if int(float(r["stage"])) == PUSH_STAGE]
    attempts = attempts_by_step(output)
    accepted = failed = failed_corrections = 0
    for row in push:
        tries = attempts[int(row["step"])]
        accepted += sum(norm != 0 for norm in tries[-1])
        failed += len(tries) - 1
        failed_corrections += sum(norm != 0 for attempt in tries[:-1]
                                  for norm in attempt)
    steps = len(push)
    last = push[-1]
    return {"steps": steps,
            "steps_at_maximum": sum(abs(float(r["dt"]) - maximum_step) < 1e-9
                                    for r in push),
            "failed_attempts": failed,
            "corrections_per_step_accepted": round(accepted / steps, 3),
            "corrections_per_step_all": round(
                (accepted + failed_corrections) / steps, 3),
            "plunger_work_Nmm": f"{push_work(output):.6g}",
            "optic_ux_mm": f"{float(last['optic_ux']):.5g}",
            "optic_uz_mm": f"{float(last['optic_uz']):.5g}"}


def plot(rows, machine, commit):
    figure, axis = plt.subplots(figsize=(12, 5))
    labels = [f"{r['label']}\n{float(r['maximum_time_step_s']) * 1e3:g} ms"
              for r in rows]
    values = [float(r["corrections_per_step_all"]) for r in rows]
    axis.bar(range(len(rows)), values, color="tab:blue")
    axis.axhline(5, color="tab:red", linestyle="--",
                 label="stop rule: 5 corrections a step")
    axis.set_xticks(range(len(rows)), labels, fontsize=7)
    finish_plot(figure, axis, "",
                "Newton corrections per push step\n(failed attempts included)",
                f"IOL push, default lens: corrections per step\n{machine}, "
                f"commit {commit}",
                os.path.join(OUT, "iol_newton_corrections.png"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--runs", default="/tmp/iol_newton_corrections")
    parser.add_argument("--binary-commit",
                        help="the commit the coshell binary was built from, "
                        "when it is not the checkout's")
    arguments = parser.parse_args()
    machine, commit = machine_and_commit()
    commit = arguments.binary_commit or commit
    rows = []
    for name, label, maximum_step, overrides in CONFIGURATIONS:
        output = run(arguments.coshell, name, maximum_step, overrides,
                     arguments.runs)
        rows.append({"configuration": name, "label": label.replace("\n", " "),
                     "maximum_time_step_s": maximum_step,
                     **count(output, maximum_step)})
        print(rows[-1])
    write_csv(os.path.join(OUT, "iol_newton_corrections.csv"), rows,
              [f"machine: {machine}", f"commit: {commit}",
               "IOL push (stage 2) of prm/iol/injection.prm, default lens; "
               "counts of Newton corrections (the same on any number of "
               "threads); doc/scripts/iol_newton_corrections.py"])
    plot([dict(r, label=l) for r, (_, l, _, _) in zip(rows, CONFIGURATIONS)],
         machine, commit)


if __name__ == "__main__":
    main()
