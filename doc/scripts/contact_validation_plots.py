#!/usr/bin/python3
"""Contact validation plots (doc/validation/contact/), from fresh runs:

- plate_on_plane.png: the plane's reaction over the drop (dynamics)
  against the weight, barrier and penalty;
- incline.png: the plate's slide u_x(t) on the incline against
  u0 + v0 t + a t^2/2 with a = g (sin theta - mu cos theta), sliding,
  sticking and frictionless;
- funnel.png: the plunger force and the smallest gap over time (every
  iterate), barrier;
- strip_on_cylinder.png: the cylinder's force on the wrapped strip's tip
  against the end moment, with the curved-beam reference;
- self_contact_rollup.png: the strip rolled onto itself (side views of
  the roll-up, coloured by contact pressure).

  /usr/bin/python3 doc/scripts/contact_validation_plots.py --coshell build/coshell \
      [--only strip_on_cylinder self_contact_rollup ...]
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import ROOT, finish_plot, machine_and_commit  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "validation", "contact")
WEIGHT = 5.886e-4  # N, rho h A g of the plate


def run(coshell, prm, output, settings=()):
    command = [coshell, os.path.join(ROOT, "prm", "contact", prm), "--output", output,
               "--set", "Output/Write VTU=false"]
    for s in settings:
        command += ["--set", s]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def plate_on_plane(coshell, work, commit):
    figure, axes = plt.subplots(figsize=(7, 4))
    for method in ("barrier", "penalty"):
        out = os.path.join(work, f"plate-{method}")
        run(coshell, "plate_on_plane.prm", out,
            ["Analysis/Type=dynamic", f"Contact/Method={method}"])
        r = [x for x in rows(os.path.join(out, "contact_forces.csv"))]
        axes.plot([float(x["time"]) * 1e3 for x in r],
                  [-float(x["fz"]) / WEIGHT for x in r], "o-", ms=3, label=method)
    axes.axhline(1, color="k", lw=0.8, label="weight")
    finish_plot(figure, axes, "time (ms)", "reaction / weight",
                f"Plate dropped on a plane ({commit})",
                os.path.join(OUT, "plate_on_plane.png"))


def incline(coshell, work, commit):
    g = 9810.0
    cases = [("sliding, 20 deg, mu 0.2", [], 0.3420201, 0.9396926, 0.2),
             ("frictionless, 20 deg", ["Contact/Obstacle 1/Friction coefficient=0"],
              0.3420201, 0.9396926, 0.0),
             ("sticking, 10 deg, mu 0.2", ["Loads/Gravity=1703.489, 0, -9660.965"],
              0.1736482, 0.9848078, 0.2)]
    figure, axes = plt.subplots(figsize=(7, 4))
    for k, (label, settings, sin, cos, mu) in enumerate(cases):
        out = os.path.join(work, f"incline-{k}")
        run(coshell, "incline_friction.prm", out, settings)
        r = rows(os.path.join(out, "time_history.csv"))
        t = [float(x["time"]) for x in r]
        u = [float(x["centre_ux"]) for x in r]
        axes.plot(t, u, "o", ms=3, label=f"{label}: CoShell")
        a = max(g * (sin - mu * cos), 0.0)
        # The analytic slide from the state at t = 10 ms (after landing).
        i0 = min(range(len(t)), key=lambda i: abs(t[i] - 0.01))
        v0 = (u[i0 + 1] - u[i0 - 1]) / (t[i0 + 1] - t[i0 - 1]) if a > 0 else 0.0
        axes.plot([s for s in t if s >= t[i0]],
                  [u[i0] + v0 * (s - t[i0]) + 0.5 * a * (s - t[i0]) ** 2 for s in t if s >= t[i0]],
                  "-", lw=1, label=f"{label}: a = {a:.1f} mm/s^2")
    finish_plot(figure, axes, "time (s)", "u_x of the plate's centre (mm)",
                f"Plate on an incline ({commit})", os.path.join(OUT, "incline.png"))


def funnel(coshell, work, commit):
    out = os.path.join(work, "funnel")
    run(coshell, "funnel.prm", out)
    r = rows(os.path.join(out, "contact_forces.csv"))
    plunger = [x for x in r if x["obstacle"] == "2"]
    figure, axes = plt.subplots(figsize=(7, 4))
    axes.plot([float(x["time"]) for x in plunger],
              [-1e3 * float(x["fx"]) for x in plunger], "-", label="plunger force (mN)")
    gaps = [float(x["min_distance"]) for x in plunger]
    axes.plot([float(x["time"]) for x in plunger],
              [1e3 * g if g != float("inf") else float("nan") for g in gaps], "-",
              label="smallest gap over the step's iterates (um)")
    axes.set_yscale("symlog", linthresh=0.1)
    finish_plot(figure, axes, "time (s)", "mN / um",
                f"Strip pushed through a funnel, barrier ({commit})",
                os.path.join(OUT, "funnel.png"))


def strip_on_cylinder(coshell, work, commit):
    """The scene of prm/contact/strip_on_cylinder.prm: EI = 1, R = 2,
    h = 0.2, start gap 0.002, L = 3.3, M_max = 1.1 EI / (R + h/2)."""
    out = os.path.join(work, "wrap")
    run(coshell, "strip_on_cylinder.prm", out)
    wrap_moment, moment_max = 1 / 2.1, 1.1 / 2.1
    radius = 2.102
    angle = 3.3 / radius
    steps = rows(os.path.join(out, "load_displacement.csv"))
    forces = rows(os.path.join(out, "contact_forces.csv"))
    moments = [float(x["load_factor"]) * moment_max for x in steps]
    measured = [(float(x["fx"]) ** 2 + float(x["fz"]) ** 2) ** 0.5 for x in forces]
    beam = [max(m - 1 / radius, 0) * (1 - math.cos(angle))
            / (radius * (angle / 2 - math.sin(2 * angle) / 4)) for m in moments]
    figure, axes = plt.subplots(figsize=(7, 4))
    axes.plot([m / wrap_moment for m in moments], [1e3 * f for f in measured],
              "o", ms=3, label="CoShell: the cylinder's force on the strip")
    axes.plot([m / wrap_moment for m in moments], [1e3 * f for f in beam], "-",
              lw=1, label="clamped arc held at its tip (Castigliano)")
    axes.axvline(1, color="k", lw=0.8, label="M* = EI / (R + h/2)")
    finish_plot(figure, axes, "end moment M / M*", "force (mN)",
                f"Strip wrapped on a cylinder ({commit})",
                os.path.join(OUT, "strip_on_cylinder.png"))


def self_contact_rollup(coshell, work, commit):
    out = os.path.join(work, "rollup")
    command = [coshell, os.path.join(ROOT, "prm", "contact",
                                     "self_contact_rollup.prm"), "--output", out]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    render = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                          "render_vtu.py")
    subprocess.run([sys.executable, render, "--pvd",
                    os.path.join(out, "solution.pvd"), "--times", "0.5", "1",
                    "1.2", "2.5", "--out", os.path.join(work, "rollup-frame"),
                    "--montage", os.path.join(OUT, "self_contact_rollup.png"),
                    "--view", "0", "-90", "--color-by", "contact_pressure",
                    "--title", f"Strip rolled onto itself ({commit})"],
                   check=True, stdout=subprocess.DEVNULL)


PLOTS = {"plate_on_plane": plate_on_plane, "incline": incline,
         "funnel": funnel, "strip_on_cylinder": strip_on_cylinder,
         "self_contact_rollup": self_contact_rollup}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--only", nargs="+", choices=sorted(PLOTS),
                        default=sorted(PLOTS))
    args = parser.parse_args()
    coshell = os.path.abspath(args.coshell)
    _, commit = machine_and_commit()
    os.makedirs(OUT, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        for name in args.only:
            PLOTS[name](coshell, work, commit)


if __name__ == "__main__":
    main()
