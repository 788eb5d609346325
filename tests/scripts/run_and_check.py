#!/usr/bin/python3
"""Runs coshell on a scene and checks its summary.json / convergence.csv
against reference values given on this command line (not in the prm), so
that a test states its own independent reference. Given no check, it
fails without running.

  run_and_check.py --coshell BIN --prm FILE --output DIR [--set A/B=v ...]
      [--value QOI REFERENCE RTOL]   |qoi - reference| <= rtol |reference|
      [--below QOI BOUND]            qoi <= bound (a value whose reference
                                     is 0, e.g. a rigid-body frequency)
      [--error-above QOI REFERENCE RTOL]  the method is known to miss the
                                     reference by more than rtol
      [--min-rate RATE]              last observed rate in convergence.csv
      [--min-self-order P]           order observed from the three finest
                                     levels alone, p = log2(d1/d2) with
                                     d = differences of successive values
                                     (needs no reference; halving h)
      [--max-rate RATE]
      [--max-iterations N] [--min-iterations N]
                                     bounds on linear_solver_iterations
                                     (Krylov iterations; deterministic)
      [--no-coarser-than SETTING QOI REFERENCE]
                                     runs the scene again with --set SETTING
                                     (into OUTPUT.baseline) and asserts, level
                                     by level of convergence.csv, that QOI's
                                     error against REFERENCE is no larger
                                     than that run's
"""
import argparse
import math
import os
import sys

from coshell_checks import (add_scene_arguments, exit_with, read_rows,
                            read_summary, run_scene)
from richardson import richardson


def run_coshell(args, output=None, extra_settings=()):
    output = run_scene(args.coshell, args.prm, output or args.output,
                       list(args.set) + list(extra_settings))
    return read_summary(output)


def level_errors(output, qoi, reference):
    return [abs(float(row[qoi]) - reference) / abs(reference)
            for row in read_rows(os.path.join(output, "convergence.csv"))]


def check_no_coarser(args, setting, qoi, reference):
    """Level by level, this run's error is at most the error of the same
    scene run with SETTING (another element, say)."""
    baseline = args.output + ".baseline"
    run_coshell(args, baseline, [setting])
    ours = level_errors(args.output, qoi, float(reference))
    theirs = level_errors(baseline, qoi, float(reference))
    failures = []
    for level, (mine, other) in enumerate(zip(ours, theirs)):
        passed = mine <= other
        print(f"{qoi} level {level}: relative error {mine:.4e} against "
              f"{other:.4e} with {setting} {'ok' if passed else 'FAIL'}")
        if not passed:
            failures.append(f"{qoi} level {level} coarser than with {setting}")
    if len(ours) != len(theirs):
        failures.append("the two runs have different numbers of levels")
    return failures


def check_values(summary, checks, within):
    """within=True: error <= rtol; within=False: error > rtol (a documented
    failure to converge, asserted so that a change is noticed)."""
    failures = []
    for name, reference, rtol in checks:
        value = summary["qoi"][name]
        error = abs(value - float(reference)) / abs(float(reference))
        passed = error <= float(rtol) if within else error > float(rtol)
        relation = "tolerance" if within else "expected above"
        print(f"{name}: {value:.8g} vs reference {reference} -> relative error "
              f"{error:.3e} ({relation} {rtol}) {'ok' if passed else 'FAIL'}")
        if not passed:
            failures.append(name)
    return failures


def check_below(summary, bounds):
    failures = []
    for name, bound in bounds:
        value = summary["qoi"][name]
        passed = value <= float(bound)
        print(f"{name}: {value:.8g}, bound {bound} "
              f"{'ok' if passed else 'FAIL'}")
        if not passed:
            failures.append(name)
    return failures


def check_rate(output, low, high):
    rows = read_rows(os.path.join(output, "convergence.csv"))
    print("convergence.csv:")
    for row in rows:
        print("  " + ", ".join(f"{k}={v}" for k, v in row.items()))
    rate = float(rows[-1]["rate"])
    failures = []
    if low is not None and rate < low:
        failures.append(f"rate {rate:.3f} < {low}")
    if high is not None and rate > high:
        failures.append(f"rate {rate:.3f} > {high}")
    print(f"observed rate on the finest pair: {rate:.3f}")
    return failures


def check_self_order(output, minimum):
    """Observed order and Richardson-extrapolated value from the three
    finest levels of convergence.csv (h halves between levels)."""
    rows = read_rows(os.path.join(output, "convergence.csv"))
    name = list(rows[0])[4]
    q1, q2, q3 = (float(r[name]) for r in rows[-3:])
    order, extrapolated = richardson(q1, q2, q3)
    if math.isnan(order):
        print(f"{name}: non-monotone finest levels ({q1}, {q2}, {q3})")
        return [f"{name} does not converge monotonically"]
    print(f"{name}: self-observed order {order:.2f} (required >= {minimum}); "
          f"Richardson extrapolation {extrapolated:.6g}")
    return [] if order >= minimum else [f"{name}: order {order:.2f} < {minimum}"]


def check_iterations(summary, low, high):
    iterations = summary["linear_solver_iterations"]
    print(f"linear solver iterations: {iterations} (bounds {low}, {high})")
    failures = []
    if low is not None and iterations < low:
        failures.append(f"{iterations} iterations < {low}")
    if high is not None and iterations > high:
        failures.append(f"{iterations} iterations > {high}")
    return failures


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--value", nargs=3, action="append", default=[],
                        metavar=("QOI", "REFERENCE", "RTOL"))
    parser.add_argument("--below", nargs=2, action="append", default=[],
                        metavar=("QOI", "BOUND"))
    parser.add_argument("--error-above", nargs=3, action="append", default=[],
                        metavar=("QOI", "REFERENCE", "RTOL"))
    parser.add_argument("--min-rate", type=float)
    parser.add_argument("--max-rate", type=float)
    parser.add_argument("--min-self-order", type=float)
    parser.add_argument("--min-iterations", type=int)
    parser.add_argument("--max-iterations", type=int)
    parser.add_argument("--no-coarser-than", nargs=3, action="append",
                        default=[], metavar=("SETTING", "QOI", "REFERENCE"))
    args = parser.parse_args()
    checks = (len(args.value) + len(args.below) + len(args.error_above) +
              len(args.no_coarser_than) +
              sum(x is not None for x in (args.min_self_order, args.min_rate,
                                          args.max_rate, args.min_iterations,
                                          args.max_iterations)))
    if checks == 0:
        # A run that checks nothing would pass whatever coshell computed.
        print("0 passed, 1 failed")
        sys.exit("FAIL: run_and_check.py was given no check (--value, "
                 "--below, --error-above, --min-rate, --max-rate, --min-self-order, "
                 "--no-coarser-than, --min-iterations or --max-iterations)")

    summary = run_coshell(args)
    failures = check_values(summary, args.value, True)
    failures += check_values(summary, args.error_above, False)
    failures += check_below(summary, args.below)
    if args.min_rate is not None or args.max_rate is not None:
        failures += check_rate(args.output, args.min_rate, args.max_rate)
    if args.min_self_order is not None:
        failures += check_self_order(args.output, args.min_self_order)
    for setting, qoi, reference in args.no_coarser_than:
        failures += check_no_coarser(args, setting, qoi, reference)
    iteration_bounds = (args.min_iterations, args.max_iterations)
    if iteration_bounds != (None, None):
        failures += check_iterations(summary, *iteration_bounds)
    exit_with(failures, checks)


if __name__ == "__main__":
    main()
