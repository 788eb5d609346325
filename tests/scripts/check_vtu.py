#!/usr/bin/python3
"""Runs one level of a scene and checks that the VTU/PVD output is complete:
the PVD indexes an existing VTU whose cell count matches summary.json, and
which carries displacement and rotation vectors, the membrane force and
bending moment tensor components and the cells' strains. deal.II writes
every field as point data of disjoint per-cell patches, so cell fields are
constant on each cell.

With --uniform-strains it also checks every cell's membrane, bending and
surface strain against values the caller derives by hand (a state of
uniform strain, where the elements are exact).""" 
import argparse
import os
import sys
import xml.etree.ElementTree as ET

from coshell_checks import (add_scene_arguments, exit_with, read_summary,
                            run_scene)

POINT_FIELDS = {"displacement": 3, "rotation": 3}
STRAINS = ["membrane_strain", "bending_strain", "surface_strain"]
CELL_FIELDS = [f"{s}_{c}" for s in "NM" for c in ("xx", "yy", "zz", "xy", "yz", "xz")] \
    + ["material_id", "thickness"] + STRAINS


def uniform_strain_problems(path, expected, tolerance):
    """Each strain field against its expected value in every cell, to a
    relative tolerance."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(
        __file__)), "..", "..", "doc", "scripts"))
    import render_vtu
    mesh = render_vtu.read_vtu(path)
    problems = []
    for name, value in zip(STRAINS, expected):
        cells = render_vtu.cell_field(mesh, name)
        worst = max(abs(c - value) for c in cells) / abs(value)
        print(f"{name}: {min(cells):.10g} to {max(cells):.10g}, expected "
              f"{value:.10g} (largest relative deviation {worst:.2e})")
        if worst > tolerance:
            problems.append(f"{name} off {value:g} by {worst:.2e} of it "
                            f"(allowed {tolerance:g})")
    return problems


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--level", type=int, default=1)
    parser.add_argument("--uniform-strains", type=float, nargs=4,
                        metavar=("MEMBRANE", "BENDING", "SURFACE", "RTOL"))
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output,
              [f"Mesh/Refinement levels={args.level}"] + args.set)
    summary = read_summary(args.output)

    problems = []
    pvd = ET.parse(os.path.join(args.output, "solution.pvd"))
    files = [d.get("file") for d in pvd.iter("DataSet")]
    if files != ["solution.vtu"]:
        problems.append(f"PVD lists {files}")
    vtu = ET.parse(os.path.join(args.output, "solution.vtu"))
    piece = next(vtu.iter("Piece"))
    if int(piece.get("NumberOfCells")) != summary["n_cells"]:
        problems.append(f"{piece.get('NumberOfCells')} cells in VTU, "
                        f"{summary['n_cells']} in summary.json")
    point_arrays = {a.get("Name"): int(a.get("NumberOfComponents", 1))
                    for a in piece.find("PointData").iter("DataArray")}
    cell_arrays = set(point_arrays)
    for name, components in POINT_FIELDS.items():
        if point_arrays.get(name) != components:
            problems.append(f"point field {name} missing or not a {components}-vector")
    for name in CELL_FIELDS:
        if name not in cell_arrays:
            problems.append(f"cell field {name} missing")
    if args.uniform_strains and not problems:
        problems += uniform_strain_problems(
            os.path.join(args.output, "solution.vtu"),
            args.uniform_strains[:3], args.uniform_strains[3])
    print("point fields:", point_arrays)
    print("cell fields:", sorted(cell_arrays))
    exit_with(problems, len(POINT_FIELDS) + len(CELL_FIELDS) + 2 +
              (len(STRAINS) if args.uniform_strains else 0))


if __name__ == "__main__":
    main()
