#!/usr/bin/python3
"""Refinement study of the IOL injection (prm/iol/injection.prm): the fold
(stage 1, 1.3 s) and the first part of the push (stage 2 for --push
seconds: the plunger drives the folded lens into the taper), one thread,
at lens meshes from about 200 to about 8000 triangles (the lens's gmsh
sizes halved from level to level to 6 400 triangles, then 8 347). Per mesh: triangles, DoFs, steps,
Newton iterations, wall time and real-time factor, the largest bending
and membrane strains over the run, the largest plunger force (mN, the
plunger's contact force along the axis), the largest force averaged over
0.5 mm of plunger travel, the work of the push (N mm) and the plunger
force at the end.
Writes doc/performance/iol_refinement.csv after every mesh (a run cut off
by --timeout leaves the finer rows out; a failed run is a row with the
error message, after which the finer meshes are not run) and
iol_refinement.png, stamped with machine and commit.

With --whole the runs are the whole scene instead: the fold, the push
until the plunger reaches the nozzle's tip (where the folded optic
passes the nozzle and the force peaks), the deployment in the bag and
the settling (stage 4); the rows add the optic's
decentration, tilt and shape deviation at rest (the Region poses'
quantities at the end), and their real-time factor is that of stages 1
to 3. Files iol_refinement_whole.csv and .png, whose fourth panel is the
rest pose against the mesh. --replot redraws a study's PNG from its CSV.

  /usr/bin/python3 doc/scripts/iol_refinement.py --coshell build/coshell \\
      [--meshes 5] [--push 1.0 | --whole] [--timeout 5400] [--tag _settled]
      [--replot] [--resume 4]

--resume K keeps the first K rows of the study's CSV and runs the meshes
from the K+1-th on, for a finest lens that did not fit in the first run's
time; the header then names both commits.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
import warnings

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import (ROOT, finish_plot, largest_strains,  # noqa: E402
                        machine_and_commit, read_csv, write_csv)
sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
from check_injection import plunger_rows, travel_measures  # noqa: E402
from coshell_checks import read_rows, surgical_real_time_factor  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
SCENE = os.path.join(ROOT, "prm", "iol", "injection.prm")
# (optic, haptic) gmsh sizes in mm: the ctest lens, the default lens, the
# default halved and quartered (6 400 triangles), and last the issue's
# largest lens, about 8 000 triangles (8 347).
MESHES = [(0.9, 0.35), (0.55, 0.22), (0.275, 0.11), (0.1375, 0.055),
          (0.12, 0.048)]
PLUNGER = 2  # the plunger is Contact/Obstacle 2 of the scene


def plunger_forces(output):
    """The plunger's displacements (mm), axial forces on the lens (N) and
    cumulative work on it (N mm)."""
    forces = read_rows(os.path.join(output, "contact_forces.csv"))
    _, _, displacement, push, work = plunger_rows(forces, PLUNGER)
    return displacement, push, work


def lens_command(sizes, coshell, work, assignments, lens_constants="",
                 tag="", deploy=False):
    """The scene on the lens of these gmsh sizes, on one thread, with
    more assignments and more lens.geo constants ("name = value, ..."),
    without the deployment (stage 3) unless 'deploy'; returns the command
    and its output directory (named by the sizes and the tag)."""
    optic, haptic = sizes
    output = os.path.join(work, f"lens_{optic}_{haptic}{tag}")
    command = [coshell, SCENE, "--output", output]
    constants = f"optic_mesh_size = {optic}, haptic_mesh_size = {haptic}"
    if lens_constants:
        constants += ", " + lens_constants
    stages = [] if deploy else ["Stage 3/Analysis type=none",
                                "Stage 4/Analysis type=none"]
    for assignment in [f"Mesh/Gmsh parameters={constants}"] + stages + [
            "Parallel/Threads=1"] + assignments:
        command += ["--set", assignment]
    return command, output


def run(sizes, coshell, push, timeout, work):
    """One mesh's row; push None: the whole scene."""
    optic, haptic = sizes
    command, output = lens_command(
        sizes, coshell, work,
        [] if push is None else [f"Stage 2/Duration={push}"],
        deploy=push is None)
    start = time.time()
    process = subprocess.run(command, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True,
                             env=dict(os.environ, OPENBLAS_NUM_THREADS="1"),
                             timeout=timeout)
    if process.returncode != 0:  # a row that says so, and the message
        return {"optic_mesh_size_mm": optic, "haptic_mesh_size_mm": haptic,
                "process_s": round(time.time() - start, 1),
                "status": process.stderr.strip().splitlines()[-1]}
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    displacement, forces, work_so_far = plunger_forces(output)
    averaged, work = travel_measures(displacement, forces, work_so_far)
    bending, membrane = largest_strains(output)
    seconds = summary["time_stepping_s"]
    at_rest = {} if push is not None else {
        f"{name}_{unit}": round(summary["qoi"][f"optic_{name}"], 4)
        for name, unit in (("decentration", "mm"), ("tilt", "degrees"),
                           ("shape_deviation", "mm"))}
    return {
        "optic_mesh_size_mm": optic, "haptic_mesh_size_mm": haptic,
        "triangles": summary["n_cells"], "dofs": summary["n_dofs"],
        "steps": summary["steps"],
        "newton_iterations": summary["newton_iterations"],
        "wall_time_s": round(seconds["total"], 1),
        "process_s": round(time.time() - start, 1),
        "real_time_factor": round(surgical_real_time_factor(summary), 5),
        "ms_per_iteration": round(
            1e3 * seconds["total"] / summary["newton_iterations"], 1),
        "max_bending_strain": round(bending, 5),
        "max_membrane_strain": round(membrane, 5),
        "max_plunger_force_mn": round(1e3 * forces.max(), 3),
        "max_plunger_force_over_0.5mm_mn": round(1e3 * averaged, 3),
        "push_work_nmm": round(work, 5),
        "final_plunger_force_mn": round(1e3 * forces[-1], 3),
        "smallest_gap_mm": summary["contact"]["smallest_gap"],
        **at_rest, "status": "ok"}


def plot(rows, push, commit, name):
    rows = [r for r in rows if r["status"] == "ok"]
    at_rest = push is None and all("tilt_degrees" in r for r in rows)
    figure, axes = plt.subplots(1, 4 if at_rest else 3,
                                figsize=(14.5 if at_rest else 11, 3.6))
    triangles = [r["triangles"] for r in rows]
    series = [
        (axes[0], [("max_plunger_force_mn", "largest"),
                   ("max_plunger_force_over_0.5mm_mn",
                    "largest over 0.5 mm of travel"),
                   ("final_plunger_force_mn",
                    "at the end" if push is None
                    else f"at t = {1.3 + push:g} s")],
         "plunger force (mN)"),
        (axes[1], [("max_bending_strain", "bending"),
                   ("max_membrane_strain", "membrane")],
         "largest strain"),
        (axes[2], [("real_time_factor", "real-time factor")],
         "real-time factor (1 thread)")]
    for ax, columns, ylabel in series:
        for column, label in columns:
            ax.plot(triangles, [r[column] for r in rows], "o-", label=label)
        ax.set_xscale("log")
        ax.set_xlabel("lens triangles")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    axes[2].set_yscale("log")
    if at_rest:
        plot_rest_pose(axes[3], triangles, rows)
    run = ("IOL injection, the whole scene" if push is None
           else f"IOL fold and {push:g} s of push")
    finish_plot(figure, axes[1], "lens triangles", "largest strain",
                f"{run}, refinement ({commit})",
                os.path.join(OUT, name + ".png"))
    plot_speed_against_error(rows, f"{run} ({commit})", name)


# The measures whose refinement converges, against the finest lens: the
# peaks of strain and force are left out, since the sharp junction's
# strain grows without bound and the raw force peak is a stick-slip sample.
CONVERGING = [("max_plunger_force_over_0.5mm_mn", "force over 0.5 mm"),
              ("push_work_nmm", "work of the push")]


def plot_speed_against_error(rows, title, name):
    """Each coarser lens's difference from the finest one (relative, of
    the converging measures) against its real-time factor: what a lens
    costs against how far it is off (name_speed_error.png)."""
    finest, coarser = rows[-1], rows[:-1]
    if not coarser:
        return
    figure, ax = plt.subplots(figsize=(5.5, 3.8))
    speed = [r["real_time_factor"] for r in coarser]
    for column, label in CONVERGING:
        reference = float(finest[column])
        errors = [abs(float(r[column]) / reference - 1) for r in coarser]
        ax.plot(speed, errors, "o-", label=label)
        for row, x, y in zip(coarser, speed, errors):
            ax.annotate(f"{row['triangles']}", (x, y), fontsize=7,
                        xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    finish_plot(figure, ax, "real-time factor (1 thread)",
                f"relative difference from {finest['triangles']} triangles",
                title, os.path.join(OUT, name + "_speed_error.png"))


def plot_rest_pose(ax, triangles, rows):
    """The optic's decentration (mm) and tilt (degrees) at the run's end,
    at rest after the settling."""
    ax.set_xscale("log")  # before the twin, which shares the x axis
    ax.plot(triangles, [float(r["decentration_mm"]) for r in rows], "o-",
            color="C0", label="decentration (mm)")
    ax.set_ylabel("decentration at rest (mm)")
    tilt = ax.twinx()
    tilt.plot(triangles, [float(r["tilt_degrees"]) for r in rows], "s--",
              color="C3", label="tilt (degrees)")
    tilt.set_ylabel("tilt at rest (degrees)")
    # Clearing the figure resets the twin's shared log axis through 0,
    # which matplotlib reports; the drawn figure is not affected.
    warnings.filterwarnings("ignore", "Attempt to set non-positive xlim")
    ax.set_xlabel("lens triangles")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(handles=ax.get_lines() + tilt.get_lines(), fontsize=7)


def read_rows_written(name):
    """The rows of a study's CSV (after its '#' lines), numbers as
    numbers, for --replot."""
    rows = read_csv(os.path.join(OUT, name + ".csv"))
    for row in rows:
        for key, value in row.items():
            for number in (int, float):
                try:
                    row[key] = number(value)
                    break
                except ValueError:
                    pass
    return rows


def resumed_study(name, kept, commit):
    """The header and first 'kept' rows of a study's CSV, to which the
    finer meshes' rows are added; the header names both commits."""
    with open(os.path.join(OUT, name + ".csv")) as f:
        written = [line[2:].rstrip("\n") for line in f
                   if line.startswith("# ")]
    written[0] += f" (the first {kept} rows); commit {commit} (the rest)"
    return written, read_rows_written(name)[:kept]


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--meshes", type=int, default=len(MESHES))
    parser.add_argument("--push", type=float, default=1.0,
                        help="seconds of stage 2 (the plunger at 5 mm/s)")
    parser.add_argument("--whole", action="store_true",
                        help="the whole scene (fold, push, deployment)")
    parser.add_argument("--timeout", type=float, default=5400,
                        help="seconds per mesh; finer meshes are skipped "
                        "after one runs out")
    parser.add_argument("--tag", default="",
                        help="appended to the files' names (a study that "
                        "must not replace the last one's)")
    parser.add_argument("--replot", action="store_true",
                        help="redraw the PNG from the study's CSV")
    parser.add_argument("--resume", type=int, default=0,
                        help="keep this many rows of the study's CSV and "
                        "run the finer meshes only")
    args = parser.parse_args()
    machine, commit = machine_and_commit()
    push = None if args.whole else args.push
    name = ("iol_refinement_whole" if args.whole else "iol_refinement") + \
        args.tag
    if args.replot:
        with open(os.path.join(OUT, name + ".csv")) as f:
            # A resumed study's header names the commit of each part.
            commit = " and ".join(re.findall(r"commit (\w+)", f.readline()))
        plot(read_rows_written(name), push, commit, name)
        return
    stages = ("the whole scene (fold, push to the nozzle's tip, deployment, "
              "settling)"
              if args.whole else f"stage 1 (fold, 1.3 s) and {args.push:g} "
              "s of stage 2 (push)")
    header = [f"machine: {machine}; commit {commit}",
              f"prm/iol/injection.prm: {stages}, Parallel/Threads = 1, "
              "OPENBLAS_NUM_THREADS = 1; meshes one after another"]
    rows = []
    if args.resume:
        header, rows = resumed_study(name, args.resume, commit)
    os.makedirs(OUT, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        for sizes in MESHES[args.resume:args.meshes]:
            try:
                rows.append(run(sizes, os.path.abspath(args.coshell),
                                push, args.timeout, work))
            except subprocess.TimeoutExpired:
                print(f"lens {sizes}: no result within {args.timeout} s")
                break
            print(rows[-1], flush=True)
            write_csv(os.path.join(OUT, name + ".csv"), rows, header,
                      list(dict.fromkeys(k for r in rows for k in r)))
            if rows[-1]["status"] != "ok":
                break  # a finer lens would take longer to fail as well
    plot(rows, push, commit, name)


if __name__ == "__main__":
    main()
