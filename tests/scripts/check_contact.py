#!/usr/bin/python3
"""Runs a contact scene and checks contact_forces.csv (and the other
outputs) against references given here.

  check_contact.py --coshell BIN --prm FILE --output DIR [--set A/B=v ...]
     [--reaction COMPONENT VALUE RTOL]  the last step's force on the
                          obstacles (summed), component fx..mz, is VALUE
                          within RTOL of |VALUE|
     [--gap-nonnegative]  min_distance >= 0 on every row (every iterate)
     [--gap-below VALUE]  the last step's smallest gap is below VALUE
                          (the shell is in contact)
     [--last-gap VALUE RTOL]  the last step's smallest gap is VALUE within
                          RTOL of |VALUE| (a penalty's penetration)
     [--active-pairs MIN] the last step has at least MIN active pairs
     [--final QOI VALUE RTOL]  the last value of a quantity of interest
                          (load_displacement.csv or time_history.csv)
     [--slope QOI T0 T1 VALUE RTOL]  least-squares d2(QOI)/dt2 over the
                          rows with T0 <= time <= T1 (a uniform
                          acceleration) is VALUE within RTOL
     [--change QOI T0 T1 MAX]  |QOI(T1) - QOI(T0)| <= MAX (rows nearest
                          those times): it stays put
     [--max-abs QOI LIMIT]  |QOI| stays below LIMIT over the run
     [--force-range OBSTACLE COMPONENT LO HI]  the last step's force on
                          obstacle OBSTACLE (1-based) lies in [LO, HI]
     [--force-ratio OBSTACLE NUM DEN VALUE RTOL]  the last step's force
                          components NUM / DEN on obstacle OBSTACLE are
                          VALUE within RTOL of |VALUE| (Coulomb: ft / fn)
     [--summary KEY LO HI]  summary.json's contact[KEY] lies in [LO, HI]
     [--edge-clearance LO HI]  at the end, the height of the obstacles'
                          lowest edge (a knife's) over the shell's deformed
                          mid-surface, smallest along the edge, lies in
                          [LO, HI] (negative: the edge cut through)
     [--energy-balance TOL]  the work of the moving obstacles on the shell
                          (plus the external work) equals its strain and
                          kinetic energy, the drag's dissipation and the
                          barrier's energy within TOL of that work
     [--report FILE]      append 'test,name,value' lines of what was measured
Prints a line per check and 'N passed, M failed'; exits 1 on a failure.
"""
import argparse
import math
import os
import sys

from coshell_checks import (Checks, add_scene_arguments, energy_balance,
                            force_file_check, read_rows, read_summary,
                            run_scene_of)


def quantity_rows(output):
    for name in ("time_history.csv", "load_displacement.csv"):
        path = os.path.join(output, name)
        if os.path.exists(path):
            return read_rows(path)
    sys.exit("FAIL: no time_history.csv or load_displacement.csv")


def last_step_rows(rows):
    last = max(int(r["step"]) for r in rows)
    return [r for r in rows if int(r["step"]) == last]


def second_derivative(times, values):
    """Least-squares fit of a + b t + c t^2: returns 2 c."""
    n = len(times)
    t0 = sum(times) / n
    ts = [t - t0 for t in times]
    # Normal equations of the quadratic fit.
    s = [sum(t ** k for t in ts) for k in range(5)]
    y = [sum(v * t ** k for t, v in zip(ts, values)) for k in range(3)]
    a = [[s[0], s[1], s[2]], [s[1], s[2], s[3]], [s[2], s[3], s[4]]]
    # Cramer's rule for the t^2 coefficient.
    def det(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    c = [row[:2] + [y[i]] for i, row in enumerate(a)]
    return 2 * det(c) / det(a)


def lowest_edge_clearance(output):
    """Smallest height of the obstacles' lowest edge (the segment between
    their two lowest vertices, as last written) over the shell's deformed
    mid-surface, sampled along the edge where it lies over the shell."""
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..",
                                    "doc", "scripts"))
    import render_vtu
    frame = render_vtu.read_pvd(os.path.join(output, "solution.pvd"))[-1]
    knife = render_vtu.read_vtu(frame.obstacle_files[0]).points
    a, b = knife[knife[:, 2].argsort()[:2]]
    shell = render_vtu.read_vtu(frame.shell_file)
    x = shell.points + shell.point_data["displacement"]
    clearances = []
    for k in range(201):
        p = a + (b - a) * k / 200
        for c in range(len(shell.cell_starts)):
            t = shell.cell_vertices[shell.cell_starts[c]:][:3]
            (x0, y0), (x1, y1), (x2, y2) = x[t, 0:2]
            det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
            u = ((p[0] - x0) * (y2 - y0) - (x2 - x0) * (p[1] - y0)) / det
            v = ((x1 - x0) * (p[1] - y0) - (p[0] - x0) * (y1 - y0)) / det
            if min(u, v, 1 - u - v) >= 0:
                z = x[t[0], 2] + u * (x[t[1], 2] - x[t[0], 2]) + v * (x[t[2], 2] - x[t[0], 2])
                clearances.append(p[2] - z)
                break
    return min(clearances)


def main():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    parser.add_argument("--reaction", nargs=3, action="append", default=[])
    parser.add_argument("--gap-nonnegative", action="store_true")
    parser.add_argument("--gap-below", type=float)
    parser.add_argument("--last-gap", nargs=2, type=float)
    parser.add_argument("--active-pairs", type=int)
    parser.add_argument("--final", nargs=3, action="append", default=[])
    parser.add_argument("--slope", nargs=5, action="append", default=[])
    parser.add_argument("--max-abs", nargs=2, action="append", default=[])
    parser.add_argument("--change", nargs=4, action="append", default=[])
    parser.add_argument("--force-range", nargs=4, action="append", default=[])
    parser.add_argument("--force-ratio", nargs=5, action="append", default=[])
    parser.add_argument("--summary", nargs=3, action="append", default=[])
    parser.add_argument("--edge-clearance", nargs=2, type=float)
    parser.add_argument("--energy-balance", type=float)
    parser.add_argument("--report")
    parser.add_argument("--force-file", nargs=6, action="append", default=[],
                        metavar=("NAME", "OBSTACLE", "DX", "DY", "DZ",
                                 "COLUMN"),
                        help="a Force file against contact_forces.csv")
    args = parser.parse_args()

    forces = run_scene_of(args, "contact_forces.csv")
    last = last_step_rows(forces)
    checks = Checks()
    check = checks.that

    for name, obstacle, dx, dy, dz, column in args.force_file:
        ok, sentence = force_file_check(
            args.output, name, int(obstacle),
            (float(dx), float(dy), float(dz)), column)
        check(ok, sentence)
    for component, value, rtol in args.reaction:
        total = sum(float(r[component]) for r in last)
        error = abs(total - float(value)) / abs(float(value))
        checks.record(f"reaction_{component}_relative_error", error)
        check(error <= float(rtol),
              f"reaction {component} = {total:.10g}, expected {value}, "
              f"relative error {error:.3g} <= {rtol}")
    gaps = [float(r["min_distance"]) for r in forces]
    finite_gaps = [g for g in gaps if math.isfinite(g)]
    smallest = min(finite_gaps) if finite_gaps else math.inf
    checks.record("smallest_gap", smallest)
    if args.gap_nonnegative:
        check(smallest >= 0, f"smallest gap over every iterate {smallest:.6g} >= 0")
    if args.gap_below is not None:
        gap = min(float(r["min_distance"]) for r in last)
        check(gap < args.gap_below,
              f"last step's smallest gap {gap:.6g} < {args.gap_below} (in contact)")
    if args.last_gap:
        gap = min(float(r["min_distance"]) for r in last)
        value, rtol = args.last_gap
        error = abs(gap - value) / abs(value)
        checks.record("last_gap", gap)
        check(error <= rtol, f"last step's smallest gap {gap:.8g}, expected "
              f"{value:.8g}, relative error {error:.3g} <= {rtol}")
    if args.active_pairs is not None:
        pairs = sum(int(float(r["active_pairs"])) for r in last)
        check(pairs >= args.active_pairs,
              f"active pairs at the last step {pairs} >= {args.active_pairs}")
    rows = (quantity_rows(args.output)
            if args.final or args.slope or args.max_abs or args.change else [])
    for name, value, rtol in args.final:
        v = float(rows[-1][name])
        error = abs(v - float(value)) / abs(float(value))
        checks.record(f"{name}_relative_error", error)
        check(error <= float(rtol),
              f"final {name} = {v:.8g}, expected {value}, relative error "
              f"{error:.3g} <= {rtol}")
    for name, t0, t1, value, rtol in args.slope:
        window = [r for r in rows if float(t0) <= float(r["time"]) <= float(t1)]
        a = second_derivative([float(r["time"]) for r in window],
                              [float(r[name]) for r in window])
        error = abs(a - float(value)) / abs(float(value))
        checks.record(f"{name}_acceleration", a)
        check(error <= float(rtol),
              f"d2({name})/dt2 over t in [{t0}, {t1}] = {a:.6g}, expected "
              f"{value}, relative error {error:.3g} <= {rtol}")
    for name, t0, t1, limit in args.change:
        def at(t):
            return float(min(rows, key=lambda r: abs(float(r["time"]) - float(t)))[name])
        change = abs(at(t1) - at(t0))
        checks.record(f"{name}_change", change)
        check(change <= float(limit),
              f"|{name}({t1}) - {name}({t0})| = {change:.6g} <= {limit}")
    for name, limit in args.max_abs:
        largest = max(abs(float(r[name])) for r in rows)
        checks.record(f"{name}_max_abs", largest)
        check(largest <= float(limit), f"max |{name}| = {largest:.6g} <= {limit}")
    for obstacle, component, lo, hi in args.force_range:
        value = sum(float(r[component]) for r in last
                    if int(float(r["obstacle"])) == int(obstacle))
        checks.record(f"obstacle_{obstacle}_{component}", value)
        check(float(lo) <= value <= float(hi),
              f"obstacle {obstacle} {component} = {value:.6g} in [{lo}, {hi}]")
    for obstacle, numerator, denominator, value, rtol in args.force_ratio:
        def component(name):
            return sum(float(r[name]) for r in last
                       if int(float(r["obstacle"])) == int(obstacle))
        ratio = component(numerator) / component(denominator)
        checks.record(f"obstacle_{obstacle}_{numerator}_over_{denominator}",
                      ratio)
        check(abs(ratio - float(value)) <= float(rtol) * abs(float(value)),
              f"obstacle {obstacle} {numerator}/{denominator} = {ratio:.6g}, "
              f"expected {value} within {rtol}")
    if args.summary:
        summary = read_summary(args.output)
        contact = summary.get("levels", [summary])[-1]["contact"]
    for key, lo, hi in args.summary:
        value = contact[key]
        checks.record(key, value)
        check(float(lo) <= value <= float(hi), f"{key} = {value:.6g} in [{lo}, {hi}]")
    if args.edge_clearance:
        clearance = lowest_edge_clearance(args.output)
        checks.record("edge_clearance", clearance)
        lo, hi = args.edge_clearance
        check(lo <= clearance <= hi, f"clearance of the obstacles' lowest edge "
              f"over the mid-surface {clearance:.6g} in [{lo}, {hi}]")
    if args.energy_balance is not None:
        energies = energy_balance(quantity_rows(args.output), forces)
        supplied = sum(energies["obstacle_work"].values())
        share = abs(energies["remainder"]) / supplied
        checks.record("energy_remainder_share", share)
        check(share <= args.energy_balance,
              f"energy: the obstacles' work {supplied:.6g} = strain "
              f"{energies['strain_energy']:.6g} + kinetic "
              f"{energies['kinetic_energy']:.3g} + drag "
              f"{energies['dissipated_energy']:.6g} + barrier "
              f"{energies['contact_energy']:.3g} (+ external "
              f"{energies['external_work']:.3g}) within "
              f"{share:.3g} <= {args.energy_balance} of it")
    if args.report:
        checks.write_report(args.report,
                            os.path.basename(os.path.normpath(args.output)))
    checks.exit()


if __name__ == "__main__":
    main()
