#!/usr/bin/env python3
"""A plate squeezed through its thickness (prm/thickness/plate_squeeze_*.prm),
the thickness-stretch shell against references computed without it.

Two ways to squeeze:
  --pressure P   a nominal face pressure P (MPa) times the load factor
                 (plate_squeeze_frictionless.prm): the force is P times
                 the factor times --area;
  --plate N      rigid plates with barrier contact (plate_squeeze_contact.prm):
                 the force is the size of obstacle N's z force
                 (contact_forces.csv) times --symmetry (4 for a quarter
                 model).
The squeeze is 1 - the mean vertex thickness stretch; the spread of the
stretches must stay within --spread (0 for a uniform squeeze; with
contact, each face's barrier gap may differ by up to its activation
distance).

References:
  * --analytic-tolerance: homogeneous uniaxial stress of CalculiX's
    neo-Hooke law W = c10 (J^-2/3 I1 - 3) + (J - 1)^2 / d1, from its
    Cauchy stress formula written out below (frictionless only);
  * --calculix-tolerance: CalculiX's C3D20R solid, the --case rows of
    doc/calculix/strip_squeeze.csv on their finest mesh."""
import argparse
import bisect
import csv
import os

from coshell_checks import (add_scene_arguments, exit_with, floats,
                            read_rows, run_scene)


def uniaxial_nominal_pressure(squeeze, youngs_modulus, poisson_ratio):
    """Force per reference area that squeezes the law's solid by 'squeeze'
    with free sides (sigma_11 = sigma_22 = 0), by bisection on the
    in-plane stretch."""
    c10 = youngs_modulus / (4 * (1 + poisson_ratio))
    d1 = 6 * (1 - 2 * poisson_ratio) / youngs_modulus
    l3 = 1 - squeeze

    def cauchy(lp):
        J = lp * lp * l3
        I1 = 2 * lp * lp + l3 * l3
        deviatoric = 2 * c10 * J ** (-5 / 3)
        pressure = 2 * (J - 1) / d1
        return (deviatoric * (lp * lp - I1 / 3) + pressure,
                deviatoric * (l3 * l3 - I1 / 3) + pressure)

    low, high = 0.5, 2.0
    for _ in range(200):
        middle = 0.5 * (low + high)
        if cauchy(middle)[0] > 0:
            high = middle
        else:
            low = middle
    lp = 0.5 * (low + high)
    return -cauchy(lp)[1] * lp * lp


def calculix_curve(path, case):
    """(squeeze, force in N) of one case on the finest mesh of the stored
    CalculiX reference."""
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if r["case"] == case]
    finest = max(int(r["elements_through_half_thickness"]) for r in rows)
    rows = [r for r in rows
            if int(r["elements_through_half_thickness"]) == finest]
    rows.sort(key=lambda r: float(r["squeeze"]))
    print(f"CalculiX reference, {case}: {len(rows)} points, {finest} C3D20R "
          f"through the half thickness")
    return floats(rows, "squeeze"), floats(rows, "force_N")


def interpolate(xs, ys, x):
    """The quadratic through the three reference points nearest x: the
    force's curvature makes a linear interpolation between points 2.5 %
    of squeeze apart err by 0.5 %, a sixth of the tolerance."""
    i = min(max(bisect.bisect_left(xs, x) - 1, 0), len(xs) - 3)
    total = 0.0
    for j in range(i, i + 3):
        weight = 1.0
        for k in range(i, i + 3):
            if k != j:
                weight *= (x - xs[k]) / (xs[j] - xs[k])
        total += weight * ys[j]
    return total


def squeeze_curve(args):
    """[(squeeze, stretch spread, force in N)] of every step."""
    steps = read_rows(os.path.join(args.output, "load_displacement.csv"))
    if args.plate is not None:
        rows = read_rows(os.path.join(args.output, "contact_forces.csv"))
        force_at = {r["step"]: abs(float(r["fz"])) * args.symmetry
                    for r in rows if int(r["obstacle"]) == args.plate}
        gaps = [float(r["min_distance"]) for r in rows]
        print(f"smallest gap over every step and plate: {min(gaps):.3g} mm")
        if min(gaps) < 0:
            raise SystemExit("FAIL: a plate crossed the shell's face")
    curve = []
    for row in steps:
        lowest = float(row["min_thickness_stretch"])
        highest = float(row["max_thickness_stretch"])
        squeeze = 1 - 0.5 * (lowest + highest)
        if args.plate is None:
            force = args.pressure * float(row["load_factor"]) * args.area
        else:
            force = force_at[row["step"]]
        curve.append((squeeze, highest - lowest, force))
    return curve


def compare(args, curve):
    squeeze_ref, force_ref = calculix_curve(args.calculix, args.case)
    failures = []
    worst_analytic = worst_calculix = worst_spread = 0.0
    for squeeze, spread, force in curve:
        worst_spread = max(worst_spread, spread)
        if squeeze < args.from_squeeze:
            continue
        solid = interpolate(squeeze_ref, force_ref, squeeze)
        worst_calculix = max(worst_calculix, abs(force / solid - 1))
        line = f"squeeze {squeeze:.4f}: force {force:.5g} N, CalculiX {solid:.5g} N"
        if args.analytic_tolerance is not None:
            law = args.area * uniaxial_nominal_pressure(
                squeeze, args.youngs_modulus, args.poisson_ratio)
            worst_analytic = max(worst_analytic, abs(force / law - 1))
            line += f", the law's {law:.5g} N"
        print(line)
    print(f"largest stretch spread {worst_spread:.2e}; largest difference "
          f"from CalculiX {worst_calculix:.2e}" +
          (f", from the law's uniaxial stress {worst_analytic:.2e}"
           if args.analytic_tolerance is not None else ""))
    if squeeze_ref[-1] < curve[-1][0] - 1e-3:
        failures.append("the CalculiX reference stops before the last squeeze")
    if worst_spread > args.spread:
        failures.append(f"the stretches spread by {worst_spread:.2e} > "
                        f"{args.spread}")
    if worst_calculix > args.calculix_tolerance:
        failures.append(f"{worst_calculix:.2e} from CalculiX > "
                        f"{args.calculix_tolerance}")
    if (args.analytic_tolerance is not None and
            worst_analytic > args.analytic_tolerance):
        failures.append(f"{worst_analytic:.2e} from the law's uniaxial stress "
                        f"> {args.analytic_tolerance}")
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    add_scene_arguments(parser)
    squeeze = parser.add_mutually_exclusive_group(required=True)
    squeeze.add_argument("--pressure", type=float,
                         help="nominal face pressure at load factor 1, MPa")
    squeeze.add_argument("--plate", type=int,
                         help="the obstacle whose z force is the squeeze's")
    parser.add_argument("--area", type=float, default=100,
                        help="full plate's reference area, mm^2")
    parser.add_argument("--symmetry", type=float, default=4,
                        help="full plate over the model")
    parser.add_argument("--youngs-modulus", type=float, default=1)
    parser.add_argument("--poisson-ratio", type=float, default=0.42)
    parser.add_argument("--calculix", required=True)
    parser.add_argument("--case", default="frictionless")
    parser.add_argument("--spread", type=float, default=1e-9)
    parser.add_argument("--from-squeeze", type=float, default=0.01,
                        help="compare from this squeeze on (below it the "
                        "plates barely touch)")
    parser.add_argument("--analytic-tolerance", type=float)
    parser.add_argument("--calculix-tolerance", type=float, required=True)
    args = parser.parse_args()

    run_scene(args.coshell, args.prm, args.output, args.set)
    failures = compare(args, squeeze_curve(args))
    exit_with(failures, 3 if args.analytic_tolerance is not None else 2)


if __name__ == "__main__":
    main()
