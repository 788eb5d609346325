#!/usr/bin/python3
"""A scene run on several MPI ranks gives the serial answer (issue: scale-out).

check_mpi_equals_serial.py --coshell BIN --prm FILE --output DIR
                           [--set A/B=v ...] [--ranks 2] [--tolerance 1e-10]
                           [--expect-solvers SERIAL PARALLEL]

Runs the scene serially and with 'mpirun -np RANKS' (same overrides) and
checks, relative to the size of each quantity in the serial run:
- every quantity of interest in summary.json, and its step count;
- displacement and rotation of every vertex in the last vertex table
  (run the scene with Output/Vertex table = true: VTU and HDF5 fields are
  single precision);
- every column of time_history.csv (dynamics), load_displacement.csv
  (statics) and contact_forces.csv,
  row by row (a vector's component relative to the whole vector's size);
and that the parallel run logged once, wrote one summary with mpi_ranks =
RANKS and left no partial files. With --expect-solvers, the two runs'
summary.json name these linear solvers ("linear_solver": the method used,
e.g. what Linear solver/Method = auto chose).

With --restart-from-middle (give Output/Checkpoint interval with --set) the
parallel run restarts from the serial run's middle checkpoint, and the
last checkpoints of both runs must agree too: the state (values, rotations,
velocity, acceleration, pseudo-acceleration), stored by mesh vertex
whatever the DoF numbering, so a serial checkpoint continues on several
ranks. A third run, serial, restarts from the same checkpoint with another
direct solver (UMFPACK, or KLU if the scene's is UMFPACK): its distance
from the serial run is the round-off floor of each dataset, and a dataset
passes within the tolerance or within ten times its floor, whichever is
larger. The floor matters for the acceleration of a bending plate: its
in-plane components are tiny (1e-4 of the largest) and carry the
positions' round-off (eps times the plate's size) times the membrane
frequencies squared, so two serial runs with different solvers differ by
about 1e-10 of the largest acceleration (the values by 1e-13).
The energy bookkeeping's support reactions are printed, not
asserted: they are differences of internal and inertia forces, so they
agree to the acceleration's difference times the mass, not relative to
their own small size; the energies built from them are compared in
time_history.csv. Newton iteration counts are not compared then (the
restart counts its own).

A point value of summary.json (Quantities of interest/Point values) is a
sample of a vertex field, and is measured against the larger of itself
and that field's largest entry in the serial vertex table, as a CSV
component is against its vector: a linear solve's round-off is relative
to the whole solution, not to each entry. So the tip rotation of a
rolled-up strip, 0.17 rad as the wrapped rotation vector of a 6.11 rad
turn, is judged against the rotation field's 3.13 rad.
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from coshell_checks import Checks, add_scene_arguments, exit_with  # noqa: E402

STATE_DATASETS = ["values", "rotations", "velocity", "acceleration",
                  "pseudo_acceleration"]
CSV_FILES = ["time_history.csv", "load_displacement.csv", "contact_forces.csv",
             "convergence.csv"]


def run(command, output, log_name):
    if os.path.isdir(output):
        shutil.rmtree(output)
    environment = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                       OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                       DEAL_II_NUM_THREADS="1")
    print("running:", " ".join(command), flush=True)
    result = subprocess.run(command, env=environment, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    with open(output + "." + log_name + ".log", "w") as log:
        log.write(result.stdout)
    if result.returncode != 0:
        print(result.stdout[-3000:])
        exit_with([f"{' '.join(command[:4])}... exited with "
                   f"{result.returncode}"])
    return result.stdout


def relative_difference(serial, parallel, floor=0.0):
    """max |serial - parallel| / max |serial|, the scale at least 'floor'
    (a column that is round-off in both runs, such as the momentum of a
    body at rest, is measured against the file's larger columns)."""
    # Empty cells (the first level's convergence rate) read as NaN in both.
    serial = np.nan_to_num(np.asarray(serial, float))
    parallel = np.nan_to_num(np.asarray(parallel, float))
    if serial.shape != parallel.shape:
        return np.inf
    scale = max(np.max(np.abs(serial)), floor) if serial.size else floor
    difference = np.max(np.abs(serial - parallel)) if serial.size else 0.0
    return difference / scale if scale > 0 else difference


def compare_fields(checks, serial, parallel, tolerance, where):
    """The last vertex table of each run (Output/Vertex table = true: double
    precision; VTU and HDF5 fields are single precision)."""
    serial_files = sorted(glob.glob(os.path.join(serial, "*.vertices.csv")))
    parallel_files = sorted(glob.glob(os.path.join(parallel,
                                                   "*.vertices.csv")))
    where = where or "."
    serial_h5 = glob.glob(os.path.join(serial, "*.h5"))
    if serial_h5:  # Output/Format = hdf5 (checkpoints are named checkpoint-*)
        fields = [f for f in serial_h5 if "checkpoint-" not in f]
        parallel_h5 = [f for f in glob.glob(os.path.join(parallel, "*.h5"))
                       if "checkpoint-" not in f]
        checks(f"{where}: {len(parallel_h5)} HDF5 field files and "
               f"{len(glob.glob(os.path.join(parallel, '*.xdmf')))} .xdmf, "
               f"serial {len(fields)}", len(parallel_h5) == len(fields) and
               os.path.exists(os.path.join(parallel, "solution.xdmf")) ==
               os.path.exists(os.path.join(serial, "solution.xdmf")))
    checks(f"{where}: {len(parallel_files)} vertex tables, serial "
           f"{len(serial_files)}", len(parallel_files) == len(serial_files))
    if not serial_files or len(parallel_files) != len(serial_files):
        return
    a = np.loadtxt(serial_files[-1], delimiter=",", skiprows=1)
    b = np.loadtxt(parallel_files[-1], delimiter=",", skiprows=1)
    for name, columns in (("vertices", slice(0, 4)),
                          ("displacement", slice(4, 7)),
                          ("rotation", slice(7, 10))):
        difference = relative_difference(a[:, columns], b[:, columns])
        checks(f"{where}: {os.path.basename(serial_files[-1])}: {name} "
               f"differs by {difference:.2e} relative (tolerance "
               f"{tolerance:g})", difference <= tolerance)


def vector_scale(table, field):
    """For a component (name ending in _x, _y or _z) the largest of its
    vector's components: a component that is zero by symmetry (the y
    momentum of a plate vibrating in z, 1e-15) is round-off, and its
    difference is measured against the vector, not against itself."""
    if field[-2:] not in ("_x", "_y", "_z"):
        return 0.0
    components = [field[:-1] + c for c in "xyz" if field[:-1] + c in table.dtype.names]
    return max(np.nanmax(np.abs(table[c])) for c in components)


# Columns that are extremes over every Newton iterate of a step, converged
# or not: an unconverged iterate carries the linear solver's round-off
# times the tangent's condition number, which no split of the work can
# remove (two serial runs with different direct solvers differ as much).
ITERATE_COLUMNS = ("min_distance",)


def compare_csv(checks, serial, parallel, tolerance, where,
                iterate_tolerance=None):
    for name in CSV_FILES:
        path = os.path.join(serial, name)
        if not os.path.exists(path):
            continue
        a = np.genfromtxt(path, delimiter=",", names=True)
        b = np.genfromtxt(os.path.join(parallel, name), delimiter=",",
                          names=True)
        name = os.path.join(where, name)
        checks(f"{name}: {b.size} rows, serial {a.size}", a.size == b.size)
        if a.size != b.size or a.size == 0:  # 0: a header only (no stage)
            continue
        fields = [f for f in a.dtype.names
                  if not f.endswith("_s") and "seconds" not in f]  # no clocks
        floor = 1e-6 * max(np.nanmax(np.abs(a[f])) for f in fields)
        iterate = [f for f in fields
                   if f in ITERATE_COLUMNS and iterate_tolerance is not None]
        groups = [([f for f in fields if f not in iterate], tolerance),
                  (iterate, iterate_tolerance)]
        for group, allowed in groups:
            worst, column = 0.0, ""
            for field in group:
                difference = relative_difference(
                    a[field], b[field], max(floor, vector_scale(a, field)))
                if difference > worst:
                    worst, column = difference, field
            if group:
                checks(f"{name}: largest relative difference {worst:.2e} "
                       f"({column or 'none'}; tolerance {allowed:g})",
                       worst <= allowed)


FIELD_COLUMNS = {"u": slice(4, 7), "r": slice(7, 10)}  # vertex table


def point_value_components(prm, assignments):
    """{name: component} of Quantities of interest/Point values (the prm's
    entry, or the last --set of it): 'tip_w: 1 0.5 0 uz; ...'."""
    entry = ""
    with open(prm) as f:
        text = re.sub(r"\\\n", " ", f.read())
    for line in text.splitlines():
        match = re.match(r"\s*set\s+Point values\s*=(.*)", line)
        if match:
            entry = match.group(1)
    for assignment in assignments:
        key, _, value = assignment.partition("=")
        if key.strip() == "Quantities of interest/Point values":
            entry = value
    components = {}
    for item in filter(None, (i.strip() for i in entry.split(";"))):
        name, _, spec = item.partition(":")
        components[name.strip()] = spec.split()[-1] if spec.split() else ""
    return components


def field_scales(directory, components):
    """{name: largest entry of the sampled field} from the directory's last
    vertex table (none without Output/Vertex table)."""
    tables = sorted(glob.glob(os.path.join(directory, "*.vertices.csv")))
    if not tables:
        return {}
    table = np.loadtxt(tables[-1], delimiter=",", skiprows=1, ndmin=2)
    return {name: float(np.max(np.abs(table[:, FIELD_COLUMNS[c[0]]])))
            for name, c in components.items() if c[:1] in FIELD_COLUMNS}


def compare_summaries(checks, serial, parallel, ranks, tolerance, restarted,
                      scales):
    with open(os.path.join(serial, "summary.json")) as f:
        a = json.load(f)
    with open(os.path.join(parallel, "summary.json")) as f:
        b = json.load(f)
    checks(f"summary.json: mpi_ranks = {b.get('mpi_ranks')}",
           b.get("mpi_ranks") == ranks)
    for name, value in a.get("qoi", {}).items():
        scale = scales.get(name, 0.0)
        difference = relative_difference([value], [b["qoi"].get(name, np.inf)],
                                         scale)
        against = f" of the field's {scale:.3g}" if scale > abs(value) else ""
        checks(f"{name} = {b['qoi'].get(name)}, serial {value} "
               f"(relative {difference:.1e}{against})", difference <= tolerance)
    for key in ("steps",) if restarted else ("newton_iterations", "steps"):
        if key in a:
            checks(f"{key}: {b.get(key)}, serial {a[key]}",
                   b.get(key) == a[key])


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--restart-from-middle", action="store_true")
    parser.add_argument("--check-pvtu", action="store_true")
    parser.add_argument("--tolerance", type=float, default=1e-10)
    parser.add_argument("--iterate-tolerance", type=float,
                        help="tolerance of the columns that are extremes "
                        "over all Newton iterates (%s); default: --tolerance"
                        % ", ".join(ITERATE_COLUMNS))
    parser.add_argument("--expect-solvers", nargs=2,
                        metavar=("SERIAL", "PARALLEL"),
                        help="the linear_solver of each run's summary.json")
    args = parser.parse_args()
    overrides = []
    for assignment in args.set:
        overrides += ["--set", assignment]
    serial = os.path.join(args.output, "serial")
    parallel = os.path.join(args.output, f"ranks-{args.ranks}")
    os.makedirs(args.output, exist_ok=True)
    run([args.coshell, args.prm, "--output", serial] + overrides, serial,
        "serial")
    pvtu = ["--set", "Output/Format=pvtu"] if args.check_pvtu else []
    restart = []
    if args.restart_from_middle:
        checkpoints = sorted(glob.glob(os.path.join(serial, "checkpoint-*.h5")))
        if not checkpoints:
            exit_with(["the serial run wrote no checkpoint"])
        restart = ["--restart", checkpoints[len(checkpoints) // 2]]
    log = run([args.mpirun, "--oversubscribe", "-np", str(args.ranks),
               args.coshell, args.prm, "--output", parallel] + overrides +
              restart + pvtu, parallel, "mpi")

    checks = Checks()
    checks(f"the parallel log says 'results written' "
           f"{log.count('results written to')} time(s)",
           log.count("results written to") == 1)
    partial = glob.glob(os.path.join(parallel, "**", "*.partial"),
                        recursive=True)
    checks(f"{len(partial)} partial files left", not partial)
    scales = field_scales(serial, point_value_components(args.prm, args.set))
    compare_summaries(checks, serial, parallel, args.ranks, args.tolerance,
                      args.restart_from_middle, scales)
    if args.expect_solvers:
        check_solvers(checks, (serial, parallel), args.expect_solvers)
    # A refinement study writes each level into its own directory.
    for level in [""] + sorted(os.path.basename(d) for d in
                               glob.glob(os.path.join(serial, "level-*"))):
        a, b = os.path.join(serial, level), os.path.join(parallel, level)
        compare_fields(checks, a, b, args.tolerance, level)
        compare_csv(checks, a, b, args.tolerance, level,
                    args.iterate_tolerance)
    if args.restart_from_middle:
        floor = run_floor(args, overrides, restart)
        compare_checkpoints(checks, serial, parallel, floor, args.tolerance)
    if args.check_pvtu:
        check_pieces(checks, parallel, args.ranks)
    checks.exit()


def check_solvers(checks, directories, expected):
    """Each run's summary.json names the expected linear solver."""
    for directory, method in zip(directories, expected):
        with open(os.path.join(directory, "summary.json")) as f:
            used = json.load(f).get("linear_solver")
        checks(f"{os.path.basename(directory)}: linear_solver {used}, "
               f"expected {method}", used == method)


def check_pieces(checks, parallel, ranks):
    """Output/Format = pvtu: the series lists .pvtu files, the last of which
    joins one piece per rank; the pieces together hold every triangle."""
    import xml.etree.ElementTree as ElementTree
    with open(os.path.join(parallel, "summary.json")) as f:
        n_cells = json.load(f)["n_cells"]
    series = ElementTree.parse(os.path.join(parallel, "solution.pvd"))
    shells = [d.get("file") for d in series.iter("DataSet")
              if d.get("part") == "0"]
    checks(f"solution.pvd lists {len(shells)} .pvtu files",
           bool(shells) and all(s.endswith(".pvtu") for s in shells))
    if not shells:
        return
    record = ElementTree.parse(os.path.join(parallel, shells[-1]))
    pieces = [p.get("Source") for p in record.iter("Piece")]
    checks(f"{shells[-1]} joins {len(pieces)} pieces", len(pieces) == ranks)
    cells = 0
    for piece in pieces:
        path = os.path.join(parallel, piece)
        if not os.path.exists(path):
            checks(f"piece {piece} is missing", False)
            continue
        piece_cells = int(next(ElementTree.parse(path).iter("Piece"))
                          .get("NumberOfCells"))
        checks(f"{piece}: {piece_cells} triangles", piece_cells > 0)
        cells += piece_cells
    checks(f"the pieces hold {cells} triangles, the mesh {n_cells}",
           cells == n_cells)


def run_floor(args, overrides, restart):
    """Restarts serially from the parallel run's checkpoint with another
    direct solver; returns that run's directory (the round-off floor)."""
    methods = [a.partition("=")[2] for a in args.set
               if a.partition("=")[0] == "Linear solver/Method"]
    other = "amesos-klu" if methods[-1:] == ["umfpack"] else "umfpack"
    floor = os.path.join(args.output, "serial-" + other)
    run([args.coshell, args.prm, "--output", floor] + overrides + restart +
        ["--set", "Linear solver/Method=" + other], floor, "floor")
    return floor


def last_checkpoint(directory):
    files = sorted(glob.glob(os.path.join(directory, "checkpoint-*.h5")))
    return files[-1] if files else None


def compare_checkpoints(checks, serial, parallel, floor, tolerance):
    """The last checkpoints' state, each dataset within the tolerance or ten
    times the floor run's distance from the serial run."""
    import h5py
    a_file, b_file, c_file = (last_checkpoint(d)
                              for d in (serial, parallel, floor))
    name_of = lambda f: os.path.basename(f) if f else None  # noqa: E731
    checks(f"last checkpoint {name_of(b_file)}, serial {name_of(a_file)}, "
           f"floor run {name_of(c_file)}",
           b_file and c_file and name_of(a_file) == name_of(b_file) ==
           name_of(c_file))
    if not (b_file and c_file):
        return
    with h5py.File(a_file, "r") as a, h5py.File(b_file, "r") as b, \
         h5py.File(c_file, "r") as c:
        for name in a:
            if name not in b:
                checks(f"dataset {name} missing in the parallel checkpoint",
                       False)
                continue
            difference = relative_difference(np.ravel(a[name][()]),
                                             np.ravel(b[name][()]))
            if name not in STATE_DATASETS:
                print(f"info last checkpoints: {name} differs by "
                      f"{difference:.2e} relative (not asserted)")
                continue
            round_off = relative_difference(np.ravel(a[name][()]),
                                            np.ravel(c[name][()]))
            allowed = max(tolerance, 10 * round_off)
            checks(f"last checkpoints: {name} differs by {difference:.2e} "
                   f"relative (floor {round_off:.2e}; allowed {allowed:.2e})",
                   difference <= allowed)

if __name__ == "__main__":
    main()
