"""Runs coshell on a scene into a fresh output directory (shared by the
test checkers)."""
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
