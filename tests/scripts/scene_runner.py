"""Runs coshell on a scene into a fresh output directory (shared by the
test checkers)."""
import csv
import json
import math
import os
import shutil
import subprocess
import sys


def run_scene(coshell, prm, output, assignments):
    """Runs 'coshell prm --output output --set a ...'; exits the checker
    with a failure line if coshell fails."""
    if os.path.isdir(output):
        shutil.rmtree(output)
    command = [coshell, prm, "--output", output]
    for assignment in assignments:
        command += ["--set", assignment]
    print("running:", " ".join(repr(c) for c in command), flush=True)
    if subprocess.run(command).returncode != 0:
        print("0 passed, 1 failed")
        sys.exit("FAIL: coshell exited with an error")


def add_scene_arguments(parser):
    """The arguments every scene checker takes: the coshell binary, the
    scene, the output directory and --set overrides."""
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--set", action="append", default=[])


def kept_factors_failures(output):
    """For runs with Linear solver/Reuse factorization: a failure line if
    no solve used kept factors, i.e. if the solver ignored the request
    (as CHOLMOD did until 2026-11-27)."""
    with open(os.path.join(output, "summary.json")) as f:
        reused = json.load(f).get("reused_factor_solves", 0)
    print(f"solves with kept factors: {reused}")
    if reused > 0:
        return []
    return ["no solve used kept factors (summary.json reused_factor_solves)"]


def exit_with(failures):
    """Prints the verdict and the failures (one line each) and exits with
    the test's status."""
    print(f"{1 - bool(failures)} passed, {int(bool(failures))} failed")
    for failure in failures:
        print("FAIL: " + failure)
    sys.exit(1 if failures else 0)


def read_rows(path):
    """The rows of a CSV file as dictionaries."""
    with open(path) as f:
        return list(csv.DictReader(f))


def run_contact_scene(args, pairs):
    """Runs the scene of 'args' (add_scene_arguments), reads its
    contact_forces.csv and time_history.csv rows and checks that the
    smallest gap over every pair and step stays >= 0 ('pairs' names them
    in the check). Returns the checks, the force rows and the history."""
    run_scene(args.coshell, args.prm, args.output, args.set)
    checks = Checks()
    forces = read_rows(os.path.join(args.output, "contact_forces.csv"))
    history = read_rows(os.path.join(args.output, "time_history.csv"))
    gaps = [float(r["min_distance"]) for r in forces]
    gap = min([g for g in gaps if math.isfinite(g)], default=math.inf)
    print(f"smallest gap over every pair and step: {gap:.4g} mm")
    checks(f"every pair's gap stays >= 0 ({pairs})", gap >= 0)
    return checks, forces, history


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


class Checks:
    """Prints 'ok'/'FAIL' per check and collects the failures for
    exit_with()."""

    def __init__(self):
        self.failures = []

    def __call__(self, what, ok):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            self.failures.append(what)
