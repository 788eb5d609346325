#!/usr/bin/env python3
"""Single C-loop haptic compression (prm/iol/haptic_compression.prm):
the stiffness of the haptic tip along the load, per refinement level,
against Castigliano's theorem for the curved beam of the haptic's centre
line. The beam's geometry follows meshes/iol/lens.geo (its defaults are
the defaults here)."""
import argparse
import json
import math
import os

from scene_runner import add_scene_arguments, exit_with, run_scene


def castigliano_compliance(a):
    """Tip displacement along the unit load direction d (towards the lens
    centre) per unit force, for the arc of radius R about (rho, 0) from the
    optic rim to tip_sweep past its farthest point, clamped at the rim:
    delta = int (m^2 / EI + n^2 / EA + k v^2 / GA) ds with m, n, v the
    moment, axial and shear force of the unit tip load."""
    rho = a.overall_diameter / 2 - a.haptic_width / 2 - a.haptic_radius
    R = a.haptic_radius
    root = -math.acos((a.optic_radius ** 2 - rho ** 2 - R ** 2) / (2 * R * rho))
    tip = math.radians(a.tip_sweep)
    T = (rho + R * math.cos(tip), R * math.sin(tip))
    d = (-T[0] / math.hypot(*T), -T[1] / math.hypot(*T))
    E, t, w = a.youngs_modulus, a.thickness, a.haptic_width
    inertia, area = t * w ** 3 / 12, t * w
    shear_modulus = E / (2 * (1 + a.poisson_ratio))
    n = 20000
    bending = axial = shear = 0.0
    for i in range(n):
        angle = root + (tip - root) * (i + 0.5) / n
        ds = R * (tip - root) / n
        X = (rho + R * math.cos(angle), R * math.sin(angle))
        tangent = (-math.sin(angle), math.cos(angle))
        normal = (math.cos(angle), math.sin(angle))
        m = (T[0] - X[0]) * d[1] - (T[1] - X[1]) * d[0]
        bending += m * m / (E * inertia) * ds
        axial += (d[0] * tangent[0] + d[1] * tangent[1]) ** 2 / (E * area) * ds
        shear += 1.2 * (d[0] * normal[0] + d[1] * normal[1]) ** 2 / (
            shear_modulus * area) * ds
    return bending, axial, shear, d


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    for name, default in [("optic-radius", 3.0), ("overall-diameter", 13.0),
                          ("haptic-width", 0.4), ("haptic-radius", 3.8),
                          ("tip-sweep", 15.0), ("thickness", 0.45),
                          ("youngs-modulus", 1.0), ("poisson-ratio", 0.42),
                          ("force", 1e-5)]:
        parser.add_argument("--" + name, type=float, default=default)
    parser.add_argument("--rtol", type=float,
                        help="finest level's stiffness within this of the "
                        "reference")
    parser.add_argument("--stiffer-than", type=float,
                        help="coarsest level's stiffness above this multiple "
                        "of the reference (a locking element)")
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output, args.set)
    with open(os.path.join(args.output, "summary.json")) as f:
        summary = json.load(f)
    bending, axial, shear, d = castigliano_compliance(args)
    reference = 1 / (bending + axial + shear)
    print(f"Castigliano: bending {bending:.6g}, axial {axial:.6g}, shear "
          f"{shear:.6g} mm/N; stiffness {reference:.6g} N/mm "
          f"(bending alone {1 / bending:.6g})")
    rows = []
    for level in summary["levels"]:
        q = level["qoi"]
        along = q["tip_ux"] * d[0] + q["tip_uy"] * d[1]
        stiffness = args.force / along
        rows.append((level["refinement_level"], level["n_cells"], stiffness,
                     stiffness / reference - 1))
    with open(os.path.join(args.output, "haptic_stiffness.csv"), "w") as f:
        f.write("level,n_cells,stiffness_n_per_mm,reference_n_per_mm,"
                "relative_error\n")
        for level, cells, k, error in rows:
            f.write(f"{level},{cells},{k:.8g},{reference:.8g},{error:.6g}\n")
            print(f"level {level}: {cells} triangles, stiffness {k:.6g} N/mm,"
                  f" {100 * error:+.2f} % against Castigliano")
    failures = []
    if args.rtol is not None and abs(rows[-1][3]) > args.rtol:
        failures.append(f"finest level off by {100 * rows[-1][3]:.2f} % "
                        f"(allowed {100 * args.rtol:.2f} %)")
    if args.stiffer_than is not None and rows[0][3] + 1 < args.stiffer_than:
        failures.append(f"coarsest level {rows[0][3] + 1:.3f} x the "
                        f"reference, expected above {args.stiffer_than}")
    exit_with(failures)


if __name__ == "__main__":
    main()
