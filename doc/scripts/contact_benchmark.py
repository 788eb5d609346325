#!/usr/bin/python3
"""Contact cost benchmark, all runs in one invocation so their ratios are
comparable. Writes to doc/performance/, stamped with machine and commit:

- contact_scaling.csv / .png: the plate resting on a plane (prm/contact/
  plate_on_plane.prm, statics, barrier, the symmetric tangent with
  CHOLMOD), shell 256 to 99856 triangles,
  plane 50 to 80000 triangles (STL written here): contact seconds per
  evaluation (detection + pair terms + collision filter; of detection and
  filter, the R-trees' builds) and their share of the solve.
- contact_methods.csv / .png: the funnel (prm/contact/funnel.prm) with
  barrier or penalty, without and with friction (mu = 0.1 on both
  obstacles): wall time, steps, Newton iterations, contact share.

  /usr/bin/python3 doc/scripts/contact_benchmark.py --coshell build/coshell \
      [--work DIR] [--timeout SECONDS]

--work keeps the runs in DIR and reuses a run whose summary.json is there
(to finish an interrupted benchmark); --timeout ends a run that takes
longer (recorded as not converged).
"""
import argparse
import json
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
SHELL_SUBDIVISIONS = [8, 16, 32, 158]  # crossed: 4 n^2 triangles (to 99856)
PLANE_SQUARES = [5, 50, 200]           # 2 m^2 triangles


def write_plane_stl(path, m):
    """The square [-10, 20]^2 in z = 0 as 2 m^2 triangles (ASCII STL)."""
    h = 30.0 / m
    with open(path, "w") as f:
        f.write("solid plane\n")
        for i in range(m):
            for j in range(m):
                x0, y0 = -10 + i * h, -10 + j * h
                corners = [(x0, y0), (x0 + h, y0), (x0 + h, y0 + h), (x0, y0 + h)]
                for a, b, c in ((0, 1, 2), (0, 2, 3)):
                    f.write(" facet normal 0 0 1\n  outer loop\n")
                    for k in (a, b, c):
                        f.write(f"   vertex {corners[k][0]} {corners[k][1]} 0\n")
                    f.write("  endloop\n endfacet\n")
        f.write("endsolid plane\n")


TIMEOUT = None  # seconds per run (--timeout)


def run(coshell, prm, output, settings, allow_failure=False):
    if os.path.exists(os.path.join(output, "summary.json")):
        with open(os.path.join(output, "summary.json")) as f:
            return json.load(f)
    command = [coshell, os.path.join(ROOT, "prm", "contact", prm), "--output", output,
               "--set", "Output/Write VTU=false", "--set", "Parallel/Threads=1",
               "--set", "Contact/Pairs=all",
               "--set", "Nonlinear solver/Residual tolerance=1e-7"]
    for s in settings:
        command += ["--set", s]
    try:
        result = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                text=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return {"error": f"not done after {TIMEOUT} s"}
    if result.returncode != 0:
        if allow_failure:
            return {"error": result.stderr.strip()}
        raise RuntimeError(result.stderr)
    with open(os.path.join(output, "summary.json")) as f:
        return json.load(f)


def contact_seconds(summary):
    c = summary["contact"]
    return c["detection_s"] + c["pair_terms_s"] + c["collision_filter_s"]


def scaling_rows(coshell, work):
    rows = []
    for m in PLANE_SQUARES:
        stl = os.path.join(work, f"plane-{m}.stl")
        write_plane_stl(stl, m)
        for n in SHELL_SUBDIVISIONS:
            # The symmetric tangent (the plate carries no moments, so it is
            # exact at equilibrium) lets CHOLMOD factorize: with UMFPACK a
            # Newton iteration of the 10^5-triangle plate took a minute.
            summary = run(coshell, "plate_on_plane.prm", os.path.join(work, f"p{m}-{n}"),
                          [f"Mesh/Subdivisions x={n}", f"Mesh/Subdivisions y={n}",
                           f"Contact/Obstacle 1/Mesh file={stl}",
                           "Nonlinear solver/Tangent=symmetric"], allow_failure=True)
            if "error" in summary:
                rows.append({"shell_triangles": 4 * n * n, "obstacle_triangles": 2 * m * m,
                             "evaluations": 0, "contact_ms_per_evaluation": None,
                             "detection_ms": None, "pair_terms_ms": None, "filter_ms": None,
                             "tree_build_ms": None,
                             "contact_share_of_solve": None,
                             "error": summary["error"].replace(",", ";")})
                continue
            steps = summary["load_steps"]
            evaluations = summary["newton_iterations"] + steps
            seconds = contact_seconds(summary)
            rows.append({"shell_triangles": 4 * n * n, "obstacle_triangles": 2 * m * m,
                         "evaluations": evaluations,
                         "contact_ms_per_evaluation": round(1e3 * seconds / evaluations, 3),
                         "detection_ms": round(1e3 * summary["contact"]["detection_s"] / evaluations, 3),
                         "pair_terms_ms": round(1e3 * summary["contact"]["pair_terms_s"] / evaluations, 3),
                         "filter_ms": round(1e3 * summary["contact"]["collision_filter_s"] / evaluations, 3),
                         # Part of detection and filter: the R-trees' builds.
                         "tree_build_ms": round(1e3 * summary["contact"]["tree_build_s"] / evaluations, 3),
                         "contact_share_of_solve": round(seconds / summary["wall_time_s"]["solve"], 3),
                         "error": ""})
    return rows


def method_rows(coshell, work):
    rows = []
    for method in ("barrier", "penalty"):
        for mu in (0.0, 0.1):
            # Friction needs the energy line search (doc/theory/contact.md,
            # section 19.7).
            summary = run(coshell, "funnel.prm", os.path.join(work, f"f-{method}-{mu}"),
                          [f"Contact/Method={method}",
                           f"Contact/Obstacle 1/Friction coefficient={mu}",
                           f"Contact/Obstacle 2/Friction coefficient={mu}",
                           f"Nonlinear solver/Line search={'true' if mu > 0 else 'false'}"],
                          allow_failure=True)
            if "error" in summary:
                rows.append({"method": method, "friction": mu, "steps": 0,
                             "newton_iterations": 0, "wall_time_s": 0,
                             "real_time_factor": 0, "contact_share": 0,
                             "smallest_gap_mm": None, "largest_penetration_mm": None,
                             "error": summary["error"].replace(",", ";")})
                continue
            total = summary["time_stepping_s"]["total"]
            rows.append({"method": method, "friction": mu, "steps": summary["steps"],
                         "newton_iterations": summary["newton_iterations"],
                         "wall_time_s": round(total, 3),
                         "real_time_factor": round(summary["real_time_factor"], 4),
                         "contact_share": round(contact_seconds(summary) / total, 3),
                         "smallest_gap_mm": summary["contact"]["smallest_gap"],
                         "largest_penetration_mm": summary["contact"]["largest_penetration"],
                         "error": ""})
    return rows


def plot_scaling(rows, commit):
    figure, axes = plt.subplots(figsize=(7, 4.5))
    for m in PLANE_SQUARES:
        part = [r for r in rows if r["obstacle_triangles"] == 2 * m * m
                and r["contact_ms_per_evaluation"] is not None]
        axes.loglog([r["shell_triangles"] for r in part],
                    [r["contact_ms_per_evaluation"] for r in part], "o-",
                    label=f"plane of {2 * m * m} triangles")
    finish_plot(figure, axes, "shell triangles", "contact ms per evaluation",
                f"Plate on a plane: detection + pair terms + filter ({commit})",
                os.path.join(OUT, "contact_scaling.png"))


def plot_methods(rows, commit):
    figure, axes = plt.subplots(figsize=(7, 4))
    labels = [f"{r['method']}\nmu = {r['friction']}" for r in rows]
    walls = [r["wall_time_s"] for r in rows]
    shares = [r["wall_time_s"] * r["contact_share"] for r in rows]
    axes.bar(labels, walls, label="time stepping")
    axes.bar(labels, shares, label="of which contact")
    for x, r in enumerate(rows):
        axes.text(x, walls[x], f"{r['steps']} steps", ha="center", va="bottom", fontsize=8)
    finish_plot(figure, axes, "", "wall time (s)",
                f"Funnel, 0.85 s simulated ({commit})",
                os.path.join(OUT, "contact_methods.png"))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--work")
    parser.add_argument("--timeout", type=float)
    args = parser.parse_args()
    global TIMEOUT
    TIMEOUT = args.timeout
    coshell = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    os.makedirs(OUT, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        work = args.work or scratch
        os.makedirs(work, exist_ok=True)
        scaling = scaling_rows(coshell, work)
        methods = method_rows(coshell, work)
    stamp = f"machine: {machine}; commit {commit}; Parallel/Threads = 1"
    write_csv(os.path.join(OUT, "contact_scaling.csv"), scaling,
              [stamp, "prm/contact/plate_on_plane.prm (statics, barrier, 4 load steps, "
                      "Contact/Pairs = all, Residual tolerance 1e-7, "
                      "Nonlinear solver/Tangent = symmetric)"])
    write_csv(os.path.join(OUT, "contact_methods.csv"), methods,
              [stamp, "prm/contact/funnel.prm (dynamics, 0.85 s simulated)"])
    plot_scaling(scaling, commit)
    plot_methods(methods, commit)


if __name__ == "__main__":
    main()
