#!/usr/bin/env python3
"""Single haptic compression (prm/iol/haptic_compression.prm): the
stiffness of the haptic tip along the load, per refinement level, against
Castigliano's theorem for the beam of the haptic's centre line. The beam's
geometry follows meshes/iol/lens.geo (its defaults are the defaults here):
the C-loop's arc, or with --haptic-type 1 the modified-L's leg, knee and
arm. For the modified-L the checker sets the mesh, the tip load and the
tip's point values itself, from the same geometry."""
import argparse
import json
import math
import os

from coshell_checks import add_scene_arguments, exit_with, run_scene


def arc(centre, radius, start, end, n):
    """Midpoint samples (point, unit tangent, ds) of a counter-clockwise
    arc from angle start to end (radians)."""
    ds = radius * (end - start) / n
    for i in range(n):
        angle = start + (end - start) * (i + 0.5) / n
        yield ((centre[0] + radius * math.cos(angle),
                centre[1] + radius * math.sin(angle)),
               (-math.sin(angle), math.cos(angle)), ds)


def arc_centre_x(a, radius):
    """x of the centre of an arc of this centre-line radius whose
    farthest point, on the x axis, puts the haptic's outer edge at
    overall_diameter / 2 (lens.geo's C-loop and modified-L arm)."""
    return a.overall_diameter / 2 - a.haptic_width / 2 - radius


def c_loop(a, n):
    """The C-loop's centre line: the arc of radius R about (rho, 0) from
    the optic rim to tip_sweep past its farthest point."""
    rho = arc_centre_x(a, a.haptic_radius)
    R = a.haptic_radius
    root = -math.acos((a.optic_radius ** 2 - rho ** 2 - R ** 2) / (2 * R * rho))
    return list(arc((rho, 0), R, root, math.radians(a.tip_sweep), n))


def modified_l(a, n):
    """The modified-L's centre line as lens.geo builds it: the straight
    leg from the optic rim, the knee (radius knee_radius, knee_angle) and
    the arm (radius arm_radius about (arm_centre, 0), from arm_start to
    tip_sweep), each tangent to the next."""
    arm_centre = arc_centre_x(a, a.arm_radius)
    beta = math.radians(a.arm_start)
    knee = (arm_centre + (a.arm_radius - a.knee_radius) * math.cos(beta),
            (a.arm_radius - a.knee_radius) * math.sin(beta))
    gamma = beta - math.radians(a.knee_angle)
    start = (knee[0] + a.knee_radius * math.cos(gamma),
             knee[1] + a.knee_radius * math.sin(gamma))
    d = (-math.sin(gamma), math.cos(gamma))
    b = start[0] * d[0] + start[1] * d[1]
    leg = b - math.sqrt(b * b - (start[0] ** 2 + start[1] ** 2
                                 - a.optic_radius ** 2))
    samples = [((start[0] - leg * (1 - (i + 0.5) / n) * d[0],
                 start[1] - leg * (1 - (i + 0.5) / n) * d[1]), d, leg / n)
               for i in range(n)]
    samples += arc(knee, a.knee_radius, gamma, beta, n)
    return samples + list(arc((arm_centre, 0), a.arm_radius, beta,
                              math.radians(a.tip_sweep), n))


def tip_point(a):
    """The centre of the haptic's square tip (the end of its centre line)."""
    radius = a.haptic_radius if a.haptic_type == 0 else a.arm_radius
    centre, tip = arc_centre_x(a, radius), math.radians(a.tip_sweep)
    return (centre + radius * math.cos(tip), radius * math.sin(tip))


def castigliano_compliance(a):
    """Tip displacement along the unit load direction d (towards the lens
    centre) per unit force, for the haptic's centre line clamped at the
    optic rim: delta = int (m^2 / EI + n^2 / EA + k v^2 / GA) ds with m,
    n, v the moment, axial and shear force of the unit tip load."""
    T = tip_point(a)
    d = (-T[0] / math.hypot(*T), -T[1] / math.hypot(*T))
    E, t, w = a.youngs_modulus, a.thickness, a.haptic_width
    inertia, area = t * w ** 3 / 12, t * w
    shear_modulus = E / (2 * (1 + a.poisson_ratio))
    centre_line = c_loop(a, 20000) if a.haptic_type == 0 else modified_l(
        a, 20000)
    bending = axial = shear = 0.0
    for X, tangent, ds in centre_line:
        normal = (tangent[1], -tangent[0])
        m = (T[0] - X[0]) * d[1] - (T[1] - X[1]) * d[0]
        bending += m * m / (E * inertia) * ds
        axial += (d[0] * tangent[0] + d[1] * tangent[1]) ** 2 / (E * area) * ds
        shear += 1.2 * (d[0] * normal[0] + d[1] * normal[1]) ** 2 / (
            shear_modulus * area) * ds
    return bending, axial, shear, d


def modified_l_assignments(a):
    """For the modified-L: its mesh, the load a.force on its tip edge
    towards the lens centre, and the tip's point values."""
    if a.haptic_type == 0:
        return []
    T = tip_point(a)
    d = (-T[0] / math.hypot(*T), -T[1] / math.hypot(*T))
    point = f"{T[0]:.9g} {T[1]:.9g} 0"
    return ["Mesh/Gmsh parameters=haptics_only = 1, haptic_type = 1, "
            f"knee_radius = {a.knee_radius}, knee_angle = {a.knee_angle}, "
            f"arm_radius = {a.arm_radius}, arm_start = {a.arm_start}, "
            f"tip_sweep = {a.tip_sweep}",
            f"Loads/Edge forces=2: {a.force * d[0]:.9g} "
            f"{a.force * d[1]:.9g} 0",
            f"Quantities of interest/Point values=tip_ux: {point} ux; "
            f"tip_uy: {point} uy"]


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    for name, default in [("optic-radius", 3.0), ("overall-diameter", 13.0),
                          ("haptic-width", 0.4), ("haptic-radius", 3.8),
                          ("tip-sweep", 15.0), ("thickness", 0.45),
                          ("knee-radius", 0.6), ("knee-angle", 90.0),
                          ("arm-radius", 4.5), ("arm-start", -70.0),
                          ("youngs-modulus", 1.0), ("poisson-ratio", 0.42),
                          ("force", 1e-5)]:
        parser.add_argument("--" + name, type=float, default=default)
    parser.add_argument("--rtol", type=float,
                        help="finest level's stiffness within this of the "
                        "reference")
    parser.add_argument("--stiffer-than", type=float,
                        help="coarsest level's stiffness above this multiple "
                        "of the reference (a locking element)")
    parser.add_argument("--haptic-type", type=int, choices=(0, 1),
                        default=0, help="0: C-loop (the prm as it is), "
                        "1: modified-L (mesh, load and tip set here)")
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output,
              args.set + modified_l_assignments(args))
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
