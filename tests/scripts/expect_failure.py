#!/usr/bin/python3
"""Runs a command that must fail cleanly: non-zero exit status, an error
message matching a pattern on stderr, no summary.json or convergence.csv
left behind, and no temporary file of the process (coshell-<pid>-*, e.g.
a gmsh mesh of an obstacle) left in the temp directory. With --output,
that directory starts with an earlier run's summary.json and
convergence.csv, which the failed run must remove: stale results that
stayed would look like this run's. A command line coshell cannot read
(exit status 2, the usage printed) runs nothing and touches no file:
there they must stay as they were. With --once exactly one line of
stderr must match the pattern (an error that every rank of an mpirun
shares is printed by one rank only).

  expect_failure.py --pattern REGEX [--output DIR] [--once] -- command args...
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pattern", required=True)
    parser.add_argument("--output")
    parser.add_argument("--once", action="store_true",
                        help="the pattern matches stderr exactly once")
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = [c for c in args.command if c != "--"]
    stale = ("summary.json", "convergence.csv")
    if args.output:
        if os.path.isdir(args.output):
            shutil.rmtree(args.output)
        os.makedirs(args.output)
        for name in stale:
            with open(os.path.join(args.output, name), "w") as f:
                f.write("an earlier run's result\n")
    started = time.time() - 1  # file times have coarse resolution
    process = subprocess.Popen(command, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    stdout, stderr = process.communicate()
    result = subprocess.CompletedProcess(command, process.returncode, stdout, stderr)
    # Only files this process made: an older one of a recycled pid is not its.
    left_behind = [path for path in glob.glob(os.path.join(
        tempfile.gettempdir(), f"coshell-{process.pid}-*"))
        if os.path.getmtime(path) >= started]
    print("command:", " ".join(repr(c) for c in command))
    print("exit status:", result.returncode)
    print("stderr:", result.stderr.strip())
    problems = []
    if result.returncode == 0:
        problems.append("exit status is 0")
    if result.returncode < 0 or "Aborted" in result.stderr:
        problems.append("the process crashed instead of reporting the error")
    if not re.search(args.pattern, result.stderr, re.S):
        problems.append(f"stderr does not match /{args.pattern}/")
    # Counted by line: a greedy .* across lines would join two copies.
    lines = [line for line in result.stderr.splitlines()
             if re.search(args.pattern, line)]
    if args.once and len(lines) != 1:
        problems.append(f"{len(lines)} lines of stderr match "
                        f"/{args.pattern}/, not one")
    for name in stale if args.output else ():
        left = os.path.exists(os.path.join(args.output, name))
        if left and result.returncode != 2:
            problems.append(f"an earlier run's {name} was left behind")
        if not left and result.returncode == 2:
            problems.append(f"a command-line error removed {name}")
    if left_behind:
        problems.append(f"temporary files were left behind: {left_behind}")
        for path in left_behind:
            os.remove(path)
    for p in problems:
        print("FAIL:", p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
