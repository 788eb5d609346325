#!/usr/bin/env python3
"""The lens's figures, regenerated from a run (the paper's Fig. 3, the
mesh, and the compression sequence), with doc/scripts/render_vtu.py.
Runs prm/iol/compression_iso11979.prm with VTU output at D = 11.55 and
10 mm, draws the reference mesh (the paper's Fig. 3: 473 triangles
there) and the compressed lens between its clamps, and checks that the
mesh has the paper's size within 2 % and that each picture was drawn."""
import argparse
import os
import re

import checker_figures
from coshell_checks import add_scene_arguments, exit_with, run_scene


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--figures", required=True,
                        help="directory for the PNG files")
    parser.add_argument("--paper-triangles", type=int, default=473)
    args = parser.parse_args()
    run_scene(args.coshell, args.prm, args.output,
              args.set + ["Output/Write VTU=true",
                          "Output/Steps between outputs=31"])
    first = sorted(f for f in os.listdir(args.output)
                   if f.startswith("solution-") and f.endswith(".vtu"))[0]
    with open(os.path.join(args.output, first)) as f:
        cells = int(re.search(r'NumberOfCells="(\d+)"', f.read()).group(1))
    failures = []
    drawn = checker_figures.lens_pictures(
        args, os.path.join(args.output, first), cells)
    print(f"lens mesh: {cells} triangles, paper {args.paper_triangles}")
    if abs(cells - args.paper_triangles) > 0.02 * args.paper_triangles:
        failures.append(f"{cells} triangles, not within 2 % of the paper's "
                        f"{args.paper_triangles}")
    for png, ok in drawn.items():
        size = os.path.getsize(png) if os.path.exists(png) else 0
        print(f"{png}: {size} bytes")
        if not ok or size < 10000:
            failures.append(f"{png} was not drawn")
    exit_with(failures)


if __name__ == "__main__":
    main()
