#!/usr/bin/env python3
"""Runs the IOL injection (prm/iol/injection.prm, or a reduced variant of it
through --set) and checks what the scene must show:

  - contact: the smallest gap of every pair (lens against the wings, the
    holding rod, the cartridge, the plunger, the bag, and itself) stays
    >= 0 at every step;
  - folding: the optic's width across the injection axis (the distance in
    the y-z plane of its rim points at y = +-3 mm) falls to the nozzle's
    inner diameter or less while the optic's centre passes the nozzle
    (from before its start to beyond its tip);
  - exit: the lens's trailing point (the trailing haptic's end) passes the
    nozzle's tip;
  - deployment: at the end, at rest in the bag (kinetic energy a small
    fraction of its peak), the optic's largest deviation from its rest
    shape after the best rigid fit is below 2 % of the optic diameter,
    every lens vertex lies inside the bag, and the optic's pose is still
    (over the last --rest-window seconds its decentration and tilt moved
    by less than 0.01 mm and 0.25 degrees);
  - the plunger force is finite and positive (a pull, friction's, of at
    most 1 % of its peak), and plunger_force.csv's force integrated over
    its travel is the push's work within 1 %;
  - energy: the work the plunger, the wings and the rod did on the lens,
    plus the external work, equals the strain energy + kinetic energy +
    the energy dissipated by drag, damping and friction + the barrier
    energy stored in contact within 2 % of that work (a fixed obstacle,
    such as the cartridge, does no work; its friction dissipates).

With --junction-fillet RADIUS the rest lens's outline at the haptic-optic
junctions is checked against fillets of that radius (lens_junctions.py).
With --junction-refined SIZE RADIUS the rest lens's triangles within
RADIUS mm of each junction's fillet (or corner) are checked to have the
size SIZE mm (lens.geo junction_mesh_size and junction_mesh_radius).

With --fold-only WIDTH the run is the fold stage alone: the gaps, the
energy and the optic's width at the end (<= WIDTH) are checked (and,
with --figures, the folded lens is drawn).

Checks coshell's plunger_force.csv (time, plunger_displacement, force_n)
against contact_forces.csv, and so the plunger's sleeve's
sleeve_force.csv where the scene has the sleeve on. With --figures DIR
it also writes the PNGs (checker_figures.py; without it nothing is
drawn): the plunger force against its travel, the plunger force,
strains and energies against time, the folded lens (the paper's Fig. 4)
and the deployment sequence.
Reports the optic's decentration and tilt in the bag, each obstacle's
smallest gap, and the real-time factor of the whole run, of each stage
and of stages 1 to 3 (the injection without the settling). The nozzle's
dimensions are the run's constants (summary.json) unless given.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

from coshell_checks import (add_scene_arguments, check_energy_balance,
                            column, force_file_check, read_rows,
                            run_contact_scene, surgical_real_time_factor)

SCRIPTS = os.path.dirname(os.path.abspath(__file__))
# x of the trailing haptic's end at rest (mm), injection.prm's trail_ux
# point.
TRAILING_END_X = -6.3
sys.path.insert(0, os.path.join(SCRIPTS, "..", "..", "doc", "scripts"))
import render_vtu  # noqa: E402
from lens_junctions import check_fillets, check_refinement  # noqa: E402


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    add_scene_arguments(parser)
    parser.add_argument("--plunger", type=int, default=2,
                        help="the plunger's obstacle number")
    parser.add_argument("--sleeve", type=int, default=7,
                        help="the plunger's sleeve's obstacle number, "
                        "checked when its sleeve_force.csv exists")
    parser.add_argument("--nozzle-radius", type=float,
                        help="inner, mm (default: the run's constant "
                        "nozzle_radius, see NOZZLE)")
    parser.add_argument("--nozzle-start", type=float,
                        help="x where the nozzle begins (the taper's end), "
                        "mm (default: nozzle_start)")
    parser.add_argument("--nozzle-tip", type=float,
                        help="x of the nozzle's tip in the lens frame, mm "
                        "(default: nozzle_tip)")
    parser.add_argument("--bag-centre", type=float, nargs=3,
                        default=(17.2, 0.0, 1.5))
    parser.add_argument("--bag-radii", type=float, nargs=2,
                        default=(5.0, 2.5), help="equator, polar (mm)")
    parser.add_argument("--optic-diameter", type=float, default=6.0)
    parser.add_argument("--shape-tolerance", type=float, default=0.02,
                        help="largest optic deviation / optic diameter")
    parser.add_argument("--shape-not-asserted", metavar="REASON",
                        help="report the optic's shape at rest against "
                        "--shape-tolerance without asserting it, saying "
                        "why: for a lens whose design misses it (the "
                        "modified-L bends its optic by about 2 %% wherever "
                        "it is held at 10 mm, doc/validation.md)")
    parser.add_argument("--energy-tolerance", type=float, default=0.02)
    parser.add_argument("--rest-window", type=float, default=2.0,
                        help="s: the optic's pose must hold still over the "
                        "run's last this many seconds")
    parser.add_argument("--figures", help="directory for the PNG files")
    parser.add_argument("--junction-fillet", type=float, metavar="RADIUS",
                        help="the lens's haptic-optic junctions are "
                             "filleted (lens.geo junction_fillet, mm): "
                             "check the rest mesh's outline")
    parser.add_argument("--junction-refined", type=float, nargs=2,
                        metavar=("SIZE", "RADIUS"),
                        help="the lens is refined at its junctions "
                             "(lens.geo junction_mesh_size and "
                             "junction_mesh_radius, mm): check the sizes")
    parser.add_argument("--haptic-type", type=int, choices=(0, 1),
                        default=0, help="the lens's haptics for "
                        "--junction-fillet and --junction-refined: 0 "
                        "C-loop, 1 modified-L")
    parser.add_argument("--fold-only", type=float, metavar="WIDTH",
                        help="the run is the fold stage alone: check the "
                             "gaps, the energy and that the optic's width "
                             "across the axis ends at most WIDTH (mm)")
    return parser.parse_args()


def rim_chord(history):
    """The optic's width across the injection axis: the distance in the
    y-z plane between its rim points at y = +3 and y = -3 (6 mm flat)."""
    plus = np.stack([3.0 + column(history, "rim_yp_uy"),
                     column(history, "rim_yp_uz")])
    minus = np.stack([-3.0 + column(history, "rim_ym_uy"),
                      column(history, "rim_ym_uz")])
    return np.linalg.norm(plus - minus, axis=0)


def plunger_rows(forces, plunger):
    """The plunger's rows, times (s), displacements (mm), axial forces on
    the lens (N) and the cumulative work it did on the lens (N mm)."""
    rows = [r for r in forces if int(r["obstacle"]) == plunger]
    time = column(rows, "time")
    push = -column(rows, "fx")  # the lens pushes back on the plunger (-x)
    return rows, time, column(rows, "ux"), push, column(rows, "work")


def travel_measures(displacement, push, work, window=0.5):
    """The forward push's largest force averaged over 'window' mm of
    travel (N; nan for a shorter push) and its work (N mm): the code's own
    cumulative work at the largest travel, the one the energy balance
    reads. The largest force itself is a spike about a tenth of a
    millimetre wide, and Newton's settings alone moved it by 8 % on the
    whole scene, the averaged force by 3 % and the work by 1 %
    (doc/validation.md)."""
    end = int(np.argmax(displacement)) + 1 if len(push) else 0
    if end < 2:  # no forward push
        return math.nan, math.nan
    # The travel so far: a prescribed push does not step back, and
    # np.interp needs it ascending.
    x, f = np.maximum.accumulate(displacement[:end]), push[:end]
    if x[-1] - x[0] < window:
        return math.nan, float(work[end - 1])
    step = window / 100
    grid = np.arange(x[0], x[-1], step)
    samples = np.interp(grid, x, f)
    averaged = np.convolve(samples, np.full(100, 0.01), mode="valid")
    return float(averaged.max()), float(work[end - 1])


def trapezoid_work(travel, force):
    """The work of 'force' over 'travel' so far, at every row (N mm, by
    trapezoids on the rows)."""
    return np.concatenate(([0.0], np.cumsum(
        0.5 * (force[1:] + force[:-1]) * np.diff(travel))))


def push_measures(rows):
    """The push's work on the lens (N mm, by trapezoids on the plunger's
    contact_forces.csv 'rows') and its largest force averaged over 0.5 mm
    of travel (N): one way to measure every run, the restarted ones
    included, whose cumulative work column starts anew."""
    travel = column(rows, "ux")
    force = -column(rows, "fx")  # on the lens
    averaged, total = travel_measures(travel, force,
                                      trapezoid_work(travel, force))
    return total, averaged


def check_force_file_work(checks, output, work):
    """plunger_force.csv's force integrated over its travel, by trapezoids
    on its rows up to the largest travel, against the code's work of the
    push, which the energy balance reads: the code takes the barrier's
    part as the change of its potential and sums friction's dissipation,
    so the two are independent sums of one work. Measured 0.3 % apart on
    the default lens (doc/validation.md); the rows are the quadrature's
    only nodes."""
    rows = read_rows(os.path.join(output, "plunger_force.csv"))
    x = np.array([float(r["plunger_displacement"]) for r in rows])
    f = np.array([float(r["force_n"]) for r in rows])
    end = int(np.argmax(x)) + 1
    trapezoids = float(trapezoid_work(x[:end], f[:end])[-1])
    print(f"plunger_force.csv: the force over the travel, by trapezoids, "
          f"{trapezoids:.5g} N mm ({100 * (trapezoids / work - 1):+.2f} % of "
          f"the code's {work:.5g} N mm)")
    checks("plunger_force.csv's force over its travel is the push's work "
           "(1 %)", abs(trapezoids - work) <= 0.01 * abs(work))


def check_sleeve_force(checks, forces, args, output):
    """With the plunger's sleeve on (injection.prm's Contact/Obstacle 7),
    its sleeve_force.csv against its rows of contact_forces.csv, and its
    largest push."""
    if not os.path.exists(os.path.join(output, "sleeve_force.csv")):
        return
    ok, sentence = force_file_check(output, "sleeve_force.csv", args.sleeve,
                                    (1, 0, 0), "plunger_sleeve_displacement")
    print(sentence)
    checks("coshell's sleeve_force.csv has the sleeve's rows of "
           "contact_forces.csv", ok)
    _, _, _, push, work = plunger_rows(forces, args.sleeve)
    print(f"plunger's sleeve: largest force {1e3 * push.max():.4g} mN, "
          f"work {work[-1]:.5g} N mm")


def check_plunger_force(checks, forces, args, output):
    _, time, displacement, push, work_so_far = plunger_rows(
        forces, args.plunger)
    ok, sentence = force_file_check(output, "plunger_force.csv", args.plunger,
                                    (1, 0, 0), "plunger_displacement")
    print(sentence)
    checks("coshell's plunger_force.csv (time,plunger_displacement,force_n) "
           "has the plunger's rows of contact_forces.csv", ok)
    check_sleeve_force(checks, forces, args, output)
    largest = push.max() if len(push) else math.nan
    print(f"plunger: largest force {1e3 * largest:.4g} mN, travel "
          f"{displacement.max():.4g} mm")
    averaged, work = travel_measures(displacement, push, work_so_far)
    print(f"plunger: largest force over 0.5 mm of travel "
          f"{1e3 * averaged:.4g} mN, work of the push {work:.5g} N mm")
    check_force_file_work(checks, output, work)
    # Positive: the plunger pushes. Its friction may pull the lens back a
    # little where the lens runs ahead of it (-0.03 mN against a 44 mN
    # peak on the coarse lens), so a pull is allowed up to 1 % of the peak.
    smallest = push.min() if len(push) else math.nan
    print(f"plunger: smallest force {1e3 * smallest:.4g} mN")
    checks("the plunger force is finite and positive (a pull of at most "
           "1 % of its peak)",
           bool(np.all(np.isfinite(push))) and largest > 0
           and smallest >= -0.01 * largest)
    return time, displacement, push


def optic_in_nozzle(history, start, tip):
    """Per step, whether the optic's centre and both rim points (at x = 0
    at rest) lie inside the nozzle, from x = start to tip (mm): as the
    centre reaches the tip a rim point may already be out and opening
    (x = 16.7 at the tip in a frictionless run), and earlier one may still
    be in the taper."""
    inside = np.ones(len(history), dtype=bool)
    for point in ("optic_ux", "rim_yp_ux", "rim_ym_ux"):
        x = column(history, point)
        inside &= (x > start) & (x < tip)
    return inside


def check_fold_and_exit(checks, history, args):
    chord = rim_chord(history)
    centre_x = column(history, "optic_ux")
    # The width counts while the centre and both rim points are inside.
    in_nozzle = optic_in_nozzle(history, args.nozzle_start, args.nozzle_tip)
    folded = chord[in_nozzle].max() if in_nozzle.any() else math.inf
    print(f"optic width across the axis: {chord[0]:.4g} mm at rest, at most "
          f"{folded:.4g} mm while its centre and rim are in the nozzle "
          f"(inner diameter {2 * args.nozzle_radius:.4g} mm; "
          f"{int(in_nozzle.sum())} steps)")
    # Passes: from before the nozzle's start to beyond its tip, so that
    # the width above was checked along the whole nozzle, not at one step.
    print(f"optic centre: x = {centre_x.min():.4g} to {centre_x.max():.4g} mm "
          f"(nozzle {args.nozzle_start:g} to {args.nozzle_tip:g} mm)")
    passes = (centre_x.min() < args.nozzle_start
              and centre_x.max() > args.nozzle_tip)
    checks("the optic folds to the nozzle's diameter and its centre passes "
           "the nozzle", passes and folded <= 2 * args.nozzle_radius)
    trailing = TRAILING_END_X + column(history, "trail_ux")
    print(f"trailing haptic's end: x = {trailing.max():.4g} mm at most "
          f"(nozzle tip {args.nozzle_tip} mm)")
    checks("the whole lens leaves the nozzle's tip",
           trailing.max() > args.nozzle_tip)
    return chord


def rigid_fit_deviation(reference, current):
    """Largest distance between 'current' and the best rigid motion of
    'reference' (Kabsch)."""
    a = reference - reference.mean(axis=0)
    b = current - current.mean(axis=0)
    u, _, vt = np.linalg.svd(a.T @ b)
    sign = np.sign(np.linalg.det(u @ vt))
    rotation = u @ np.diag([1.0, 1.0, sign]) @ vt
    return np.linalg.norm(a @ rotation - b, axis=1).max()


def final_lens(output):
    frames = render_vtu.read_pvd(os.path.join(output, "solution.pvd"))
    mesh = render_vtu.read_vtu(frames[-1].shell_file)
    optic = mesh.point_data["material_id"].astype(int).ravel() == 1
    current = render_vtu.deformed_positions(mesh, 1.0)
    return mesh.points, current, optic, frames


def check_deployment(checks, history, args, output):
    kinetic = column(history, "kinetic_energy")
    print(f"kinetic energy: peak {kinetic.max():.3g}, end {kinetic[-1]:.3g} "
          "N mm")
    checks("the lens comes to rest in the bag (end kinetic energy below 1 % "
           "of its peak)", kinetic[-1] <= 0.01 * kinetic.max())
    reference, current, optic, frames = final_lens(output)
    # Each vertex once (the VTU repeats a vertex in every cell), as coshell
    # counts them.
    _, first = np.unique(reference[optic], axis=0, return_index=True)
    deviation = rigid_fit_deviation(reference[optic][first],
                                    current[optic][first])
    theirs = column(history, "optic_shape_deviation")[-1]
    print(f"optic's deviation from its rest shape: {deviation:.6g} mm here, "
          f"{theirs:.6g} mm from coshell (optic_shape_deviation)")
    # The history's 6 digits and the VTU's single precision (half a unit in
    # the 24th bit of the largest coordinate, per coordinate of the two
    # points of a distance) bound the difference.
    single = 4 * np.abs(current[optic]).max() * 2.0**-24
    checks("coshell's optic_shape_deviation agrees with that of the last "
           f"VTU (1e-5 of it and {single:.2g} mm for single precision)",
           abs(deviation - theirs) <= 1e-5 * deviation + single)
    _, first = np.unique(reference, axis=0, return_index=True)
    whole = rigid_fit_deviation(reference[first], current[first])
    print(f"largest deviation from the rest shape after a rigid fit: optic "
          f"{deviation:.4g} mm ({100 * deviation / args.optic_diameter:.3g} % "
          f"of its diameter), whole lens {whole:.4g} mm (haptics held by "
          "the bag)")
    recovered = deviation < args.shape_tolerance * args.optic_diameter
    shape = ("the optic recovers its shape: deviation below "
             f"{100 * args.shape_tolerance:g} % of its diameter")
    if args.shape_not_asserted:
        print(f"not asserted: {shape} ({'yes' if recovered else 'no'}): "
              f"{args.shape_not_asserted}")
    else:
        checks(shape, recovered)
    centre = np.asarray(args.bag_centre)
    equator, polar = args.bag_radii
    scaled = (current - centre) / np.array([equator, equator, polar])
    inside = np.linalg.norm(scaled, axis=1).max()
    checks("every lens vertex lies inside the bag", inside < 1)
    check_optic_pose(checks, history, current[optic], centre)
    print_tilt_components(current[optic], current[~optic], centre)
    check_optic_settled(checks, history, args.rest_window)
    return frames


def tilt_components(optic_points, haptic_points, centre):
    """The optic's tilt (degrees) split into its turn about the haptics'
    line (through the haptic vertex farthest from the bag's axis and the
    farthest one on the other side, seen along the axis) and about the
    line across it. Turning about the haptics' line moves neither of the
    two contacts that hold the lens in the rigid bag."""
    optic = np.unique(optic_points, axis=0)
    normal = np.linalg.svd(optic - optic.mean(axis=0))[2][2]
    radial = (np.unique(haptic_points, axis=0) - centre)[:, :2]
    reach = np.linalg.norm(radial, axis=1)
    far = radial[np.argmax(reach)]
    beyond = radial @ far < 0
    other = radial[beyond][np.argmax(reach[beyond])]
    line = (far - other) / np.linalg.norm(far - other)
    across = np.array([-line[1], line[0]])
    return (math.degrees(math.asin(min(1.0, abs(normal[:2] @ across)))),
            math.degrees(math.asin(min(1.0, abs(normal[:2] @ line)))))


def print_tilt_components(optic_points, haptic_points, centre):
    """Reported, not asserted: the rest pose's turn about the haptics'
    line depends on the path (doc/validation.md, "The lens at rest")."""
    about_line, across = tilt_components(optic_points, haptic_points,
                                         centre)
    print(f"optic tilt about the haptics' line {about_line:.3g} degrees "
          "(a turn that moves neither haptic's contact with the bag), "
          f"about the line across it {across:.3g} degrees")


def check_optic_settled(checks, history, window):
    """The decentration and tilt reported at the end are the optic's at
    rest: over the last 'window' seconds they changed by less than 0.01
    mm and 0.25 degrees. A kinetic energy near zero does not show it: in
    the viscous medium the optic turned at 2 degrees/s, with a kinetic
    energy of 1e-9 of its peak, at the end of the 1 s deploy stage."""
    t = column(history, "time")
    recent = t >= t[-1] - window
    changes = {}
    for name in ("optic_decentration", "optic_tilt"):
        values = column(history, name)[recent]
        changes[name] = values.max() - values.min()
    print(f"over the last {window:g} s: decentration changed by "
          f"{changes['optic_decentration']:.3g} mm, tilt by "
          f"{changes['optic_tilt']:.3g} degrees")
    checks(f"the optic is at rest: over the last {window:g} s its "
           "decentration changed by less than 0.01 mm and its tilt by less "
           "than 0.25 degrees", changes["optic_decentration"] < 0.01
           and changes["optic_tilt"] < 0.25)


def check_optic_pose(checks, history, optic_points, centre):
    """coshell's optic_decentration, optic_axial and optic_tilt (Quantities
    of interest/Region poses) at the last step against the same measures
    computed here from the last VTU: the centroid of the optic's vertices
    (each once; the VTU repeats a vertex in every cell) and the normal of
    their least-squares plane, against the bag's axis along z."""
    points = np.unique(optic_points, axis=0)
    centroid = points.mean(axis=0)
    normal = np.linalg.svd(points - centroid)[2][2]
    ours = {"optic_decentration": np.linalg.norm((centroid - centre)[:2]),
            "optic_axial": centroid[2] - centre[2],
            "optic_tilt": math.degrees(math.acos(min(1.0, abs(normal[2]))))}
    theirs = {name: column(history, name)[-1] for name in ours}
    print(f"at rest in the bag: optic decentration "
          f"{theirs['optic_decentration']:.4g} mm, tilt "
          f"{theirs['optic_tilt']:.3g} degrees, axial position "
          f"{theirs['optic_axial']:.4g} mm from the equator plane (coshell; "
          f"from the VTU here: {ours['optic_decentration']:.4g} mm, "
          f"{ours['optic_tilt']:.3g} degrees, {ours['optic_axial']:.4g} mm)")
    # The VTU's single-precision positions (about 1e-6 mm here) bound the
    # difference.
    checks("coshell's optic decentration, axial position and tilt agree with "
           "those of the last VTU (1e-4 mm, 0.01 degrees)",
           abs(ours["optic_decentration"] - theirs["optic_decentration"])
           < 1e-4 and abs(ours["optic_axial"] - theirs["optic_axial"]) < 1e-4
           and abs(ours["optic_tilt"] - theirs["optic_tilt"]) < 1e-2)


def check_energy(checks, history, forces, args):
    check_energy_balance(checks, history, forces, args.energy_tolerance,
                         "the plunger, wings and rod (and the sleeve)",
                         plunger=args.plunger)


def check_fold(checks, history, args):
    """The fold stage alone: the optic rolled up in the closed wings.
    Returns the last frame written."""
    chord = rim_chord(history)
    print(f"optic width across the axis: {chord[0]:.4g} mm at rest, "
          f"{chord[-1]:.4g} mm folded")
    checks(f"the wings fold the optic to {args.fold_only:g} mm or less",
           chord[-1] <= args.fold_only)
    last = render_vtu.read_pvd(os.path.join(args.output, "solution.pvd"))[-1]
    check_strain_fields(checks, history, last)
    return last


def check_junctions(checks, args):
    """The rest lens at the haptic-optic junctions, from the first VTU
    (deal.II writes each cell's own copies of its vertices: merged here
    by position): the fillets' outline and the local refinement."""
    first = render_vtu.read_pvd(os.path.join(args.output, "solution.pvd"))[0]
    mesh = render_vtu.read_vtu(first.shell_file)
    triangles = np.array([mesh.cell_vertices[start:start + 3] for start in
                          mesh.cell_starts[mesh.cell_sizes == 3]])
    points, merged = np.unique(np.round(mesh.points, 6), axis=0,
                               return_inverse=True)
    cells = merged.reshape(-1)[triangles]
    if args.junction_fillet:
        check_fillets(checks, points, cells, args.junction_fillet,
                      args.haptic_type)
    if args.junction_refined:
        size, radius = args.junction_refined
        check_refinement(checks, points, cells, args.junction_fillet or 0.0,
                         size, radius, args.haptic_type)


def check_strain_fields(checks, history, frame):
    """The VTU's per-cell strains against the time history's largest ones
    of the same step: the same recovery, written two ways (VTU in float32).
    Reports where and how large the surface strain is."""
    row = min(history, key=lambda r: abs(float(r["time"]) - frame.time))
    mesh = render_vtu.read_vtu(frame.shell_file)
    cells = {name: render_vtu.cell_field(mesh, name + "_strain")
             for name in ("membrane", "bending", "surface")}
    for name in ("membrane", "bending", "surface"):
        listed = float(row[f"max_{name}_strain"])
        drawn = float(np.max(cells[name]))
        checks(f"largest {name} strain of the VTU at t = {frame.time:.6g} s "
               f"({drawn:.6g}) is the time history's ({listed:.6g})",
               abs(drawn - listed) <= 1e-6 * listed)
    material = render_vtu.cell_field(mesh, "material_id")
    worst = int(np.argmax(cells["surface"]))
    print(f"largest surface strain {cells['surface'][worst]:.4g} in a cell "
          f"of material {int(round(material[worst]))} (1 optic, 2 haptic)")


# The nozzle's constants of injection.prm and the values for a scene
# without them (mm).
NOZZLE = {"nozzle_radius": 1.75, "nozzle_start": 11.5, "nozzle_tip": 15.0}


def take_nozzle_from_run(args):
    """The nozzle's dimensions not given on the command line are those the
    run used: its constants in summary.json (Changes applied), so that a
    nozzle changed with --set "Constants/Changes=nozzle_radius = ..." is
    checked as built."""
    with open(os.path.join(args.output, "summary.json")) as f:
        constants = json.load(f).get("constants", {})
    for name, fallback in NOZZLE.items():
        if getattr(args, name) is None:
            setattr(args, name, constants.get(name, fallback))
    print(f"nozzle: inner radius {args.nozzle_radius:g} mm from x = "
          f"{args.nozzle_start:g} to {args.nozzle_tip:g} mm")


def check_stage_times(checks, summary):
    """summary.json's dynamic_stages add up: their simulated times to
    simulated_time_s, their wall times to the time stepping's total."""
    stages = summary.get("dynamic_stages", [])
    simulated = sum(s["simulated_time_s"] for s in stages)
    wall = sum(s["wall_time_s"] for s in stages)
    total = summary["time_stepping_s"]["total"]
    checks("the dynamic stages' simulated and wall times add up to the "
           "run's (1e-9 and 1e-6 relative)", bool(stages)
           and abs(simulated - summary["simulated_time_s"])
           <= 1e-9 * summary["simulated_time_s"]
           and abs(wall - total) <= 1e-6 * total)


def print_stage_speeds(summary):
    """The real-time factor of each dynamic stage, and of the surgical
    scene, stages 1 to 3 (fold, push, deploy), without the wait for the
    lens to settle (stage 4), whose slow, cheap steps would flatter it."""
    stages = summary.get("dynamic_stages", [])
    for stage in stages:
        print(f"stage {stage['stage']}: {stage['simulated_time_s']:.4g} s "
              f"simulated in {stage['wall_time_s']:.4g} s, real-time factor "
              f"{stage['real_time_factor']:.3g}")
    if stages:
        print(f"stages 1 to 3 (the injection without the settling): "
              f"real-time factor {surgical_real_time_factor(summary):.3g}")


def main():
    args = parse_arguments()
    checks, forces, history = run_contact_scene(
        args, "lens against the wings, rod, cartridge, plunger, bag and "
        "itself")
    take_nozzle_from_run(args)
    if args.junction_fillet or args.junction_refined:
        check_junctions(checks, args)
    if args.fold_only is not None:
        last = check_fold(checks, history, args)
        check_energy(checks, history, forces, args)
        if args.figures:
            import checker_figures
            checks("the folded lens and its strain are drawn",
                   checker_figures.folded_lens_pictures(args.figures, last))
        checks.exit()
    time, displacement, push = check_plunger_force(checks, forces, args,
                                                   args.output)
    chord = check_fold_and_exit(checks, history, args)
    frames = check_deployment(checks, history, args, args.output)
    check_strain_fields(checks, history, render_vtu.read_pvd(
        os.path.join(args.output, "solution.pvd"))[-1])
    check_energy(checks, history, forces, args)
    with open(os.path.join(args.output, "summary.json")) as f:
        summary = json.load(f)
    print(f"real-time factor {summary['real_time_factor']:.3g} "
          f"({summary['simulated_time_s']:.3g} s simulated, "
          f"{summary['steps']} steps, {summary['newton_iterations']} Newton "
          "iterations)")
    print_stage_speeds(summary)
    check_stage_times(checks, summary)
    if args.figures:
        import checker_figures
        checker_figures.injection_history(args, history, time, displacement,
                                          push, chord)
        checks("the folded lens and the sequence are drawn",
               checker_figures.injection_pictures(args, history, frames))
    checks.exit()


if __name__ == "__main__":
    main()
