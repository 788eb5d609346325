"""The helpers every test checker shares: run a scene, read its outputs,
check values and collect the failures, and the energy balance of a
dynamic run with contact.

  run_scene(coshell, prm, output, assignments)  the run's directory
  run_scene_of(args, csv, ...)                   the same from the
                                                 checker's arguments; the
                                                 rows of its CSV files
  read_rows(path), read_summary(output)          CSV rows, summary.json
  Checks()                                       'ok'/'FAIL' per check,
      checks(what, ok) (or checks.that(ok, what)),
      checks.near(name, value, reference, tolerance),
      checks.exit(): 'N passed, M failed' and the exit status
  exit_with(failures, checks)                    the same for a list
  energy_balance(history, forces), check_energy_balance(...)

Drawing lives in checker_figures.py, imported only when a checker is
asked for figures."""
import csv
import json
import math
import os
import shutil
import subprocess
import sys


def run_scene(coshell, prm, output, assignments=(), restart=None,
              quiet=False):
    """Runs 'coshell prm --output output --set a ...' (from the checkpoint
    'restart' if given) into a fresh 'output' and returns it. Exits the
    checker with a failure line if coshell fails. quiet: coshell's own
    output is not shown."""
    if os.path.isdir(output):
        shutil.rmtree(output)
    command = [coshell, prm, "--output", output]
    if restart:
        command += ["--restart", restart]
    for assignment in assignments:
        command += ["--set", assignment]
    print("running:", " ".join(repr(c) for c in command), flush=True)
    status = subprocess.run(
        command, stdout=subprocess.DEVNULL if quiet else None).returncode
    if status != 0:
        print("0 passed, 1 failed")
        sys.exit(f"FAIL: coshell exited with status {status}: "
                 + " ".join(command))
    return output


def run_scene_of(args, *csv_files):
    """Runs the scene of the checker's arguments (add_scene_arguments:
    --coshell, --prm, --output, --set) and returns the rows of each of
    'csv_files' the run wrote (one list of rows, or a tuple of them)."""
    run_scene(args.coshell, args.prm, args.output, args.set)
    tables = tuple(read_rows(os.path.join(args.output, name))
                   for name in csv_files)
    return tables[0] if len(tables) == 1 else tables


def add_scene_arguments(parser):
    """The arguments every scene checker takes: the coshell binary, the
    scene, the output directory and --set overrides."""
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--set", action="append", default=[])


def kept_factors_failures(output):
    """For runs with Linear solver/Reuse factorization: a failure line if
    no solve used kept factors, i.e. if the solver ignored the request."""
    reused = read_summary(output).get("reused_factor_solves", 0)
    print(f"solves with kept factors: {reused}")
    if reused > 0:
        return []
    return ["no solve used kept factors (summary.json reused_factor_solves)"]


def exit_with(failures, checks=None):
    """Prints the verdict, 'N passed, M failed' of 'checks' checks (one
    check in all without it), and the failures (one line each), and
    exits with the test's status."""
    if checks is None:
        print(f"{1 - bool(failures)} passed, {int(bool(failures))} failed")
    else:
        print(f"{checks - len(failures)} passed, {len(failures)} failed")
    for failure in failures:
        print("FAIL: " + failure)
    sys.exit(1 if failures else 0)


def surgical_real_time_factor(summary):
    """Simulated over wall time of the IOL injection's stages 1 to 3
    (fold, push, deploy), from summary.json's dynamic_stages: stage 4, the
    wait for the lens to settle, has slow, cheap steps that would flatter
    the whole run's factor. The whole run's for a summary without
    stages."""
    stages = [s for s in summary.get("dynamic_stages", []) if s["stage"] <= 3]
    if not stages:
        return summary["real_time_factor"]
    return (sum(s["simulated_time_s"] for s in stages) /
            sum(s["wall_time_s"] for s in stages))


def read_rows(path):
    """The rows of a CSV file as dictionaries (values as text)."""
    with open(path) as f:
        return list(csv.DictReader(f))


def floats(rows, name):
    """Column 'name' of CSV rows as a list of floats."""
    return [float(r[name]) for r in rows]


def column(rows, name):
    """Column 'name' of CSV rows as a numpy array."""
    import numpy as np
    return np.array(floats(rows, name))


def read_summary(output):
    """summary.json of the run in 'output'."""
    with open(os.path.join(output, "summary.json")) as f:
        return json.load(f)


def run_contact_scene(args, pairs):
    """Runs the scene of 'args' (add_scene_arguments), reads its
    contact_forces.csv and time_history.csv rows and checks that the
    smallest gap over every pair and step stays >= 0 ('pairs' names them
    in the check). Returns the checks, the force rows and the history."""
    forces, history = run_scene_of(args, "contact_forces.csv",
                                   "time_history.csv")
    checks = Checks()
    gaps = [float(r["min_distance"]) for r in forces]
    finite = [g for g in gaps if math.isfinite(g)]
    gap = min(finite, default=math.nan)
    print(f"smallest gap over every pair and step: {gap:.4g} mm "
          f"({len(finite)} rows with a pair in reach)")
    print_gaps_by_obstacle(forces)
    checks(f"every pair's gap stays >= 0 ({pairs})", bool(finite) and gap >= 0)
    return checks, forces, history


def print_gaps_by_obstacle(forces):
    """Each obstacle's smallest gap over the run (obstacle 0: the shell
    against itself), as each row of contact_forces.csv gives its own."""
    smallest = {}
    for row in forces:
        obstacle = int(float(row["obstacle"]))
        smallest[obstacle] = min(smallest.get(obstacle, math.inf),
                                 float(row["min_distance"]))
    print("smallest gap by obstacle (0: self contact), mm: " + ", ".join(
        f"{k}: {v:.3g}" for k, v in sorted(smallest.items())))


def force_file_check(output, name, obstacle, direction, column):
    """Contact/Obstacle k/Force file 'name' against the obstacle's rows of
    contact_forces.csv (both written by one run, 17 digits): its header
    is 'time,<column>,force_n' and each row is the time, the obstacle's
    displacement (ux, uy, uz) along the unit 'direction' and minus its
    force (fx, fy, fz) along it. A consistency check of two outputs.
    Returns (ok, a sentence)."""
    with open(os.path.join(output, name)) as f:
        header = f.readline().strip()
    written = read_rows(os.path.join(output, name))
    forces = [r for r in read_rows(os.path.join(output, "contact_forces.csv"))
              if int(float(r["obstacle"])) == obstacle]
    norm = math.sqrt(sum(d * d for d in direction))
    unit = [d / norm for d in direction]
    worst = 0.0
    for row, force in zip(written, forces):
        u = [float(force[c]) for c in ("ux", "uy", "uz")]
        f = [float(force[c]) for c in ("fx", "fy", "fz")]
        expected = (float(force["time"]), sum(a * b for a, b in zip(u, unit)),
                    -sum(a * b for a, b in zip(f, unit)))
        scales = (1.0, max(map(abs, u)), max(map(abs, f)))
        for value, want, scale in zip(
                (float(row[k]) for k in ("time", column, "force_n")),
                expected, scales):
            worst = max(worst, abs(value - want) / max(scale, 1e-300))
    ok = (header == f"time,{column},force_n" and len(written) == len(forces)
          and len(forces) > 0 and worst < 1e-10)
    return ok, (f"{name}: header '{header}', {len(written)} rows, the "
                f"obstacle {obstacle}'s rows of contact_forces.csv along "
                f"{unit} to {worst:.1e} of their components (1e-10)")


def energy_balance(history, forces):
    """The energies at the last step of a dynamic run with contact: the
    work the moving obstacles did on the shell (contact_forces.csv 'work',
    per obstacle), the external work, and the shell's strain and kinetic
    energy, the energy dissipated by drag, damping and friction and the
    barrier (or penalty) energy stored in contact (time_history.csv).
    'remainder' is what the first two supplied and the others do not hold:
    the integrator's error."""
    last = history[-1]
    works = {int(r["obstacle"]): float(r["work"]) for r in forces
             if r["step"] == last["step"] and int(r["obstacle"]) > 0}
    energies = {name: float(last[name]) for name in
                ("external_work", "strain_energy", "kinetic_energy",
                 "dissipated_energy", "contact_energy")}
    held = sum(energies.values()) - energies["external_work"]
    energies["obstacle_work"] = works
    energies["remainder"] = (sum(works.values()) + energies["external_work"]
                             - held)
    return energies


def add_strip_arguments(parser):
    """The strip of the contact wrap and roll-up checkers: its length
    (the loaded part), thickness, bending stiffness EI and largest end
    moment (load factor 1)."""
    for name in ("--length", "--thickness", "--bending-stiffness",
                 "--moment-max"):
        parser.add_argument(name, type=float, required=True)


def check_energy_balance(checks, history, forces, tolerance, suppliers,
                         plunger=None):
    """The energy balance of energy_balance() at the run's end: the
    remainder within 'tolerance' of the work supplied (the moving
    obstacles' and the external work). 'suppliers' names the obstacles in
    the check; 'plunger', an obstacle whose work is printed on its own."""
    energies = energy_balance(history, forces)
    works = energies["obstacle_work"]
    supplied = sum(works.values()) + energies["external_work"]
    remainder = energies["remainder"]
    own = ""
    if plunger is not None:
        part = works.get(plunger, 0.0)
        own = (f"obstacle {plunger}'s work {part:.5g}, the other obstacles' "
               f"{sum(works.values()) - part:.4g}, ")
    print("energy (N mm): {}work supplied {:.5g} (external "
          "{external_work:.3g}); strain {strain_energy:.5g}, kinetic "
          "{kinetic_energy:.3g}, drag, damping and friction "
          "{dissipated_energy:.5g}, barrier {contact_energy:.3g}; remainder "
          "{remainder:.3g} ({:.3g} % of the work supplied)".format(
              own, supplied, 100 * remainder / supplied, **energies))
    checks(f"energy balance within {100 * tolerance:g} % of the work "
           f"{suppliers} supplied", abs(remainder) <= tolerance * supplied)
    return energies


class Checks:
    """Prints 'ok'/'FAIL' per check and collects the failures; exit()
    prints 'N passed, M failed' and exits with the test's status.
    record() keeps measured values for write_report()."""

    def __init__(self):
        self.failures = []
        self.passed = 0
        self.measured = []

    def __call__(self, what, ok, name=None, value=None):
        """One check: 'what' says it, 'ok' is its verdict; a 'name' and a
        'value' are recorded for the report."""
        print(("ok   " if ok else "FAIL ") + what)
        if ok:
            self.passed += 1
        else:
            self.failures.append(what)
        if name is not None:
            self.record(name, value)
        return ok

    def that(self, ok, what, name=None, value=None):
        """The same with the verdict first: checks.that(ok, what)."""
        return self(what, ok, name, value)

    def near(self, name, value, reference, tolerance, scale=None):
        """|value - reference| <= tolerance * scale, scale |reference| by
        default (a relative tolerance)."""
        scale = abs(reference) if scale is None else scale
        error = abs(value - reference) / scale
        return self(f"{name} = {value:.8g}, reference {reference:.8g}: "
                    f"relative error {error:.3e} (tolerance {tolerance:g})",
                    error <= tolerance)

    def record(self, name, value):
        self.measured.append((name, value))

    def write_report(self, path, test, digits=10):
        """Appends 'test,name,value' lines of the recorded values."""
        with open(path, "a") as f:
            for name, value in self.measured:
                f.write(f"{test},{name},{value:.{digits}g}\n")

    def exit(self):
        print(f"{self.passed} passed, {len(self.failures)} failed")
        for failure in self.failures:
            print("FAIL: " + failure)
        sys.exit(1 if self.failures else 0)
