#!/usr/bin/python3
"""Speed against error of the two Lie groups (Time integration/Lie group =
R3xSO3 | SE3) with generalized alpha (rho_inf = 1) on two motions of the
free plate (prm/dynamics/free_flying_plate.prm, 256 triangles, 1 thread):

- tumbling: the scene as given (spin about a non-principal axis plus a
  twist rate), final positions of two corners after 1 s against a run at
  dt = 0.00078125 s on R3xSO3 (the same reference for both groups);
- spin: a stiff plate (E = 1e11) spinning at 1 rad/s about its normal, the
  far corner after 150 degrees against the rigid rotation (exact).

Writes doc/performance/lie_group_speed_error.csv and .png (error against
wall time of the time stepping), stamped with machine and commit; all runs
in one invocation so their ratios are comparable.

  /usr/bin/python3 doc/scripts/lie_group_speed_error.py --coshell build/coshell
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import ROOT, finish_plot, machine_and_commit, write_csv  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
PRM = os.path.join(ROOT, "prm", "dynamics", "free_flying_plate.prm")
GROUPS = ["R3xSO3", "SE3"]
SPIN_ANGLE = 2.617993878  # 150 degrees at 1 rad/s
MOTIONS = {
    "tumbling": {"end": 1.0, "steps": [0.1, 0.05, 0.025, 0.0125, 0.00625],
                 "settings": ["Quantities of interest/Point values=corner_x: 0 0 0 ux; "
                              "corner_z: 0 0 0 uz; far_x: 1 1 0 ux; far_y: 1 1 0 uy; "
                              "far_z: 1 1 0 uz"]},
    "spin": {"end": SPIN_ANGLE, "steps": [SPIN_ANGLE / n for n in (5, 10, 20, 40, 80)],
             "settings": ["Material/Young's modulus=1e11",
                          "Mass and damping/Initial angular velocity=0; 0; 1",
                          "Mass and damping/Initial velocity=-1.0*(y-0.5); 1.0*(x-0.5); 0",
                          "Quantities of interest/Point values=far_x: 1 1 0 ux; "
                          "far_y: 1 1 0 uy; far_z: 1 1 0 uz"]},
}


def run(coshell, motion, group, dt, work):
    spec = MOTIONS[motion]
    output = os.path.join(work, f"{motion}-{group}-{dt:.6g}")
    command = [coshell, PRM, "--output", output,
               "--set", f"Time integration/Lie group={group}",
               "--set", f"Time integration/Time step={dt!r}",
               "--set", f"Time integration/Maximum time step={dt!r}",
               "--set", f"Time integration/End time={spec['end']!r}",
               "--set", "Time integration/Spectral radius=1",
               "--set", "Nonlinear solver/Residual tolerance=1e-10",
               "--set", "Parallel/Threads=1"]
    for assignment in spec["settings"]:
        command += ["--set", assignment]
    environment = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, env=environment)
    with open(os.path.join(output, "summary.json")) as f:
        return json.load(f)


def spin_error(qoi):
    # The far corner (1, 1) turned by 150 degrees about (0.5, 0.5).
    c, s = math.cos(SPIN_ANGLE), math.sin(SPIN_ANGLE)
    exact = (0.5 + 0.5 * c - 0.5 * s - 1.0, 0.5 + 0.5 * s + 0.5 * c - 1.0, 0.0)
    return math.dist(exact, (qoi["far_x"], qoi["far_y"], qoi["far_z"]))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    args = parser.parse_args()
    coshell = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        reference = run(coshell, "tumbling", "R3xSO3", 0.00078125, work)["qoi"]
        for motion, spec in MOTIONS.items():
            for group in GROUPS:
                for dt in spec["steps"]:
                    summary = run(coshell, motion, group, dt, work)
                    qoi = summary["qoi"]
                    error = spin_error(qoi) if motion == "spin" else math.sqrt(
                        sum((qoi[k] - reference[k]) ** 2 for k in reference))
                    rows.append({"motion": motion, "lie_group": group,
                                 "dt": round(dt, 8), "steps": summary["steps"],
                                 "newton_iterations": summary["newton_iterations"],
                                 "wall_time_s": round(summary["time_stepping_s"]["total"], 4),
                                 "error": f"{error:.4e}"})
    os.makedirs(OUT, exist_ok=True)
    write_csv(os.path.join(OUT, "lie_group_speed_error.csv"), rows,
              [f"machine: {machine}; commit {commit}",
               "prm/dynamics/free_flying_plate.prm, generalized alpha rho_inf = 1, "
               "Parallel/Threads = 1; error: corner positions (tumbling: against "
               "R3xSO3 at dt = 0.00078125 s; spin: against the rigid rotation)"])
    figure, axes = plt.subplots(figsize=(7, 4.5))
    for motion, marker in (("tumbling", "o"), ("spin", "s")):
        for group, style in (("R3xSO3", "-"), ("SE3", "--")):
            points = [(float(r["wall_time_s"]), max(float(r["error"]), 1e-16))
                      for r in rows if r["motion"] == motion and r["lie_group"] == group]
            axes.loglog(*zip(*points), style, marker=marker, label=f"{motion}, {group}")
    axes.legend(fontsize=8)
    finish_plot(figure, axes, "wall time of the time stepping (s)",
                "error of the corner positions",
                f"Free plate: R3xSO3 against SE3 ({commit})",
                os.path.join(OUT, "lie_group_speed_error.png"))


if __name__ == "__main__":
    main()
