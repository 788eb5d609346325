#!/usr/bin/env python3
"""ISO 11979-3 compression test of the lens (prm/iol/compression_iso11979.prm):
force against compressed diameter, in mN, with the optic's decentration,
axial displacement and tilt. Writes compression.csv (and a PNG with
--plot) to the output directory and checks what must hold: the barrier's
gap stays non-negative at every step, the two clamps' forces balance
(the lens is in quasi-static equilibrium), the force grows with the
compression and is finite and positive at the end. A lens that buckles
out of its plane (the modified-L: its force peaks, then drops) is
checked with --buckle-between: the force grows until a first drop that
starts at a diameter in the given window, and need not grow after it.
A lens lying on a floor under its weight (more obstacles than the two
clamps, Loads/Gravity along -z) is checked with --gravity: at every step
the obstacles carry the lens's weight, mass (summary.json) times gravity,
within 1 % (vertical equilibrium)."""
import argparse
import csv
import json
import math
import os

from coshell_checks import (add_scene_arguments, exit_with,
                            kept_factors_failures, run_scene)


def read_clamp_forces(output):
    """{time: [fx of obstacle 1, fx of obstacle 2, smallest gap of any
    obstacle, the z forces of all obstacles summed, how far the clamps
    have closed (ux of obstacle 1 less ux of obstacle 2)]}"""
    rows = {}
    with open(os.path.join(output, "contact_forces.csv")) as f:
        for row in csv.DictReader(f):
            forces = rows.setdefault(float(row["time"]),
                                     [0.0, 0.0, math.inf, 0.0, 0.0])
            obstacle = int(row["obstacle"])
            if obstacle <= 2:  # the clamps; a floor is obstacle 3
                forces[obstacle - 1] = float(row["fx"])
                forces[4] += (1 if obstacle == 1 else -1) * float(row["ux"])
            forces[2] = min(forces[2], float(row["min_distance"]))
            forces[3] += float(row["fz"])
    return rows


def weight_failures(output, forces, gravity):
    """The obstacles carry the lens's weight at every step: the z forces
    the lens exerts on them sum to -mass * gravity (1 %)."""
    with open(os.path.join(output, "summary.json")) as f:
        mass = json.load(f)["mass"]  # t
    weight = 1e3 * mass * gravity  # mN (t mm/s^2 = N)
    worst = max(abs(1e3 * row[3] + weight) for row in forces.values())
    print(f"lens mass {1e9 * mass:.4g} mg, weight {weight:.4g} mN; largest "
          f"difference of the obstacles' vertical load: {worst:.3g} mN")
    if worst > 0.01 * weight:
        return [f"the obstacles carry the weight {weight:.4g} mN to "
                f"{worst:.3g} mN, more than 1 %"]
    return []


def read_optic(output):
    """{time: (decentration, axial displacement, tilt in degrees)}"""
    optic = {}
    with open(os.path.join(output, "time_history.csv")) as f:
        for row in csv.DictReader(f):
            q = {k: float(v) for k, v in row.items() if k != "stage"}
            slope_x = (q["rim_xp_uz"] - q["rim_xm_uz"]) / 6
            slope_y = (q["rim_yp_uz"] - q["rim_ym_uz"]) / 6
            # ISO 11979-3's axial displacement: the optic's, relative to
            # where the haptics touch the clamps.
            axial = q["optic_uz"] - 0.5 * (q["haptic_xp_uz"] +
                                           q["haptic_xm_uz"])
            optic[q["time"]] = (math.hypot(q["optic_ux"], q["optic_uy"]),
                                axial,
                                math.degrees(math.atan(math.hypot(slope_x,
                                                                  slope_y))))
    return optic


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--clamp-start", type=float, default=1.55,
                        help="clamp centre's distance from the lens centre "
                        "at t = 0, mm")
    parser.add_argument("--contact-radius", type=float, default=5.0,
                        help="radius of the clamps' offset faces, mm")
    parser.add_argument("--final-diameter", type=float, default=10.0)
    parser.add_argument("--plot", help="PNG to write (checker_figures.py)")
    parser.add_argument("--buckle-between", nargs=2, type=float,
                        metavar=("D_LARGE", "D_SMALL"),
                        help="the force's first drop starts at a diameter "
                        "in [D_SMALL, D_LARGE] mm (a buckle); later drops "
                        "are allowed")
    parser.add_argument("--gravity", type=float,
                        help="the scene's gravity along -z, mm/s^2: check "
                        "that the obstacles carry the lens's weight")
    parser.add_argument("--kept-factors-used", action="store_true",
                        help="some solve used kept factors (with Linear "
                        "solver/Reuse factorization)")
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output, args.set)
    forces, optic = read_clamp_forces(args.output), read_optic(args.output)
    rows = []
    for t in sorted(forces):
        right, left, gap, _, closed = forces[t]
        # From where the clamps are, as coshell moved them (the prm's
        # Translation), not from an assumed speed.
        diameter = 2 * (args.clamp_start + args.contact_radius) + closed
        rows.append((t, diameter, 1e3 * right, *optic[t][:2], optic[t][2],
                     -1e3 * left, gap))
    with open(os.path.join(args.output, "compression.csv"), "w") as f:
        f.write("time,diameter_mm,force_mn,optic_decentration_mm,"
                "optic_axial_mm,optic_tilt_deg,left_force_mn,min_gap_mm\n")
        for r in rows:
            f.write(",".join(f"{v:.8g}" for v in r) + "\n")
    if args.plot:
        import checker_figures
        checker_figures.compression_chart(rows, args.plot)
    failures = []
    final = rows[-1]
    print(f"at D = {final[1]:.3f} mm: force {final[2]:.5g} mN (left clamp "
          f"{final[6]:.5g}), decentration {final[3]:.3g} mm, axial "
          f"{final[4]:.4g} mm, tilt {final[5]:.3g} deg")
    if abs(final[1] - args.final_diameter) > 1e-6:
        failures.append(f"the run ended at D = {final[1]} mm")
    if not (0 < final[2] < math.inf):
        failures.append(f"final force {final[2]} mN is not finite and positive")
    smallest = min(r[7] for r in rows)
    print(f"smallest gap over the run: {smallest:.4g} mm")
    if smallest < 0:
        failures.append(f"gap {smallest} < 0: interpenetration")
    imbalance = max(abs(r[2] - r[6]) for r in rows)
    print(f"largest difference of the two clamp forces: {imbalance:.3g} mN")
    if imbalance > 0.01 * final[2]:
        failures.append(f"clamp forces differ by {imbalance} mN, more than "
                        f"1 % of {final[2]} mN")
    failures += check_growth(rows, final, args.buckle_between)
    if args.gravity is not None:
        failures += weight_failures(args.output, forces, args.gravity)
    if args.kept_factors_used:
        failures += kept_factors_failures(args.output)
    exit_with(failures)


def check_growth(rows, final, buckle_between):
    """The force grows with the compression; with a buckle window, until a
    first drop that starts inside it."""
    loaded = [r for r in rows if r[2] > 0.05 * final[2]]
    drops = [(a[1], b[1]) for a, b in zip(loaded, loaded[1:]) if b[2] < a[2]]
    if not buckle_between:
        if drops:
            return [f"force drops while compressing, first between "
                    f"D = {drops[0][0]:.3f} and {drops[0][1]:.3f} mm"]
        return []
    large, small = buckle_between
    if not drops:
        return [f"no buckle: the force never drops (expected between D = "
                f"{large} and {small} mm)"]
    start = drops[0][0]
    peak = max(r[2] for r in rows if r[1] >= start)
    print(f"buckle: the force peaks at {peak:.4g} mN and first drops from "
          f"D = {start:.3f} mm (window {large} to {small} mm)")
    if not small <= start <= large:
        return [f"the force first drops at D = {start:.3f} mm, outside "
                f"[{small}, {large}] mm"]
    return []


if __name__ == "__main__":
    main()
