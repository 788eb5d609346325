#!/usr/bin/env python3
"""The interactive protocol (coshell --interactive): targets on standard
input, one line per step and one 'done' per target on standard output,
the log on standard error. Feeds a scripted session and checks the
replies."""
import argparse
import json
import os
import shutil
import subprocess

from scene_runner import exit_with

SESSION = "0.1\n# a comment\nnot-a-time\n0.3\n0.2\nquit\n0.5\n"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--obstacles", type=int, required=True)
    args = parser.parse_args()
    if os.path.isdir(args.output):
        shutil.rmtree(args.output)
    run = subprocess.run([args.coshell, args.prm, "--interactive", "--output",
                          args.output, "--set", "Output/Write VTU=false"],
                         input=SESSION, capture_output=True, text=True)
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
    exit_with(failures)


if __name__ == "__main__":
    main()
