#!/usr/bin/env python3
"""Checkpoint and restart of a dynamic scene (issue: scale-out, item 5).

check_restart.py --coshell BIN --prm FILE --output DIR [--set A/B=v ...]
                 --end T [--end-parameter "Stage 2/Duration"] --interval DT
                 --tolerance TOL

1. Run A to T with Output/Checkpoint interval = DT.  Every checkpoint holds
   the datasets and attributes a restart needs (read with h5py), its
   rotation matrices are orthonormal, and its time is past a multiple of DT.
2. Run B from A's middle checkpoint, which h5py holds open meanwhile (as
   a second run restarting from the same file would: the restart opens it
   read-only, so HDF5's lock does not refuse it):
   B's final checkpoint equals A's to TOL
   (relative, every dataset), and B's time_history.csv has A's rows (the
   earlier ones copied, the later ones recomputed; 17 printed digits), as
   have its contact_forces.csv where A wrote it and each --force-file.
3. Run C to T and stop it with SIGINT half-way: exit status 3, a checkpoint
   named in its message, no summary.json and no finished time_history.csv.
   Run D from that checkpoint into C's directory: D's final checkpoint equals
   A's to TOL and its time_history.csv has A's rows.
4. With --interactive-targets T1 T2 ...: run E through --interactive to
   those times and T; its final checkpoint equals A's to TOL.
5. Run F from A's last checkpoint: its time_history.csv has A's rows and
   its summary.json the same quantities of interest (a restart at the
   stage's end takes no step: the quantities are the checkpoint's).
"""
import argparse
import csv
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coshell_checks import Checks, add_scene_arguments  # noqa: E402

VECTORS = ["values", "velocity", "acceleration", "generalized_force",
           "damping_force"]
ATTRIBUTES = ["format", "stage", "step", "time", "step_size",
              "converged_force_scale", "external_work", "dissipated_energy",
              "pvd_entries", "last_written", "prm_file"]

checks = Checks()
check = checks.that


def run(args, directory, extra, **popen):
    command = [args.coshell, args.prm, "--output", directory]
    for assignment in args.set + extra:
        command += ["--set", assignment]
    return subprocess.Popen(command, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, **popen)


def finish(process, what):
    out, err = process.communicate()
    if process.returncode != 0:
        sys.stdout.write(out[-2000:] + err)
        sys.exit(f"FAIL: {what} exited with status {process.returncode}")
    return out


def checkpoints(directory):
    return sorted(glob.glob(os.path.join(directory, "checkpoint-*.h5")))


def check_contents(path, interval):
    with h5py.File(path, "r") as f:
        missing = [a for a in ATTRIBUTES if a not in f.attrs]
        missing += [d for d in VECTORS + ["rotations", "csv_rows"] if d not in f]
        check(not missing, f"{os.path.basename(path)} holds every dataset "
              f"and attribute (missing: {missing})")
        if missing:
            return
        n = f["values"].shape[0]
        sizes = {d: f[d].shape for d in VECTORS}
        check(all(s == (n,) for s in sizes.values()),
              f"vectors have the {n} DoFs: {sizes}")
        rotations = f["rotations"][()].reshape(-1, 3, 3)
        error = np.abs(np.einsum("vji,vjk->vik", rotations, rotations)
                       - np.eye(3)).max()
        check(error < 1e-12, f"rotations orthonormal to {error:.1e}")
        t = float(f.attrs["time"])
        check(t / interval - np.floor(t / interval + 1e-9) <
              float(f.attrs["step_size"]) / interval + 1e-9,
              f"written at t = {t:.6g} s, the first step past a multiple of "
              f"{interval} s")


def compare_checkpoints(a, b, tolerance, what,
                        names=VECTORS + ["rotations", "pseudo_acceleration"]):
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        worst = 0.0
        for name in names:
            if name not in fa:
                continue
            x, y = fa[name][()], fb[name][()]
            scale = max(np.abs(x).max(), 1e-300)
            worst = max(worst, np.abs(x - y).max() / scale)
        same_time = fa.attrs["time"] == fb.attrs["time"] and \
            fa.attrs["step"] == fb.attrs["step"]
    check(same_time and worst <= tolerance,
          f"{what}: final state equals the uninterrupted run's, largest "
          f"relative difference {worst:.2e} (tolerance {tolerance:g})")


def rows(directory, name):
    with open(os.path.join(directory, name)) as f:
        return list(csv.reader(f))


def compare_histories(a, b, what, force_files):
    """B's (or D's, F's) rows of the time history, the contact forces
    where A wrote them, and the Force files the scene sets, which A and B
    must both have written."""
    for name in ["time_history.csv", "contact_forces.csv"] + force_files:
        exist = [os.path.exists(os.path.join(d, name)) for d in (a, b)]
        if name not in force_files and not exist[0]:
            continue
        if not all(exist):
            check(False, f"{what}: {name} written by A and by {what}")
            continue
        ra, rb = rows(a, name), rows(b, name)
        worst = 0.0
        for x, y in zip(ra[1:], rb[1:]):
            for u, v in zip(x, y):
                u, v = float(u), float(v)
                worst = max(worst, abs(u - v) / max(abs(u), 1e-6))
        check(len(ra) == len(rb) and ra[0] == rb[0] and worst < 1e-9,
              f"{what}: {name} has the uninterrupted run's {len(ra) - 1} "
              f"rows (largest difference {worst:.1e} of a value)")


def last_step(history):
    """The step of the last complete row of a time history being written
    (its rows may be thinned: Output/Steps between history rows)."""
    with open(history) as f:
        lines = [line for line in f if line.endswith("\n")]
    try:
        return int(float(lines[-1].split(",")[0]))
    except (IndexError, ValueError):  # no row yet, or the header only
        return 0


def interrupt_half_way(args, directory, steps, timing):
    process = run(args, directory, timing)
    partial = os.path.join(directory, "time_history.csv.partial")
    deadline = time.time() + 600
    while process.poll() is None and time.time() < deadline:
        if os.path.exists(partial) and last_step(partial) > steps // 2:
            process.send_signal(signal.SIGINT)
            break
        time.sleep(0.01)
    out, err = process.communicate()
    return process.returncode, err


def restart(args, directory, checkpoint, timing, name):
    """Runs the scene from 'checkpoint' into 'directory' to its end."""
    command = [args.coshell, args.prm, "--output", directory, "--restart",
               checkpoint]
    for assignment in args.set + timing:
        command += ["--set", assignment]
    finish(subprocess.Popen(command, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True),
           f"the restarted run {name}")


def resume_and_compare(args, reference, directory, checkpoint, final, timing,
                       name):
    """Restarts from 'checkpoint' into 'directory'; its final checkpoint and
    time history must be the uninterrupted run's (in 'reference')."""
    restart(args, directory, checkpoint, timing, name)
    compare_checkpoints(os.path.join(reference, final),
                        os.path.join(directory, final), args.tolerance,
                        f"{name} restarted from {os.path.basename(checkpoint)}")
    compare_histories(reference, directory, name, args.force_file)


def check_interactive(args, reference, final, timing):
    """Run E driven by --interactive to the given targets and on to the
    end: the integrator carries its state across targets, so E ends in
    the uninterrupted run's state (to round-off: the steps before each
    target are clipped to it)."""
    directory = os.path.join(args.output, "E")
    command = [args.coshell, args.prm, "--output", directory, "--interactive"]
    for assignment in args.set + timing:
        command += ["--set", assignment]
    targets = "".join(f"{t}\n" for t in args.interactive_targets + [args.end])
    result = subprocess.run(command, input=targets + "quit\n",
                            capture_output=True, text=True)
    check(result.returncode == 0, f"interactive run E to {targets.split()}")
    if result.returncode != 0:
        return
    # The steps before each target are clipped to it: their sizes differ
    # from the straight run's by the round-off of t (1e-17 s), which the
    # configuration keeps at that level and the rates see divided by dt.
    compare_checkpoints(os.path.join(reference, final),
                        os.path.join(directory, final), args.tolerance,
                        "E driven interactively, configuration",
                        ["values", "rotations"])
    compare_checkpoints(os.path.join(reference, final),
                        os.path.join(directory, final), 1e-9,
                        "E driven interactively, rates",
                        ["velocity", "acceleration", "pseudo_acceleration"])


def check_bad_files(args, good):
    """A foreign HDF5 file, a checkpoint missing a dataset and one whose
    'format' holds two strings are refused with a message naming the file
    and what is wrong."""
    foreign = os.path.join(args.output, "foreign.h5")
    with h5py.File(foreign, "w") as f:
        f["x"] = [1.0]
    damaged = os.path.join(args.output, "damaged.h5")
    shutil.copy(good, damaged)
    with h5py.File(damaged, "a") as f:
        del f["velocity"]
    # Two strings where one is read: they once overran the reader's buffer.
    listed = os.path.join(args.output, "listed.h5")
    shutil.copy(good, listed)
    with h5py.File(listed, "a") as f:
        f.attrs["format"] = [str(f.attrs["format"]), "again"]
    for path, expected in [(foreign, "lacks attribute 'format'"),
                           (damaged, "lacks dataset 'velocity'"),
                           (listed, "attribute 'format' is not a single "
                            "string")]:
        result = subprocess.run(
            [args.coshell, args.prm, "--restart", path, "--output",
             os.path.join(args.output, "refused")],
            capture_output=True, text=True)
        check(result.returncode == 1 and path in result.stderr and
              expected in result.stderr,
              f"{os.path.basename(path)} refused: {result.stderr.strip()}")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    add_scene_arguments(parser)
    parser.add_argument("--end", type=float, required=True)
    parser.add_argument("--interval", type=float, required=True)
    parser.add_argument("--end-parameter", default="Time integration/End time",
                        help="the duration to set to --end (a staged "
                        "scene: 'Stage k/Duration')")
    parser.add_argument("--tolerance", type=float, default=1e-12)
    parser.add_argument("--interactive-targets", type=float, nargs="*",
                        default=[])
    parser.add_argument("--force-file", action="append", default=[],
                        help="a Contact/Obstacle k/Force file the scene "
                        "sets: compared like the histories")
    args = parser.parse_args()
    shutil.rmtree(args.output, ignore_errors=True)
    a, b, c = (os.path.join(args.output, x) for x in ("A", "B", "C"))
    timing = [f"{args.end_parameter}={args.end}",
              f"Output/Checkpoint interval={args.interval}"]

    finish(run(args, a, timing), "the uninterrupted run A")
    written = checkpoints(a)
    check(len(written) >= 3, f"run A wrote {len(written)} checkpoints")
    for path in written:
        check_contents(path, args.interval)
    final = os.path.basename(written[-1])
    middle = written[len(written) // 2 - 1]
    with h5py.File(written[-1], "r") as f:
        steps = int(f.attrs["step"])

    with h5py.File(middle, "r"):
        resume_and_compare(args, a, b, middle, final, timing, "B")

    status, message = interrupt_half_way(args, c, steps, timing)
    named = re.search(r"checkpoint written to (\S+);", message)
    check(status == 3 and named is not None,
          f"SIGINT: exit status {status} (3 expected), message: "
          f"{message.strip()[-200:]}")
    check(not os.path.exists(os.path.join(c, "summary.json")) and
          not os.path.exists(os.path.join(c, "time_history.csv")),
          "SIGINT: no summary.json, time_history.csv still .partial")
    if named:
        resume_and_compare(args, a, c, named.group(1), final, timing, "D")
    if args.interactive_targets:
        check_interactive(args, a, final, timing)
    check_last_checkpoint(args, a, written[-1], timing)
    check_bad_files(args, written[len(written) // 2 - 1])
    checks.exit()


def check_last_checkpoint(args, reference, checkpoint, timing):
    """Run F from the last checkpoint: A's rows and A's quantities."""
    directory = os.path.join(args.output, "F")
    restart(args, directory, checkpoint, timing, "F")
    compare_histories(reference, directory, "F", args.force_file)
    quantities = []
    for run_directory in (reference, directory):
        with open(os.path.join(run_directory, "summary.json")) as f:
            quantities.append(json.load(f).get("qoi"))
    check(quantities[0] == quantities[1] and quantities[0],
          f"F: summary.json's quantities of interest are A's ({quantities[1]})")


if __name__ == "__main__":
    main()
