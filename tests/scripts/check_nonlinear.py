#!/usr/bin/python3
"""Runs a nonlinear coshell scene and checks its load-displacement path and
Newton history against references given here.

  check_nonlinear.py --coshell BIN --prm FILE --output DIR [--set A/B=v ...]
     [--point QOI LOAD_FACTOR REFERENCE]...  value at that load factor
     [--table CSV COLUMN QOI SIGN]...  every row of a published table
                               (first column: load factor; '#' lines are
                               notes) whose load factor the path reaches:
                               SIGN * QOI against COLUMN
     [--rtol R] [--length L]   |value - reference| <= R * max(|reference|, L)
     [--min-order P]           some Newton iteration shows convergence order
                               >= P (log r_{k+1} / log r_k, relative residuals)
     [--min-correction-order P] the same for the Newton correction norms
     [--max-iterations N]      no step needs more than N iterations
     [--limit-point]           the load factor rises, then falls (a limit point
                               was passed) while the QOI of --monotone grows
     [--monotone QOI]
     [--minimum QOI LOAD_FACTOR VALUE]  the QOI at that load factor is at
                               least VALUE
     [--min-steps N]           the path has at least N converged steps (with
                               one requested load step: a step was cut)
     [--parameter COLUMN]      --point positions are values of COLUMN
                               (default load_factor; time for staged scenes)
"""
import argparse
import csv
import math

from coshell_checks import (add_scene_arguments, exit_with, read_summary,
                            run_scene_of)


def check_points(rows, points, rtol, length, column="load_factor"):
    failures = []
    for name, factor, reference in points:
        factor, reference = float(factor), float(reference)
        row = min(rows, key=lambda r: abs(float(r[column]) - factor))
        if abs(float(row[column]) - factor) > 1e-9:
            failures.append(f"no step at {column} {factor}")
            continue
        value = float(row[name])
        scale = max(abs(reference), length)
        error = abs(value - reference) / scale
        verdict = "ok" if error <= rtol else "FAIL"
        print(f"{name} at {column} {factor}: {value:.6g} vs {reference:.6g} "
              f"-> error {error:.3e} of {scale:.4g} (tolerance {rtol}) {verdict}")
        if verdict != "ok":
            failures.append(f"{name} at {factor}")
    return failures


def table_points(path, column, qoi, sign):
    """The (QOI, load factor, reference) triples of a reference table; the
    sign turns the table's magnitudes into the QOI's signed values."""
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    points = []
    for row in csv.DictReader(lines):
        factor = float(row["load_factor"])
        if factor > 0:
            points.append((qoi, factor, float(sign) * float(row[column])))
    return points


def reached(rows, points, column):
    """The points whose load factor the path has a step at."""
    return [p for p in points
            if any(abs(float(r[column]) - p[1]) <= 1e-9 for r in rows)]


def observed_orders(history, column, floor):
    """Observed orders p = log(e2/e1) / log(e1/e0) of three consecutive
    decreasing values of COLUMN in one step, in the asymptotic range
    (e0 < 1e-2, e2 above the round-off FLOOR). This estimate is independent
    of the constant C in e_{k+1} = C e_k^p."""
    orders = []
    steps = {}
    for row in history:
        if float(row[column]) > 0:
            steps.setdefault(row["step"], []).append(float(row[column]))
    for values in steps.values():
        for e0, e1, e2 in zip(values, values[1:], values[2:]):
            if e0 < 1e-2 and e2 < e1 < e0 and e2 > floor:
                orders.append(math.log(e2 / e1) / math.log(e1 / e0))
    return orders


def convergence_orders(history):
    """Orders of the relative residuals (round-off floor 1e-13)."""
    return observed_orders(history, "relative_residual", 1e-13)


def correction_orders(history):
    """Orders of the Newton correction norms (floor 1e-15): the error
    estimate when the residual stalls at a round-off floor (stiff
    membranes) before its order shows."""
    return observed_orders(history, "correction_norm", 1e-15)


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--point", nargs=3, action="append", default=[])
    parser.add_argument("--table", nargs=4, action="append", default=[])
    parser.add_argument("--rtol", type=float, default=0.01)
    parser.add_argument("--length", type=float, default=0.0)
    parser.add_argument("--min-order", type=float)
    parser.add_argument("--min-correction-order", type=float)
    parser.add_argument("--max-iterations", type=int)
    parser.add_argument("--max-total-iterations", type=int,
                        help="bound on every Newton correction of the run, "
                             "failed attempts included (a regression "
                             "guard on a measured count)")
    parser.add_argument("--limit-point", action="store_true")
    parser.add_argument("--monotone")
    parser.add_argument("--minimum", nargs=3, action="append", default=[])
    parser.add_argument("--min-steps", type=int)
    parser.add_argument("--parameter", default="load_factor",
                        help="column the --point positions refer to "
                             "(load_factor, or time for staged scenes)")
    args = parser.parse_args()

    rows, history = run_scene_of(args, "load_displacement.csv",
                                 "newton_history.csv")

    points = list(args.point)
    for path, column, qoi, sign in args.table:
        table = table_points(path, column, qoi, sign)
        # Step cuts may put the path beside some rows; most must be hit.
        hit = reached(rows, table, args.parameter)
        print(f"{path}: {len(hit)} of {len(table)} rows of {column} reached")
        if len(hit) < len(table) // 2:
            points += table  # the missing ones fail below
        else:
            points += hit
    failures = check_points(rows, points, args.rtol, args.length,
                            args.parameter)
    checks = len(points) + len(args.minimum)
    for name, factor, minimum in args.minimum:
        row = min(rows, key=lambda r: abs(float(r["load_factor"]) - float(factor)))
        value = float(row[name])
        print(f"{name} at load factor {row['load_factor']}: {value:.6g} "
              f"(required >= {minimum})")
        if abs(float(row["load_factor"]) - float(factor)) > 1e-9 or value < float(minimum):
            failures.append(f"{name} below {minimum}")
    for minimum, orders, what, failure in (
            (args.min_correction_order, correction_orders,
             "order of the Newton corrections",
             "no quadratic convergence of the corrections"),
            (args.min_order, convergence_orders,
             "Newton convergence order", "no quadratic convergence observed")):
        if minimum is None:
            continue
        checks += 1
        best = max(orders(history), default=0)
        print(f"best observed {what}: {best:.2f} (required >= {minimum})")
        if best < minimum:
            failures.append(failure)
    if args.max_iterations is not None:
        checks += 1
        worst = max(int(r["iterations"]) for r in rows)
        print(f"most Newton iterations in a step: {worst} (limit {args.max_iterations})")
        if worst > args.max_iterations:
            failures.append("too many iterations")
    if args.max_total_iterations is not None:
        checks += 1
        total = sum(1 for r in history if float(r["correction_norm"]) != 0)
        reported = read_summary(args.output)["newton_corrections"]
        print(f"Newton corrections in the run, failed attempts included: "
              f"{total} (summary.json: {reported}; limit "
              f"{args.max_total_iterations})")
        if reported != total:
            failures.append("summary.json's newton_corrections differs from "
                            "newton_history.csv")
        if total > args.max_total_iterations:
            failures.append("too many Newton iterations in the run")
    if args.min_steps is not None:
        checks += 1
        print(f"converged steps: {len(rows)} (required >= {args.min_steps})")
        if len(rows) < args.min_steps:
            failures.append("fewer converged steps than required (no step cut?)")
    if args.limit_point:
        checks += 1
        factors = [float(r["load_factor"]) for r in rows]
        peaks = [i for i in range(1, len(factors) - 1)
                 if factors[i - 1] < factors[i] > factors[i + 1]]
        passed = bool(peaks)
        growing = all(float(b[args.monotone]) * float(rows[-1][args.monotone]) >= 0
                      for b in rows) if args.monotone else True
        if args.monotone:
            values = [abs(float(r[args.monotone])) for r in rows]
            growing = growing and all(b > a for a, b in zip(values, values[1:]))
        for i in peaks:
            print(f"limit point: load factor {factors[i]:.5g} at step {i + 1}")
        if not passed:
            failures.append("no limit point passed")
        if not growing:
            failures.append(f"|{args.monotone}| did not grow at every step")
    exit_with(failures, checks)


if __name__ == "__main__":
    main()
