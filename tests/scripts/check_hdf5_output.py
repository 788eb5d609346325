#!/usr/bin/env python3
"""Output/Format = hdf5: the HDF5 files and the XDMF index ParaView reads.

check_hdf5_output.py --coshell BIN --prm FILE --output DIR [--set A/B=v ...]
                     [--qoi NAME X Y Z]

Runs the scene with Output/Format = hdf5 and checks, with h5py and an XML
parser:
- solution.xdmf lists one grid per .h5 file written, at increasing times,
  and every DataItem it names exists in its file with the dimensions it
  states;
- each file holds nodes (n x 3, duplicate vertices merged: no two nodes
  closer than 1e-12), cells (triangles, indices below n, every node used),
  displacement and rotation (n x 3);
- with --qoi, the last file's displacement at the node nearest (X, Y, Z)
  gives the quantity of interest summary.json reports (the vertical
  deflection), within 2e-7 relative (DataOut's patch data are single
  precision, in VTU too): the field written is the solution.
"""
import argparse
import json
import os
import sys
import xml.etree.ElementTree as ElementTree

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coshell_checks import Checks, add_scene_arguments, run_scene  # noqa: E402

checks = Checks()
check = checks.that


def data_items(grid):
    for item in grid.iter("DataItem"):
        file, dataset = item.text.strip().split(":")
        yield file, dataset, tuple(int(d) for d in item.get("Dimensions").split())


def check_file(directory, grid):
    items = list(data_items(grid))
    files = {f for f, _, _ in items}
    check(len(files) == 1, f"grid at t = {grid.find('Time').get('Value')} "
          f"refers to one file: {sorted(files)}")
    path = os.path.join(directory, files.pop())
    with h5py.File(path, "r") as f:
        for _, dataset, dims in items:
            present = dataset.lstrip("/") in f
            check(present and f[dataset].shape == dims,
                  f"{os.path.basename(path)}{dataset} has dimensions {dims}")
        nodes, cells = f["nodes"][()], f["cells"][()]
        n = nodes.shape[0]
        check(nodes.shape == (n, 3) and cells.shape[1] == 3 and
              cells.max() < n and len(np.unique(cells)) == n,
              f"{n} nodes, {cells.shape[0]} triangles, every node used")
        rounded = np.unique(np.round(nodes, 12), axis=0)
        check(len(rounded) == n, "duplicate vertices merged")
        for field in ("displacement", "rotation"):
            check(field in f and f[field].shape == (n, 3),
                  f"field '{field}' has one 3-vector per node")
        return nodes, f["displacement"][()]


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    add_scene_arguments(parser)
    parser.add_argument("--qoi", nargs=4)
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output,
              ["Output/Format=hdf5"] + args.set)

    root = ElementTree.parse(os.path.join(args.output, "solution.xdmf"))
    grids = [g for g in root.iter("Grid") if g.get("GridType") == "Uniform"]
    written = sorted(f for f in os.listdir(args.output) if f.endswith(".h5"))
    times = [float(g.find("Time").get("Value")) for g in grids]
    check(len(grids) == len(written) and len(grids) > 0,
          f"solution.xdmf lists {len(grids)} grids for {len(written)} .h5 files")
    check(all(b > a for a, b in zip(times, times[1:])) or len(times) == 1,
          f"at increasing times {times[:3]}...{times[-1:]}")
    for grid in grids:
        nodes, displacement = check_file(args.output, grid)
    if args.qoi:
        name, point = args.qoi[0], np.array([float(x) for x in args.qoi[1:]])
        with open(os.path.join(args.output, "summary.json")) as f:
            expected = json.load(f)["qoi"][name]
        node = np.argmin(np.linalg.norm(nodes - point, axis=1))
        measured = displacement[node, 2]
        # DataOut keeps its patch data in single precision (as in VTU).
        check(abs(abs(measured) - abs(expected)) <= 2e-7 * abs(expected),
              f"{name}: {measured:.12g} in the HDF5 file, {expected:.12g} in "
              f"summary.json")
    checks.exit()


if __name__ == "__main__":
    main()
