#!/usr/bin/python3
"""Geometrically nonlinear peer comparison with CalculiX: the two Sze, Liu
& Lo (2004) benchmarks, the pinched hemisphere with an 18-degree hole
(3.4) and the slit annular plate (3.3), solved along the whole load path
by CalculiX shells (NLGEOM) and by coshell, timed on the same machine in
the same run at the accuracy each reaches against the published tables.

  scripts/calculix_nonlinear_compare.py [--coshell build/coshell]
      [--work /tmp/calculix_nonlinear_compare] [--output doc/calculix]
      [--benchmarks hemisphere slit_plate] [--codes calculix coshell]
      [--elements S4 S8R C3D8I C3D20R] [--hemisphere-n 8 16 32]
      [--hemisphere-levels 1 2 3] [--plate-calculix 3x15 6x30 12x60]
      [--plate-coshell 6x30 12x60 16x80 24x120] [--max-seconds 120]
      [--repeats 3]

Scenes: coshell runs prm/benchmarks/pinched_hemisphere.prm (Refinement
levels = k: 4*2^k squares per side, each cut in two triangles) and
prm/benchmarks/slit_annular_plate.prm (Subdivisions x, y = NR, NT in r
and theta) as they are. The CalculiX decks model the same problems on
structured quads:
  hemisphere: the quarter between the equator, the meridians at longitude
    0 and 90 degrees and the hole edge at latitude 72 degrees, mapped from
    the unit square by longitude and latitude (the boundary spacing of
    meshes/pinched_hemisphere.geo), n x n quads. Symmetry on y = 0 and on
    x = 0; the hole corner (3.09, 0, 9.51) held in z; 200 along +x at
    (10, 0, 0) and along -y at (0, 10, 0), fixed in direction.
  slit plate: NR x NT quads in (r, theta), theta in [0, 2 pi - 1e-5];
    theta = 0 clamped; the line force 0.8 per length along +z on
    theta = 2 pi - 1e-5 as consistent nodal forces (quadratic: 1/6, 4/6,
    1/6 of each edge's 0.8 * 4 / NR; linear: half each).
Elements (--elements): shells S4 (CalculiX expands it to C3D8I), S8R
(C3D20R; midside nodes on the true geometry), S4R, S8; and C3D8I, C3D20R
(or C3D8R, C3D20): one layer of bricks through the thickness written out
by this script, i.e. CalculiX's own expansion of S4 / S8R without its
constraint equations (coarsest meshes: within 6e-4 of the shells on the
plate; on the hemisphere C3D20R = S8R to 4e-5 up to load factor 0.4, and
C3D8I 0.5 % below S4, whose nodal normals CalculiX averages over facets).
Shell boundary conditions: a shell node without a knot takes a rotational
SPC as a nonlinear mean-rotation MPC of its expanded nodes, the axis
projected onto the tangent plane; two rotations in one plane of symmetry
(x = 0: dofs 5 and 6) project onto one tangent and CalculiX 2.20 then
adds a second MPC about the other tangent, locking the symmetry line.
So each symmetry node fixes its translation normal to the plane and the
one rotation whose axis is more nearly perpendicular to its normal
(y = 0: about x or z; x = 0: about y or z); the clamp fixes dofs 1-5 (6 is
the drilling rotation). On the hemisphere these MPCs stall S8R's Newton
iterations near load factor 0.45 (too many cutbacks); the brick decks
need no MPCs: symmetry and clamp fix the translations of all
through-thickness nodes, the z hold one node, and a mid-surface nodal
force is spread over a node's through-thickness nodes (1/6, 4/6, 1/6 or
1/2, 1/2); outputs are the mid-thickness node or the mean of bottom and
top.
Load path: *STEP, NLGEOM, *STATIC with CalculiX's default automatic
increment control (first increment 0.025 of the step, at most 0.05),
output by *NODE PRINT at *TIME POINTS every 0.05 of the load (increments
are cut to land on them), the load factors coshell's 20 steps reach; the
errors
are |value / reference - 1| at those load factors (the reference's
extra plate rows at 0.025, 0.075 and 0.125 are not used), worst over the
path and at load factor 1 for each of the two points. coshell outputs the
same factors (its scene's 20 steps, sub-stepped where it cuts back).

Timing as in scripts/calculix_compare.py (whose helpers this imports):
every run is a whole process timed inside `flock /tmp/coshell-measure.lock`,
ccx with OMP_NUM_THREADS=1, coshell with Parallel/Threads=1,
OPENBLAS_NUM_THREADS=1 and DEAL_II_NUM_THREADS=1; runs under 10 s are
repeated in --repeats rounds over all cases, best time kept. Each run is
killed after --max-seconds; a code/element stops at its first mesh that
times out (runs that fail to converge are kept, marked, and not timed).
Writes
calculix_nonlinear.csv, hemisphere_nonlinear.png and
slit_plate_nonlinear.png into --output and prints, for error targets at
full load, the fastest run of each code reaching it and the time ratio.
Needs ccx (Debian calculix-ccx) and /usr/bin/python3 with matplotlib.
"""
import argparse
import csv
import json
import math
import os
import re
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from calculix_compare import (LOCK, ROOT, ccx_version, equations,  # noqa: E402
                              fastest, repeat_short_runs, run_timed,
                              structured_quads)
from doc_common import finish_plot, machine_and_commit, write_csv  # noqa: E402
from sze_benchmarks import CASES, read_table  # noqa: E402

FIELDS = ["benchmark", "code", "element", "mesh", "level", "n_nodes", "n_dofs",
          "increments", "newton_iterations", "max_load_factor", "worst_error_on_path",
          "value_full_load_p1", "value_full_load_p2", "error_full_load_p1",
          "error_full_load_p2", "error_full_load", "process_wall_s", "status"]
TARGETS = (2e-2, 1e-2, 5e-3)
LOAD_FACTORS = [round(0.05 * k, 6) for k in range(1, 21)]  # coshell's 20 load steps
HEMISPHERE_RADIUS, HOLE_LATITUDE = 10.0, math.radians(72.0)
PLATE_RADII, PLATE_ANGLE = (6.0, 10.0), 2 * math.pi - 1e-5

BENCHMARKS = {
    "hemisphere": dict(
        case="pinched_hemisphere", prm="prm/benchmarks/pinched_hemisphere.prm",
        material=("6.825e7, 0.3", "0.04"),
        # qoi of sze_benchmarks.CASES: (s, t) on the unit square, component
        points={"pulled_ux": (0.0, 0.0, 0), "pushed_uy": (1.0, 0.0, 1)}),
    "slit_plate": dict(
        case="slit_annular_plate", prm="prm/benchmarks/slit_annular_plate.prm",
        material=("21e6, 0.0", "0.03"),
        points={"w_A": (0.0, 1.0, 2), "w_B": (1.0, 1.0, 2)}),
}


# ---------------------------------------------------------------- meshes

def hemisphere_point(s, t):
    """Longitude s * 90 degrees, latitude t * 72 degrees."""
    longitude, latitude = s * math.pi / 2, t * HOLE_LATITUDE
    return (HEMISPHERE_RADIUS * math.cos(latitude) * math.cos(longitude),
            HEMISPHERE_RADIUS * math.cos(latitude) * math.sin(longitude),
            HEMISPHERE_RADIUS * math.sin(latitude))


def plate_point(s, t):
    """Radius 6 + 4 s, angle t (2 pi - 1e-5)."""
    radius = PLATE_RADII[0] + s * (PLATE_RADII[1] - PLATE_RADII[0])
    return (radius * math.cos(t * PLATE_ANGLE), radius * math.sin(t * PLATE_ANGLE), 0.0)


# ---------------------------------------------------------------- decks

def sphere_normal(point):
    return [c / HEMISPHERE_RADIUS for c in point]


def symmetry_rotation(normal, in_plane_axes):
    """The rotational dof (4, 5, 6) about whichever of the two in-plane
    axes is the more nearly perpendicular to the shell normal."""
    return min(in_plane_axes, key=lambda axis: abs(normal[axis - 4]))


def hemisphere_model(points, by_parameter, quadratic):
    """Constraints [(node, dofs, through the thickness?)], nodal forces
    [(node, dof, value)] on the mid-surface nodes (0-based), normals."""
    constraints = []
    for (s, t), k in by_parameter.items():
        normal = sphere_normal(points[k])
        if s == 0.0:  # y = 0: u_y, rotation about x or z
            constraints.append((k, (2, symmetry_rotation(normal, (4, 6))), True))
            if t == 1.0:  # the hole corner (3.09, 0, 9.51), held in z
                constraints.append((k, (3,), False))
        if s == 1.0:  # x = 0: u_x, rotation about y or z
            constraints.append((k, (1, symmetry_rotation(normal, (5, 6))), True))
    forces = [(by_parameter[0.0, 0.0], 1, 200.0), (by_parameter[1.0, 0.0], 2, -200.0)]
    return constraints, forces, sphere_normal


def plate_model(points, by_parameter, quadratic):
    """Clamp at theta = 0 (rotation about the normal z is no dof of an
    expanded shell node), consistent nodal forces on theta = 2 pi - 1e-5."""
    constraints = [(k, (1, 2, 3, 4, 5), True) for (s, t), k in by_parameter.items() if t == 0.0]
    loaded = sorted((s, k) for (s, t), k in by_parameter.items() if t == 1.0)
    force = {k: 0.0 for _, k in loaded}
    step = 2 if quadratic else 1
    weights = (1 / 6, 4 / 6, 1 / 6) if quadratic else (0.5, 0.5)
    for e in range(0, len(loaded) - 1, step):
        edge = loaded[e:e + step + 1]
        length = (edge[-1][0] - edge[0][0]) * (PLATE_RADII[1] - PLATE_RADII[0])
        for (_, k), weight in zip(edge, weights):
            force[k] += weight * 0.8 * length
    return constraints, [(k, 3, f) for k, f in sorted(force.items())], lambda p: [0.0, 0.0, 1.0]


def solid_layer(points, quads, normal, thickness, quadratic):
    """One layer of C3D8(I/R) or C3D20(R) bricks through the thickness:
    the expansion CalculiX makes of S4 / S8 shells, written out. Returns
    the nodes, the bricks and, per mid-surface node, its through-thickness
    nodes with the weights of a force at the mid-surface node (0-based)."""
    corners = {k for quad in quads for k in quad[:4]}
    nodes, layers = [], []
    for k, p in enumerate(points):
        n = normal(p)
        offsets = (-0.5, 0.0, 0.5) if quadratic and k in corners else (-0.5, 0.5)
        layers.append([])
        for offset in offsets:
            layers[-1].append(len(nodes))
            nodes.append(tuple(x + offset * thickness * c for x, c in zip(p, n)))
    bricks = []
    for quad in quads:
        bottom = [layers[k][0] for k in quad]
        top = [layers[k][-1] for k in quad]
        if quadratic:  # corners, mid-edges bottom and top, vertical mid-edges
            bricks.append(bottom[:4] + top[:4] + bottom[4:] + top[4:] + [layers[k][1] for k in quad[:4]])
        else:
            bricks.append(bottom + top)
    weights = [(1 / 6, 4 / 6, 1 / 6) if len(layer) == 3 else (0.5, 0.5) for layer in layers]
    return nodes, bricks, [list(zip(layer, w)) for layer, w in zip(layers, weights)]


def mid_surface(layer):
    """1-based nodes and weights giving a mid-surface node's displacement:
    itself, the mid-thickness node, or the mean of bottom and top."""
    if len(layer) == 3:
        return [(layer[1][0] + 1, 1.0)]
    return [(j + 1, 1.0 / len(layer)) for j, _ in layer]


def write_deck(path, benchmark, element, nx, ny):
    """Shell elements (S...) on the mid-surface, or their one-layer solid
    equivalent (C3D...) with the rotational constraints replaced by the
    translational ones on all through-thickness nodes. Returns the node
    count and {qoi: [(node, weight)]} (1-based) for the output."""
    spec = BENCHMARKS[benchmark]
    quadratic = element[1:].startswith("8") or element.startswith("C3D20")
    point = hemisphere_point if benchmark == "hemisphere" else plate_point
    points, quads, by_parameter = structured_quads(nx, ny, point, quadratic)
    model = hemisphere_model if benchmark == "hemisphere" else plate_model
    constraints, forces, normal = model(points, by_parameter, quadratic)
    if element.startswith("S"):
        nodes, elements = points, quads
        section = f"SHELL SECTION, ELSET=EALL, MATERIAL=SHELL\n{spec['material'][1]}"
        through = [[(k, 1.0)] for k in range(len(points))]
        boundary = [f"{k + 1}, {dof}, {dof}" for k, dofs, _ in constraints for dof in dofs]
    else:
        nodes, elements, through = solid_layer(points, quads, normal, float(spec["material"][1]), quadratic)
        section = "SOLID SECTION, ELSET=EALL, MATERIAL=SHELL"
        boundary = [f"{j + 1}, {dof}, {dof}" for k, dofs, all_nodes in constraints
                    for j, _ in (through[k] if all_nodes else through[k][:1]) for dof in dofs if dof <= 3]
    loads = [f"{j + 1}, {dof}, {value * weight:.12g}" for k, dof, value in forces for j, weight in through[k]]
    output = {qoi: mid_surface(through[by_parameter[s, t]]) for qoi, (s, t, _) in spec["points"].items()}
    with open(path, "w") as f:
        f.write("*NODE, NSET=NALL\n")
        f.writelines(f"{i}, {x:.12g}, {y:.12g}, {z:.12g}\n"
                     for i, (x, y, z) in enumerate(nodes, start=1))
        f.write(f"*ELEMENT, TYPE={element}, ELSET=EALL\n")
        for i, element_nodes in enumerate(elements, start=1):
            ids = [str(i)] + [str(n + 1) for n in element_nodes]
            f.write(",\n".join(", ".join(ids[j:j + 16]) for j in range(0, len(ids), 16)) + "\n")
        qoi_nodes = sorted({j for nodes_and_weights in output.values() for j, _ in nodes_and_weights})
        f.write("*NSET, NSET=QOI\n" + ", ".join(map(str, qoi_nodes)) + "\n")
        f.write(f"*MATERIAL, NAME=SHELL\n*ELASTIC\n{spec['material'][0]}\n*{section}\n")
        f.write("*BOUNDARY\n" + "\n".join(boundary) + "\n")
        f.write("*TIME POINTS, NAME=PATH\n"
                + "\n".join(", ".join(f"{x:g}" for x in LOAD_FACTORS[i:i + 8])
                            for i in range(0, len(LOAD_FACTORS), 8)) + "\n")
        f.write("*STEP, NLGEOM, INC=10000\n*STATIC\n0.025, 1.0, 1e-6, 0.05\n")
        f.write("*CLOAD\n" + "\n".join(loads) + "\n")
        f.write("*NODE PRINT, NSET=QOI, TIME POINTS=PATH\nU\n*END STEP\n")
    return len(nodes), output


def read_dat_path(path, output, spec):
    """{load factor: {qoi: value}} from the *NODE PRINT blocks of the .dat
    (weighted over a point's through-thickness nodes for bricks)."""
    component = {qoi: c for qoi, (_, _, c) in spec["points"].items()}
    blocks, factor = {}, None
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        for line in f:
            match = re.search(r"displacements \(vx,vy,vz\) for set \S+ and time\s+(\S+)", line)
            if match:
                factor = round(float(match.group(1)), 6)
                continue
            fields = line.split()
            if factor is not None and len(fields) == 4 and fields[0].isdigit():
                blocks.setdefault(factor, {})[int(fields[0])] = [float(v) for v in fields[1:]]
    return {factor: {qoi: sum(w * values[j][component[qoi]] for j, w in nodes)
                     for qoi, nodes in output.items()}
            for factor, values in blocks.items() if all(j in values for n in output.values() for j, _ in n)}


def read_sta(path):
    """Converged increments (the .sta rows without a U(nconverged) mark)."""
    if not os.path.exists(path):
        return ""
    with open(path) as f:
        return sum(1 for line in f if re.match(r"\s+\d+\s+\d+\s+\d+\s+\d+\s", line))


# ---------------------------------------------------------------- errors

def path_errors(benchmark, path):
    """Errors of a {load factor: {qoi: value}} path (coshell's signs)
    against the Sze table: worst over the rows reached, and per point at
    load factor 1."""
    _, table, columns, *_ = CASES[BENCHMARKS[benchmark]["case"]]
    reference = {round(float(r["load_factor"]), 6): r
                 for r in read_table(os.path.join(ROOT, "tests", "data", table))}
    worst = 0.0
    for factor, values in path.items():
        if factor in LOAD_FACTORS:  # the rows both codes output
            for column, qoi, sign in columns:
                worst = max(worst, abs(sign * values[qoi] / float(reference[factor][column]) - 1))
    result = dict(max_load_factor=f"{max(path, default=0):g}",
                  worst_error_on_path=f"{worst:.4e}" if path else "")
    if 1.0 in path:
        errors = []
        for p, (column, qoi, sign) in enumerate(columns, start=1):
            value = sign * path[1.0][qoi]
            errors.append(abs(value / float(reference[1.0][column]) - 1))
            result[f"value_full_load_p{p}"] = f"{value:.6g}"
            result[f"error_full_load_p{p}"] = f"{errors[-1]:.4e}"
        result["error_full_load"] = f"{max(errors):.4e}"
    return result


def add_errors(row, benchmark, path):
    """The errors of the path into the row; a run that ended without
    error before the full load is marked."""
    row.update(path_errors(benchmark, path))
    if row["status"] == "ok" and "error_full_load" not in row:
        row["status"] = f"stopped at load factor {row['max_load_factor']}"
    return row


def full_load_error(row):
    return float(row["error_full_load"]) if row.get("error_full_load") else math.inf


# ---------------------------------------------------------------- runs

def timed(args, command, cwd, env):
    """(seconds, stdout) of a whole process under the measurement lock and
    `timeout --max-seconds`, or (None, reason) if it failed."""
    try:
        return run_timed(["timeout", f"{args.max_seconds:g}"] + command, cwd, env)
    except RuntimeError as error:
        seconds = float((re.findall(r"TIMED_EXEC (\S+)", str(error)) or ["nan"])[-1])
        if seconds >= 0.99 * args.max_seconds:
            return None, f"timeout after {args.max_seconds:g} s"
        errors = re.findall(r"\*ERROR[^\n]*", str(error))
        return None, f"failed after {seconds:.3g} s" + (f" ({errors[-1].strip()})" if errors else "")


def run_calculix(args, benchmark, element, mesh):
    nx, ny = mesh
    spec = BENCHMARKS[benchmark]
    directory = os.path.join(args.work, benchmark, f"{element}-{nx}x{ny}")
    os.makedirs(directory, exist_ok=True)
    for stale in ("deck.dat", "deck.sta"):
        if os.path.exists(os.path.join(directory, stale)):
            os.remove(os.path.join(directory, stale))
    n_nodes, output = write_deck(os.path.join(directory, "deck.inp"), benchmark, element, nx, ny)
    seconds, stdout = timed(args, [args.ccx, "-i", "deck"], directory,
                            {"OMP_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1"})
    path = read_dat_path(os.path.join(directory, "deck.dat"), output, spec)
    increments = read_sta(os.path.join(directory, "deck.sta"))
    iterations = len(re.findall(r"^ iteration \d+\s*$", stdout, re.M)) if seconds else ""
    row = dict(benchmark=spec["case"], code="calculix", element=element, mesh=f"{nx}x{ny}",
               level="", n_nodes=n_nodes, n_dofs=equations(stdout) if seconds else "",
               increments=increments, newton_iterations=iterations,
               process_wall_s=f"{seconds:.4f}" if seconds else "",
               status="ok" if seconds else stdout)
    return add_errors(row, benchmark, path)


def run_coshell(args, benchmark, mesh):
    spec = BENCHMARKS[benchmark]
    if benchmark == "hemisphere":
        label, sets = f"level {mesh}", [f"Mesh/Refinement levels={mesh}"]
        n = 4 * 2 ** mesh
        mesh_name, level = f"{n}x{n}", mesh
    else:
        nr, nt = mesh
        label, sets = f"{nr}x{nt}", [f"Mesh/Subdivisions x={nr}", f"Mesh/Subdivisions y={nt}"]
        mesh_name, level = f"{nr}x{nt}", ""
    directory = os.path.join(args.work, benchmark, f"coshell-{label.replace(' ', '')}")
    command = [args.coshell, os.path.join(ROOT, spec["prm"]), "--output", directory,
               "--set", "Output/Write VTU=false", "--set", "Parallel/Threads=1"]
    for setting in sets:
        command += ["--set", setting]
    seconds, reason = timed(args, command, args.work, {
        "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "DEAL_II_NUM_THREADS": "1"})
    row = dict(benchmark=spec["case"], code="coshell", mesh=mesh_name, level=level,
               process_wall_s=f"{seconds:.4f}" if seconds else "",
               status="ok" if seconds else reason)
    path = {}
    if seconds:
        with open(os.path.join(directory, "summary.json")) as f:
            summary = json.load(f)
        with open(os.path.join(directory, "load_displacement.csv")) as f:
            path = {round(float(r["load_factor"]), 6): {q: float(r[q]) for q in spec["points"]}
                    for r in csv.DictReader(f)}
        row.update(element=summary["element"], n_nodes=summary["n_vertices"],
                   n_dofs=summary["n_dofs"], increments=summary["load_steps"],
                   newton_iterations=summary["newton_iterations"])
    return add_errors(row, benchmark, path)


def mesh_series(args, run_one, meshes):
    """(row, rerun) per mesh, coarse to fine, until a run times out (a
    finer mesh would too); rows of runs that failed or missed the full
    load come back with rerun None."""
    series = []
    for mesh in meshes:
        row = run_one(mesh)
        print(f"  {row['code']} {row.get('element', '')} {row['mesh']}: "
              f"full load {row.get('value_full_load_p1', '-')}, {row.get('value_full_load_p2', '-')} "
              f"(error {row.get('error_full_load', '-')}, path {row['worst_error_on_path']}) "
              f"in {row['process_wall_s'] or '-'} s [{row['status']}]", flush=True)
        ok = row["status"] == "ok" and row.get("error_full_load")
        series.append((row, (lambda m=mesh: run_one(m)) if ok else None))
        if row["status"].startswith("timeout"):
            break
    return series


def parse_mesh(text):
    nr, nt = text.lower().split("x")
    return int(nr), int(nt)


def run_benchmark(args, benchmark):
    if benchmark == "hemisphere":
        calculix_meshes = [(n, n) for n in args.hemisphere_n]
        coshell_meshes = args.hemisphere_levels
    else:
        calculix_meshes = [parse_mesh(m) for m in args.plate_calculix]
        coshell_meshes = [parse_mesh(m) for m in args.plate_coshell]
    series = []
    if "coshell" in args.codes:
        series += mesh_series(args, lambda m: run_coshell(args, benchmark, m), coshell_meshes)
    if "calculix" in args.codes:
        for element in args.elements:
            series += mesh_series(args, lambda m, e=element: run_calculix(args, benchmark, e, m),
                                  calculix_meshes)
    return series


# ---------------------------------------------------------------- report

def plot(rows, benchmark, path):
    figure, axes = plt.subplots(figsize=(7, 5))
    labels = sorted({(r["code"], r["element"]) for r in rows if r["status"] == "ok"})
    for index, (code, element) in enumerate(labels):
        mine = [r for r in rows if (r["code"], r["element"]) == (code, element)
                and r["status"] == "ok" and r.get("error_full_load")]
        axes.loglog([float(r["process_wall_s"]) for r in mine],
                    [max(full_load_error(r), 1e-6) for r in mine],
                    marker="o" if code == "coshell" else "s",
                    linestyle="-" if code == "coshell" else "--",
                    color=f"C{index % 10}", label=f"{code} {element}")
        for r in mine:
            axes.annotate(r["mesh"], (float(r["process_wall_s"]), max(full_load_error(r), 1e-6)),
                          fontsize=6, xytext=(3, 3), textcoords="offset points")
    for target in TARGETS:
        axes.axhline(target, color="gray", linewidth=0.6, linestyle=":")
    finish_plot(figure, axes, "process wall time [s], whole load path, 1 thread",
                "relative error at full load (worse point)",
                f"{BENCHMARKS[benchmark]['case'].replace('_', ' ')}, NLGEOM", path)
    plt.close(figure)


def converged(rows, code):
    return [r for r in rows if r["code"] == code and r["status"] == "ok"]


def describe(row):
    if row is None:
        return "not reached"
    return (f"{row['element']} {row['mesh']} ({row['n_dofs']} dofs): "
            f"{float(row['process_wall_s']):.3g} s")


def print_ratios(rows, benchmark):
    mine = [r for r in rows if r["benchmark"] == BENCHMARKS[benchmark]["case"]]
    print(f"\n{BENCHMARKS[benchmark]['case']} (error at full load, worse of the two points):")
    for target in TARGETS:
        ours = fastest(converged(mine, "coshell"), target, full_load_error)
        theirs = fastest(converged(mine, "calculix"), target, full_load_error)
        ratio = (f"; calculix / coshell {float(theirs['process_wall_s']) / float(ours['process_wall_s']):.1f}x"
                 if ours and theirs else "")
        print(f"  to {target:.1%}: coshell {describe(ours)}; calculix {describe(theirs)}{ratio}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--coshell", default=os.path.join(ROOT, "build", "coshell"))
    parser.add_argument("--ccx", default=shutil.which("ccx") or "ccx")
    parser.add_argument("--work", default="/tmp/calculix_nonlinear_compare")
    parser.add_argument("--output", default=os.path.join(ROOT, "doc", "calculix"))
    parser.add_argument("--benchmarks", nargs="+", default=list(BENCHMARKS), choices=list(BENCHMARKS))
    parser.add_argument("--codes", nargs="+", default=["calculix", "coshell"], choices=["calculix", "coshell"])
    parser.add_argument("--elements", nargs="+", default=["S4", "S8R", "C3D8I", "C3D20R"])
    parser.add_argument("--hemisphere-n", nargs="+", type=int, default=[8, 16, 32])
    parser.add_argument("--hemisphere-levels", nargs="+", type=int, default=[1, 2, 3])
    parser.add_argument("--plate-calculix", nargs="+", default=["3x15", "6x30", "12x60"])
    parser.add_argument("--plate-coshell", nargs="+", default=["6x30", "12x60", "16x80", "24x120"])
    parser.add_argument("--max-seconds", type=float, default=120.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    if "calculix" in args.codes and not shutil.which(args.ccx):
        sys.exit("ccx not found (Debian package calculix-ccx)")
    if "coshell" in args.codes and not os.access(args.coshell, os.X_OK):
        sys.exit(f"no coshell binary at {args.coshell} (--coshell)")
    # The runs start in their work directories.
    args.coshell, args.work = os.path.abspath(args.coshell), os.path.abspath(args.work)
    os.makedirs(args.output, exist_ok=True)
    series = []
    for benchmark in args.benchmarks:
        print(BENCHMARKS[benchmark]["case"], flush=True)
        os.makedirs(os.path.join(args.work, benchmark), exist_ok=True)
        series += run_benchmark(args, benchmark)
    repeat_short_runs(args, [item for item in series if item[1]])  # updates the rows
    rows = [row for row, _ in series]
    machine, commit = machine_and_commit()
    points = "; ".join(f"{BENCHMARKS[b]['case']}: p1 = {CASES[BENCHMARKS[b]['case']][2][0][0]}, "
                       f"p2 = {CASES[BENCHMARKS[b]['case']][2][1][0]}" for b in BENCHMARKS)
    header = [f"machine: {machine}", f"coshell commit: {commit} (binary {args.coshell})",
              f"CalculiX: {ccx_version(args.ccx)}" if "calculix" in args.codes else "CalculiX: not run",
              f"points: {points}; errors |value / reference - 1| against tests/data/sze_*.csv at "
              "the load factors 0.05, 0.10, ..., 1 (worst over the path; at 1 per point and the worse)",
              "n_nodes: coshell's vertices, calculix's shell or brick nodes; n_dofs: coshell's dofs, "
              "calculix's number of equations (of the expanded 3D model for shells). "
              "increments, newton_iterations: coshell's load steps and Newton iterations; "
              "calculix's converged increments (.sta) and all Newton iterations, cut-back attempts included",
              "process_wall_s: whole process, 1 thread, best of "
              f"{args.repeats} rounds (runs under 10 s) under flock {LOCK}; killed after "
              f"{args.max_seconds:g} s; command: scripts/calculix_nonlinear_compare.py"]
    write_csv(os.path.join(args.output, "calculix_nonlinear.csv"), rows, header, FIELDS)
    for benchmark in args.benchmarks:
        mine = [r for r in rows if r["benchmark"] == BENCHMARKS[benchmark]["case"]]
        plot(mine, benchmark, os.path.join(args.output, f"{benchmark}_nonlinear.png"))
        print_ratios(rows, benchmark)


if __name__ == "__main__":
    main()
