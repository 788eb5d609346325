"""Runs coshell on a scene into a fresh output directory (shared by the
test checkers)."""
import csv
import os
import shutil
import subprocess
import sys


def run_scene(coshell, prm, output, assignments):
    """Runs 'coshell prm --output output --set a ...'; exits the checker
    with a failure line if coshell fails."""
    if os.path.isdir(output):
        shutil.rmtree(output)
    command = [coshell, prm, "--output", output]
    for assignment in assignments:
        command += ["--set", assignment]
    print("running:", " ".join(repr(c) for c in command), flush=True)
    if subprocess.run(command).returncode != 0:
        print("0 passed, 1 failed")
        sys.exit("FAIL: coshell exited with an error")


def add_scene_arguments(parser):
    """The arguments every scene checker takes: the coshell binary, the
    scene, the output directory and --set overrides."""
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--set", action="append", default=[])


def exit_with(failures):
    """Prints the verdict and the failures (one line each) and exits with
    the test's status."""
    print(f"{1 - bool(failures)} passed, {int(bool(failures))} failed")
    for failure in failures:
        print("FAIL: " + failure)
    sys.exit(1 if failures else 0)


def read_rows(path):
    """The rows of a CSV file as dictionaries."""
    with open(path) as f:
        return list(csv.DictReader(f))


def add_strip_arguments(parser):
    """The strip of the contact wrap and roll-up checkers: its length
    (the loaded part), thickness, bending stiffness EI and largest end
    moment (load factor 1)."""
    for name in ("--length", "--thickness", "--bending-stiffness",
                 "--moment-max"):
        parser.add_argument(name, type=float, required=True)


class Checks:
    """Prints 'ok'/'FAIL' per check and collects the failures for
    exit_with()."""

    def __init__(self):
        self.failures = []

    def __call__(self, what, ok):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            self.failures.append(what)
