#!/usr/bin/python3
"""The haptic rate against the lens's size: haptic_rate.py's mode with
the scene's tangent (linearized implicit Euler, penalty contact with its
step filter, 0.5 ms steps, history every 20th step, one thread; the
paper's tangent, haptic_rate.py's last mode, runs 1.10x to 1.16x faster
on both lenses, measured by hand) on the coarse
lens of the ctests (203 triangles) and the default lens (480), in
alternating pairs, so that the machine's load, which moves within minutes
on a shared machine, falls on both alike. Each lens is folded once with
the penalty and pushed from that checkpoint. Per run: the rate and its
split, the largest strains and the smallest gap (negative: the penalty's
penetration). Writes doc/performance/haptic_rate_by_lens.csv and .png,
stamped with machine and commit.

  /usr/bin/python3 doc/scripts/haptic_rate_by_lens.py --coshell build/coshell \\
      [--pairs 4] [--push 0.2]
"""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import finish_plot, machine_and_commit, write_csv  # noqa: E402
from haptic_rate import MODES, OUT, PENALTY, folded_checkpoint, measure  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The linearized penalty at 0.5 ms, history thinned, the scene's tangent:
# the mode this script's tables measured before the paper's tangent was
# added to haptic_rate.py.
FASTEST = next(m for m in MODES if m[0].endswith("history every 20th step"))
# (optic, haptic) gmsh sizes in mm.
LENSES = {"coarse": (0.9, 0.35), "default": (0.55, 0.22)}


def folded_lenses(binary, work):
    """Per lens: its contact settings (the penalty and its mesh), the
    checkpoint after its fold and its number of triangles."""
    lenses = {}
    for name, (optic, haptic) in LENSES.items():
        contact = PENALTY + [f"Mesh/Gmsh parameters=optic_mesh_size = "
                             f"{optic}, haptic_mesh_size = {haptic}"]
        os.makedirs(os.path.join(work, name))
        checkpoint = folded_checkpoint(binary, os.path.join(work, name),
                                       contact)
        with open(os.path.join(os.path.dirname(checkpoint),
                               "summary.json")) as f:
            triangles = json.load(f)["n_cells"]
        lenses[name] = (contact, checkpoint, triangles)
    return lenses


def plot(rows, commit):
    figure, axes = plt.subplots(figsize=(6.5, 4))
    for name in LENSES:
        mine = [r for r in rows if r["lens"] == name]
        axes.plot([r["pair"] for r in mine],
                  [r["steps_per_second"] for r in mine], "o-",
                  label=f"{name} lens, {mine[0]['triangles']} triangles")
    axes.axhline(500, color="k", ls="--", lw=1, label="goal, 500 steps/s")
    axes.set_yscale("log")
    axes.set_ylim(top=1000)  # the goal inside the frame
    axes.set_xticks(sorted({r["pair"] for r in rows}))
    finish_plot(figure, axes, "pair (the two lenses one after the other)",
                "steps per second",
                f"IOL push, linearized penalty, 0.5 ms, one thread ({commit})",
                os.path.join(OUT, "haptic_rate_by_lens.png"))


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--pairs", type=int, default=4)
    parser.add_argument("--push", type=float, default=0.2,
                        help="seconds of push after the fold")
    args = parser.parse_args()
    binary = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    label, method, _, extra, step = FASTEST
    rows = []
    with tempfile.TemporaryDirectory() as work:
        lenses = folded_lenses(binary, work)
        for pair in range(1, args.pairs + 1):
            for name, (contact, checkpoint, triangles) in lenses.items():
                row = measure(binary, {contact[0]: checkpoint},
                              (label, method, contact, extra, step),
                              args.push, step, os.path.join(work, name))
                rows.append({"pair": pair, "lens": name,
                             "triangles": triangles, **row})
                print(rows[-1], flush=True)
    write_csv(os.path.join(OUT, "haptic_rate_by_lens.csv"), rows,
              [f"machine: {machine}; commit {commit}",
               f"prm/iol/injection.prm: {label}; each lens folded once with "
               f"the penalty, then {args.push:g} s of push per run; the "
               "lenses alternate, one run at a time"],
              list(dict.fromkeys(k for r in rows for k in r)))
    plot(rows, commit)


if __name__ == "__main__":
    main()
