#!/usr/bin/env python3
"""Self-convergence in the time step of the IOL fold (prm/iol/injection.prm,
stage 1 alone): compares the folded lens of runs that differ only in
Time integration/Maximum time step against the run with the smallest
step, which stands for the converged answer. It is a self-convergence
check: the reference is this code's own finer run, not an independent
solution.

Each --run DT DIR names a run's Maximum time step (s) and its output
directory (written by check_injection.py --fold-only, so its own checks
already passed). For every run it reads the last frame of solution.pvd
(the lens at the end of the fold) and time_history.csv, and measures
against the finest run:
  - the largest distance between corresponding lens vertices (mm);
  - the difference of the optic's width across the injection axis
    (check_injection.py's rim chord, mm).
Asserted:
  - every run took DT as its largest step (within 1 %: the controller
    may stretch a step to land on the stage's end), so that each output
    is the run it is said to be;
  - every run reached the fold's end, the finest run's end time;
  - the runs' meshes are the same (same vertices at rest);
  - from each run to the next finer one the largest vertex distance
    falls by at least --min-reduction (a factor; the step falls by 4
    and 5 between 20, 5 and 1 ms, so first order in dt would give about
    4 and 9 against a 0.5 ms reference).
Prints the table (dt, steps, vertex distance, width, width difference)
and, with --table FILE, writes it as CSV."""
import argparse
import csv
import math
import os
import sys

import numpy as np

from coshell_checks import Checks, column, read_rows

SCRIPTS = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(SCRIPTS, "..", "..", "doc", "scripts"))
import render_vtu  # noqa: E402
from check_injection import rim_chord  # noqa: E402


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--run", nargs=2, action="append", required=True,
                        metavar=("DT", "DIR"),
                        help="a run's Maximum time step (s) and its output")
    parser.add_argument("--min-reduction", type=float, default=1.0,
                        help="the factor by which the largest vertex "
                             "distance must at least fall from each run "
                             "to the next finer one (1: it must fall)")
    parser.add_argument("--table", help="CSV file for the measured table")
    return parser.parse_args()


def folded_lens(output):
    """The last frame's time, rest points and current points (mm), the
    optic's width across the axis at the end (mm) and the step count."""
    frame = render_vtu.read_pvd(os.path.join(output, "solution.pvd"))[-1]
    mesh = render_vtu.read_vtu(frame.shell_file)
    history = read_rows(os.path.join(output, "time_history.csv"))
    return {"time": frame.time, "rest": mesh.points,
            "current": render_vtu.deformed_positions(mesh, 1.0),
            "width": rim_chord(history)[-1], "steps": len(history),
            "largest_step": max(column(history, "dt"))}


def main():
    args = parse_arguments()
    runs = sorted(((float(dt), folded_lens(d)) for dt, d in args.run),
                  key=lambda r: -r[0])
    checks = Checks()
    finest_dt, finest = runs[-1]
    rows = []
    for dt, run in runs:
        checks(f"dt {dt:g} s: the run's largest step is "
               f"{run['largest_step']:.6g} s", abs(run["largest_step"] - dt)
               <= 0.01 * dt)
        checks(f"dt {dt:g} s: the run reached the fold's end, t = "
               f"{run['time']:g} s (finest run: {finest['time']:g} s)",
               abs(run["time"] - finest["time"]) <= 1e-9)
        same_mesh = (run["rest"].shape == finest["rest"].shape
                     and np.allclose(run["rest"], finest["rest"], atol=1e-12))
        checks(f"dt {dt:g} s: the lens mesh is the finest run's "
               f"({len(run['rest'])} VTU points)", same_mesh)
        if not same_mesh:
            checks.exit()
        distance = np.linalg.norm(run["current"] - finest["current"],
                                  axis=1).max()
        rows.append((dt, run["steps"], distance, run["width"],
                     run["width"] - finest["width"]))
    print("dt (s), steps, largest vertex distance from the finest (mm), "
          "optic width (mm), width difference (mm)")
    for row in rows:
        print(f"{row[0]:g}, {row[1]}, {row[2]:.4g}, {row[3]:.5g}, "
              f"{row[4]:+.3g}")
    coarse = rows[:-1]
    for (dt_a, _, d_a, _, _), (dt_b, _, d_b, _, _) in zip(coarse, coarse[1:]):
        reduction = d_a / d_b if d_b > 0 else math.inf
        checks(f"from dt {dt_a:g} to {dt_b:g} s the folded lens's largest "
               f"distance from the dt {finest_dt:g} s one falls from "
               f"{d_a:.3g} to {d_b:.3g} mm, by {reduction:.3g} (at least "
               f"{args.min_reduction:g})", reduction >= args.min_reduction
               and d_b < d_a)
    if args.table:
        with open(args.table, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["max_time_step_s", "steps",
                             "max_vertex_distance_mm", "optic_width_mm",
                             "width_difference_mm"])
            writer.writerows(rows)
    checks.exit()


if __name__ == "__main__":
    main()
