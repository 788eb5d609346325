#!/usr/bin/python3
"""The injection against the nozzle's bore: prm/iol/injection.prm with
--set "Constants/Changes=nozzle_radius = r" for a list of bores, stages 1
to 3 (fold, push to the nozzle's tip, deployment; no settling), one
thread. The plunger follows the bore (plunger_radius = nozzle_radius -
0.05 mm), so a narrower nozzle also leaves more room beside the plunger in
the 4 mm loading chamber, which the wings' radius sets. Per bore: whether
the lens got through (or where the run jammed: the time, the obstacles
that pinched the lens and the vertex's position, from coshell's last
message), the largest plunger force, the largest force over 0.5 mm of
travel and the push's work (over the run so far where it jammed), the
optic's largest width across the axis while it is in the nozzle, how far
the optic's centre and the trailing haptic's end got along the axis, the
smallest gap, steps, Newton iterations and the real-time factor. Writes
doc/performance/iol_nozzle_sweep<tag>.csv and each bore's force against
the plunger's travel (iol_nozzle_sweep<tag>_force.csv) after every bore,
and the PNG (the force against the bore, the optic's rim-to-rim chord
against the bore, the force against the travel), stamped with machine and
commit; --replot redraws the PNG from the two CSV files.

  /usr/bin/python3 doc/scripts/iol_nozzle_sweep.py --coshell build/coshell \\
      [--radii 1.9 1.75 1.6] [--lens 0.55 0.22] [--sleeve 0|1|2]
      [--thickness-stretch] [--tag _coarse] [--replot]

A bore the scene refuses (injection.prm's Constants/Requirements: the
tip narrower than the lens can pass by volume) is a row 'refused'.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import (ROOT, machine_and_commit, read_csv,  # noqa: E402
                        write_csv)
sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
from check_injection import (TRAILING_END_X, column,  # noqa: E402
                             optic_in_nozzle, plunger_rows, rim_chord,
                             travel_measures)
from iol_refinement import OUT, PLUNGER, lens_command  # noqa: E402
from coshell_checks import read_rows, surgical_real_time_factor  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# injection.prm's constants the checks need (mm): the nozzle runs from
# nozzle_start to nozzle_tip, the chamber's inner radius is the wings'.
NOZZLE_START, NOZZLE_TIP, CHAMBER_RADIUS = 11.5, 15.0, 2.0
PLUNGER_CLEARANCE = 0.05
# The plunger's sleeves are Contact/Obstacles 7 and 8 (the inner one),
# off unless their meshes are set.
SLEEVES = (7, 8)
SLEEVE_ON = ["Contact/Obstacle 7/Mesh file=../../meshes/contact/plunger.geo"]
INNER_SLEEVE_ON = [
    "Contact/Obstacle 8/Mesh file=../../meshes/contact/plunger.geo"]
# The shell whose thickness changes (doc/theory.md, section 21) on the
# CST membrane it needs; the bore's volume check lets it thin to half.
THICKNESS_STRETCH = ["Element/Membrane element=cst",
                     "Element/Thickness stretch=true"]


def finished_or_partial(output, name):
    """A run's CSV file, or the '.partial' one a failed run leaves."""
    path = os.path.join(output, name)
    return read_rows(path if os.path.exists(path) else path + ".partial")


def jam(message):
    """The time, the obstacles and the vertex of coshell's last message
    about a failed step ('' where it names none)."""
    when = re.search(r"time step from t = (\S+) s", message)
    pinch = re.search(r"pinched between obstacles '([^']+)' and '([^']+)' "
                      r"at vertex \d+ \(([^)]*)\)", message)
    return (float(when.group(1)) if when else float("nan"),
            f"{pinch.group(1)} and {pinch.group(2)} at ({pinch.group(3)})"
            if pinch else "")


def pushing_forces(forces, sleeves):
    """The plunger's travel (mm), and the push on the lens along the axis
    (N) and its cumulative work (N mm) of the plunger and of its first
    'sleeves' sleeves together (they share steps)."""
    _, _, displacement, push, work = plunger_rows(forces, PLUNGER)
    for sleeve in SLEEVES[:sleeves]:
        _, _, _, sleeve_push, sleeve_work = plunger_rows(forces, sleeve)
        push, work = push + sleeve_push, work + sleeve_work
    return displacement, push, work


def path_measures(output, sleeve):
    """What the rows written so far show: the optic's width in the
    nozzle, how far the lens got and the push's force and work (the
    plunger's, with the sleeve the plunger's and the sleeve's)."""
    history = finished_or_partial(output, "time_history.csv")
    centre = column(history, "optic_ux")
    in_nozzle = optic_in_nozzle(history, NOZZLE_START, NOZZLE_TIP)
    chord = rim_chord(history)
    forces = finished_or_partial(output, "contact_forces.csv")
    displacement, push, work_so_far = pushing_forces(forces, sleeve)
    averaged, work = travel_measures(displacement, push, work_so_far)
    gaps = [float(r["min_distance"]) for r in forces]
    thinnest = ({"min_thickness_stretch": round(float(column(
        history, "min_thickness_stretch").min()), 4)}
        if "min_thickness_stretch" in history[0] else {})
    return {**thinnest,
        "optic_width_in_nozzle_mm": round(float(chord[in_nozzle].max()), 3)
        if in_nozzle.any() else "",
        "optic_centre_max_x_mm": round(float(centre.max()), 3),
        "trailing_end_max_x_mm": round(
            TRAILING_END_X + float(column(history, "trail_ux").max()), 3),
        "max_plunger_force_mn": round(1e3 * float(push.max()), 3),
        "max_plunger_force_over_0.5mm_mn": round(1e3 * averaged, 3),
        "push_work_nmm": round(work, 5),
        "smallest_gap_mm": float(np.nanmin(gaps)),
    }, (displacement, push)


def run(radius, lens, coshell, work, timeout, sleeve, stretch):
    """One bore's row and its force-travel curve ('sleeve': how many of
    the plunger's sleeves; 'stretch': the thickness may change)."""
    command, output = lens_command(
        lens, coshell, work,
        [f"Constants/Changes=nozzle_radius = {radius}"
         + (", thinnest_fraction = 0.5" if stretch else ""),
         "Stage 4/Analysis type=none"] + (SLEEVE_ON + INNER_SLEEVE_ON)[:sleeve]
        + (THICKNESS_STRETCH if stretch else []),
        tag=f"_nozzle_{radius}", deploy=True)
    process = subprocess.run(command, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True,
                             env=dict(os.environ, OPENBLAS_NUM_THREADS="1"),
                             timeout=timeout)
    plunger = radius - PLUNGER_CLEARANCE
    row = {"nozzle_diameter_mm": 2 * radius,
           "plunger_diameter_mm": round(2 * plunger, 3),
           "room_beside_plunger_in_chamber_mm":
               round(CHAMBER_RADIUS - plunger, 3)}
    if not os.path.exists(os.path.join(output, "solution.pvd")):
        # Refused before it ran (the bore's requirements): no curve.
        return {**row, "status": "refused", "failed_at_s": "",
                "pinched_by": "", "message": process.stderr.strip()
                .splitlines()[-1]}, (np.array([]), np.array([]))
    measures, curve = path_measures(output, sleeve)
    if process.returncode != 0:
        message = process.stderr.strip().splitlines()[-1]
        when, where = jam(message)
        # A jam's last steps squeeze the barrier to gaps of 1e-8 mm, where
        # its force is no longer a push on a lens that moves: no forces.
        for key in ("max_plunger_force_mn", "max_plunger_force_over_0.5mm_mn",
                    "push_work_nmm"):
            measures[key] = ""
        return {**row, "status": "failed", "failed_at_s": when,
                "pinched_by": where, **measures, "message": message}, curve
    with open(os.path.join(output, "summary.json")) as f:
        summary = json.load(f)
    passed = (measures["optic_centre_max_x_mm"] > NOZZLE_TIP and
              measures["trailing_end_max_x_mm"] > NOZZLE_TIP)
    return {**row, "status": "through" if passed else "not out of the tip",
            "failed_at_s": "", "pinched_by": "", **measures,
            "steps": summary["steps"],
            "newton_iterations": summary["newton_iterations"],
            "real_time_factor": round(surgical_real_time_factor(summary), 5)
            }, curve


def plot(rows, curves, title, path, pusher="plunger"):
    """The force and the optic's chord against the bore, and the force
    against the travel; 'pusher' names what the force is of."""
    figure, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    through = [r for r in rows if r["status"] == "through"]
    bores = [r["nozzle_diameter_mm"] for r in through]
    axes[0].plot(bores, [r["max_plunger_force_over_0.5mm_mn"]
                         for r in through], "o", label="through the tip")
    axes[1].plot(bores, [r["optic_width_in_nozzle_mm"] for r in through],
                 "o", label="through the tip")
    for row in (r for r in rows if r["status"] != "through"):
        what = (f"jammed at t = {row['failed_at_s']:g} s"
                if row["status"] == "failed" else row["status"])
        for ax in axes[:2]:
            ax.axvline(row["nozzle_diameter_mm"], color="C3", ls="--",
                       label=f"{row['nozzle_diameter_mm']:g} mm: {what}")
    axes[0].set_ylabel(f"largest {pusher} force over 0.5 mm (mN)")
    bores = sorted(r["nozzle_diameter_mm"] for r in rows)
    axes[1].plot(bores, bores, "k:", label="the bore")
    axes[1].set_ylabel("largest rim-to-rim chord in the nozzle (mm)")
    for ax in axes[:2]:
        ax.set_xlabel("nozzle's inner diameter (mm)")
    for row, (displacement, push) in zip(rows, curves):
        through = row["status"] == "through"
        axes[2].plot(displacement, 1e3 * push, lw=0.8 if through else 0.6,
                     ls="-" if through else "--",
                     label=f"{row['nozzle_diameter_mm']:g} mm"
                     + ("" if through else ", jammed"))
    peaks = [1e3 * push.max() for row, (_, push) in zip(rows, curves)
             if row["status"] == "through"]
    if peaks:  # a jam's barrier force runs to 1e6 N: show the passages
        axes[2].set_ylim(0, 1.3 * max(peaks))
    axes[2].set_xlabel("plunger travel (mm)")
    axes[2].set_ylabel(f"{pusher} force (mN)")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    figure.suptitle(title, fontsize=9)
    figure.tight_layout(rect=(0, 0, 1, 0.95))
    figure.savefig(path, dpi=110)
    print("wrote", path)


def pusher(sleeves):
    return ("plunger", "plunger and sleeve", "plunger and sleeves")[sleeves]


def write_curves(path, rows, curves, header):
    """Each bore's plunger force (mN) against its travel (mm)."""
    table = [{"nozzle_diameter_mm": row["nozzle_diameter_mm"],
              "plunger_displacement_mm": round(float(x), 4),
              "force_mn": round(1e3 * float(f), 4)}
             for row, (displacement, push) in zip(rows, curves)
             for x, f in zip(displacement, push)]
    write_csv(path, table, header,
              ["nozzle_diameter_mm", "plunger_displacement_mm", "force_mn"])


def read_study(name):
    """The rows and the force curves a sweep wrote, for --replot."""
    rows = read_csv(os.path.join(OUT, name + ".csv"))
    for row in rows:
        row["nozzle_diameter_mm"] = float(row["nozzle_diameter_mm"])
        for key in ("failed_at_s", "max_plunger_force_over_0.5mm_mn",
                    "optic_width_in_nozzle_mm"):
            row[key] = float(row[key]) if row[key] else ""
    points = read_csv(os.path.join(OUT, name + "_force.csv"))
    curves = []
    for row in rows:
        mine = [p for p in points if float(p["nozzle_diameter_mm"]) ==
                row["nozzle_diameter_mm"]]
        curves.append((np.array([float(p["plunger_displacement_mm"])
                                 for p in mine]),
                       1e-3 * np.array([float(p["force_mn"]) for p in mine])))
    return rows, curves


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--radii", type=float, nargs="+",
                        default=[1.9, 1.8, 1.75, 1.7, 1.65, 1.6, 1.55, 1.5],
                        help="nozzle inner radii (mm)")
    parser.add_argument("--lens", type=float, nargs=2, default=[0.55, 0.22],
                        metavar=("OPTIC", "HAPTIC"),
                        help="lens.geo's optic and haptic mesh sizes (mm)")
    parser.add_argument("--timeout", type=float, default=3600,
                        help="seconds per bore")
    parser.add_argument("--sleeve", type=int, default=0, choices=(0, 1, 2),
                        help="with the plunger's sleeve (1, injection.prm's "
                        "Contact/Obstacle 7) or both sleeves (2, Obstacles "
                        "7 and 8); the forces are the plunger's and the "
                        "sleeves' together")
    parser.add_argument("--thickness-stretch", action="store_true",
                        help="the lens's thickness may change "
                        "(Element/Thickness stretch on the CST membrane, "
                        "Constants thinnest_fraction = 0.5)")
    parser.add_argument("--tag", default="")
    parser.add_argument("--replot", action="store_true",
                        help="redraw the PNG from the CSV files of the "
                        "last sweep with this tag")
    args = parser.parse_args()
    name = "iol_nozzle_sweep" + args.tag
    if args.replot:
        with open(os.path.join(OUT, name + ".csv")) as f:
            stamp = f.readline()[2:].strip().replace("machine: ", "")
            setting = f.readline()
        lens = re.search(r"lens sizes (\S+) mm", setting)
        rows, curves = read_study(name)
        sleeves = ("sleeves on" in setting) + ("sleeve" in setting)
        plot(rows, curves, "IOL injection against the nozzle's bore, lens "
             f"{lens.group(1) if lens else '?'} mm ({stamp})",
             os.path.join(OUT, name + ".png"), pusher(sleeves))
        return
    machine, commit = machine_and_commit()
    header = [f"machine: {machine}; commit {commit}",
              "prm/iol/injection.prm, stages 1 to 3, lens sizes "
              f"{args.lens[0]:g}/{args.lens[1]:g} mm, Constants/Changes="
              "nozzle_radius = diameter/2"
              + ("", ", the plunger's sleeve on (Contact/Obstacle 7), forces "
                 "and work of the plunger and the sleeve together",
                 ", the plunger's two sleeves on (Contact/Obstacles 7 and "
                 "8), forces and work of the plunger and the sleeves "
                 "together")[args.sleeve]
              + (", the thickness stretch on (CST membrane, "
                 "thinnest_fraction = 0.5)" if args.thickness_stretch else "")
              + ", Parallel/Threads = 1, "
              "OPENBLAS_NUM_THREADS = 1; a failed run's measures are up "
              "to its failure"]
    rows, curves = [], []
    with tempfile.TemporaryDirectory() as work:
        for radius in args.radii:
            row, curve = run(radius, tuple(args.lens),
                             os.path.abspath(args.coshell), work,
                             args.timeout, args.sleeve,
                             args.thickness_stretch)
            rows.append(row)
            curves.append(curve)
            print(row, flush=True)
            write_csv(os.path.join(OUT, name + ".csv"), rows, header,
                      list(dict.fromkeys(k for r in rows for k in r)))
            write_curves(os.path.join(OUT, name + "_force.csv"), rows,
                         curves, header)
    plot(rows, curves, f"IOL injection against the nozzle's bore, lens "
         f"{args.lens[0]:g}/{args.lens[1]:g} mm ({machine}, {commit})",
         os.path.join(OUT, name + ".png"), pusher(args.sleeve))


if __name__ == "__main__":
    main()
