#!/usr/bin/python3
"""Haptic-rate benchmark of the IOL injection (prm/iol/injection.prm, the
default lens): steps per second of the push with the plunger engaging the
folded lens, in the scene's own mode (backward Euler, full Newton, barrier
contact) and in the linearized modes a training simulator's haptic loop
would run (one linear solve per step: `linearized implicit euler`), with
the barrier and with the penalty, without and with its step filter; all
with the scene's friction, the linearized modes with a 0.01 mm floor on
its smoothing length. Each step's matrix is factorized (CHOLMOD): kept
factors measure no faster on this bed. The fold is run once, in the
scene's mode, and written as a checkpoint; each mode restarts from it for --push
seconds at a fixed step. Per mode: steps per second, the per-step split
(assembly with contact, linear solver, the rest), contact detection per
step, the smallest gap (negative: penetration), the largest strains,
the plunger's travel, and the accuracy side: the push's work on the lens
and its largest force over 0.5 mm of travel, the work also relative to
the scene's mode. A mode counts as working ("ok") only if its plunger
travelled as far as in the scene's mode and its largest membrane strain
stayed below twice that mode's: a lens that blew up, or a plunger held
back while the scene stood still, is reported as such, not as a rate.
The linearized penalty runs at --step and, since it breaks the lens
there, at 0.5 ms too; at 0.5 ms also with the history thinned, and with
the seed paper's tangent R K R^T instead of the scene's symmetric one.
The penalty modes restart from a fold made with the penalty (the scene's
mode otherwise): the barrier's fold holds the lens's layers apart at the
barrier's gaps, and a penalty, which acts only on penetration, drops
them at once. Writes
doc/performance/haptic_rate.csv and haptic_rate.png, stamped with machine
and commit. One thread; the modes run one after another.

  /usr/bin/python3 doc/scripts/haptic_rate.py --coshell build/coshell \\
      [--push 0.2] [--step 0.001]
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import (ROOT, finish_plot, largest_strains,  # noqa: E402
                        machine_and_commit, write_csv)
sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
from check_injection import push_measures  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
SCENE = os.path.join(ROOT, "prm", "iol", "injection.prm")
FOLD_END = 1.3  # s, stage 1 of the scene
QUIET = ["Parallel/Threads=1", "Output/Write VTU=false",
         "Stage 3/Analysis type=none", "Stage 4/Analysis type=none"]
# The scene's friction in one linear solve per step needs a floor on its
# smoothing length: with IPC's v dt alone (0.1 mm/s x 1 ms = 1e-4 mm) the
# linearized lens blows up (membrane strain 3.3; doc/performance/iol.md).
FLOOR = ["Contact/Stiction displacement=0.01"]
# No kept factors (Linear solver/Reuse factorization): on this bed GMRES
# preconditioned with CHOLMOD's kept factors costs as much as factorizing
# the 1 890 DoFs afresh (doc/performance/iol.md, "Why tuning cannot close
# the gap").
# The penalty (E / h) with a step filter of 0.5: the fold's Newton steps
# jam at 0.9 (at t = 0.6 s the wings cannot press the lens within a tenth
# of its half thickness), so the penalty modes share 0.5.
PENALTY = ["Contact/Method=penalty", "Contact/Penalty step filter=0.5"]
BARRIER = ["Contact/Method=barrier"]
# label, integrator, the contact of the fold and of the push, more, and
# the time step if not --step: the linearized penalty breaks the lens (or,
# with its filter, jams) at 1 ms and keeps it whole at 0.5 ms
# (doc/performance/iol.md).
MODES = [
    ("backward Euler, Newton, barrier", "implicit euler", BARRIER, [], None),
    ("linearized Euler, barrier", "linearized implicit euler", BARRIER,
     FLOOR, None),
    ("backward Euler, Newton, penalty, step filter 0.5", "implicit euler",
     PENALTY, [], None),
    ("linearized Euler, penalty, step filter 0.5",
     "linearized implicit euler", PENALTY, FLOOR, None),
    ("linearized Euler, penalty", "linearized implicit euler", PENALTY,
     FLOOR + ["Contact/Penalty step filter=0"], None),
    ("linearized Euler, penalty, step filter 0.5, dt 0.5 ms",
     "linearized implicit euler", PENALTY, FLOOR, 0.0005),
    # The same as a haptic loop would run it, reading only the interactive
    # replies: time_history.csv every 20th step (its strain energy,
    # strains and quantities computed for those rows only).
    ("linearized Euler, penalty, step filter 0.5, dt 0.5 ms, history "
     "every 20th step", "linearized implicit euler", PENALTY,
     FLOOR + ["Output/Steps between history rows=20"], 0.0005),
    # The same with the seed paper's tangent R K R^T (the element's
    # constant local stiffness turned by its frame, no geometric terms), as
    # its SOFA implementation stepped: half the element's cost per cell
    # (doc/performance/elements-and-assembly.md, "Element kernels"). The residual is the same;
    # the step's matrix lacks the terms linear in the element forces.
    ("linearized Euler, penalty, step filter 0.5, dt 0.5 ms, history "
     "every 20th step, the paper's tangent", "linearized implicit euler",
     PENALTY, FLOOR + ["Output/Steps between history rows=20",
                       "Nonlinear solver/Tangent=paper"], 0.0005),
]
PLUNGER = "2"  # its obstacle number in the scene and in contact_forces.csv


def coshell(binary, output, assignments, restart=None):
    command = [binary, SCENE, "--output", output]
    if restart:
        command += ["--restart", restart]
    for assignment in QUIET + assignments:
        command += ["--set", assignment]
    return subprocess.run(command, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True,
                          env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))


def folded_checkpoint(binary, work, contact):
    """Runs the fold in the scene's own mode with the given contact;
    returns its last checkpoint."""
    output = os.path.join(work, "fold_" + contact[0].split("=")[1])
    process = coshell(binary, output, contact + [
        "Stage 2/Analysis type=none",
        f"Output/Checkpoint interval={FOLD_END}"])
    if process.returncode != 0:
        sys.exit("the fold failed: " + process.stderr.strip()[-400:])
    return os.path.join(output, sorted(
        f for f in os.listdir(output) if f.startswith("checkpoint-"))[-1])


def plunger_rows(output):
    """The plunger's rows of contact_forces.csv after the fold: one a step
    (time_history.csv may be thinned)."""
    with open(os.path.join(output, "contact_forces.csv")) as f:
        return [r for r in csv.DictReader(f)
                if r["obstacle"] == PLUNGER and float(r["time"]) > FOLD_END]


def accuracy(plunger):
    """The push's work on the lens (N mm) and its largest force averaged
    over 0.5 mm of travel (mN): the accuracy side of a mode, against the
    scene's mode."""
    total, averaged = push_measures(plunger)
    return {"push_work_nmm": round(total, 9),
            "force_over_0.5mm_mn": round(1e3 * averaged, 4)}


def measure(binary, checkpoints, mode, push, step, work):
    label, method, contact, extra, own_step = mode
    step = own_step or step
    output = os.path.join(work, label.replace(" ", "_").replace(",", ""))
    process = coshell(binary, output, [
        f"Stage 2/Duration={push}", f"Time integration/Method={method}",
        f"Time integration/Time step={step}",
        f"Time integration/Maximum time step={step}"] + contact + extra,
        restart=checkpoints[contact[0]])
    if process.returncode != 0:
        return {"mode": label, "status": process.stderr.strip().splitlines()[-1]}
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    seconds = summary["time_stepping_s"]
    # Steps of this run only: the restart continues the fold's numbering
    # (summary.json counts only this run's Newton iterations).
    plunger = plunger_rows(output)
    steps = len(plunger)
    bending, membrane = largest_strains(output)
    return {
        "mode": label, "steps": steps,
        "newton_iterations": summary["newton_iterations"],
        "time_step_s": step,
        "steps_per_second": round(steps / seconds["total"], 1),
        "ms_per_step": round(1e3 * seconds["total"] / steps, 2),
        "assembly_ms_per_step": round(1e3 * seconds["assembly"] / steps, 2),
        "contact_detection_ms_per_step": round(
            1e3 * summary["contact"]["detection_s"] / steps, 2),
        "linear_solver_ms_per_step": round(
            1e3 * seconds["linear_solver"] / steps, 2),
        "factorization_ms_per_step": round(
            1e3 * seconds["factorization"] / steps, 2),
        "other_ms_per_step": round(1e3 * seconds["other"] / steps, 2),
        "smallest_gap_mm": summary["contact"]["smallest_gap"],
        "max_bending_strain": round(bending, 4),
        "max_membrane_strain": round(membrane, 4),
        "plunger_travel_mm": round(float(plunger[-1]["ux"]), 4),
        **accuracy(plunger), "status": "ok"}


def judge(rows):
    """Marks the modes whose plunger fell behind the scene's mode (the
    first row) or whose membrane strain passed twice its, and gives each
    mode's push work relative to the scene's mode's."""
    reference = rows[0]
    for row in rows[1:]:
        if row["status"] != "ok":
            continue
        if row["plunger_travel_mm"] < 0.95 * reference["plunger_travel_mm"]:
            row["status"] = "plunger held back"
        elif row["max_membrane_strain"] > 2 * reference["max_membrane_strain"]:
            row["status"] = "lens destroyed"
        else:
            row["work_against_scene_mode"] = round(
                row["push_work_nmm"] / reference["push_work_nmm"] - 1, 4)


def breakdown(rows):
    """The issue's split of a step, ms per step: contact detection, the
    rest of the assembly, factorization, substitution, and the rest."""
    def ms(name):
        return [r[f"{name}_ms_per_step"] for r in rows]
    return {
        "contact detection": ms("contact_detection"),
        "assembly without detection": [
            a - d for a, d in zip(ms("assembly"), ms("contact_detection"))],
        "factorization": ms("factorization"),
        "substitution": [s - f for s, f in zip(ms("linear_solver"),
                                                ms("factorization"))],
        "other": ms("other")}


def plot(rows, commit):
    # Broken modes stay in the plot, labelled: their rate is no answer.
    rows = [r for r in rows if "steps_per_second" in r]
    figure, axes = plt.subplots(figsize=(9.5, 4.5))
    labels = [r["mode"].replace(", ", ",\n") for r in rows]
    bottom = [0.0] * len(rows)
    for part, values in breakdown(rows).items():
        axes.bar(labels, values, bottom=bottom, label=part)
        bottom = [b + v for b, v in zip(bottom, values)]
    axes.axhline(2.0, color="k", ls="--", lw=1, label="500 steps/s")
    for x, r in enumerate(rows):
        verdict = "" if r["status"] == "ok" else f"\n{r['status']}"
        if "work_against_scene_mode" in r:
            verdict += f"\nwork {100 * r['work_against_scene_mode']:+.1f} %"
        axes.text(x, bottom[x], f"{r['steps_per_second']:g} steps/s{verdict}",
                  ha="center", va="bottom", fontsize=7,
                  color="k" if r["status"] == "ok" else "tab:red")
    axes.set_yscale("log")
    axes.set_ylim(1, 10 * max(bottom))  # room for the legend above the bars
    axes.tick_params(axis="x", labelsize=7)
    finish_plot(figure, axes, "", "wall time per step (ms)",
                f"IOL push, default lens, one thread ({commit})",
                os.path.join(OUT, "haptic_rate.png"))


def add_bed_arguments(parser):
    """The coshell binary and the push's length, shared with
    haptic_speed_error.py."""
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--push", type=float, default=0.2,
                        help="seconds of push after the fold")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    add_bed_arguments(parser)
    parser.add_argument("--step", type=float, default=0.001,
                        help="fixed time step, s")
    args = parser.parse_args()
    binary = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    with tempfile.TemporaryDirectory() as work:
        checkpoints = {contact[0]: folded_checkpoint(binary, work, contact)
                       for contact in (BARRIER, PENALTY)}
        rows = []
        for mode in MODES:
            rows.append(measure(binary, checkpoints, mode, args.push,
                                args.step, work))
            print(rows[-1], flush=True)
    judge(rows)
    os.makedirs(OUT, exist_ok=True)
    write_csv(os.path.join(OUT, "haptic_rate.csv"), rows,
              [f"machine: {machine}; commit {commit}",
               f"prm/iol/injection.prm, default lens: the fold (1.3 s, the "
               f"scene's mode) as a checkpoint, then {args.push:g} s of push "
               f"per mode at dt = {args.step:g} s unless its time_step_s "
               "says otherwise, Parallel/Threads = 1, no "
               "VTU; the scene's friction, the linearized modes with "
               "Contact/Stiction displacement = 0.01 mm, every step's "
               "matrix factorized (CHOLMOD); the penalty "
               "modes (E / h) from a fold with the penalty and its step "
               "filter 0.5; status ok: the plunger's travel at least 0.95 "
               "and the largest membrane strain at most 2 times the "
               "first mode's"],
              status_last(list(dict.fromkeys(k for r in rows for k in r))))
    plot(rows, commit)


def status_last(fields):
    return [f for f in fields if f != "status"] + ["status"]


if __name__ == "__main__":
    main()
