#!/usr/bin/python3
"""Runs prm/contact/strip_on_cylinder.prm and checks the wrap against the
elastica and a curved-beam reference.

A strip (bending stiffness EI, length L, thickness h) clamped tangent to
a rigid cylinder of radius R (axis along y) with its mid-surface
R + h/2 + g0 from the axis, an end moment M = lambda * M_max:
  - below M* = EI / (R + h/2) it is an arc of curvature M / EI, clear of
    the cylinder (tip rotation M L / EI, no active pair);
  - at M* (within 1 %) it wraps the cylinder: its centre line lies on the
    circle of radius R + h/2 about the axis, within 1 %;
  - above M* it bears on the cylinder at its tip. Inextensible curved
    beam (Castigliano, an arc of radius r = R + h/2 + g0 over the angle
    phi = L / r, clamped at one end, moment dM = M - EI / r and radial
    force F at the other, tip held at the cylinder):
        F = dM (1 - cos phi) / (r (phi/2 - sin(2 phi)/4)),
    (tip_force() below); for phi = pi/2, F = 4 dM / (pi r).
  - min_distance >= 0 on every row (every Newton iterate).
"""
import argparse
import math
import os
import sys

from coshell_checks import (Checks, add_scene_arguments, add_strip_arguments,
                            read_rows, run_scene)

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "doc",
                                "scripts"))
import render_vtu  # noqa: E402


def tip_force(excess_moment, radius, angle):
    """Radial force at the tip of a clamped circular arc (radius, angle)
    that cancels the tip's radial displacement under an end moment
    excess_moment (inextensible, bending only). With t the angle from the
    clamp, the moment of a radial tip force F at t is F r sin(angle - t)
    and the tip's radial displacement is the derivative of the bending
    energy with respect to F."""
    moment_integral = radius * (1 - math.cos(angle))  # int r sin(a - t) dt
    force_integral = radius ** 2 * (angle / 2 - math.sin(2 * angle) / 4)
    return excess_moment * moment_integral / force_integral


def centre_line_radii(vtu_file, axis_z):
    """Distances from the cylinder's axis (along y through (0, *, axis_z))
    of the deformed nodes on the edge y = 0."""
    mesh = render_vtu.read_vtu(vtu_file)
    deformed = mesh.points + mesh.point_data["displacement"]
    on_edge = abs(mesh.points[:, 1]) < 1e-9
    return [math.hypot(p[0], p[2] - axis_z) for p in deformed[on_edge]]


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    add_strip_arguments(parser)
    parser.add_argument("--radius", type=float, required=True)
    parser.add_argument("--start-gap", type=float, required=True)
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output, args.set)

    steps = read_rows(os.path.join(args.output, "load_displacement.csv"))
    contact = {int(r["step"]): r for r in read_rows(
        os.path.join(args.output, "contact_forces.csv"))}
    wrap_radius = args.radius + args.thickness / 2
    wrap_moment = args.bending_stiffness / wrap_radius
    check = Checks()

    moments = {int(r["step"]): float(r["load_factor"]) * args.moment_max
               for r in steps}
    touching = [s for s in sorted(moments) if int(contact[s]["active_pairs"])]
    free = [s for s in moments if s not in touching]
    last_free, first_touch = max(free), min(touching)
    # The wrap lies between the last free step and the first bearing one:
    # both must be within 1 % of the reference.
    check(f"wrap moment: clear at M = {moments[last_free]:.6g}, bearing at "
          f"M = {moments[first_touch]:.6g}; reference EI/(R + h/2) = "
          f"{wrap_moment:.6g}, both within 1 %",
          max(abs(moments[s] / wrap_moment - 1) for s in
              (last_free, first_touch)) <= 0.01)

    rotation = float(steps[last_free - 1]["tip_rotation"])
    free_rotation = moments[last_free] * args.length / args.bending_stiffness
    check(f"before the wrap, tip rotation {rotation:.6g} = M L / EI = "
          f"{free_rotation:.6g} within 1e-3",
          abs(rotation - free_rotation) <= 1e-3 * free_rotation)

    gaps = [float(r["min_distance"]) for r in read_rows(
        os.path.join(args.output, "contact_forces.csv"))]
    check(f"min_distance >= 0 on every row (smallest {min(gaps):.4g})",
          min(gaps) >= 0)

    contact_radius = wrap_radius + args.start_gap
    last = max(moments)
    angle = args.length / contact_radius
    force = tip_force(moments[last] - args.bending_stiffness / contact_radius,
                      contact_radius, angle)
    measured = math.hypot(float(contact[last]["fx"]), float(contact[last]["fz"]))
    check(f"tip force at M = {moments[last]:.6g}: {measured:.6g} N, curved "
          f"beam {force:.6g} N, within 2 %",
          abs(measured - force) <= 0.02 * force)

    axis_z = -contact_radius
    frames = render_vtu.read_pvd(os.path.join(args.output, "solution.pvd"))
    touch_factor = float(steps[first_touch - 1]["load_factor"])
    at_wrap = min(frames, key=lambda f: abs(f.time - touch_factor))
    for frame in (at_wrap, frames[-1]):
        radii = centre_line_radii(frame.shell_file, axis_z)
        spread = (min(radii) / wrap_radius - 1, max(radii) / wrap_radius - 1)
        what = (f"load factor {frame.time:.4g}: centre line {spread[0]:+.3%} "
                f"to {spread[1]:+.3%} off the radius R + h/2 = {wrap_radius}")
        if frame is at_wrap:
            check(what + ", within 1 %", max(abs(s) for s in spread) <= 0.01)
        else:  # above M* the strip lifts between clamp and tip
            print("info " + what)
    check.exit()


if __name__ == "__main__":
    main()
