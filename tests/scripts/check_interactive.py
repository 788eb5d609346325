#!/usr/bin/env python3
"""The interactive protocol (coshell --interactive): targets on standard
input, one line per step and one 'done' per target on standard output,
the log on standard error. Feeds a scripted session and checks the
replies. With --history-rows N the session is run again with Output/Steps
between history rows = N: its time_history.csv must hold exactly the
full run's rows of every N-th step and of the last one (the run ends at
'quit', between two such steps), and its summary's quantities of
interest must be the full run's. With --case, each given session is run
instead (on a scene of several stages: a target past a stage's end
carries on into the next, 'quit' ends the run there, and a target past
the scene's end is answered at its end); --static-stage, with --case,
gives a static stage's pseudo-time, which the simulated time in
summary.json does not count."""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

from coshell_checks import exit_with, read_rows

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "doc", "scripts"))
import render_vtu  # noqa: E402

SESSION = "0.1\n# a comment\nnot-a-time\n0.3\n0.2\nquit\n0.5\n"


def session_parser():
    """The arguments every interactive check takes: the binary, the
    scene, the output directory, its number of obstacles and settings."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--obstacles", type=int, required=True)
    parser.add_argument("--set", action="append", default=[],
                        help="a setting passed on to coshell")
    return parser


def main():
    parser = session_parser()
    parser.add_argument("--history-rows", type=int, default=0,
                        help="also run with Output/Steps between history "
                             "rows = N and compare the histories")
    parser.add_argument("--case", nargs=3, action="append",
                        metavar=("LINES", "DONE", "END"),
                        help="a session (its lines separated by spaces), "
                        "the times its 'done' lines must give and the time "
                        "(s) the run must end at")
    parser.add_argument("--pushing", type=int, metavar="K",
                        help="with --case: obstacle K's force on the last "
                        "step line of each session is positive (it pushes "
                        "the shell by then: the injection's plunger)")
    parser.add_argument("--static-stage", nargs=2, type=float,
                        metavar=("START", "DURATION"),
                        help="a static stage's pseudo-time (s), which "
                        "summary.json's simulated time does not count")
    args = parser.parse_args()
    if os.path.isdir(args.output):
        shutil.rmtree(args.output)
    if args.case:
        failures = []
        for k, (lines, done, end) in enumerate(args.case):
            session = "\n".join(lines.split()) + "\n"
            output = os.path.join(args.output, f"session_{k + 1}")
            print(f"session {k + 1}: {lines!r}")
            run = run_session(args.coshell, args.prm, output, args.set,
                              session)
            failures += [f"session {k + 1}: {failure}" for failure in
                         session_failures(run, output, args.obstacles,
                                          done.split(), float(end),
                                          static_stage=args.static_stage,
                                          settings=args.set)
                         + pushing_failures(run, args.pushing)]
        exit_with(failures)
    # This run writes its VTU, against which its centroids are checked.
    run = run_session(args.coshell, args.prm, args.output,
                      args.set + ["Output/Write VTU=true"])
    failures = session_failures(run, args.output, args.obstacles,
                                ["0.1", "0.3", "0.3"], 0.3,
                                bad_line="not-a-time", settings=args.set)
    failures += centroid_failures(run, args.output)
    if args.history_rows and not failures:
        n_steps = sum(line.startswith("step ")
                      for line in run.stdout.splitlines())
        failures += sparse_history_failures(args, n_steps)
    exit_with(failures)


def session_failures(run, output, n_obstacles, done_times, end,
                     bad_line=None, static_stage=None, settings=()):
    """What the replies of one session and its summary.json get wrong:
    the 'done' lines, the step lines (rising to 'end', each with the
    time, a force per obstacle as contact_forces.csv gives it, the
    centroid and a positive real-time factor), the error line for
    'bad_line', nothing else on stdout, and the simulated time (up to
    'end', less the part of 'static_stage', (start, duration), before
    it). 'settings' are the session's, for the obstacles' input
    directions."""
    lines = run.stdout.splitlines()
    print("\n".join(lines))
    if run.returncode != 0:
        return [f"exit status {run.returncode}: {run.stderr[-500:]}"]
    if not done_times:  # ended before any stage: nothing may have run
        return nothing_run_failures(lines, output)
    failures = []
    steps = [l.split() for l in lines if l.startswith("step ")]
    done = [l for l in lines if l.startswith("done ")]
    errors = [l for l in lines if l.startswith("error ")]
    others = [l for l in lines
              if not l.split()[0] in ("step", "slope", "done", "error")]
    times = [float(s[2]) for s in steps]
    expected_fields = 3 + n_obstacles + 3 + 1
    if others:
        failures.append(f"lines outside the protocol on stdout: {others[:3]}")
    if done != [f"done {t}" for t in done_times]:
        failures.append(f"done lines {done}, expected {done_times}")
    if (len(errors) != (1 if bad_line else 0) or
            (bad_line and bad_line not in errors[0])):
        failures.append(f"error lines {errors}")
    rising = all(a < b for a, b in zip(times, times[1:]))
    if not steps or not rising or abs(times[-1] - end) > 1e-12:
        failures.append(f"step times {times} do not rise to {end}")
    if any(len(s) != expected_fields for s in steps):
        failures.append(f"a step line has not {expected_fields} fields")
    if steps and not all(float(s[-1]) > 0 for s in steps):
        failures.append("a real-time factor is not positive")
    if n_obstacles and steps:
        failures += step_force_failures(steps, output,
                                        input_directions(settings))
    failures += slope_line_failures(lines, len(input_directions(settings)))
    expected = end
    if static_stage:
        start, duration = static_stage
        expected -= max(0.0, min(end, start + duration) - start)
    with open(os.path.join(output, "summary.json")) as f:
        simulated = json.load(f)["simulated_time_s"]
    if abs(simulated - expected) > 1e-12:
        failures.append(f"summary.json: simulated_time_s {simulated}, not "
                        f"{expected}")
    return failures


def pushing_failures(run, obstacle):
    """Obstacle 'obstacle' (None: no check) pushes the shell at the
    session's last step: its force on that step line is positive."""
    steps = [l.split() for l in run.stdout.splitlines()
             if l.startswith("step ")]
    if obstacle is None or not steps:
        return []
    force = float(steps[-1][2 + obstacle])
    print(f"obstacle {obstacle}'s force at the last step (t = "
          f"{steps[-1][2]} s): {force:.6g} N")
    if force > 0:
        return []
    return [f"obstacle {obstacle}'s force {force} N at the last step is not "
            "positive: it does not push the shell"]


def input_directions(settings):
    """Obstacle number -> unit vector of its 'Contact/Obstacle k/Input
    direction' among the settings."""
    directions = {}
    for setting in settings:
        key, _, value = setting.partition("=")
        words = key.strip().split("/")
        if (len(words) == 3 and words[0] == "Contact" and
                words[2] == "Input direction"):
            vector = [float(x) for x in value.split(",")]
            norm = sum(x * x for x in vector) ** 0.5
            directions[int(words[1].split()[-1])] = [x / norm for x in vector]
    return directions


def centroid_failures(run, output):
    """Each step line's centroid against the mean of the shell's vertices,
    each once, in the VTU written at that step's time (the VTU repeats a
    vertex in every cell; its single precision and the line's 6 digits
    bound the difference). Some step must have a VTU."""
    steps = [l.split() for l in run.stdout.splitlines()
             if l.startswith("step ")]
    pvd = os.path.join(output, "solution.pvd")
    if not os.path.exists(pvd):
        return ["no solution.pvd to check the centroids against"]
    by_time = {float(s[2]): s for s in steps}
    failures, checked = [], 0
    for frame in render_vtu.read_pvd(pvd):
        fields = by_time.get(frame.time)
        if fields is None:
            continue
        mesh = render_vtu.read_vtu(frame.shell_file)
        _, first = np.unique(mesh.points, axis=0, return_index=True)
        positions = render_vtu.deformed_positions(mesh, 1.0)[first]
        mean = positions.mean(axis=0)
        printed = np.array([float(f) for f in fields[-4:-1]])
        checked += 1
        # The line's 6 digits, and the VTU's single precision: half a unit
        # in the 24th bit of the largest coordinate, for the reference
        # point and the displacement each.
        tolerance = (1e-5 * np.abs(mean).max()
                     + 2 * np.abs(positions).max() * 2.0**-24)
        if np.abs(printed - mean).max() > tolerance:
            failures.append(f"step {fields[1]}: centroid {printed} printed, "
                            f"{mean} in {os.path.basename(frame.shell_file)}")
    print(f"step lines' centroids: {checked} checked against the VTU, "
          f"{len(failures)} differ")
    if not checked:
        failures.append("no VTU was written at a step line's time")
    return failures[:5]


def step_force_failures(steps, output, directions):
    """Each step line's force per obstacle against that step's rows of
    contact_forces.csv: the magnitude, or for an obstacle with an input
    direction the signed component along it, to the line's 6 significant
    digits. Steps without rows are skipped; some must have them."""
    rows = {}
    for row in read_rows(os.path.join(output, "contact_forces.csv")):
        obstacle = int(float(row["obstacle"]))
        if obstacle > 0:  # 0: self contact, no net force
            rows[(int(float(row["step"])), obstacle)] = [
                float(row[c]) for c in ("fx", "fy", "fz")]
    failures, checked = [], 0
    for fields in steps:
        for k, printed in enumerate(fields[3:-4], start=1):
            vector = rows.get((int(fields[1]), k))
            if vector is None:
                continue
            direction = directions.get(k)
            expected = (sum(f * d for f, d in zip(vector, direction))
                        if direction else sum(f * f for f in vector) ** 0.5)
            checked += 1
            if abs(float(printed) - expected) > 1e-5 * abs(expected) + 1e-12:
                failures.append(f"step {fields[1]}, obstacle {k}: force "
                                f"{printed} printed, {expected} in "
                                "contact_forces.csv")
    print(f"step lines' forces: {checked} checked against "
          f"contact_forces.csv, {len(failures)} differ")
    if not checked:
        failures.append("no step line's force has a contact_forces.csv row")
    return failures[:5]


def slope_line_failures(lines, n_driven):
    """With driven obstacles, each step line is followed by its slope
    line: 'slope N s' and one finite slope per driven obstacle; without,
    there is no slope line."""
    slopes = [l.split() for l in lines if l.startswith("slope ")]
    if not n_driven:
        return [f"slope lines without a driven obstacle: {slopes[:2]}"] \
            if slopes else []
    failures = []
    for k, line in enumerate(lines):
        if not line.startswith("step "):
            continue
        following = lines[k + 1].split() if k + 1 < len(lines) else []
        if (len(following) != 3 + n_driven or following[0] != "slope" or
                following[1] != line.split()[1]):
            failures.append(f"step {line.split()[1]}: no slope line with "
                            f"{n_driven} slope(s) after it: {following}")
        elif not all(math.isfinite(float(x)) for x in following[2:]):
            failures.append(f"a slope line is not finite: {following}")
    print(f"slope lines: {len(slopes)}, {len(failures)} wrong")
    return failures[:5]


def nothing_run_failures(lines, output):
    """A session that ends before its first target: no reply, no step
    and no Newton iteration (a static stage first does not run either)."""
    with open(os.path.join(output, "summary.json")) as f:
        iterations = json.load(f).get("newton_iterations", 0)
    print(f"summary.json: {iterations} Newton iterations")
    failures = [f"replies {lines[:3]} to a session with no target"] if lines \
        else []
    if iterations != 0:
        failures.append(f"{iterations} Newton iterations: a stage ran")
    return failures


def run_session(coshell, prm, output, settings=(), session=SESSION):
    command = [coshell, prm, "--interactive", "--output", output,
               "--set", "Output/Write VTU=false"]
    for setting in settings:
        command += ["--set", setting]
    return subprocess.run(command, input=session, capture_output=True,
                          text=True)


def sparse_history_failures(args, n_steps):
    """The session again with every N-th history row: the same rows where
    both have one, the last step's row too, the same final quantities."""
    n = args.history_rows
    output = os.path.join(args.output, f"every_{n}th_row")
    run = run_session(args.coshell, args.prm, output,
                      args.set + [f"Output/Steps between history rows={n}"])
    if run.returncode != 0:
        return [f"with every {n}th history row: exit status "
                f"{run.returncode}: {run.stderr[-500:]}"]
    full = {row["step"]: row for row in
            read_rows(os.path.join(args.output, "time_history.csv"))}
    sparse = read_rows(os.path.join(output, "time_history.csv"))
    steps = [int(row["step"]) for row in sparse]
    expected = [s for s in range(1, n_steps + 1) if s % n == 0 or s == n_steps]
    print(f"every {n}th history row: steps {steps} (expected {expected})")
    failures = []
    if steps != expected:
        failures.append(f"history rows at steps {steps}, expected {expected}")
    if any(row != full.get(row["step"]) for row in sparse):
        failures.append("a sparse history row differs from the full run's")
    summaries = [json.load(open(os.path.join(d, "summary.json")))["qoi"]
                 for d in (args.output, output)]
    if summaries[0] != summaries[1]:
        failures.append("summary.json quantities differ with sparse rows")
    return failures


if __name__ == "__main__":
    main()
