#!/usr/bin/python3
"""Mesh convergence of the ISO 11979-3 compression of the whole lens
(prm/iol/compression_iso11979.prm, checked by
tests/scripts/check_compression.py): the lens's gmsh sizes halved from
the default (optic 0.55, haptic 0.22 mm: about two triangles across a
haptic) twice, one thread, one run after another. Per mesh: triangles,
the clamp force at the diameters of the table in
doc/validation/iol-haptic-and-compression.md ("The whole lens: ISO
11979-3 compression"), the initial stiffness per clamp (a straight-line
fit of the force against one clamp's travel while D goes from 12.9 to 12.6 mm) and the optic's
decentration, axial displacement and tilt at 10 mm. A last row
extrapolates the force at 10 mm and the initial stiffness from the three
meshes (Richardson, with the order they show). Writes
doc/performance/iol_compression_refinement.csv and .png, stamped with
machine and commit.

  /usr/bin/python3 doc/scripts/iol_compression_refinement.py \\
      --coshell build/coshell [--meshes 3] [--lens "junction_fillet = 0.25"
      --tag _fillet] [--replot]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import ROOT, finish_plot, machine_and_commit, write_csv  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
from richardson import richardson  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
SCENE = os.path.join(ROOT, "prm", "iol", "compression_iso11979.prm")
CHECKER = os.path.join(ROOT, "tests", "scripts", "check_compression.py")
# (optic, haptic) gmsh sizes in mm: the default lens, halved, quartered.
MESHES = [(0.55, 0.22), (0.275, 0.11), (0.1375, 0.055)]
DIAMETERS = (12.6, 12.1, 11.6, 11.1, 10.6, 10.0)  # mm, that table's
# Castigliano's initial stiffness of the square-cut C-loop loaded at its
# farthest point (doc/validation/iol-haptic-and-compression.md, "One
# C-loop haptic against Castigliano").
CASTIGLIANO_MN_PER_MM = 0.0321
# The extrapolated row's order of convergence, per column extrapolated.
ORDER_COLUMNS = {"initial_stiffness_mn_per_mm": "initial_stiffness_order",
                 "force_at_10_mm_mn": "force_at_10_mm_order"}


def compress(coshell, sizes, lens_constants, output):
    """Runs the checked compression on the lens of these gmsh sizes and
    more lens.geo constants ("name = value, ..."); returns its
    compression.csv rows and its number of triangles."""
    optic, haptic = sizes
    constants = f"optic_mesh_size = {optic}, haptic_mesh_size = {haptic}"
    if lens_constants:
        constants += ", " + lens_constants
    command = [sys.executable, CHECKER, "--coshell", coshell, "--prm", SCENE,
               "--output", output, "--set", "Output/Write VTU=false",
               "--set", "Parallel/Threads=1", "--set",
               f"Mesh/Gmsh parameters={constants}"]
    process = subprocess.run(command, capture_output=True, text=True,
                             env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    if process.returncode != 0:
        sys.exit(f"lens {sizes}: {process.stdout[-1500:]}{process.stderr}")
    with open(os.path.join(output, "compression.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    with open(os.path.join(output, "summary.json")) as f:
        return rows, json.load(f)["n_cells"]


def mesh_row(sizes, rows, triangles):
    diameter = np.array([r["diameter_mm"] for r in rows])
    force = np.array([r["force_mn"] for r in rows])
    early = (diameter <= 12.9 + 1e-9) & (diameter >= 12.6 - 1e-9)
    # One clamp travels half the change of the diameter.
    stiffness = -np.polyfit(diameter[early] / 2, force[early], 1)[0]
    row = {"optic_mesh_size_mm": sizes[0], "haptic_mesh_size_mm": sizes[1],
           "triangles": triangles,
           "initial_stiffness_mn_per_mm": round(stiffness, 6)}
    for d in DIAMETERS:
        row[f"force_at_{d:g}_mm_mn"] = round(
            float(force[np.argmin(abs(diameter - d))]), 6)
    final = rows[int(np.argmin(abs(diameter - 10.0)))]
    row.update({"decentration_at_10_mm_mm": final["optic_decentration_mm"],
                "axial_at_10_mm_mm": final["optic_axial_mm"],
                "tilt_at_10_mm_deg": final["optic_tilt_deg"]})
    return row


def extrapolated(values):
    """Richardson's limit of three values on meshes halved in turn and
    the order they converge at. No limit below the order 0.5: so slow a
    convergence is not yet the asymptotic one, and its extrapolation would
    mean nothing."""
    order, limit = richardson(*values)
    return (limit if order >= 0.5 else math.nan), order


def plot(rows, commit, name):
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    meshes = [r for r in rows if r["triangles"] != "extrapolated"]
    limit = next((r["initial_stiffness_mn_per_mm"] for r in rows
                  if r["triangles"] == "extrapolated"), math.nan)
    for r in meshes:
        left.plot(DIAMETERS, [r[f"force_at_{d:g}_mm_mn"] for d in DIAMETERS],
                  "o-", label=f"{r['triangles']} triangles")
    left.invert_xaxis()
    left.set_xlabel("compressed diameter D (mm)")
    left.set_ylabel("clamp force (mN)")
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8)
    triangles = [r["triangles"] for r in meshes]
    right.plot(triangles, [r["initial_stiffness_mn_per_mm"] for r in meshes],
               "o-", label="initial stiffness per clamp")
    if not math.isnan(limit):
        right.axhline(limit, ls="--", color="tab:blue", lw=1,
                      label=f"extrapolated, {limit:.4f}")
    right.axhline(CASTIGLIANO_MN_PER_MM, ls=":", color="k", lw=1,
                  label="Castigliano, square-cut haptic at its far point")
    right.set_xscale("log")
    figure.suptitle(f"IOL compression, mesh convergence ({commit})",
                    fontsize=10)
    finish_plot(figure, right, "lens triangles", "mN per mm of one clamp",
                "", os.path.join(OUT, name + ".png"))


def read_rows(path):
    """The rows and the commit of a CSV this script wrote."""
    with open(path) as f:
        lines = f.readlines()
    commit = lines[0].split("; commit ", 1)[1].strip()
    rows = list(csv.DictReader(line for line in lines if line[0] != "#"))
    for row in rows:
        for key, text in row.items():
            if key == "triangles":
                row[key] = int(text) if text.isdigit() else text
            else:
                row[key] = float(text) if text else math.nan
    return rows, commit


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", help="the binary (not for --replot)")
    parser.add_argument("--meshes", type=int, default=len(MESHES))
    parser.add_argument("--lens", default="",
                        help="more lens.geo constants, e.g. "
                        "'junction_fillet = 0.25'")
    parser.add_argument("--tag", default="",
                        help="appended to the files' names")
    parser.add_argument("--replot", action="store_true",
                        help="redraw the PNG from the CSV, without runs")
    args = parser.parse_args()
    name = "iol_compression_refinement" + args.tag
    if args.replot:
        rows, commit = read_rows(os.path.join(OUT, name + ".csv"))
        plot(rows, commit, name)
        return
    if not args.coshell:
        parser.error("--coshell is needed to run the compressions")
    machine, commit = machine_and_commit()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for k, sizes in enumerate(MESHES[:args.meshes]):
            compression, triangles = compress(
                os.path.abspath(args.coshell), sizes, args.lens,
                os.path.join(work, f"mesh_{k}"))
            rows.append(mesh_row(sizes, compression, triangles))
            print(rows[-1], flush=True)
    if len(rows) == 3:
        limits = {"triangles": "extrapolated"}
        for key, order_key in ORDER_COLUMNS.items():
            value, order = extrapolated([r[key] for r in rows])
            limits[key], limits[order_key] = round(value, 6), round(order, 2)
        rows.append(limits)
    os.makedirs(OUT, exist_ok=True)
    write_csv(os.path.join(OUT, name + ".csv"), rows,
              [f"machine: {machine}; commit {commit}",
               "prm/iol/compression_iso11979.prm checked by "
               "check_compression.py, Output/Write VTU = false, "
               "Parallel/Threads = 1; lens.geo constants: "
               f"{args.lens or 'the defaults'}; the last row: Richardson's "
               "limit of the three meshes (none below order 0.5) and the "
               "order they show"],
              list(dict.fromkeys(k for r in rows for k in r)))
    plot(rows, commit, name)


if __name__ == "__main__":
    main()
