#!/usr/bin/env python3
"""An obstacle driven by the interactive protocol's input (Contact/
Obstacle k/Input direction; lines 't s'), against the same motion
prescribed by its Translation. The two sessions must give the same
time_history.csv and contact_forces.csv to round-off (an invariance: the
input path is linear between its samples, as the prescribed motion is).
The step lines' forces are those of contact_forces.csv: the prescribed
obstacle's magnitude, the driven one's signed component along its
input direction. Then the protocol's refusals: an input for a time not
after the present, a line that is not 't' or 't s' with finite numbers,
and an input when no obstacle takes one, each answered with an error
line while the run goes on."""
import os
import shutil

from check_interactive import run_session, session_failures, session_parser
from coshell_checks import exit_with, read_rows


def main():
    parser = session_parser()  # its --set: a setting of every session
    parser.add_argument("--prescribed", action="append", default=[],
                        help="a setting of the prescribed session")
    parser.add_argument("--driven", action="append", default=[],
                        help="a setting of the driven session")
    parser.add_argument("--targets", required=True,
                        help="target times (s), separated by spaces")
    parser.add_argument("--inputs", required=True,
                        help="the driven obstacle's input at each target "
                        "('-': none, the input held)")
    parser.add_argument("--rtol", type=float, default=1e-12)
    args = parser.parse_args()
    if os.path.isdir(args.output):
        shutil.rmtree(args.output)
    targets, inputs = args.targets.split(), args.inputs.split()
    end = float(targets[-1])
    prescribed = os.path.join(args.output, "prescribed")
    driven = os.path.join(args.output, "driven")
    failures = []
    for name, output, settings, lines in [
            ("prescribed", prescribed, args.prescribed, targets),
            ("driven", driven, args.driven,
             [t if s == "-" else f"{t} {s}" for t, s in zip(targets, inputs)])]:
        print(f"{name} session:")
        run = run_session(args.coshell, args.prm, output,
                          args.set + settings, "\n".join(lines) + "\n")
        failures += [f"{name}: {f}" for f in session_failures(
            run, output, args.obstacles, targets, end,
            settings=args.set + settings)]
        if name == "driven":
            failures += [f"{name}: {f}" for f in resistance_failures(run)]
    if not failures:
        for csv_file in ("time_history.csv", "contact_forces.csv"):
            failures += differences(prescribed, driven, csv_file, args.rtol)
    failures += refusal_failures(args, targets, inputs)
    exit_with(failures)


def resistance_failures(run):
    """Without friction and with an input that only advances, as here,
    the driven obstacle's force along its input direction must not be
    positive (the barrier pushes the obstacle back, never pulls it) and
    must be negative somewhere (the shell resists the input)."""
    forces = [float(line.split()[3]) for line in run.stdout.splitlines()
              if line.startswith("step ")]
    if forces and (max(forces) > 0 or min(forces) >= 0):
        return [f"the driven obstacle's forces run from {min(forces)} to "
                f"{max(forces)} N: not resisting the input"]
    return []


def differences(first, second, csv_file, rtol):
    """Rows of 'csv_file' in the two directories that differ by more than
    rtol of the larger value (or 1e-15 absolute)."""
    a = read_rows(os.path.join(first, csv_file))
    b = read_rows(os.path.join(second, csv_file))
    if len(a) != len(b):
        return [f"{csv_file}: {len(a)} rows prescribed, {len(b)} driven"]
    worst, where = 0.0, None
    for row_a, row_b in zip(a, b):
        for key, value in row_a.items():
            x, y = float(value), float(row_b[key])
            if x == y:
                continue
            gap = abs(x - y) / max(abs(x), abs(y))
            if abs(x - y) > 1e-15 and gap > worst:
                worst, where = gap, (key, row_a.get("time"), x, y)
    print(f"{csv_file}: {len(a)} rows, largest relative difference {worst:.3g}"
          + (f" ({where[0]} at t = {where[1]}: {where[2]} against "
             f"{where[3]})" if where else ""))
    if worst > rtol:
        return [f"{csv_file}: {where[0]} at t = {where[1]} differs by "
                f"{worst:.3g} relative (> {rtol})"]
    return []


def refusal_failures(args, targets, inputs):
    """Bad lines of a driven session, and an input to a scene whose
    obstacles take none: each gets its error line, the run goes on."""
    failures = []
    first = f"{targets[0]} {inputs[0]}"  # the first input is a number
    cases = [
        ("driven", args.driven,
         [first, f"{float(targets[0]) / 2} {inputs[0]}", f"{targets[1]} x",
          "nan", f"{targets[1]} inf", targets[1], "quit"],
         ["an input is for a time after the present",
          f"cannot read '{targets[1]} x'", "cannot read 'nan'",
          f"cannot read '{targets[1]} inf'"]),
        ("prescribed", args.prescribed, [first, targets[1], "quit"],
         ["no obstacle takes input"])]
    for k, (name, settings, lines, errors) in enumerate(cases):
        output = os.path.join(args.output, f"refusals_{k + 1}")
        print(f"{name} session with bad lines: {lines}")
        run = run_session(args.coshell, args.prm, output,
                          args.set + settings, "\n".join(lines) + "\n")
        replies = run.stdout.splitlines()
        got = [line for line in replies if line.startswith("error ")]
        print("\n".join(got))
        if run.returncode != 0:
            failures.append(f"{name} with bad lines: exit status "
                            f"{run.returncode}: {run.stderr[-300:]}")
        elif (len(got) != len(errors) or
              any(e not in line for e, line in zip(errors, got))):
            failures.append(f"{name} with bad lines: error lines {got}, "
                            f"expected ones with {errors}")
        elif f"done {targets[1]}" not in replies:
            failures.append(f"{name} with bad lines: no 'done {targets[1]}'")
    return failures


if __name__ == "__main__":
    main()
