#!/usr/bin/python3
"""The strain fields of the VTU on a strip rolled by an end moment (Sze's
benchmark 3.1, prm/benchmarks/cantilever_end_moment.prm), against the
elastica. Under a pure end moment M the bending moment is M everywhere and
the axial force zero, whatever the rotation, so the exact strip has a
uniform curvature k = M / EI and no mid-surface strain: its bending strain
is h k / 2 in every cell, its membrane strain 0 and its surface strain
h k / 2. At the last load step M L / EI = 2 pi (a full circle).

On each mesh (--subdivisions along the strip) the run's last VTU gives,
per cell, membrane_strain, bending_strain and surface_strain. Checked:
  - on the finest mesh every cell's bending strain lies within --rtol of
    h k / 2;
  - the largest membrane strain (the chord's stretch against the arc) and
    the largest deviations of the bending and surface strains from h k / 2
    fall with the mesh at an observed order of at least --min-order
    between each pair of meshes.
"""
import argparse
import math
import os
import sys

import numpy as np

from coshell_checks import exit_with, run_scene

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "doc", "scripts"))
import render_vtu  # noqa: E402


def last_strains(coshell, prm, output, subdivisions):
    """Per cell of the last VTU: membrane, bending and surface strain."""
    run_scene(coshell, prm, output, [f"Mesh/Subdivisions x={subdivisions}"],
              quiet=True)
    frames = render_vtu.read_pvd(os.path.join(output, "solution.pvd"))
    mesh = render_vtu.read_vtu(frames[-1].shell_file)
    return {name: render_vtu.cell_field(mesh, name + "_strain")
            for name in ("membrane", "bending", "surface")}


def errors(strains, exact):
    """Largest membrane strain and largest deviations of the bending and
    surface strains, relative to the exact surface strain."""
    return {"membrane": np.max(np.abs(strains["membrane"])) / exact,
            "bending": np.max(np.abs(strains["bending"] - exact)) / exact,
            "surface": np.max(np.abs(strains["surface"] - exact)) / exact}


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--subdivisions", type=int, nargs="+",
                        default=[48, 96, 192])
    parser.add_argument("--length", type=float, default=12.0)
    parser.add_argument("--thickness", type=float, default=0.1)
    parser.add_argument("--turn", type=float, default=2 * math.pi,
                        help="M L / EI at the last step (rad)")
    parser.add_argument("--rtol", type=float, default=1e-4)
    parser.add_argument("--min-order", type=float, default=1.8)
    args = parser.parse_args()
    exact = 0.5 * args.thickness * args.turn / args.length
    print(f"elastica: curvature {args.turn / args.length:.6g}, bending "
          f"strain h k / 2 = {exact:.6g}, membrane strain 0")
    rows = []
    for n in args.subdivisions:
        strains = last_strains(args.coshell, args.prm,
                               os.path.join(args.output, f"n{n}"), n)
        rows.append((n, strains, errors(strains, exact)))
        print(f"{n} subdivisions: " + ", ".join(
            f"{k} {v:.3e}" for k, v in rows[-1][2].items()) +
            " (relative to h k / 2)")
    problems = []
    finest = rows[-1][2]["bending"]
    if finest > args.rtol:
        problems.append(f"bending strain off the elastica by {finest:.2e} "
                        f"on the finest mesh (allowed {args.rtol:g})")
    for (n0, _, e0), (n1, _, e1) in zip(rows, rows[1:]):
        for name in e0:
            order = math.log(e0[name] / e1[name]) / math.log(n1 / n0)
            print(f"{name}: order {order:.2f} from {n0} to {n1}")
            if not order >= args.min_order:
                problems.append(f"{name} converges at order {order:.2f} "
                                f"from {n0} to {n1} subdivisions "
                                f"(at least {args.min_order} required)")
    exit_with(problems, 1 + 3 * (len(rows) - 1))


if __name__ == "__main__":
    main()
