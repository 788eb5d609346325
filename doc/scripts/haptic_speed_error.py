#!/usr/bin/python3
"""Speed against error of the IOL push's time-stepping modes
(prm/iol/injection.prm, the default lens): the same 0.2 s of push after
the fold as doc/scripts/haptic_rate.py (whose modes, fold checkpoints and
per-run measures it reuses), each mode at a ladder of fixed time steps.
Per run: the real-time factor (simulated over wall time of the time
stepping, one thread) and the plunger's force on the lens averaged over
0.5 mm of travel and its work, against the reference, the scene's own
mode (backward Euler, full Newton, barrier) at the smallest step of its
ladder; a linearized run's force also against Newton's with the same
contact, friction floor and step. haptic_rate.py counts steps per second; a step of a linearized
mode is cheaper, but its force drifts from the converged one by an
amount that falls with the step, so what a mode costs for a given
accuracy is the measure here.
Writes doc/performance/haptic_speed_error.csv and .png, stamped with
machine and commit. One thread; the runs go one after another.

  /usr/bin/python3 doc/scripts/haptic_speed_error.py --coshell build/coshell \\
      [--push 0.2] [--replot]
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import (finish_plot, machine_and_commit,  # noqa: E402
                        read_csv, write_csv)
import haptic_rate  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = haptic_rate.OUT
# haptic_rate.MODES by label: the scene's mode, the linearized barrier,
# the Newton penalty and the linearized penalty with its step filter (the
# issue's haptic mode), each with its time steps in s, largest first, and
# settings of its own. The reference is the first mode's last step. The
# fifth family is the scene's mode with Newton stopped once a correction
# is at most 1 um (the scene's 1e-5 mm asks for 10 nm): mostly one
# correction a step, as the linearized scheme, but a correction the
# collision filter shortened is followed by more. The last two are Newton
# with the linearized runs' friction floor, at their steps.
LOOSE = ["Nonlinear solver/Correction tolerance=1e-3"]
LADDERS = [
    (0, [0.016, 0.008, 0.004, 0.002, 0.001, 0.0005, 0.00025], []),
    (2, [0.001, 0.0005], []),
    (1, [0.001, 0.0005, 0.00025], []),
    (3, [0.0005, 0.00025, 0.000125], []),
    (0, [0.016, 0.008, 0.004, 0.002, 0.001, 0.0005], LOOSE),
    (0, [0.001, 0.0005, 0.00025], haptic_rate.FLOOR),
    (2, [0.0005, 0.00025, 0.000125], haptic_rate.FLOOR),
]
FAMILIES = ["backward Euler, Newton, barrier (the scene's)",
            "backward Euler, Newton, penalty",
            "linearized Euler, barrier",
            "linearized Euler, penalty (the haptic mode)",
            "backward Euler, Newton to 1 um, barrier",
            "backward Euler, Newton, barrier, friction floor",
            "backward Euler, Newton, penalty, friction floor"]
# The linearized runs carry haptic_rate.FLOOR on friction's smoothing,
# which alone moves the converged force, and by an amount that depends on
# the step (friction's force in a step grows with the step's slip up to
# the floor): their error against Newton with the same contact, friction
# and step is the linearization's.
SAME_FRICTION = {FAMILIES[2]: FAMILIES[5], FAMILIES[3]: FAMILIES[6]}


def run_ladders(binary, push, work):
    checkpoints = {contact[0]: haptic_rate.folded_checkpoint(
        binary, work, contact)
        for contact in (haptic_rate.BARRIER, haptic_rate.PENALTY)}
    rows = []
    for (index, steps, own), family in zip(LADDERS, FAMILIES):
        _, method, contact, extra, _ = haptic_rate.MODES[index]
        for step in steps:
            mode = (f"{family}, dt {1e3 * step:g} ms", method, contact,
                    extra + own, step)
            row = haptic_rate.measure(binary, checkpoints, mode, push, step,
                                      work)
            row.update(family=family, time_step_s=step)
            if row["status"] == "ok":
                row["real_time_factor"] = round(
                    step * row["steps_per_second"], 5)
            rows.append(row)
            print({k: row.get(k) for k in (
                "mode", "real_time_factor", "force_over_0.5mm_mn",
                "push_work_nmm", "status")}, flush=True)
    return rows


def add_errors(rows):
    """Each run's force and work relative to the reference run's."""
    reference = [r for r in rows if r["family"] == FAMILIES[0]][-1]
    for row in rows:
        if row["status"] != "ok":
            continue
        for column, name in (("force_over_0.5mm_mn", "force_error"),
                             ("push_work_nmm", "work_error")):
            row[name] = round(row[column] / reference[column] - 1, 4)
    for row in rows:
        same = [r for r in rows if r["family"] == SAME_FRICTION.get(
            row["family"]) and r["time_step_s"] == row["time_step_s"]
            and r["status"] == "ok"]
        if row["status"] == "ok" and same:
            row["force_error_same_friction"] = round(
                row["force_over_0.5mm_mn"] / same[-1]["force_over_0.5mm_mn"]
                - 1, 4)
    return reference


def replot():
    """The PNG again from the CSV (--replot)."""
    path = os.path.join(OUT, "haptic_speed_error.csv")
    with open(path) as f:
        commit = f.readline().split("commit ")[-1].strip()
    rows = read_csv(path)
    for row in rows:
        for key in ("time_step_s", "real_time_factor", "force_error",
                    "force_error_same_friction", "force_over_0.5mm_mn"):
            if row.get(key):
                row[key] = float(row[key])
            else:
                row.pop(key, None)
    reference = [r for r in rows if r["family"] == FAMILIES[0]][-1]
    plot(rows, reference, commit)


def plot(rows, reference, commit):
    figure, ax = plt.subplots(figsize=(9, 6.5))
    for family in FAMILIES:
        # A linearized run is measured against Newton with its friction.
        key, label = ("force_error_same_friction",
                      family + ", against Newton with its floor and step") \
            if family in SAME_FRICTION else ("force_error", family)
        runs = [r for r in rows if r["family"] == family and key in r
                and r is not reference]
        if not runs:
            continue
        x = [r["real_time_factor"] for r in runs]
        # An error below the CSV's 4 digits is drawn at 1e-4, so marked.
        y = [max(abs(r[key]), 1e-4) for r in runs]
        ax.plot(x, y, "o-", label=label)
        for r, xi, yi in zip(runs, x, y):
            below = ", < 1e-4" if abs(r[key]) < 1e-4 else ""
            ax.annotate(f"{1e3 * r['time_step_s']:g} ms{below}", (xi, yi),
                        fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    finish_plot(figure, ax, "real-time factor (one thread)",
                "force over 0.5 mm: relative error",
                f"IOL push, default lens: speed against error ({commit}); "
                f"reference {reference['force_over_0.5mm_mn']:g} mN",
                os.path.join(OUT, "haptic_speed_error.png"),
                legend_below=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    haptic_rate.add_bed_arguments(parser)
    parser.add_argument("--replot", action="store_true",
                        help="redraw the PNG from the CSV")
    args = parser.parse_args()
    if args.replot:
        replot()
        return
    binary = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    with tempfile.TemporaryDirectory() as work:
        rows = run_ladders(binary, args.push, work)
    reference = add_errors(rows)
    fields = ["family", "time_step_s", "real_time_factor",
              "force_over_0.5mm_mn", "force_error",
              "force_error_same_friction", "push_work_nmm",
              "work_error", "steps", "newton_iterations", "steps_per_second",
              "smallest_gap_mm", "max_membrane_strain", "status"]
    write_csv(os.path.join(OUT, "haptic_speed_error.csv"),
              [{k: r.get(k, "") for k in fields} for r in rows],
              [f"machine: {machine}; commit {commit}",
               "prm/iol/injection.prm, default lens: the fold (1.3 s, the "
               f"scene's mode) as a checkpoint, then {args.push:g} s of push "
               "per run at a fixed time step, Parallel/Threads = 1, no VTU; "
               "modes and settings of doc/scripts/haptic_rate.py; errors "
               "relative to the scene's mode at "
               f"{1e3 * reference['time_step_s']:g} ms; "
               "force_error_same_friction: a linearized run's against "
               "Newton with its contact, friction floor and step"], fields)
    plot(rows, reference, commit)


if __name__ == "__main__":
    main()
