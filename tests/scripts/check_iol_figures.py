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
import subprocess
import sys

from scene_runner import add_scene_arguments, exit_with, run_scene

RENDER = os.path.join(os.path.dirname(__file__), "..", "..", "doc", "scripts",
                      "render_vtu.py")


def render(arguments):
    command = [sys.executable, RENDER] + arguments
    print("rendering:", " ".join(command), flush=True)
    return subprocess.run(command).returncode == 0


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
    os.makedirs(args.figures, exist_ok=True)
    pvd = os.path.join(args.output, "solution.pvd")
    first = sorted(f for f in os.listdir(args.output)
                   if f.startswith("solution-") and f.endswith(".vtu"))[0]
    with open(os.path.join(args.output, first)) as f:
        cells = int(re.search(r'NumberOfCells="(\d+)"', f.read()).group(1))
    failures = []
    mesh_png = os.path.join(args.figures, "lens_mesh.png")
    sequence_png = os.path.join(args.figures, "compression_sequence.png")
    drawn = {
        mesh_png: render(["--vtu", os.path.join(args.output, first), "--out",
                          mesh_png, "--warp-scale", "0", "--edges",
                          "--color-by", "thickness", "--view", "90", "-90",
                          "--no-obstacles", "--title",
                          f"the lens, {cells} triangles (paper: "
                          f"{args.paper_triangles})"]),
        sequence_png: render(["--pvd", pvd, "--all", "--out",
                              os.path.join(args.output, "compression"),
                              "--montage", sequence_png, "--color-by",
                              "displacement_magnitude", "--view", "60", "-90"]),
    }
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
