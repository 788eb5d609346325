#!/usr/bin/env python3
"""A restart under tighter step limits obeys them from its first step.

check_restart_step_limits.py --coshell BIN --prm FILE --output DIR
    [--set A/B=v ...] --interval DT --maximum H

1. Run A with Output/Checkpoint interval = DT (the scene's own steps).
2. Run B from A's first checkpoint with Time integration/Maximum time
   step = H (below the step A carried): every step of B after the
   checkpoint, the first included, is at most H (time_history.csv's dt),
   and B's log says that the carried step was clipped to that limit.
"""
import argparse
import csv
import glob
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coshell_checks import Checks, add_scene_arguments  # noqa: E402


def run(args, directory, extra):
    """Runs coshell into a fresh 'directory'; returns its standard output."""
    if os.path.isdir(directory):
        shutil.rmtree(directory)
    command = [args.coshell, args.prm, "--output", directory] + extra
    for assignment in args.set:
        command += ["--set", assignment]
    print("running:", " ".join(repr(c) for c in command), flush=True)
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.stdout.write(result.stdout[-2000:] + result.stderr)
        sys.exit(f"FAIL: coshell exited with status {result.returncode}")
    return result.stdout


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--interval", type=float, required=True)
    parser.add_argument("--maximum", type=float, required=True)
    args = parser.parse_args()
    checks = Checks()

    first = os.path.join(args.output, "A")
    run(args, first,
        ["--set", f"Output/Checkpoint interval={args.interval}"])
    checkpoint = sorted(glob.glob(os.path.join(first, "checkpoint-*.h5")))[0]

    limit = f"Time integration/Maximum time step={args.maximum}"
    log = run(args, os.path.join(args.output, "B"),
              ["--restart", checkpoint, "--set", limit])
    with open(os.path.join(args.output, "B", "time_history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(first, "time_history.csv")) as f:
        step_of_checkpoint = int(os.path.basename(checkpoint)[11:17])
        carried = float(list(csv.DictReader(f))[step_of_checkpoint - 1]["dt"])
    after = [r for r in rows if int(r["step"]) > step_of_checkpoint]
    largest = max(float(r["dt"]) for r in after)
    checks.that(carried > args.maximum,
                f"run A's step at the checkpoint, {carried:g} s, exceeds the "
                f"restart's limit {args.maximum:g} s")
    checks.that(len(after) > 0 and float(after[0]["dt"]) <= args.maximum,
                f"the first step after the restart, {after[0]['dt']} s, "
                f"respects Maximum time step = {args.maximum:g} s")
    checks.that(largest <= args.maximum * (1 + 1e-12),
                f"the largest of the {len(after)} steps after the restart, "
                f"{largest:g} s, respects it")
    checks.that("clipped to Time integration/Maximum time step" in log,
                "the restart's log says the carried step was clipped")
    checks.exit()


if __name__ == "__main__":
    main()
