#!/usr/bin/python3
"""Runs one level of a scene and checks that the VTU/PVD output is complete:
the PVD indexes an existing VTU whose cell count matches summary.json, and
which carries displacement and rotation vectors and the membrane force and
bending moment tensor components. deal.II writes every field as point data
of disjoint per-cell patches, so cell fields are constant on each cell.""" 
import argparse
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

POINT_FIELDS = {"displacement": 3, "rotation": 3}
CELL_FIELDS = [f"{s}_{c}" for s in "NM" for c in ("xx", "yy", "zz", "xy", "yz", "xz")]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    args = parser.parse_args()
    subprocess.run([args.coshell, args.prm, "--output", args.output,
                    "--set", "Mesh/Refinement levels=1"], check=True)
    with open(os.path.join(args.output, "summary.json")) as f:
        summary = json.load(f)

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
    print("point fields:", point_arrays)
    print("cell fields:", sorted(cell_arrays))
    for p in problems:
        print("FAIL:", p)
    print(f"{len(POINT_FIELDS) + len(CELL_FIELDS) + 2 - len(problems)} passed, "
          f"{len(problems)} failed")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
