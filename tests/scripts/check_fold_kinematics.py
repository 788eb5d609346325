#!/usr/bin/env python3
"""Co-rotational against linear kinematics on the IOL fold
(prm/iol/injection.prm, stage 1 only): what the paper's co-rotation is
for.

Runs the scene twice, Element/Formulation = corotational and linear, to
the same time, and follows the optic's material line from rim to centre
to rim (the quantities of interest rim_yp, optic, rim_ym: 6 mm long at
rest). The wings fold the lens by bending; a thin shell folded by
bending keeps the length of its material lines to within its membrane
strain, so the polyline rim-centre-rim (never longer than the line) may
not grow by more than that. Linear kinematics turns each rotation theta
into a stretch (a point at distance r moves r*theta along the tangent
instead of along the arc), so the same line grows with the wings'
rotation. Asserted:
  - corotational: the polyline grows by at most --corotational-stretch
    (a fraction) at every step;
  - linear: the polyline has grown by at least --linear-stretch at the
    end (the defect co-rotation removes), reported side by side.
Writes fold_kinematics.csv (time, stretch and largest membrane strain of
both runs) and, with --figure, a PNG of both."""
import argparse
import csv
import math
import os

from coshell_checks import Checks, add_scene_arguments, read_rows, run_scene

REST_LENGTH = 6.0  # mm, rim to centre to rim


def line_stretch(row):
    """Length of the polyline rim (y=+3) - centre - rim (y=-3) over its
    rest length, minus 1."""
    def point(name, y):
        return (float(row[name + "_ux"]), y + float(row[name + "_uy"]),
                float(row[name + "_uz"]))
    upper, centre, lower = point("rim_yp", 3), point("optic", 0), point(
        "rim_ym", -3)
    length = math.dist(upper, centre) + math.dist(centre, lower)
    return length / REST_LENGTH - 1


def run(args, formulation):
    output = os.path.join(args.output, formulation)
    run_scene(args.coshell, args.prm, output, args.set + [
        f"Element/Formulation={formulation}",
        f"Stage 1/Duration={args.until}",
        "Stage 2/Analysis type=none", "Stage 3/Analysis type=none",
        "Stage 4/Analysis type=none"])
    return read_rows(os.path.join(output, "time_history.csv"))


def write_table(path, runs):
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["formulation", "time", "line_stretch",
                         "max_membrane_strain", "strain_energy"])
        for formulation, rows in runs.items():
            for r in rows:
                writer.writerow([formulation, r["time"],
                                 f"{line_stretch(r):.6g}",
                                 r["max_membrane_strain"],
                                 r["strain_energy"]])


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    add_scene_arguments(parser)
    parser.add_argument("--until", type=float, default=0.6,
                        help="simulated time of both runs, s")
    parser.add_argument("--corotational-stretch", type=float, default=0.03)
    parser.add_argument("--linear-stretch", type=float, default=0.3)
    parser.add_argument("--figure")
    args = parser.parse_args()

    runs = {f: run(args, f) for f in ("corotational", "linear")}
    write_table(os.path.join(args.output, "fold_kinematics.csv"), runs)
    if args.figure:
        import checker_figures
        checker_figures.fold_kinematics_chart(args.figure, runs, line_stretch)

    check = Checks()
    corotational = max(line_stretch(r) for r in runs["corotational"])
    linear = line_stretch(runs["linear"][-1])
    for formulation, rows in runs.items():
        last = rows[-1]
        print(f"{formulation}: t = {float(last['time']):.4g} s, line stretch "
              f"{100 * line_stretch(last):.3g} % (largest "
              f"{100 * max(line_stretch(r) for r in rows):.3g} %), largest "
              f"membrane strain {100 * float(last['max_membrane_strain']):.3g}"
              f" %, strain energy {float(last['strain_energy']):.4g} N mm, "
              f"{len(rows)} steps")
    check(f"co-rotational: the optic's line grows by at most "
          f"{100 * corotational:.3g} % <= {100 * args.corotational_stretch:g}"
          f" % (folding by bending)", corotational <= args.corotational_stretch)
    check(f"linear: the same line has grown by {100 * linear:.3g} % >= "
          f"{100 * args.linear_stretch:g} % (rotations taken as stretch)",
          linear >= args.linear_stretch)
    check.exit()


if __name__ == "__main__":
    main()
