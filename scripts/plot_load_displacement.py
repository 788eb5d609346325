#!/usr/bin/python3
"""Plots load_displacement.csv of a nonlinear coshell run against its
reference_points.csv: one panel, load factor on the vertical axis, each
quantity of interest that has reference points as a line (ours) and
markers (reference). Writes load_displacement.png beside the CSV files.

  plot_load_displacement.py OUTPUT_DIR [--title TITLE]
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("directory")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    curve = read_rows(os.path.join(args.directory, "load_displacement.csv"))
    references = read_rows(os.path.join(args.directory, "reference_points.csv"))
    names = sorted({r["qoi"] for r in references})

    figure, axes = plt.subplots(figsize=(6, 4.5))
    for index, name in enumerate(names):
        colour = f"C{index}"
        axes.plot([float(r[name]) for r in curve],
                  [float(r["load_factor"]) for r in curve],
                  "-", color=colour, label=f"{name} (CoShell)")
        points = [r for r in references if r["qoi"] == name]
        axes.plot([float(r["value"]) for r in points],
                  [float(r["load_factor"]) for r in points],
                  "o", color=colour, mfc="none", label=f"{name} (reference)")
    axes.set_xlabel("displacement")
    axes.set_ylabel("load factor")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=8)
    if args.title:
        axes.set_title(args.title)
    figure.tight_layout()
    figure.savefig(os.path.join(args.directory, "load_displacement.png"), dpi=120)


if __name__ == "__main__":
    main()
