#!/usr/bin/python3
"""Runs coshell on a scene and checks its summary.json / convergence.csv
against reference values given on this command line (not in the prm), so
that a test states its own independent reference.

  run_and_check.py --coshell BIN --prm FILE --output DIR [--set A/B=v ...]
      [--value QOI REFERENCE RTOL]   |qoi - reference| <= rtol |reference|
      [--error-above QOI REFERENCE RTOL]  the method is known to miss the
                                     reference by more than rtol
      [--min-rate RATE]              last observed rate in convergence.csv
      [--max-rate RATE]
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys


def run_coshell(args):
    if os.path.isdir(args.output):
        shutil.rmtree(args.output)
    command = [args.coshell, args.prm, "--output", args.output]
    for assignment in args.set:
        command += ["--set", assignment]
    print("running:", " ".join(repr(c) for c in command), flush=True)
    result = subprocess.run(command)
    if result.returncode != 0:
        sys.exit(f"FAIL: coshell exited with status {result.returncode}")
    with open(os.path.join(args.output, "summary.json")) as f:
        return json.load(f)


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


def check_rate(output, low, high):
    with open(os.path.join(output, "convergence.csv")) as f:
        rows = list(csv.DictReader(f))
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


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--value", nargs=3, action="append", default=[],
                        metavar=("QOI", "REFERENCE", "RTOL"))
    parser.add_argument("--error-above", nargs=3, action="append", default=[],
                        metavar=("QOI", "REFERENCE", "RTOL"))
    parser.add_argument("--min-rate", type=float)
    parser.add_argument("--max-rate", type=float)
    args = parser.parse_args()

    summary = run_coshell(args)
    failures = check_values(summary, args.value, True)
    failures += check_values(summary, args.error_above, False)
    if args.min_rate is not None or args.max_rate is not None:
        failures += check_rate(args.output, args.min_rate, args.max_rate)
    checks = len(args.value) + len(args.error_above) + (args.min_rate is not None) + (args.max_rate is not None)
    print(f"{checks - len(failures)} passed, {len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
