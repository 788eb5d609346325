#!/usr/bin/python3
"""Measures the order of accuracy in the time step of a dynamic scene: runs
it with each --dt (fixed steps), compares the final values of the --qoi
quantities with a run at --reference-dt, and asserts the observed order.

  time_order.py --coshell BIN --prm FILE --output DIR [--set A/B=v ...]
     --end T --dt h1 h2 ... --reference-dt h_ref --qoi NAME ...
     --min-order P [--csv FILE]
The error of a run is max over the QOIs of |q(h) - q(h_ref)|; the order is
the least-squares slope of log e against log h, which must be >= P (the
orders of consecutive pairs are printed too). Prints 'N passed, M failed'.
"""
import argparse
import math
import os

from coshell_checks import Checks, add_scene_arguments, read_rows, run_scene


def final_values(args, dt, qois):
    output = run_scene(args.coshell, args.prm,
                       os.path.join(args.output, f"dt_{dt:g}"),
                       [f"Time integration/Time step={dt!r}",
                        f"Time integration/Maximum time step={dt!r}",
                        f"Time integration/End time={args.end!r}"] + args.set,
                       quiet=True)
    last = read_rows(os.path.join(output, "time_history.csv"))[-1]
    return [float(last[q]) for q in qois]


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--end", type=float, required=True)
    parser.add_argument("--dt", type=float, nargs="+", required=True)
    parser.add_argument("--reference-dt", type=float, required=True)
    parser.add_argument("--qoi", nargs="+", required=True)
    parser.add_argument("--min-order", type=float, required=True)
    parser.add_argument("--csv")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    reference = final_values(args, args.reference_dt, args.qoi)
    errors = []
    for dt in args.dt:
        values = final_values(args, dt, args.qoi)
        errors.append(max(abs(v - r) for v, r in zip(values, reference)))
        print(f"dt = {dt:g}: error {errors[-1]:.4e}")
    orders = [math.log(errors[k] / errors[k + 1]) / math.log(args.dt[k] / args.dt[k + 1])
              for k in range(len(errors) - 1)]
    print("observed orders:", ", ".join(f"{p:.3f}" for p in orders))
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("dt,error\n")
            f.writelines(f"{dt!r},{e!r}\n" for dt, e in zip(args.dt, errors))
    x = [math.log(h) for h in args.dt]
    y = [math.log(e) for e in errors]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    slope = (sum((a - mx) * (b - my) for a, b in zip(x, y)) /
             sum((a - mx) ** 2 for a in x))
    checks = Checks()
    checks(f"observed order (least squares) {slope:.3f} (required >= "
           f"{args.min_order})", slope >= args.min_order)
    checks.exit()


if __name__ == "__main__":
    main()
