#!/usr/bin/python3
"""Does the interactive protocol's slope line help a haptic loop between
two updates of the simulation?

A device drives the plunger of the IOL injection (prm/iol/injection.prm,
default lens, the plunger on its `Input direction` as in
doc/user-guide/interactive.md, "Driven obstacles")
after the fold: s(t) = v (t - 1.3 s) + A sin(2 pi f (t - 1.3 s)), a push
with a tremor. The reference run of the interactive protocol sends the
device's position every millisecond, so its step at each millisecond
gives the force there. A multirate run sends it every --update ms only; between two of its
step lines a 1 kHz loop renders either the last force F (hold) or the
local model F + k (s_device - s) with the step's input s and slope k
(Cavusoglu and Tendick, ICRA 2000), or that model applied only to the
device's deviation from the input's last rate, F + k (s_device - s -
r (t - t_n)) with r the rate between the last two updates. Each is
compared with the reference at every millisecond. The simulation is taken to keep up with
the device (sim time = device time); how far it does not is the haptic
rate of doc/performance/iol.md.

Writes doc/performance/haptic_local_model.csv (error per update
interval) and haptic_local_model.png (forces of one interval, errors of
all), stamped with machine and commit.

  /usr/bin/python3 doc/scripts/haptic_local_model.py --coshell build/coshell \\
      [--updates 5 10 20] [--duration 0.2]
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import (ROOT, finish_plot, machine_and_commit,  # noqa: E402
                        write_csv)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
SCENE = os.path.join(ROOT, "prm", "iol", "injection.prm")
FOLD_END = 1.3  # s, the end of the scene's fold stage
SETTINGS = ["Parallel/Threads=1", "Output/Write VTU=false",
            "Contact/Obstacle 2/Translation=plunger_start; 0; axis_height",
            "Contact/Obstacle 2/Input direction=1, 0, 0"]
PLUNGER = 2  # its place among the obstacles' forces on a step line


def device(t, speed, amplitude, frequency):
    """The device's input at time t (mm along the plunger's axis)."""
    tau = t - FOLD_END
    return speed * tau + amplitude * math.sin(2 * math.pi * frequency * tau)


def session(binary, output, times, args):
    """Step lines (time, force, input, slope) of an interactive session that
    sends the device's position at 'times' after the fold."""
    lines = [repr(FOLD_END)] + [
        f"{t!r} {device(t, args.speed, args.amplitude, args.frequency)!r}"
        for t in times] + ["quit"]
    command = [binary, SCENE, "--interactive", "--output", output]
    for setting in SETTINGS:
        command += ["--set", setting]
    run = subprocess.run(command, input="\n".join(lines) + "\n",
                         capture_output=True, text=True,
                         env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    if run.returncode != 0:
        sys.exit(f"{output}: {run.stderr.strip()[-400:]}")
    replies = run.stdout.splitlines()
    steps = []
    for k, line in enumerate(replies):
        words = line.split()
        if words[0] == "step" and float(words[2]) > FOLD_END + 1e-12:
            slope = replies[k + 1].split()
            steps.append((float(words[2]), float(words[2 + PLUNGER]),
                          float(slope[2]), float(slope[3])))
    return steps


def rendered(steps, t, s_device):
    """Hold, local model, and local model on the device's deviation from
    the input's last rate, at device time t from the last step line at or
    before t (and the one before it, for the rate)."""
    k = max(i for i, step in enumerate(steps) if step[0] <= t + 1e-12)
    t_n, force, s, slope = steps[k]
    rate = ((s - steps[k - 1][2]) / (t_n - steps[k - 1][0]) if k > 0
            else 0.0)
    return (force, force + slope * (s_device - s),
            force + slope * (s_device - s - rate * (t - t_n)))


def compare(reference, steps, ticks, args):
    """RMS and largest errors of hold and local model against the
    reference force at every tick, and the rendered series."""
    exact = {round(t, 9): f for t, f, _, _ in reference}
    series = []
    for t in ticks:
        s_device = device(t, args.speed, args.amplitude, args.frequency)
        series.append((t, exact[round(t, 9)],
                       *rendered(steps, t, s_device)))
    errors = {name: [row[k] - row[1] for row in series]
              for k, name in ((2, "hold"), (3, "local"), (4, "deviation"))}
    summary = {}
    for name, e in errors.items():
        summary[f"{name}_rms_mN"] = 1e3 * math.sqrt(sum(x * x for x in e) /
                                                    len(e))
        summary[f"{name}_max_mN"] = 1e3 * max(abs(x) for x in e)
    return summary, series


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--updates", type=float, nargs="+",
                        default=[5, 10, 20], help="update intervals, ms")
    parser.add_argument("--duration", type=float, default=0.2,
                        help="seconds of push after the fold")
    parser.add_argument("--speed", type=float, default=5.0, help="mm/s")
    parser.add_argument("--amplitude", type=float, default=0.05, help="mm")
    parser.add_argument("--frequency", type=float, default=10.0, help="Hz")
    args = parser.parse_args()
    binary = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    n = round(args.duration * 1000)
    ticks = [FOLD_END + k / 1000 for k in range(1, n + 1)]
    rows, shown = [], None
    with tempfile.TemporaryDirectory() as work:
        reference = session(binary, os.path.join(work, "reference"), ticks,
                            args)
        for update in args.updates:
            every = round(update)
            times = [FOLD_END + k / 1000 for k in range(every, n + 1, every)]
            # A step between two updates needs the later update's input,
            # so it is known only once that update has come: the loop
            # renders from the update's own step.
            updated = {round(t, 9) for t in times}
            steps = [step for step in
                     session(binary, os.path.join(work, f"every_{every}"),
                             times, args) if round(step[0], 9) in updated]
            summary, series = compare(reference, steps, ticks[every - 1:],
                                      args)
            rows.append({"update_ms": update, "updates": len(steps),
                         **summary})
            print(rows[-1], flush=True)
            if shown is None or update == 10:
                shown = (update, series)
    os.makedirs(OUT, exist_ok=True)
    write_csv(os.path.join(OUT, "haptic_local_model.csv"), rows,
              [f"machine: {machine}; commit {commit}",
               f"prm/iol/injection.prm, default lens, plunger driven after "
               f"the fold: s = {args.speed:g} mm/s t + {args.amplitude:g} mm "
               f"sin(2 pi {args.frequency:g} Hz t) for {args.duration:g} s; "
               "errors of the force rendered at 1 kHz against the session "
               "driven every 1 ms (mN): hold = the last step's force, "
               "local = plus the slope line's k (s_device - s), deviation = "
               "plus k (s_device - s - r (t - t_n)), r the input's rate "
               "between the last two updates"])
    plot(rows, shown, machine, commit)


def plot(rows, shown, machine, commit):
    figure, axes = plt.subplots(1, 2, figsize=(11, 4))
    update, series = shown
    t = [1e3 * (row[0] - FOLD_END) for row in series]
    for k, label in ((1, "reference (driven every 1 ms)"),
                     (2, f"hold, updates every {update:g} ms"),
                     (3, "local model F + k (s - s_n)"),
                     (4, "F + k (s - s_n - rate (t - t_n))")):
        axes[0].plot(t, [1e3 * row[k] for row in series], label=label,
                     linewidth=1, color=f"C{k - 1}")
    axes[0].set_xlabel("time after the fold (ms)")
    axes[0].set_ylabel("plunger force along its axis (mN)")
    axes[0].legend(fontsize=8)
    axes[0].grid(True, alpha=0.3)
    updates = [row["update_ms"] for row in rows]
    for k, (name, marker) in enumerate((("hold", "o"), ("local", "s"),
                                        ("deviation", "^")), start=1):
        axes[1].plot(updates, [row[f"{name}_rms_mN"] for row in rows],
                     marker=marker, label=f"{name}, RMS", color=f"C{k}")
    finish_plot(figure, axes[1], "update interval (ms)",
                "error against the 1 ms session (mN)",
                f"{machine}, {commit}",
                os.path.join(OUT, "haptic_local_model.png"))


if __name__ == "__main__":
    main()
