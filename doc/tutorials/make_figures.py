#!/usr/bin/python3
"""Draws the tutorials' figures (doc/tutorials/*.png) from the CSV files
of the tutorials' runs.

Run the tutorials' commands first (their output directories under
/tmp/tutorials/, as each tutorial gives them; the injection's checker
with --figures /tmp/tutorials/injection/png, whose deployment sequence
is copied at a smaller size), then

    /usr/bin/python3 doc/tutorials/make_figures.py [--runs /tmp/tutorials]
        [--only clamped cantilever vibration cylinder injection]

A figure whose run directory is missing is skipped with a note.
"""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def column(table, name):
    return [float(r[name]) for r in table]


def save(fig, name):
    path = os.path.join(HERE, name)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print("wrote", path)


def clamped(run):
    """Tutorial 1: the centre deflection's error against h."""
    table = rows(os.path.join(run, "convergence.csv"))
    h = column(table, "h")
    error = column(table, "relative_error")
    fig, ax = plt.subplots(figsize=(5, 3.6))
    ax.loglog(h, error, "o-", label="CST+DKT, crossed")
    ax.loglog(h, [error[-1] * (x / h[-1]) ** 2 for x in h], "k--", lw=0.8,
              label="slope 2")
    ax.set_xticks(h)
    ax.set_xticks([], minor=True)
    ax.set_xticklabels([f"{x:g}" for x in h])
    ax.set_xlabel("h (longest edge)")
    ax.set_ylabel("relative error of w at the centre")
    ax.set_title("Clamped square plate, uniform pressure")
    ax.grid(True, which="both", lw=0.3)
    ax.legend()
    save(fig, "clamped_plate_convergence.png")


def cantilever(run):
    """Tutorial 2: tip displacements against the elastica, and the tip's
    path in the x-z plane."""
    table = rows(os.path.join(run, "load_displacement.csv"))
    lam = [0.0] + column(table, "load_factor")
    u = [0.0] + column(table, "tip_u")
    w = [0.0] + column(table, "tip_w")
    length = 12.0
    fine = [i / 400 for i in range(401)]

    def exact(x):
        theta = 2 * math.pi * x
        if theta == 0:
            return 0.0, 0.0
        return (length * (math.sin(theta) / theta - 1),
                length * (1 - math.cos(theta)) / theta)

    eu = [exact(x)[0] for x in fine]
    ew = [exact(x)[1] for x in fine]
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.6))
    a.plot(fine, eu, "C0-", lw=1, label="u, elastica")
    a.plot(fine, ew, "C1-", lw=1, label="w, elastica")
    a.plot(lam, u, "C0o", ms=4, label="u, CoShell")
    a.plot(lam, w, "C1s", ms=4, label="w, CoShell")
    a.set_xlabel("load factor (M / M_max)")
    a.set_ylabel("tip displacement")
    a.grid(True, lw=0.3)
    a.legend(fontsize=8)
    b.plot([length + x for x in eu], ew, "k-", lw=1, label="elastica")
    b.plot([length + x for x in u], w, "C3o", ms=4, label="CoShell")
    b.set_aspect("equal")
    b.set_xlabel("x of the tip")
    b.set_ylabel("z of the tip")
    b.set_title("path of the tip", fontsize=10)
    b.grid(True, lw=0.3)
    b.legend(fontsize=8)
    fig.suptitle("Cantilever rolled up by an end moment", fontsize=11)
    save(fig, "cantilever_end_moment.png")


def vibration(run):
    """Tutorial 3: the free edge's deflection and the energy's drift in
    the dynamic stage."""
    table = [r for r in rows(os.path.join(run, "time_history.csv"))
             if int(float(r["stage"])) == 2]
    t = column(table, "time")
    t0 = t[0] - float(table[0]["dt"])
    t = [x - t0 for x in t]
    w = column(table, "tip_w")
    energy = column(table, "total_energy")
    fig, (a, b) = plt.subplots(2, 1, figsize=(8, 4.6), sharex=True)
    a.plot(t, w, "C0-", lw=1)
    period = 2 * math.pi / 3.492
    for k in range(11):
        a.axvline(k * period, color="0.7", lw=0.5)
    a.set_ylabel("tip_w (m)")
    a.set_title("Cantilever plate released from its static deflection "
                "(grey: multiples of Leissa's T_1)", fontsize=10)
    a.grid(True, axis="y", lw=0.3)
    b.plot(t, [e / energy[0] - 1 for e in energy], "C2-", lw=1)
    b.set_ylabel("total energy / first - 1")
    b.set_xlabel("time since the release (s)")
    b.grid(True, lw=0.3)
    save(fig, "cantilever_free_vibration.png")


def cylinder(run, bending_stiffness=1.0, length=3.3, radius=2.0,
             thickness=0.2, start_gap=0.002):
    """Tutorial 4: the cylinder's force on the strip and the smallest gap
    against the end moment, with the curved-beam reference above M*."""
    steps = rows(os.path.join(run, "load_displacement.csv"))
    forces = rows(os.path.join(run, "contact_forces.csv"))
    wrap_moment = bending_stiffness / (radius + thickness / 2)
    moment_max = 2 * 0.261904762
    by_step = {int(float(r["step"])): r for r in forces}
    ratio, force, gap = [], [], []
    for r in steps:
        step = int(float(r["step"]))
        ratio.append(float(r["load_factor"]) * moment_max / wrap_moment)
        f = by_step[step]
        force.append(1e3 * math.hypot(float(f["fx"]), float(f["fz"])))
        gap.append(float(f["min_distance"]))
    r = radius + thickness / 2 + start_gap
    phi = length / r
    factor = (1 - math.cos(phi)) / (r * (phi / 2 - math.sin(2 * phi) / 4))
    above = [x for x in ratio if x * wrap_moment >= bending_stiffness / r]
    reference = [1e3 * (x * wrap_moment - bending_stiffness / r) * factor
                 for x in above]
    rotation = column(steps, "tip_rotation")
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(11, 3.4))
    a.plot(ratio, rotation, "C0.", ms=3, label="CoShell")
    a.plot([0, 1], [0, wrap_moment * length / bending_stiffness], "k-",
           lw=1, label="free arc, M L / EI")
    a.axvline(1.0, color="0.6", lw=0.6)
    a.set_xlabel("M / M*")
    a.set_ylabel("tip rotation (rad)")
    a.grid(True, lw=0.3)
    a.legend(fontsize=8)
    near = [i for i, x in enumerate(ratio) if x >= 0.95]
    b.plot([ratio[i] for i in near], [force[i] for i in near], "C0.", ms=4,
           label="CoShell, |f| on the cylinder")
    b.plot(above, reference, "k-", lw=1, label="curved beam (Castigliano)")
    b.axvline(1.0, color="0.6", lw=0.6)
    b.set_xlabel("M / M*")
    b.set_ylabel("contact force (mN)")
    b.grid(True, lw=0.3)
    b.legend(fontsize=8)
    finite = [(x, g) for x, g in zip(ratio, gap) if math.isfinite(g)]
    c.plot([x for x, _ in finite], [1e3 * g for _, g in finite], "C3.",
           ms=4)
    c.axhline(1.0, color="0.6", lw=0.6)
    c.text(1.002, 0.97, "activation distance", fontsize=8, va="top")
    c.set_ylim(0, 1.1)
    c.set_xlabel("M / M*")
    c.set_ylabel("min_distance (um)")
    c.set_title("smallest gap (none in reach below M*)", fontsize=10)
    c.grid(True, lw=0.3)
    fig.suptitle("Strip wrapped on a cylinder", fontsize=11)
    save(fig, "strip_on_cylinder.png")


def injection(run):
    """Tutorial 5: the plunger force against its travel, and the optic's
    width across the axis (its rims at y = +-3 mm) in time."""
    table = rows(os.path.join(run, "plunger_force.csv"))
    t = column(table, "time")
    x = column(table, "plunger_displacement")
    f = [1e3 * v for v in column(table, "force_n")]
    push_time = 1.3 + (15 + 6.9) / 5  # rod_out_time + stroke / speed, s
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.4))
    push = [i for i, v in enumerate(t) if v <= push_time + 1e-9]
    a.plot([x[i] for i in push], [f[i] for i in push], "C0-", lw=0.8)
    a.set_xlabel("plunger travel (mm)")
    a.set_ylabel("plunger force (mN)")
    a.set_title("the push (stage 2)", fontsize=10)
    a.grid(True, lw=0.3)
    history = [r for r in rows(os.path.join(run, "time_history.csv"))
               if float(r["time"]) <= push_time + 1.0 + 1e-9]
    th = column(history, "time")
    width = [math.hypot(6 + float(r["rim_yp_uy"]) - float(r["rim_ym_uy"]),
                        float(r["rim_yp_uz"]) - float(r["rim_ym_uz"]))
             for r in history]
    centre = column(history, "optic_ux")
    inside = [tt for tt, c in zip(th, centre) if 11.5 <= c <= 15]
    if inside:
        b.axvspan(min(inside), max(inside), color="C1", alpha=0.2,
                  label="optic's centre in the nozzle")
    b.plot(th, width, "C0-", lw=1, label="optic's width (rim to rim)")
    b.axhline(3.5, color="k", lw=0.8, ls="--", label="nozzle, 3.5 mm")
    for edge, name in ((1.3, "push"), (push_time, "deploy")):
        b.axvline(edge, color="0.6", lw=0.6)
        b.text(edge + 0.05, 6.3, name, fontsize=8)
    b.set_ylim(0, 6.8)
    b.set_xlabel("time (s)")
    b.set_ylabel("mm")
    b.set_title("stages 1 to 3: fold, push, deploy", fontsize=10)
    b.grid(True, lw=0.3)
    b.legend(fontsize=7, loc="lower left")
    fig.suptitle("IOL injection", fontsize=11)
    save(fig, "iol_plunger_force.png")
    sequence = os.path.join(run, "png", "injection_sequence.png")
    if os.path.exists(sequence):
        from PIL import Image
        image = Image.open(sequence).convert("RGB")
        image = image.resize((1200, round(1200 * image.height / image.width)),
                             Image.LANCZOS)
        path = os.path.join(HERE, "iol_injection_sequence.png")
        image.quantize(colors=96).save(path, optimize=True)
        print("wrote", path)


FIGURES = {"clamped": clamped, "cantilever": cantilever,
           "vibration": vibration, "cylinder": cylinder,
           "injection": injection}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", default="/tmp/tutorials",
                        help="the directory holding the runs' outputs")
    parser.add_argument("--only", nargs="+", choices=sorted(FIGURES),
                        default=sorted(FIGURES))
    args = parser.parse_args()
    for name in args.only:
        run = os.path.join(args.runs, name)
        if not os.path.isdir(run):
            print(f"skipped {name}: no {run}")
            continue
        FIGURES[name](run)


if __name__ == "__main__":
    main()
