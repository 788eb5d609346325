#!/usr/bin/env python3
"""The interactive protocol's slope line against finite differences.

With an obstacle driven by the input (Contact/Obstacle k/Input
direction), each step line is followed by 'slope N s dF/ds': how the
force along the direction changes with the input, as the step's linear
system answers. Three sessions differ only in the input of their last
target, one time step after the target before it: s, s + delta and
s - delta. The central difference of the forces in contact_forces.csv
(17 digits) is compared with the slope the middle session printed for
that step.

A linearized step reports its force at its end through the force's
slopes (Contact::extrapolate_loads()), so the changed step is where the
change shows there too.
"""
import os
import shutil

from check_interactive import (input_directions, run_session,
                               session_failures, session_parser)
from coshell_checks import exit_with, read_rows


def main():
    parser = session_parser()  # its --set: a setting of every session
    parser.add_argument("--driven", type=int, required=True,
                        help="the number k of the driven obstacle")
    parser.add_argument("--lines", required=True,
                        help="the sessions' first lines, separated by ';'")
    parser.add_argument("--last", nargs=2, type=float, required=True,
                        metavar=("T", "S"), help="the last target and input")
    parser.add_argument("--delta", type=float, required=True,
                        help="the input's change (length)")
    parser.add_argument("--rtol", type=float, required=True)
    args = parser.parse_args()
    if os.path.isdir(args.output):
        shutil.rmtree(args.output)
    direction = input_directions(args.set)[args.driven]
    t, s = args.last
    forces, slope, failures = {}, None, []
    for name, change in [("minus", -1), ("middle", 0), ("plus", 1)]:
        lines = [line.strip() for line in args.lines.split(";")]
        lines.append(f"{t!r} {s + change * args.delta!r}")
        done = [line.split()[0] for line in lines]
        output = os.path.join(args.output, name)
        print(f"{name} session: {lines}")
        run = run_session(args.coshell, args.prm, output, args.set,
                          "\n".join(lines) + "\n")
        failures += [f"{name}: {f}" for f in session_failures(
            run, output, args.obstacles, done, float(done[-1]),
            settings=args.set)]
        if failures:
            exit_with(failures)
        forces[change] = last_force(output, args.driven, direction)
        if change == 0:
            slope = printed_slope(run.stdout, t)
    if slope == 0 or forces[0] == 0:
        exit_with([f"no contact force to check: slope {slope}, force "
                   f"{forces[0]} N at the compared step"])
    difference = (forces[1] - forces[-1]) / (2 * args.delta)
    print(f"force at s - delta, s, s + delta: {forces[-1]!r}, {forces[0]!r}, "
          f"{forces[1]!r} N")
    print(f"one-sided differences: {(forces[0] - forces[-1]) / args.delta:.6g}"
          f", {(forces[1] - forces[0]) / args.delta:.6g} N per input unit")
    print(f"central difference {difference:.6g}, slope line {slope:.6g}: "
          f"relative difference {abs(difference - slope) / abs(slope):.3g} "
          f"(tolerance {args.rtol})")
    if not abs(difference - slope) <= args.rtol * abs(slope):
        failures.append(f"the slope line's {slope:.6g} is not the central "
                        f"difference {difference:.6g} within {args.rtol}")
    exit_with(failures)


def last_force(output, obstacle, direction):
    """The obstacle's force along 'direction' at the last step of
    contact_forces.csv."""
    rows = [row for row in read_rows(os.path.join(output, "contact_forces.csv"))
            if int(float(row["obstacle"])) == obstacle]
    last = max(rows, key=lambda row: int(float(row["step"])))
    return sum(float(last[c]) * d for c, d in zip(("fx", "fy", "fz"),
                                                   direction))


def printed_slope(stdout, time):
    """The first driven obstacle's slope of the step that ends at 'time'."""
    lines = stdout.splitlines()
    for k, line in enumerate(lines):
        words = line.split()
        if words[0] == "step" and abs(float(words[2]) - time) <= 1e-9:
            return float(lines[k + 1].split()[3])
    raise SystemExit(f"no step line at t = {time}")


if __name__ == "__main__":
    main()
