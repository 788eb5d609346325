#!/usr/bin/python3
"""How far the folded lens's strains are converged: the fold stage of the
IOL injection (prm/iol/injection.prm, stage 1 only, 1.3 s), one thread,
on the refinement study's lens meshes (iol_refinement.py's MESHES, about
200 to 8 000 triangles). Per mesh, from the last VTU (the wings closed):
the largest surface, bending and membrane strain (the VTU's per-cell
strain fields) in three regions: the optic inside --rim (mm from its
centre), where the largest lies along the fold line, a smooth curl; the
optic's rim outside it, where the haptics join the optic's edge (a corner
and a step in thickness, whose peak a shell cannot resolve); and the
haptics. Each region's largest surface strain is placed by its cell's
rest coordinates (the lens in z = 0, the injection axis along x).
Runs the meshes two at a time (--jobs) and writes
doc/performance/iol_fold_strain.csv and .png, stamped with machine and
commit. With --fillet F the lenses' haptic-optic junctions are rounded
(lens.geo's junction_fillet = F mm), and the files are
iol_fold_strain_fillet.csv and .png. With --junction-sizes the lens is
refined near its four junctions only: the default lens halved (0.275 and
0.11 mm) with lens.geo's junction_mesh_size set to each size given (mm)
within --junction-radius of each fillet (or corner), and the files are
iol_fold_strain_junction[_fillet].csv and .png; the first row is the lens
without local refinement. --haptic-type 1 folds the modified-L lens
instead (files ending _modified_l).

  /usr/bin/python3 doc/scripts/iol_fold_strain.py --coshell build/coshell \\
      [--meshes 4] [--jobs 2] [--fillet 0.25] \\
      [--junction-sizes 0.055,0.0275,0.01375 --junction-radius 0.15]
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import ROOT, finish_plot, machine_and_commit, write_csv  # noqa: E402
from iol_refinement import MESHES, lens_command  # noqa: E402
import render_vtu  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
OPTIC, HAPTICS = 1, 2  # material ids of lens.geo


# The lens refined near its junctions only: the default lens halved.
JUNCTION_BASE = (0.275, 0.11)


def fold(case, coshell, work):
    """Runs the fold on one lens mesh, a case (sizes, lens.geo constants,
    tag, junction size); returns its output directory and wall time."""
    sizes, constants, tag, _ = case
    command, output = lens_command(
        sizes, coshell, work, ["Stage 2/Analysis type=none"], constants,
        tag)
    if os.path.exists(os.path.join(output, "summary.json")):
        return output, None  # finished in an earlier call (--keep)
    start = time.time()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL,
                   env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    return output, time.time() - start


def regions(mesh, rim):
    """Cell masks of the optic's interior, the optic's rim and the
    haptics, by material and rest radius."""
    material = np.rint(render_vtu.cell_field(mesh, "material_id"))
    # deal.II writes the reference positions; the displacement apart.
    rest = render_vtu.cell_means(mesh, mesh.points)
    radius = np.hypot(rest[:, 0], rest[:, 1])
    return rest, {"optic": (material == OPTIC) & (radius < rim),
                  "optic_rim": (material == OPTIC) & (radius >= rim),
                  "haptics": material == HAPTICS}


def base_constants(args):
    """lens.geo constants every case shares: the haptics and the fillet."""
    constants = []
    if args.haptic_type == 1:
        constants.append("haptic_type = 1")
    if args.fillet > 0:
        constants.append(f"junction_fillet = {args.fillet}")
    return constants


def cases(args):
    """The lens meshes to fold: (gmsh sizes, lens.geo constants, tag,
    junction_mesh_size in mm or "" when not refined there)."""
    base = base_constants(args)
    if not args.junction_sizes:
        return [(sizes, ", ".join(base), "", "") for sizes in
                MESHES[:args.meshes]]
    local = [(JUNCTION_BASE, ", ".join(base), "", "")]
    for size in args.junction_sizes.split(","):
        refined = base + [f"junction_mesh_size = {size}",
                          f"junction_mesh_radius = {args.junction_radius}"]
        local.append((JUNCTION_BASE, ", ".join(refined), f"_junction_{size}",
                      float(size)))
    return local


def describe(args):
    """The lens in words, for the plot's title."""
    haptics = "modified-L, " if args.haptic_type == 1 else ""
    if args.fillet > 0:
        return f"{haptics}junctions filleted {args.fillet:g} mm"
    return f"{haptics}sharp junctions"


def folded_strains(case, output, seconds, rim):
    """The largest strains per region of the last VTU."""
    sizes, _, _, junction_size = case
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    last = render_vtu.read_pvd(os.path.join(output, "solution.pvd"))[-1]
    mesh = render_vtu.read_vtu(last.shell_file)
    rest, masks = regions(mesh, rim)
    row = {"optic_mesh_size_mm": sizes[0], "haptic_mesh_size_mm": sizes[1],
           "junction_mesh_size_mm": junction_size,
           "triangles": summary["n_cells"], "time_s": last.time,
           "newton_iterations": summary["newton_iterations"],
           "wall_s": round(seconds, 1) if seconds is not None else "",
           "time_loop_s": round(summary["simulated_time_s"]
                                / summary["real_time_factor"], 1)}
    for kind in ("surface", "bending", "membrane"):
        cells = render_vtu.cell_field(mesh, kind + "_strain")
        for region, mask in masks.items():
            inside = np.flatnonzero(mask)
            worst = inside[np.argmax(cells[inside])]
            row[f"{region}_{kind}_strain"] = round(float(cells[worst]), 5)
            if kind == "surface":
                row[f"{region}_largest_at_x_mm"] = round(float(rest[worst, 0]), 3)
                row[f"{region}_largest_at_y_mm"] = round(float(rest[worst, 1]), 3)
    return row


def plot(rows, commit, name, shape, local):
    """Strains against the lens's triangles, or, refined at the junctions
    only, against the size of the triangles there (finer to the right;
    the unrefined lens at its haptic's size)."""
    figure, axes = plt.subplots(figsize=(6.5, 4))
    if local:
        x = [r["junction_mesh_size_mm"] or r["haptic_mesh_size_mm"]
             for r in rows]
        axes.invert_xaxis()
    else:
        x = [r["triangles"] for r in rows]
    largest = 0.0
    for region, marker in (("optic", "o-"), ("optic_rim", "^:"),
                           ("haptics", "s--")):
        for kind in ("surface", "bending"):  # the CSV has the membrane's
            values = [100 * r[f"{region}_{kind}_strain"] for r in rows]
            largest = max(largest, *values)
            axes.plot(x, values, marker,
                      label=f"{region.replace('_', ' ')}, {kind}")
    axes.set_xscale("log")
    # Room for the legend above the curves, and a sharp corner's peaks.
    axes.set_ylim(0, max(45, 1.1 * largest))
    finish_plot(figure, axes,
                "triangles' size at the junctions (mm)" if local
                else "lens triangles",
                "largest strain at the fold's end (%)",
                f"IOL fold, {shape}" + (", refined there" if local else "")
                + f"\n({commit})",
                os.path.join(OUT, name + ".png"))


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--meshes", type=int, default=4)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--rim", type=float, default=2.5,
                        help="radius (mm) from which the optic's rim counts")
    parser.add_argument("--fillet", type=float, default=0.0,
                        help="radius (mm) of the haptic-optic junctions' "
                        "fillet (default 0: sharp, the scene's lens)")
    parser.add_argument("--haptic-type", type=int, choices=(0, 1),
                        default=0, help="0: C-loop (the scene's), 1: "
                        "modified-L (lens.geo haptic_type)")
    parser.add_argument("--junction-sizes",
                        help="comma-separated sizes (mm) of the triangles "
                        "near the junctions, on the default lens halved")
    parser.add_argument("--junction-radius", type=float, default=0.15,
                        help="mm from each junction's fillet (or corner) "
                        "within which --junction-sizes hold")
    parser.add_argument("--keep", help="a directory for the runs' output "
                        "(default: a temporary one, removed); a run that "
                        "finished there before is read, not run again, "
                        "and its wall time is left blank")
    args = parser.parse_args()
    coshell = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    meshes = cases(args)
    with tempfile.TemporaryDirectory() as scratch, \
            concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        work = os.path.abspath(args.keep) if args.keep else scratch
        runs = list(pool.map(lambda case: fold(case, coshell, work), meshes))
        rows = [folded_strains(case, output, seconds, args.rim)
                for case, (output, seconds) in zip(meshes, runs)]
    for row in rows:
        print(row)
    local = bool(args.junction_sizes)
    name = ("iol_fold_strain" + ("_junction" if local else "")
            + ("_fillet" if args.fillet > 0 else "")
            + ("_modified_l" if args.haptic_type == 1 else ""))
    write_csv(os.path.join(OUT, name + ".csv"), rows,
              [f"machine: {machine}; commit {commit}",
               "prm/iol/injection.prm, stage 1 (the fold) only, one thread "
               f"per run, {args.jobs} runs at a time; strains from the "
               f"last VTU; optic: rest radius < {args.rim:g} mm, optic_rim: "
               "the rest of the optic"
               + ("; modified-L haptics" if args.haptic_type == 1 else "")
               + (f"; junctions filleted, radius {args.fillet:g} mm"
                  if args.fillet > 0 else "")
               + (f"; refined to junction_mesh_size within "
                  f"{args.junction_radius:g} mm of each junction"
                  if local else "")])
    plot(rows, commit, name, describe(args), local)


if __name__ == "__main__":
    main()
