#!/usr/bin/env python3
"""The interactive protocol (coshell --interactive): targets on standard
input, one line per step and one 'done' per target on standard output,
the log on standard error. Feeds a scripted session and checks the
replies. With --history-rows N the session is run again with Output/Steps
between history rows = N: its time_history.csv must hold exactly the
full run's rows of every N-th step and of the last one (the run ends at
'quit', between two such steps), and its summary's quantities of
interest must be the full run's."""
import argparse
import json
import os
import shutil
import subprocess

from scene_runner import exit_with, read_rows

SESSION = "0.1\n# a comment\nnot-a-time\n0.3\n0.2\nquit\n0.5\n"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--obstacles", type=int, required=True)
    parser.add_argument("--history-rows", type=int, default=0,
                        help="also run with Output/Steps between history "
                             "rows = N and compare the histories")
    args = parser.parse_args()
    if os.path.isdir(args.output):
        shutil.rmtree(args.output)
    run = run_session(args.coshell, args.prm, args.output)
    lines = run.stdout.splitlines()
    print("\n".join(lines))
    failures = []
    if run.returncode != 0:
        failures.append(f"exit status {run.returncode}: {run.stderr[-500:]}")
    steps = [l.split() for l in lines if l.startswith("step ")]
    done = [l for l in lines if l.startswith("done ")]
    errors = [l for l in lines if l.startswith("error ")]
    others = [l for l in lines if not l.split()[0] in ("step", "done", "error")]
    times = [float(s[2]) for s in steps]
    expected_fields = 3 + args.obstacles + 3 + 1
    if others:
        failures.append(f"lines outside the protocol on stdout: {others[:3]}")
    if done != ["done 0.1", "done 0.3", "done 0.3"]:
        failures.append(f"done lines {done}, expected 0.1, 0.3, 0.3")
    if len(errors) != 1 or "not-a-time" not in errors[0]:
        failures.append(f"error lines {errors}")
    if not steps or times != sorted(times) or abs(times[-1] - 0.3) > 1e-12:
        failures.append(f"step times {times} do not rise to 0.3")
    if any(len(s) != expected_fields for s in steps):
        failures.append(f"a step line has not {expected_fields} fields")
    if steps and not all(float(s[-1]) > 0 for s in steps):
        failures.append("a real-time factor is not positive")
    with open(os.path.join(args.output, "summary.json")) as f:
        simulated = json.load(f)["simulated_time_s"]
    if abs(simulated - 0.3) > 1e-12:
        failures.append(f"summary.json: simulated_time_s {simulated}, not 0.3 "
                        "('quit' ends the run)")
    if args.history_rows:
        failures += sparse_history_failures(args, len(steps))
    exit_with(failures)


def run_session(coshell, prm, output, settings=()):
    command = [coshell, prm, "--interactive", "--output", output,
               "--set", "Output/Write VTU=false"]
    for setting in settings:
        command += ["--set", setting]
    return subprocess.run(command, input=SESSION, capture_output=True,
                          text=True)


def sparse_history_failures(args, n_steps):
    """The session again with every N-th history row: the same rows where
    both have one, the last step's row too, the same final quantities."""
    n = args.history_rows
    output = os.path.join(args.output, f"every_{n}th_row")
    run = run_session(args.coshell, args.prm, output,
                      [f"Output/Steps between history rows={n}"])
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
