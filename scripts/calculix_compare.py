#!/usr/bin/python3
"""Peer comparison with CalculiX: the clamped plate and the
Scordelis-Lo roof solved by CalculiX shells on the meshes coshell uses,
timed against coshell on the same machine, in the same run.

  scripts/calculix_compare.py [--coshell build/coshell]
      [--work /tmp/calculix_compare] [--output doc/calculix]
      [--benchmarks plate roof] [--max-seconds 120] [--repeats 3]

For each benchmark and refinement level the triangle mesh is taken from
coshell itself (one run with VTU output, duplicated points merged) and
written as S3 and S6 decks (S6: midside nodes, on the cylinder for the
roof); S4, S4R, S8 and S8R decks use the structured squares the triangles
are cut from (plate: 4*2^k squares per side; roof: the n x n grid in angle
and axial position of meshes/scordelis_lo_roof.geo). Every timed run, ccx
(OMP_NUM_THREADS=1) or coshell (default threads and DEAL_II_NUM_THREADS=1),
is a whole process timed inside `flock /tmp/coshell-measure.lock`; runs
under 10 s are repeated in --repeats rounds over all cases, best time
kept. An element's levels stop when a run exceeds
--max-seconds / 5 (the next level costs about 5x) or its error is below
--stop-error. Writes calculix_comparison.csv and <benchmark>.png into
--output and prints the time ratios to reach the error targets.
Needs ccx (Debian calculix-ccx) and /usr/bin/python3 with matplotlib.
"""
import argparse
import base64
import functools
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import time
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "doc", "scripts"))
from doc_common import finish_plot, machine_and_commit, write_csv  # noqa: E402

LOCK = "/tmp/coshell-measure.lock"
FIELDS = ["benchmark", "code", "element", "level", "n_nodes", "n_dofs", "value",
          "reference", "relative_error", "process_wall_s", "threads"]
TRIANGLE_ELEMENTS = ["S3", "S6"]
QUAD_ELEMENTS = ["S4", "S4R", "S8", "S8R"]
COSHELL_ELEMENTS = ["cst+dkt", "andes+dkt"]
ROOF_RADIUS, ROOF_ANGLE, ROOF_HALF_LENGTH = 25.0, math.radians(40.0), 25.0

BENCHMARKS = {
    "plate": dict(name="plates/clamped_square_pressure",
                  prm="prm/plates/clamped_square_pressure.prm",
                  reference=0.126532, qoi_point=(5.0, 5.0, 0.0),
                  levels=[0, 1, 2, 3, 4, 5], base_squares=4),
    "roof": dict(name="obstacle_course/scordelis_lo_roof",
                 prm="prm/obstacle_course/scordelis_lo_roof.prm",
                 reference=-0.3024,
                 qoi_point=(ROOF_RADIUS * math.sin(ROOF_ANGLE), 0.0,
                            ROOF_RADIUS * math.cos(ROOF_ANGLE)),
                 levels=[0, 1, 2, 3, 4, 5], base_squares=4),
}


# ---------------------------------------------------------------- timing

def timed_exec(command):
    """Child mode (run under flock): time one whole process, print seconds
    last on stderr so the lock wait is not counted."""
    start = time.perf_counter()
    status = subprocess.run(command).returncode
    print(f"TIMED_EXEC {time.perf_counter() - start:.6f}", file=sys.stderr)
    sys.exit(status)


def run_timed(command, cwd, env_extra):
    """Wall time of one run taken under the measurement lock."""
    wrapped = ["flock", LOCK, sys.executable, os.path.abspath(__file__),
               "--timed-exec", "--"] + command
    result = subprocess.run(wrapped, cwd=cwd, env=dict(os.environ, **env_extra),
                            capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed in {cwd}:\n"
                           f"{result.stdout[-2000:]}{result.stderr[-2000:]}")
    return float(re.findall(r"TIMED_EXEC (\S+)", result.stderr)[-1]), result.stdout


# ---------------------------------------------------------------- meshes

def decode_vtu_array(text):
    """deal.II's zlib-compressed base64 DataArray: a base64 header of
    uint32 (blocks, block size, last block size, compressed sizes...),
    then the base64 of the concatenated compressed blocks."""
    text = text.strip()
    n_blocks = struct.unpack("<I", base64.b64decode(text[:8])[:4])[0]
    header_chars = 4 * math.ceil((3 + n_blocks) * 4 / 3)
    header = struct.unpack(f"<{3 + n_blocks}I", base64.b64decode(text[:header_chars]))
    data = base64.b64decode(text[header_chars:])
    raw, offset = b"", 0
    for size in header[3:]:
        raw += zlib.decompress(data[offset:offset + size])
        offset += size
    return raw


def read_vtu_triangles(path):
    """Points (merged by coordinates) and triangles of a deal.II VTU."""
    with open(path) as f:
        xml = f.read()
    arrays = dict(re.findall(r'<DataArray type="\w+"(?: Name="(\w+)")?[^>]*>(.*?)</DataArray>',
                             xml, re.S)[:3])
    raw_points = decode_vtu_array(arrays[""])
    coordinates = struct.unpack(f"<{len(raw_points) // 4}f", raw_points)
    raw_cells = decode_vtu_array(arrays["connectivity"])
    connectivity = struct.unpack(f"<{len(raw_cells) // 4}i", raw_cells)
    index_of, points, merged = {}, [], []
    for i in range(0, len(coordinates), 3):
        key = coordinates[i:i + 3]
        if key not in index_of:
            index_of[key] = len(points)
            points.append(key)
        merged.append(index_of[key])
    triangles = [tuple(merged[c] for c in connectivity[i:i + 3])
                 for i in range(0, len(connectivity), 3)]
    return points, triangles


def coshell_triangles(args, benchmark, level):
    """The triangle mesh coshell builds at this level (float32 points
    snapped back to the exact geometry)."""
    spec = BENCHMARKS[benchmark]
    directory = os.path.join(args.work, benchmark, f"coshell-mesh-{level}")
    vtu = os.path.join(directory, "solution.vtu")
    if not os.path.exists(vtu):
        subprocess.run([args.coshell, os.path.join(ROOT, spec["prm"]), "--output", directory,
                        "--set", f"Mesh/Refinement levels={level}",
                        "--set", "Output/Write VTU=true"],
                       check=True, stdout=subprocess.DEVNULL)
    points, triangles = read_vtu_triangles(vtu)
    n = spec["base_squares"] * 2 ** level
    snap = snap_to_roof if benchmark == "roof" else snap_to_plate
    return [snap(p, n) for p in points], triangles


def snap_to_plate(point, n):
    step = 10.0 / (2 * n)  # crossed pattern: square centres at half steps
    return tuple(round(c / step) * step for c in point)


def snap_to_roof(point, n):
    angle = round(math.atan2(point[0], point[2]) / (ROOF_ANGLE / n)) * ROOF_ANGLE / n
    axial = round(point[1] / (ROOF_HALF_LENGTH / n)) * ROOF_HALF_LENGTH / n
    return roof_point(angle, axial)


def roof_point(angle, axial):
    return (ROOF_RADIUS * math.sin(angle), axial, ROOF_RADIUS * math.cos(angle))


def grid_point(benchmark, s, t):
    """Point at parameters s, t in [0, 1] of the structured grid."""
    if benchmark == "roof":
        return roof_point(s * ROOF_ANGLE, t * ROOF_HALF_LENGTH)
    return (10.0 * s, 10.0 * t, 0.0)


def structured_quads(nx, ny, point, quadratic):
    """nx x ny quads of the map point(s, t) of the unit square (8 nodes,
    midside nodes mapped too, when quadratic), counter-clockwise in (s, t).
    Returns the points, the quads (0-based) and {(s, t): node index}."""
    mx, my = (2 * nx, 2 * ny) if quadratic else (nx, ny)
    index, points = {}, []
    for j in range(my + 1):
        for i in range(mx + 1):
            if quadratic and i % 2 and j % 2:
                continue  # no centre node in 8-node quads
            index[i, j] = len(points)
            points.append(point(i / mx, j / my))
    step = 2 if quadratic else 1
    quads = []
    for j in range(0, my, step):
        for i in range(0, mx, step):
            nodes = [index[c] for c in ((i, j), (i + step, j), (i + step, j + step), (i, j + step))]
            if quadratic:
                nodes += [index[i + 1, j], index[i + 2, j + 1], index[i + 1, j + 2], index[i, j + 1]]
            quads.append(tuple(nodes))
    by_parameter = {(i / mx, j / my): k for (i, j), k in index.items()}
    return points, quads, by_parameter


def quad_mesh(benchmark, level, quadratic):
    """n x n structured quads (8 nodes with midside nodes when quadratic),
    nodes ordered counter-clockwise seen from the outward normal."""
    n = BENCHMARKS[benchmark]["base_squares"] * 2 ** level
    points, quads, _ = structured_quads(n, n, lambda s, t: grid_point(benchmark, s, t),
                                        quadratic)
    return points, quads


def add_midside_nodes(benchmark, points, triangles):
    """6-node triangles; roof midside nodes go onto the cylinder."""
    points, midside = list(points), {}
    result = []
    for triangle in triangles:
        extra = []
        for a, b in ((0, 1), (1, 2), (2, 0)):
            edge = tuple(sorted((triangle[a], triangle[b])))
            if edge not in midside:
                midside[edge] = len(points)
                points.append(midpoint(benchmark, points[edge[0]], points[edge[1]]))
            extra.append(midside[edge])
        result.append(tuple(triangle) + tuple(extra))
    return points, result


def midpoint(benchmark, p, q):
    if benchmark == "roof":
        angles = [math.atan2(x[0], x[2]) for x in (p, q)]
        return roof_point(sum(angles) / 2, (p[1] + q[1]) / 2)
    return tuple((a + b) / 2 for a, b in zip(p, q))


def orient(benchmark, points, triangles):
    """Counter-clockwise about the outward normal (+z, or radial on the
    roof): CalculiX merges expanded nodes only where normals agree."""
    oriented = []
    for t in triangles:
        a, b, c = (points[i] for i in t[:3])
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        normal = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        outward = (a[0], 0.0, a[2]) if benchmark == "roof" else (0.0, 0.0, 1.0)
        flip = sum(x * y for x, y in zip(normal, outward)) < 0
        oriented.append((t[0], t[2], t[1]) if flip else tuple(t))
    return oriented


def element_mesh(args, benchmark, element, level):
    if element in TRIANGLE_ELEMENTS:
        points, triangles = coshell_triangles(args, benchmark, level)
        triangles = orient(benchmark, points, triangles)
        if element == "S6":
            return add_midside_nodes(benchmark, points, triangles)
        return points, triangles
    return quad_mesh(benchmark, level, quadratic=element in ("S8", "S8R"))


# ---------------------------------------------------------------- decks

def near(a, b):
    return abs(a - b) < 1e-6


def boundary_lines(benchmark, points):
    """*BOUNDARY lines (node, first dof, last dof). A translational SPC on a
    shell node fixes only the mean of its expanded nodes; rotations are
    mean-rotation MPCs, so only rotations not about the normal are fixed."""
    lines = []
    for node, (x, y, z) in enumerate(points, start=1):
        if benchmark == "plate":
            if near(x, 0) or near(x, 10) or near(y, 0) or near(y, 10):
                lines.append(f"{node}, 1, 5")  # clamped: translations, rot_x, rot_y
            continue
        if near(y, 0):  # symmetry plane y = 0: u_y, rotation about x
            lines += [f"{node}, 2, 2", f"{node}, 4, 4"]
        if near(y, ROOF_HALF_LENGTH):  # rigid diaphragm: u_x = u_z = 0
            lines += [f"{node}, 1, 1", f"{node}, 3, 3"]
        if near(x, 0):  # symmetry plane x = 0 (crown, normal z): u_x, rotation about y
            lines += [f"{node}, 1, 1", f"{node}, 5, 5"]
    return lines


def qoi_node(benchmark, points):
    target = BENCHMARKS[benchmark]["qoi_point"]
    return 1 + min(range(len(points)),
                   key=lambda i: sum((p - q) ** 2 for p, q in zip(points[i], target)))


def write_deck(path, benchmark, element, points, elements):
    # Plate: a positive CalculiX shell pressure pushes along the +z normal
    # here (checked: level-0 deflection sign), as coshell's Pressure = 1.
    # Roof: self weight 360 * 0.25 = 90 per area, downwards.
    material = ("1.092e6, 0.3", "0.1") if benchmark == "plate" else ("4.32e8, 0.0", "0.25")
    load = ("*DLOAD\nEALL, P, 1.0" if benchmark == "plate"
            else "*DLOAD\nEALL, GRAV, 1.0, 0.0, 0.0, -1.0")
    with open(path, "w") as f:
        f.write("*NODE, NSET=NALL\n")
        f.writelines(f"{i}, {x:.12g}, {y:.12g}, {z:.12g}\n"
                     for i, (x, y, z) in enumerate(points, start=1))
        f.write(f"*ELEMENT, TYPE={element}, ELSET=EALL\n")
        f.writelines(f"{i}, {', '.join(str(n + 1) for n in nodes)}\n"
                     for i, nodes in enumerate(elements, start=1))
        f.write(f"*NSET, NSET=QOI\n{qoi_node(benchmark, points)}\n")
        f.write("*MATERIAL, NAME=SHELL\n*ELASTIC\n" + material[0] + "\n")
        if benchmark == "roof":
            f.write("*DENSITY\n360.0\n")
        f.write(f"*SHELL SECTION, ELSET=EALL, MATERIAL=SHELL\n{material[1]}\n")
        f.write("*BOUNDARY\n" + "\n".join(boundary_lines(benchmark, points)) + "\n")
        f.write("*STEP\n*STATIC\n" + load + "\n*NODE PRINT, NSET=QOI\nU\n*END STEP\n")


def read_dat_uz(path):
    """Vertical displacement of the single QOI node printed in the .dat."""
    with open(path) as f:
        rows = [line.split() for line in f if re.match(r"\s+\d+\s+\S+\s+\S+\s+\S+\s*$", line)]
    return float(rows[-1][3])


def equations(stdout):
    match = re.search(r"number of equations\s+(\d+)", stdout)
    return int(match.group(1)) if match else ""


# ---------------------------------------------------------------- runs

def result_row(benchmark, code, element, level, n_nodes, n_dofs, value, seconds, threads):
    reference = BENCHMARKS[benchmark]["reference"]
    return dict(benchmark=BENCHMARKS[benchmark]["name"], code=code, element=element,
                level=level, n_nodes=n_nodes, n_dofs=n_dofs, value=f"{value:.7g}",
                reference=reference, relative_error=f"{abs(value - reference) / abs(reference):.4e}",
                process_wall_s=f"{seconds:.4f}", threads=threads)


def run_calculix(args, benchmark, element, level):
    directory = os.path.join(args.work, benchmark, f"{element}-{level}")
    os.makedirs(directory, exist_ok=True)
    points, elements = element_mesh(args, benchmark, element, level)
    write_deck(os.path.join(directory, "deck.inp"), benchmark, element, points, elements)
    env = {"OMP_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1"}
    seconds, stdout = run_timed([args.ccx, "-i", "deck"], directory, env)
    value = read_dat_uz(os.path.join(directory, "deck.dat"))
    return result_row(benchmark, "calculix", element, level, len(points),
                      equations(stdout), value, seconds, 1)


def run_coshell(args, benchmark, elements, level, threads):
    membrane, bending = elements.split("+")
    directory = os.path.join(args.work, benchmark, f"coshell-{elements}-{level}-{threads}")
    command = [args.coshell, os.path.join(ROOT, BENCHMARKS[benchmark]["prm"]),
               "--output", directory, "--set", f"Mesh/Refinement levels={level}",
               "--set", f"Element/Membrane element={membrane}",
               "--set", f"Element/Bending element={bending}",
               "--set", "Output/Write VTU=false"]
    env = {"DEAL_II_NUM_THREADS": "1"} if threads == 1 else {}
    seconds, _ = run_timed(command, args.work, env)
    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    value = next(iter(summary["qoi"].values()))
    return result_row(benchmark, "coshell", elements, level, summary["n_vertices"],
                      summary["n_dofs"], value, seconds, threads if threads else os.cpu_count())


def level_series(args, benchmark, run_one):
    """(row, rerun) per level, in turn until a run is too slow for the next
    level or accurate enough."""
    series = []
    for level in BENCHMARKS[benchmark]["levels"]:
        row = run_one(level)
        print(f"  {row['code']} {row['element']} level {level}: {row['value']} "
              f"(error {float(row['relative_error']):.2e}) in {row['process_wall_s']} s "
              f"[{row['threads']} thread(s)]", flush=True)
        series.append((row, lambda k=level: run_one(k)))
        if (float(row["process_wall_s"]) * 5 > args.max_seconds
                or float(row["relative_error"]) < args.stop_error):
            break
    return series


def run_benchmark(args, benchmark):
    series = []
    for elements in COSHELL_ELEMENTS:
        for threads in (0, 1):
            series += level_series(args, benchmark, functools.partial(
                run_coshell, args, benchmark, elements, threads=threads))
    for element in args.elements:
        try:
            series += level_series(args, benchmark, functools.partial(
                run_calculix, args, benchmark, element))
        except RuntimeError as error:
            print(f"  calculix {element}: {error}")
    return series


def repeat_short_runs(args, series):
    """Further rounds over all runs under 10 s, keeping each run's best
    time: rounds spread the repeats over minutes, so a slow spell of the
    shared machine does not hit all repeats of one case."""
    for round_number in range(1, args.repeats):
        print(f"timing round {round_number + 1} of {args.repeats}", flush=True)
        for row, rerun in series:
            if float(row["process_wall_s"]) < 10:
                again = rerun()["process_wall_s"]
                row["process_wall_s"] = min(row["process_wall_s"], again, key=float)
    return [row for row, _ in series]


# ---------------------------------------------------------------- report

def curve_label(row):
    threads = "" if row["code"] == "calculix" else f", {row['threads']} thr"
    return f"{row['code']} {row['element']}{threads}"


def plot(rows, benchmark, path):
    figure, axes = plt.subplots(figsize=(7, 5))
    labels = sorted({curve_label(r) for r in rows})
    for index, label in enumerate(labels):
        mine = [r for r in rows if curve_label(r) == label]
        axes.loglog([float(r["process_wall_s"]) for r in mine],
                    [max(float(r["relative_error"]), 1e-8) for r in mine],
                    marker="o" if "coshell" in label else "s",
                    linestyle="-" if "coshell" in label else "--",
                    color=f"C{index % 10}", label=label)
    for target in (5e-3, 2e-3, 1e-3):
        axes.axhline(target, color="gray", linewidth=0.6, linestyle=":")
    finish_plot(figure, axes, "process wall time [s]", "relative error",
                BENCHMARKS[benchmark]["name"], path)
    plt.close(figure)


def fastest(rows, target, error=lambda row: float(row["relative_error"])):
    """The quickest run (whole process) whose error is within the target."""
    reached = [r for r in rows if error(r) <= target]
    return min(reached, key=lambda r: float(r["process_wall_s"])) if reached else None


def describe(row):
    if row is None:
        return "not reached"
    return (f"{row['element']} level {row['level']} ({row['n_dofs']} dofs, "
            f"{row['threads']} thr): {float(row['process_wall_s']):.3g} s")


def print_ratios(rows, benchmark):
    """Fastest coshell run to 0.5 % / 0.1 % against the fastest CalculiX
    run to 0.5 %, 0.2 %, 0.1 % (whole processes, actual runs)."""
    mine = [r for r in rows if r["benchmark"] == BENCHMARKS[benchmark]["name"]]
    coshell = [r for r in mine if r["code"] == "coshell"]
    calculix = [r for r in mine if r["code"] == "calculix"]
    print(f"\n{BENCHMARKS[benchmark]['name']}:")
    for target in (5e-3, 2e-3, 1e-3):
        print(f"  to {target:.1%}: coshell {describe(fastest(coshell, target))}; "
              f"calculix {describe(fastest(calculix, target))}")
    for ours in (5e-3, 1e-3):
        for theirs in (5e-3, 2e-3, 1e-3):
            a, b = fastest(coshell, ours), fastest(calculix, theirs)
            if a and b:
                ratio = float(b["process_wall_s"]) / float(a["process_wall_s"])
                print(f"  calculix to {theirs:.1%} / coshell to {ours:.1%}: {ratio:.1f}x")


def ccx_version(ccx):
    result = subprocess.run([ccx, "-v"], capture_output=True, text=True)
    return (result.stdout + result.stderr).strip().splitlines()[-1]


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--timed-exec":
        timed_exec(sys.argv[3:])
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--coshell", default=os.path.join(ROOT, "build", "coshell"))
    parser.add_argument("--ccx", default=shutil.which("ccx") or "ccx")
    parser.add_argument("--work", default="/tmp/calculix_compare")
    parser.add_argument("--output", default=os.path.join(ROOT, "doc", "calculix"))
    parser.add_argument("--benchmarks", nargs="+", default=list(BENCHMARKS), choices=list(BENCHMARKS))
    parser.add_argument("--elements", nargs="+", default=TRIANGLE_ELEMENTS + QUAD_ELEMENTS)
    parser.add_argument("--max-seconds", type=float, default=120.0)
    parser.add_argument("--stop-error", type=float, default=2e-4)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    if not shutil.which(args.ccx):
        sys.exit("ccx not found (Debian package calculix-ccx)")
    # The runs start in the work directory.
    args.coshell, args.work = os.path.abspath(args.coshell), os.path.abspath(args.work)
    os.makedirs(args.output, exist_ok=True)
    series = []
    for benchmark in args.benchmarks:
        print(f"{BENCHMARKS[benchmark]['name']}", flush=True)
        os.makedirs(os.path.join(args.work, benchmark), exist_ok=True)
        series += run_benchmark(args, benchmark)
    rows = repeat_short_runs(args, series)
    machine, commit = machine_and_commit()
    header = [f"machine: {machine}", f"coshell commit: {commit} (binary {args.coshell})",
              f"CalculiX: {ccx_version(args.ccx)}, OMP_NUM_THREADS=1",
              "process_wall_s: whole process, best of "
              f"{args.repeats} rounds (runs under 10 s) under flock {LOCK}; command: scripts/calculix_compare.py"]
    write_csv(os.path.join(args.output, "calculix_comparison.csv"), rows, header, FIELDS)
    for benchmark in args.benchmarks:
        mine = [r for r in rows if r["benchmark"] == BENCHMARKS[benchmark]["name"]]
        plot(mine, benchmark, os.path.join(args.output, f"{benchmark}.png"))
        print_ratios(rows, benchmark)


if __name__ == "__main__":
    main()
