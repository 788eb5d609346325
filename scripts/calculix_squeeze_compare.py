#!/usr/bin/python3
"""Solid reference for a thick strip squeezed between two rigid plates
(issue #71): CalculiX C3D20R bricks at converged meshes, for validating
CoShell's thickness-stretch shell, whose thickness changes under face
pressure (compressible neo-Hookean law).

  scripts/calculix_squeeze_compare.py [--work /tmp/calculix_squeeze]
      [--output doc/calculix] [--cases frictionless friction_0.1]
      [--meshes 1x5 2x10 3x15 2x20 4x10] [--max-seconds 3600] [--threads 1]
      [--lock /tmp/coshell-measure.lock] [--reuse]

The problem (units mm, N, MPa):
  plate L x L x h, L = 10, h = 1 (h / L = 0.1); CalculiX
  *HYPERELASTIC, NEO HOOKE with C10 = E / (4 (1 + nu)) and
  D1 = 6 (1 - 2 nu) / E for E = 1, nu = 0.42 (the intraocular-lens
  material): U = C10 (J^(-2/3) I1 - 3) + (J - 1)^2 / D1 (CalculiX 2.20
  manual, *HYPERELASTIC: the NEO HOOKE line is C10, D1, temperature).
  Two rigid plates, larger than the plate, squeeze it symmetrically by
  s = (h - current thickness) / h from 0 to 0.30; quasi-static
  *STEP, NLGEOM; output at s = 0, 0.025, ..., 0.30 (*TIME POINTS every
  1/12 of the step; s = 0 is the unloaded state, force 0).
Symmetry: the quarter x, y in [0, L/2] with u_x = 0 on x = 0 and
u_y = 0 on y = 0, and the half thickness z in [0, h/2] with u_z = 0 on
the mid-surface z = 0; the plate meets the top face z = h/2. Forces are
for the full plate (4 x the quarter's), compressive positive, in N.
  frictionless: a frictionless rigid plate is exactly u_z = -s h / 2 on
    the top face with the in-plane motion free, so no contact is
    modelled; force = 4 |sum of RF_z over the top face|.
  friction_0.1: the plate is a slab of C3D8 bricks over
    x, y in [-L/20, 3 L/4], z in [h/2, h/2 + h/2], every node of which is
    prescribed (u_x = u_y = 0, u_z = -s h / 2): a rigid plate without
    *RIGID BODY. *CONTACT PAIR, TYPE=SURFACE TO SURFACE (penalty), slave
    the strip's top faces, master the slab's bottom faces;
    *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR with slope
    PENALTY_SLOPE (MPa/mm), *FRICTION mu = 0.1 with stick slope
    STICK_SLOPE (MPa/mm, elastic slip <= mu p / STICK_SLOPE). Force =
    4 |sum of RF_z over the slab|; the penetration is the largest normal
    overlap of *CONTACT PRINT CDIS over the slave integration points.
  analytic: the frictionless case is homogeneous uniaxial stress: with
    lambda3 = 1 - s, the in-plane stretch lp solves sigma_11 = 0 for
    CalculiX's neo-Hooke form and force = |sigma_33| (L lp)^2; the
    script prints the worst relative difference of the frictionless
    CalculiX runs from it (a check of the deck and the units).
Meshes (--meshes NxM): N C3D20R bricks through the half thickness and
M x M over the quarter. 1x5, 2x10, 3x15 are bricks twice as wide as
thick (in-plane size h / N, through size h / (2 N)); 2x20 refines 2x10
in plane only (cubes of h / 4), 4x10 through the thickness only. With
friction 4x20 (24,500 equations) takes about 10 s per Newton iteration
on one core and an estimated 400 iterations, too slow for this
reference. Increments: *STATIC, first 1/48 of the step, at most 1/24
(at most 1/12 fails with friction: increment below the minimum);
*CONTROLS tightened for the frictionless runs so their residual does
not limit the comparison with the analytic force.
Runs as scripts/calculix_compare.py times them (helpers imported from
there and from scripts/calculix_nonlinear_compare.py): whole ccx
processes under `flock /tmp/coshell-measure.lock`, OMP_NUM_THREADS =
--threads, killed after --max-seconds; --lock takes another lock file
so that two invocations can share the machine's cores. Each run leaves
rows.json in its directory; --reuse reads it instead of running again,
so the CSV and the figure can be assembled from runs made apart.
Writes strip_squeeze.csv (no '#' lines: one row per case, mesh and
squeeze, plus the analytic rows) and strip_squeeze.png into --output. Needs ccx (Debian calculix-ccx) and
/usr/bin/python3 with matplotlib.
"""
import argparse
import json
import os
import re
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import calculix_compare  # noqa: E402
from calculix_compare import ROOT, ccx_version, structured_quads  # noqa: E402
from calculix_nonlinear_compare import timed  # noqa: E402
from doc_common import finish_plot, write_csv  # noqa: E402

LENGTH, THICKNESS = 10.0, 1.0
YOUNG, POISSON = 1.0, 0.42
C10 = YOUNG / (4 * (1 + POISSON))
D1 = 6 * (1 - 2 * POISSON) / YOUNG
FRICTION = 0.1
PENALTY_SLOPE = 1e4   # MPa/mm: overlap = p / slope
STICK_SLOPE = 1e3     # MPa/mm: elastic slip = shear / slope
MAX_SQUEEZE, N_OUTPUTS = 0.30, 12
SQUEEZES = [round(MAX_SQUEEZE * k / N_OUTPUTS, 6) for k in range(N_OUTPUTS + 1)]
CASES = ["frictionless", f"friction_{FRICTION:g}"]
FIELDS = ["case", "elements_through_half_thickness", "in_plane_elements", "squeeze",
          "force_N", "max_penetration_mm", "relative_difference_to_analytic",
          "n_nodes", "ccx_seconds", "status"]


# ---------------------------------------------------------------- analytic

def neo_hooke_stresses(in_plane, through):
    """Cauchy stresses (sigma_11, sigma_33) of CalculiX's neo-Hooke law
    for the stretches diag(in_plane, in_plane, through)."""
    jacobian = in_plane ** 2 * through
    shear = 2 * C10 * jacobian ** (-5.0 / 3.0)
    pressure = 2 * (jacobian - 1) / D1
    return (shear * (in_plane ** 2 - through ** 2) / 3 + pressure,
            shear * 2 * (through ** 2 - in_plane ** 2) / 3 + pressure)


def analytic_force(squeeze):
    """Full-plate force (N, compressive positive) of homogeneous uniaxial
    stress at through-thickness stretch 1 - squeeze: sigma_11 = 0 by
    bisection on the in-plane stretch."""
    through = 1 - squeeze
    low, high = 1.0, 2.0  # sigma_11 < 0 at 1 when compressed, > 0 at 2
    for _ in range(200):
        middle = 0.5 * (low + high)
        if neo_hooke_stresses(middle, through)[0] < 0:
            low = middle
        else:
            high = middle
    in_plane = 0.5 * (low + high)
    return abs(neo_hooke_stresses(in_plane, through)[1]) * (LENGTH * in_plane) ** 2


# ---------------------------------------------------------------- meshes

def brick_mesh(n_in_plane, n_through, extent, z_range):
    """n_in_plane^2 x n_through C3D20 bricks (CalculiX node order) over
    [extent]^2 x [z_range], built on the 8-node quads of
    structured_quads; midside levels in z carry only the corner columns.
    Returns the nodes (x, y, z) and the bricks (0-based)."""
    low, high = extent
    points, quads, _ = structured_quads(
        n_in_plane, n_in_plane, lambda s, t: (low + s * (high - low), low + t * (high - low)), True)
    corners = sorted({k for quad in quads for k in quad[:4]})
    nodes, level_index = [], []
    for level in range(2 * n_through + 1):
        z = z_range[0] + level / (2 * n_through) * (z_range[1] - z_range[0])
        index = {}
        for k in (corners if level % 2 else range(len(points))):
            index[k] = len(nodes)
            nodes.append((points[k][0], points[k][1], z))
        level_index.append(index)
    bricks = []
    for layer in range(n_through):
        bottom, middle, top = level_index[2 * layer:2 * layer + 3]
        for quad in quads:
            bricks.append([bottom[k] for k in quad[:4]] + [top[k] for k in quad[:4]]
                          + [bottom[k] for k in quad[4:]] + [top[k] for k in quad[4:]]
                          + [middle[k] for k in quad[:4]])
    return nodes, bricks


def slab_mesh(n_in_plane):
    """The rigid plate: one layer of C3D8 bricks over
    [-L/20, 3 L/4]^2 x [h/2, h]; nodes and bricks (0-based)."""
    low, high, n = -LENGTH / 20, 0.75 * LENGTH, n_in_plane
    nodes = [(low + i / n * (high - low), low + j / n * (high - low), z)
             for z in (THICKNESS / 2, THICKNESS) for j in range(n + 1) for i in range(n + 1)]
    layer = (n + 1) ** 2
    bricks = []
    for j in range(n):
        for i in range(n):
            quad = [j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i]
            bricks.append(quad + [k + layer for k in quad])
    return nodes, bricks


def node_set(name, ids):
    """*NSET lines of 1-based node ids, 16 a line."""
    ids = list(ids)
    return (f"*NSET, NSET={name}\n"
            + "\n".join(", ".join(map(str, ids[i:i + 16])) for i in range(0, len(ids), 16)) + "\n")


def element_lines(element_type, elset, bricks, first_id, node_offset):
    """*ELEMENT block (1-based ids, continuation lines of 16 entries)."""
    lines = [f"*ELEMENT, TYPE={element_type}, ELSET={elset}"]
    for number, brick in enumerate(bricks, start=first_id):
        ids = [str(number)] + [str(k + 1 + node_offset) for k in brick]
        lines.append(",\n".join(", ".join(ids[j:j + 16]) for j in range(0, len(ids), 16)))
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- decks

def strip_model(n_through, n_in_plane):
    """The quarter strip's nodes and bricks, and the *NODE, *ELEMENT,
    symmetry *BOUNDARY and node-set text of the deck."""
    nodes, bricks = brick_mesh(n_in_plane, n_through, (0.0, LENGTH / 2), (0.0, THICKNESS / 2))

    def on(axis, value):
        return [k + 1 for k, p in enumerate(nodes) if abs(p[axis] - value) < 1e-9]

    text = "*NODE, NSET=NSTRIP\n" + "".join(
        f"{k}, {x:.12g}, {y:.12g}, {z:.12g}\n" for k, (x, y, z) in enumerate(nodes, start=1))
    text += element_lines("C3D20R", "STRIP", bricks, 1, 0)
    text += node_set("XSYM", on(0, 0.0)) + node_set("YSYM", on(1, 0.0))
    text += node_set("ZSYM", on(2, 0.0)) + node_set("TOP", on(2, THICKNESS / 2))
    text += ("*MATERIAL, NAME=LENS\n*HYPERELASTIC, NEO HOOKE\n"
             f"{C10:.12g}, {D1:.12g}\n*SOLID SECTION, ELSET=STRIP, MATERIAL=LENS\n"
             "*BOUNDARY\nXSYM, 1, 1\nYSYM, 2, 2\nZSYM, 3, 3\n")
    return nodes, bricks, text


def contact_model(n_strip_nodes, strip_bricks, n_in_plane):
    """The slab (all nodes in NSET PLATE) and the friction contact pair:
    slave the strip's top faces (S2 of the top layer), master the slab's
    bottom faces (S1)."""
    nodes, bricks = slab_mesh(max(4, n_in_plane // 4))
    first_element = len(strip_bricks) + 1
    text = "*NODE, NSET=PLATE\n" + "".join(
        f"{k}, {x:.12g}, {y:.12g}, {z:.12g}\n"
        for k, (x, y, z) in enumerate(nodes, start=n_strip_nodes + 1))
    text += element_lines("C3D8", "SLAB", bricks, first_element, n_strip_nodes)
    top_layer = range(len(strip_bricks) - n_in_plane ** 2 + 1, len(strip_bricks) + 1)
    text += ("*SURFACE, NAME=STRIPTOP, TYPE=ELEMENT\n" + "".join(f"{e}, S2\n" for e in top_layer)
             + "*SURFACE, NAME=PLATEFACE, TYPE=ELEMENT\n"
             + "".join(f"{e}, S1\n" for e in range(first_element, first_element + len(bricks)))
             + "*MATERIAL, NAME=RIGID\n*ELASTIC\n1000, 0.3\n"
             "*SOLID SECTION, ELSET=SLAB, MATERIAL=RIGID\n"
             "*SURFACE INTERACTION, NAME=PLATECONTACT\n"
             f"*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{PENALTY_SLOPE:g}\n"
             f"*FRICTION\n{FRICTION:g}, {STICK_SLOPE:g}\n"
             "*CONTACT PAIR, INTERACTION=PLATECONTACT, TYPE=SURFACE TO SURFACE\n"
             "STRIPTOP, PLATEFACE\n*BOUNDARY\nPLATE, 1, 2\n")
    return len(nodes), text


def write_deck(path, case, n_through, n_in_plane):
    """The whole deck of one case and mesh; returns the node count."""
    nodes, bricks, text = strip_model(n_through, n_in_plane)
    n_nodes, pushed = len(nodes), "TOP"
    if case != "frictionless":
        n_plate, contact = contact_model(len(nodes), bricks, n_in_plane)
        text += contact
        n_nodes, pushed = n_nodes + n_plate, "PLATE"
    times = [k / N_OUTPUTS for k in range(1, N_OUTPUTS + 1)]
    text += ("*TIME POINTS, NAME=PATH\n"
             + "\n".join(", ".join(f"{t:.10g}" for t in times[i:i + 6]) for i in range(0, len(times), 6))
             + f"\n*STEP, NLGEOM, INC=10000\n*STATIC\n{1 / 48:.10g}, 1.0, 1e-7, {1 / 24:.10g}\n")
    if case == "frictionless":
        text += "*CONTROLS, PARAMETERS=FIELD\n1e-7, 1e-7\n"
    text += (f"*BOUNDARY\n{pushed}, 3, 3, {-MAX_SQUEEZE * THICKNESS / 2:.12g}\n"
             f"*NODE PRINT, NSET={pushed}, TOTALS=ONLY, TIME POINTS=PATH\nRF\n")
    if case != "frictionless":
        text += "*CONTACT PRINT, TIME POINTS=PATH\nCDIS\n"
    with open(path, "w") as f:
        f.write(text + "*END STEP\n")
    return n_nodes


# ---------------------------------------------------------------- results

def read_dat(path):
    """{squeeze: (full-plate force, largest contact overlap or None)}
    from the .dat: the *NODE PRINT totals and the normal component of the
    *CONTACT PRINT CDIS rows (CalculiX 2.20 prints an overlap as a
    negative normal value; the largest magnitude is kept)."""
    forces, overlaps, time, block = {}, {}, None, None
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        for line in f:
            match = re.search(r"^ (total force|relative contact displacement).* time\s+(\S+)", line)
            if match:
                block, time = match.group(1), round(MAX_SQUEEZE * float(match.group(2)), 6)
                continue
            fields = line.split()
            if block == "total force" and len(fields) == 3:
                forces[time] = 4 * abs(float(fields[2]))
                block = None
            elif block and block.startswith("relative") and len(fields) == 5:
                overlaps[time] = max(overlaps.get(time, 0.0), abs(float(fields[2])))
    return {s: (force, overlaps.get(s)) for s, force in forces.items()}


def run_ccx(args, case, mesh):
    """Rows of one case and mesh (n_through, n_in_plane): the deck
    written and run in --work/<case>/<n_through>x<n_in_plane>, its .dat
    read; with --reuse, the rows.json a finished run left there."""
    n_through, n_in_plane = mesh
    directory = os.path.join(args.work, case, f"{n_through}x{n_in_plane}")
    saved = os.path.join(directory, "rows.json")
    if args.reuse and os.path.exists(saved):
        with open(saved) as f:
            return json.load(f)
    os.makedirs(directory, exist_ok=True)
    for stale in ("deck.dat", "deck.sta", "rows.json"):
        if os.path.exists(os.path.join(directory, stale)):
            os.remove(os.path.join(directory, stale))
    n_nodes = write_deck(os.path.join(directory, "deck.inp"), case, n_through, n_in_plane)
    threads = str(args.threads)
    seconds, stdout = timed(args, [args.ccx, "-i", "deck"], directory,
                            {"OMP_NUM_THREADS": threads, "CCX_NPROC_EQUATION_SOLVER": threads})
    with open(os.path.join(directory, "ccx.log"), "w") as f:
        f.write(stdout)
    path = read_dat(os.path.join(directory, "deck.dat"))
    status = "ok" if seconds and len(path) == N_OUTPUTS else (stdout if not seconds else "incomplete")
    path[0.0] = (0.0, 0.0 if case != "frictionless" else None)  # the unloaded state
    rows = [dict(case=case, elements_through_half_thickness=n_through, in_plane_elements=n_in_plane,
                 squeeze=f"{s:g}", force_N=f"{path[s][0]:.7g}",
                 max_penetration_mm="" if path[s][1] is None else f"{path[s][1]:.4e}",
                 n_nodes=n_nodes, ccx_seconds=f"{seconds:.1f}" if seconds else "", status=status)
            for s in SQUEEZES if s in path]
    print(f"  {case} {n_through}x{n_in_plane}: force at s = {rows[-1]['squeeze']}: "
          f"{rows[-1]['force_N']} N in {rows[-1]['ccx_seconds'] or '-'} s [{status}]", flush=True)
    with open(saved, "w") as f:
        json.dump(rows, f)
    return rows


def analytic_rows():
    return [dict(case="analytic", squeeze=f"{s:g}", force_N=f"{analytic_force(s):.7g}", status="ok")
            for s in SQUEEZES]


def compare_with_analytic(rows):
    """Fills relative_difference_to_analytic of the frictionless rows;
    returns the worst."""
    worst = 0.0
    for row in rows:
        squeeze = float(row["squeeze"])
        if row["case"] == "frictionless" and squeeze > 0:
            difference = abs(float(row["force_N"]) / analytic_force(squeeze) - 1)
            row["relative_difference_to_analytic"] = f"{difference:.3e}"
            worst = max(worst, difference)
    return worst


# ---------------------------------------------------------------- report

def at_full_squeeze(rows, case):
    """[(n_nodes, mesh label, force at s = MAX_SQUEEZE)] of a case's
    finished meshes, coarse to fine."""
    found = [(int(r["n_nodes"]), f"{r['elements_through_half_thickness']}x{r['in_plane_elements']}",
              float(r["force_N"]))
             for r in rows if r["case"] == case and float(r["squeeze"]) == MAX_SQUEEZE]
    return sorted(found)


def finest(rows, case):
    series = at_full_squeeze(rows, case)
    if not series:
        return []
    label = series[-1][1]
    return [r for r in rows if r["case"] == case
            and f"{r['elements_through_half_thickness']}x{r['in_plane_elements']}" == label]


def plot(rows, path):
    """Force against squeeze (finest meshes and the analytic curve), and
    the force at full squeeze against the mesh."""
    figure, (curves, convergence) = plt.subplots(1, 2, figsize=(11, 4.5))
    dense = [MAX_SQUEEZE * k / 120 for k in range(121)]
    curves.plot(dense, [analytic_force(s) for s in dense], color="gray", linewidth=3, alpha=0.5,
                label="analytic, frictionless")
    for index, case in enumerate(CASES):
        mine = finest(rows, case)
        if mine:
            curves.plot([float(r["squeeze"]) for r in mine], [float(r["force_N"]) for r in mine],
                        marker="os"[index], color=f"C{index}", label=f"CalculiX C3D20R {case} "
                        f"({mine[0]['elements_through_half_thickness']}x{mine[0]['in_plane_elements']})")
    series = at_full_squeeze(rows, CASES[1])  # the frictionless force is the same on every mesh
    convergence.semilogx([n for n, _, _ in series], [100 * (f / series[-1][2] - 1) for _, _, f in series],
                         "s", color="C1", label=CASES[1])
    for n, label, f in series:
        convergence.annotate(label, (n, 100 * (f / series[-1][2] - 1)), fontsize=8,
                             xytext=(4, 4), textcoords="offset points")
    curves.set_xlabel("squeeze s = (h - current thickness) / h")
    curves.set_ylabel("force on the full plate [N]")
    curves.grid(True, alpha=0.3)
    curves.legend(fontsize=8)
    curves.set_title(f"{LENGTH:g} x {LENGTH:g} x {THICKNESS:g} mm, neo-Hooke E = {YOUNG:g} MPa, "
                     f"nu = {POISSON:g}", fontsize=10)
    finish_plot(figure, convergence, "nodes (strip and plate)",  # saves the figure
                f"force at s = {MAX_SQUEEZE:g} / finest - 1 [%]", "mesh convergence (N x M: through x in-plane)",
                path)
    plt.close(figure)


def print_summary(rows, worst):
    print(f"\nfrictionless CalculiX against analytic: worst relative difference {worst:.2e}")
    for case in CASES:
        series = at_full_squeeze(rows, case)
        print(f"{case}: force at s = {MAX_SQUEEZE:g} by mesh (nodes; change to the finest): "
              + ", ".join(f"{label} ({n}) {force:.6g} N ({force / series[-1][2] - 1:+.3%})"
                          for n, label, force in series))
        mine = finest(rows, case)
        for r in mine:
            if float(r["squeeze"]) in (0.1, 0.2, 0.3):
                print(f"  finest, s = {r['squeeze']}: {r['force_N']} N"
                      + (f", penetration {r['max_penetration_mm']} mm" if r["max_penetration_mm"] else ""))


def parse_mesh(text):
    through, in_plane = text.lower().split("x")
    return int(through), int(in_plane)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--ccx", default=shutil.which("ccx") or "ccx")
    parser.add_argument("--work", default="/tmp/calculix_squeeze")
    parser.add_argument("--output", default=os.path.join(ROOT, "doc", "calculix"))
    parser.add_argument("--cases", nargs="+", default=CASES, choices=CASES)
    parser.add_argument("--meshes", nargs="+", default=["1x5", "2x10", "3x15", "2x20", "4x10"])
    parser.add_argument("--max-seconds", type=float, default=3600.0)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--lock", default=calculix_compare.LOCK)
    parser.add_argument("--reuse", action="store_true")
    args = parser.parse_args()
    if not shutil.which(args.ccx):
        sys.exit("ccx not found (Debian package calculix-ccx)")
    calculix_compare.LOCK = args.lock  # run_timed's flock
    args.work = os.path.abspath(args.work)
    print(f"CalculiX: {ccx_version(args.ccx)}", flush=True)
    rows = []
    for case in args.cases:
        for mesh in args.meshes:
            rows += run_ccx(args, case, parse_mesh(mesh))
    rows += analytic_rows()
    worst = compare_with_analytic(rows)
    os.makedirs(args.output, exist_ok=True)
    write_csv(os.path.join(args.output, "strip_squeeze.csv"), rows, [], FIELDS)
    plot(rows, os.path.join(args.output, "strip_squeeze.png"))
    print_summary(rows, worst)


if __name__ == "__main__":
    main()
