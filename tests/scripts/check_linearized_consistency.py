#!/usr/bin/python3
"""Consistency in time of the linearized implicit Euler (the seed paper's
one linear solve per step) on the IOL push, prm/iol/injection.prm.

The fold (stage 1, the scene's own mode) runs once and leaves a
checkpoint at its end. From it, --push seconds of push run at each of
--steps (halving): in the linearized implicit Euler, and in the scene's
mode (backward Euler, full Newton, the barrier) as its reference. Every
run has the same settings otherwise, --set included, so that at each
step the only difference is one correction against Newton's converged
iterate. (The reference must take the same step: with a floor on
friction's smoothing length, Contact/Stiction displacement, friction's
force in a step grows with the step's slip, so the converged force itself
depends on the step.)

The reference is independent of the linearized mode: the converged
implicit solution of the same equations. Asserted:
- every run completes, and its plunger travels as far as the
  reference's (a prescribed motion; a jam would stop it);
- the linearized force on the lens averaged over 0.5 mm of travel tends
  to the reference's at its step: its relative error falls at least
  twofold per halving of the step (consistency of at least first order).
The linearized step reports its forces at its end by their slopes
(Contact::extrapolate_loads()); the forces at its start would be 6 to 14
times as far off.
With --loose-tolerance TOL, one more push runs Newton stopped once a
correction is at most TOL (Nonlinear solver/Correction tolerance) at the
first of --steps, the cheap accurate mode of that section. Asserted: its
force is within --loose-within (relative) of the reference's there.
Printed: the errors in that force and in the push's work, each run's
real-time factor, and the loose run's corrections per step
(doc/performance.md, "Speed against error of the time-stepping modes").
"""
import argparse
import glob
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_injection import column, push_measures  # noqa: E402
from coshell_checks import (add_scene_arguments, exit_with,  # noqa: E402
                            read_rows, run_scene)

FOLD_END = 1.3  # s, stage 1 of the scene
PLUNGER = 2  # its obstacle number
QUIET = ["Stage 3/Analysis type=none", "Stage 4/Analysis type=none",
         "Output/Write VTU=false", "Parallel/Threads=1"]


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__)
    add_scene_arguments(parser)
    parser.add_argument("--push", type=float, default=0.2,
                        help="seconds of push after the fold")
    parser.add_argument("--steps", type=float, nargs="+",
                        default=[0.001, 0.0005, 0.00025],
                        help="the linearized runs' time steps, s, halving")
    parser.add_argument("--loose-tolerance", type=float,
                        help="Newton's Correction tolerance of the loose "
                        "run, mm (none: no loose run)")
    parser.add_argument("--loose-within", type=float, default=0.01,
                        help="the loose run's largest relative force error")
    return parser.parse_args()


def folded_checkpoint(args):
    output = os.path.join(args.output, "fold")
    run_scene(args.coshell, args.prm, output, args.set + QUIET + [
        "Stage 2/Analysis type=none",
        f"Output/Checkpoint interval={FOLD_END}"])
    return sorted(glob.glob(os.path.join(output, "checkpoint-*.h5")))[-1]


def push(args, checkpoint, name, method, step, more=()):
    """One push from the fold's checkpoint: its plunger travel (mm), force
    over 0.5 mm (N), work (N mm), real-time factor and Newton iterations
    per step."""
    output = os.path.join(args.output, name)
    run_scene(args.coshell, args.prm, output, args.set + QUIET + [
        f"Stage 2/Duration={args.push}", f"Time integration/Method={method}",
        f"Time integration/Time step={step}",
        f"Time integration/Maximum time step={step}"] + list(more),
        restart=checkpoint)
    rows = [r for r in read_rows(os.path.join(output, "contact_forces.csv"))
            if int(r["obstacle"]) == PLUNGER and float(r["time"]) > FOLD_END]
    work, force = push_measures(rows)
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    return {"name": name, "travel": column(rows, "ux")[-1], "force": force,
            "work": work, "real_time_factor":
            args.push / summary["time_stepping_s"]["total"],
            "iterations_per_step": summary["newton_iterations"] / len(rows)}


def check_loose(args, checkpoint, reference):
    """The failures of Newton stopped at --loose-tolerance against the
    reference at the first step."""
    loose = push(args, checkpoint, "newton_loose", "implicit euler",
                 args.steps[0], [
                     "Nonlinear solver/Correction tolerance="
                     f"{args.loose_tolerance:g}"])
    error = loose["force"] / reference["force"] - 1
    print(f"Newton to {args.loose_tolerance:g} mm: force "
          f"{1e3 * loose['force']:.4g} mN (error {100 * error:+.3g} %), "
          f"{loose['iterations_per_step']:.3g} corrections a step (the "
          f"reference {reference['iterations_per_step']:.3g}), real-time "
          f"factor {loose['real_time_factor']:.3g}")
    if abs(error) > args.loose_within:
        return [f"Newton to {args.loose_tolerance:g} mm is "
                f"{100 * error:+.3g} % off, more than "
                f"{100 * args.loose_within:g} %"]
    return []


def main():
    args = parse_arguments()
    checkpoint = folded_checkpoint(args)
    failures, errors = [], []
    for step in args.steps:
        reference = push(args, checkpoint, f"newton_{step:g}",
                         "implicit euler", step)
        run = push(args, checkpoint, f"linearized_{step:g}",
                   "linearized implicit euler", step)
        errors.append(abs(run["force"] / reference["force"] - 1))
        print(f"dt {step:g} s: Newton's force over 0.5 mm "
              f"{1e3 * reference['force']:.4g} mN, work "
              f"{reference['work']:.4g} N mm, real-time factor "
              f"{reference['real_time_factor']:.3g}; linearized "
              f"{1e3 * run['force']:.4g} mN (error {100 * errors[-1]:.3g} "
              f"%), work {run['work']:.4g} N mm (error "
              f"{100 * (run['work'] / reference['work'] - 1):+.3g} %), "
              f"real-time factor {run['real_time_factor']:.3g}")
        if abs(run["travel"] - reference["travel"]) > 1e-9:
            failures.append(f"{run['name']}: the plunger travelled "
                            f"{run['travel']:g} mm, not {reference['travel']:g}")
        if step == args.steps[0]:
            first_reference = reference
    for coarse, fine, step in zip(errors, errors[1:], args.steps[1:]):
        if fine > coarse / 2:
            failures.append(f"at dt {step:g} s the force's error "
                            f"{100 * fine:.3g} % is not half of "
                            f"{100 * coarse:.3g} %")
    if args.loose_tolerance:
        failures += check_loose(args, checkpoint, first_reference)
    exit_with(failures)


if __name__ == "__main__":
    main()
