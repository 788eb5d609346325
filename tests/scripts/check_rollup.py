#!/usr/bin/python3
"""Runs prm/contact/self_contact_rollup.prm and checks the strip that an
end moment winds onto itself.

  - End of stage 1 (statics, tip resting on the clamped tail): an
    elastica reference. The rolling part (length L, clamped at its root,
    tangent along +x) carries the end moment M and, at its tip, the
    tail's vertical force F; frictionless, so F is normal to the flat
    tail. Bending moment m(s) = M + F (x_tip - x(s)), EI theta' = m. F and
    x_tip are found by shooting so that the tip lies at x_tip and at the
    height of the contact distance (h, plus the barrier's measured gap).
    The contact force on the rolling part and its tip position must match
    within the given tolerances.
  - Every row of contact_forces.csv (every Newton iterate): gap >= 0.
  - End of the run (dynamics, at rest): the centre line turns through
    more than a full turn; the layers touch (active pairs, a non-zero
    contact force on both layers); the contact forces on the shell sum to
    zero (action and reaction of self contact).
"""
import argparse
import math
import os
import sys

import numpy as np

from coshell_checks import (Checks, add_scene_arguments, add_strip_arguments,
                            read_rows, run_scene)

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "doc",
                                "scripts"))
import render_vtu  # noqa: E402


def integrate_elastica(moment, force, tip_x, length, stiffness, n=4000):
    """Tip position (x, z) of the strip from its root at the origin,
    theta(0) = 0, under the end moment and the vertical tip force (RK4)."""
    def rate(state):
        theta, x, _ = state
        return np.array([(moment + force * (tip_x - x)) / stiffness,
                         math.cos(theta), math.sin(theta)])
    state, ds = np.zeros(3), length / n
    for _ in range(n):
        k1 = rate(state)
        k2 = rate(state + 0.5 * ds * k1)
        k3 = rate(state + 0.5 * ds * k2)
        k4 = rate(state + ds * k3)
        state = state + ds / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return state[1], state[2]


def solve_elastica(moment, tip_height, length, stiffness):
    """(F, x_tip) with the tip at (x_tip, tip_height): Newton on the two
    residuals with a finite-difference Jacobian, from the free circle."""
    unknowns = np.array([0.0, -0.2])
    for _ in range(50):
        def residual(u):
            x, z = integrate_elastica(moment, u[0], u[1], length, stiffness)
            return np.array([x - u[1], z - tip_height])
        r = residual(unknowns)
        if np.linalg.norm(r) < 1e-12 * length:
            return unknowns
        jacobian = np.empty((2, 2))
        for j in range(2):
            step = np.zeros(2)
            step[j] = 1e-7
            jacobian[:, j] = (residual(unknowns + step) - r) / 1e-7
        unknowns = unknowns - np.linalg.solve(jacobian, r)
    sys.exit("FAIL: the elastica reference did not converge")


def unique_vertices(mesh):
    """Per-vertex reference points, deformed points and contact forces
    (deal.II writes each cell's vertices separately)."""
    seen = {}
    for i, p in enumerate(mesh.points):
        seen.setdefault(tuple(np.round(p, 9)), i)
    index = np.array(list(seen.values()))
    return (mesh.points[index],
            mesh.points[index] + mesh.point_data["displacement"][index],
            mesh.point_data["contact_force"][index])


def turning(reference, deformed, root_x):
    """Total turning (radians) of the centre line y = 0 of the rolling part
    in the x-z plane."""
    line = sorted((r[0], d[0], d[2]) for r, d in zip(reference, deformed)
                  if abs(r[1]) < 1e-9 and r[0] >= root_x - 1e-9)
    angles = [math.atan2(b[2] - a[2], b[1] - a[1]) for a, b in zip(line, line[1:])]
    return float(np.sum(np.diff(np.unwrap(angles))))


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    add_strip_arguments(parser)
    parser.add_argument("--root-x", type=float, required=True)
    parser.add_argument("--force-tolerance", type=float, required=True,
                        help="relative, on the tip force")
    parser.add_argument("--position-tolerance", type=float, required=True,
                        help="on the tip position, relative to the length")
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output, args.set)
    check = Checks()

    static = [r for r in read_rows(os.path.join(args.output,
                                                "load_displacement.csv"))
              if r["stage"] == "1"][-1]
    moment = float(static["load_factor"]) * args.moment_max
    tip_x = args.length + float(static["tip_ux"])  # from the root
    tip_z = float(static["tip_uz"])
    check(f"stage 1: the tip rests on the tail, {tip_z - args.thickness:.4g} "
          f"above the contact distance h", 0 <= tip_z - args.thickness < 0.2 * args.thickness)
    force, reference_x = solve_elastica(moment, tip_z, args.length,
                                        args.bending_stiffness)
    frames = render_vtu.read_pvd(os.path.join(args.output, "solution.pvd"))
    at_rest = min(frames, key=lambda f: abs(f.time - float(static["time"])))
    reference, deformed, contact = unique_vertices(
        render_vtu.read_vtu(at_rest.shell_file))
    rolling = reference[:, 0] > args.root_x + 1e-9
    measured = contact[rolling].sum(axis=0)
    check(f"stage 1, M = {moment:.6g}: tail's force on the tip "
          f"{measured[2]:.6g} N, elastica {force:.6g} N, within "
          f"{args.force_tolerance:.1%}",
          abs(measured[2] - force) <= args.force_tolerance * force)
    check(f"stage 1: tip at x = {tip_x:.6g} from the root, elastica "
          f"{reference_x:.6g}, within {args.position_tolerance:.1%} of the "
          f"length", abs(tip_x - reference_x) <=
          args.position_tolerance * args.length)

    rows = read_rows(os.path.join(args.output, "contact_forces.csv"))
    gaps = [float(r["min_distance"]) for r in rows]
    check(f"min_distance >= 0 on every row (smallest {min(gaps):.4g})",
          min(gaps) >= 0)

    history = read_rows(os.path.join(args.output, "time_history.csv"))
    kinetic = float(history[-1]["kinetic_energy"])
    strain = float(history[-1]["strain_energy"])
    check(f"end: at rest (kinetic energy {kinetic:.3g} <= 1e-9 x strain "
          f"energy {strain:.4g})", kinetic <= 1e-9 * strain)
    reference, deformed, contact = unique_vertices(
        render_vtu.read_vtu(frames[-1].shell_file))
    turns = turning(reference, deformed, args.root_x) / (2 * math.pi)
    check(f"end: the rolling part turns through {turns:.4g} turns (> 1)",
          turns > 1)
    loaded = reference[np.linalg.norm(contact, axis=1) > 0, 0]
    middle = args.root_x + args.length / 2
    check(f"end: {int(rows[-1]['active_pairs'])} active pairs; contact "
          f"forces on {len(loaded)} vertices, of the inner layer (x > "
          f"{middle}) and of the first turn ({args.root_x} <= x < {middle})",
          int(rows[-1]["active_pairs"]) > 0 and (loaded > middle).any() and
          ((loaded >= args.root_x) & (loaded < middle)).any())
    # The VTU holds single-precision values (relative rounding 6e-8).
    total = np.linalg.norm(contact.sum(axis=0))
    largest = np.linalg.norm(contact, axis=1).max()
    check(f"end: self-contact forces sum to zero ({total:.3g} N against "
          f"{largest:.3g} N on the most loaded vertex; VTU precision)",
          total <= 1e-6 * largest)
    check.exit()


if __name__ == "__main__":
    main()
