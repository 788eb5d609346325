#!/usr/bin/python3
"""Real-time benchmark of the IOL injection (prm/iol/injection.prm, the
default lens, as a user runs it): stages 1 to 3 (fold, push, deploy;
the 90 s settle is left out, its cheap steps would flatter the factor)
in the scene's own mode (backward Euler, full Newton, barrier contact
with friction), once per thread count. Per stage: simulated and wall
time, real-time factor, steps and Newton corrections (failed attempts
included). Per run: where a correction's time goes, from summary.json
(contact detection, the barrier's pair terms, the rest of the assembly,
factorization, substitution, the collision filter, the rest). The goal
of issue 12 is a real-time factor of 1 on one core. Writes
doc/performance/iol_real_time.csv and .png, stamped with machine and
commit. Runs one after another; the machine should be otherwise idle.

  /usr/bin/python3 doc/scripts/iol_real_time.py --coshell build/coshell \\
      [--threads 1 2]
"""
import argparse
import csv
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_common import (ROOT, machine_and_commit,  # noqa: E402
                        run_scene_measured, write_csv)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = os.path.join(ROOT, "doc", "performance")
SCENE = os.path.join(ROOT, "prm", "iol", "injection.prm")
SETTINGS = ["Stage 4/Analysis type=none", "Output/Write VTU=false"]
STAGE_NAMES = {1: "fold", 2: "push", 3: "deploy"}
# summary.json's split of the time stepping, and contact's part of it,
# as the parts a correction's time goes to (the filter runs in Newton
# between the solve and the update, so it is in 'other').
PARTS = ["detection", "pair terms", "rest of assembly", "factorization",
         "substitution", "collision filter", "rest"]


def steps_and_corrections(output):
    """Per stage: the steps (time_history.csv's rows) and the Newton
    corrections of every attempt (newton_history.csv's rows with a
    correction), the steps' stage taken from the time history."""
    with open(os.path.join(output, "time_history.csv")) as f:
        stage_of_step = {int(r["step"]): int(r["stage"])
                         for r in csv.DictReader(f)}
    counts = {stage: [0, 0] for stage in set(stage_of_step.values())}
    for stage in stage_of_step.values():
        counts[stage][0] += 1
    with open(os.path.join(output, "newton_history.csv")) as f:
        for r in csv.DictReader(f):
            if float(r["correction_norm"]) > 0:
                counts[stage_of_step[int(r["step"])]][1] += 1
    return counts


def time_split(summary):
    """Seconds of the time stepping by part (PARTS)."""
    stepping, contact = summary["time_stepping_s"], summary["contact"]
    assembly_rest = (stepping["assembly"] - contact["detection_s"]
                     - contact["pair_terms_s"])
    substitution = stepping["linear_solver"] - stepping["factorization"]
    rest = stepping["other"] - contact["collision_filter_s"]
    return dict(zip(PARTS, [contact["detection_s"], contact["pair_terms_s"],
                            assembly_rest, stepping["factorization"],
                            substitution, contact["collision_filter_s"],
                            rest]))


def measure(binary, threads, work):
    """The rows of one run on 'threads' threads: one per stage and one
    for stages 1 to 3."""
    output = os.path.join(work, f"threads_{threads}")
    command = [binary, SCENE, "--output", output,
               "--set", f"Parallel/Threads={threads}"]
    for setting in SETTINGS:
        command += ["--set", setting]
    measured = run_scene_measured(command, 1, threads, output)
    if measured is None:
        sys.exit(f"the scene failed on {threads} thread(s)")
    summary = measured[0]
    counts = steps_and_corrections(output)
    rows = []
    for stage in summary["dynamic_stages"]:
        steps, corrections = counts[stage["stage"]]
        rows.append({"threads": threads,
                     "stage": STAGE_NAMES[stage["stage"]],
                     "simulated_s": stage["simulated_time_s"],
                     "wall_s": round(stage["wall_time_s"], 3),
                     "real_time_factor": round(stage["real_time_factor"], 4),
                     "steps": steps, "newton_corrections": corrections})
    simulated = sum(r["simulated_s"] for r in rows)
    wall = sum(r["wall_s"] for r in rows)
    corrections = summary["newton_corrections"]
    whole = {"threads": threads, "stage": "stages 1 to 3",
             "simulated_s": round(simulated, 6), "wall_s": round(wall, 3),
             "real_time_factor": round(simulated / wall, 4),
             "steps": summary["steps"], "newton_corrections": corrections}
    for part, seconds in time_split(summary).items():
        whole["ms_per_correction_" + part.replace(" ", "_")] = round(
            1e3 * seconds / corrections, 3)
    print(f"{threads} thread(s): real-time factor {whole['real_time_factor']}"
          f" ({simulated} s simulated in {wall:.1f} s, {corrections} "
          "corrections)")
    return rows + [whole]


def plot(rows, path, machine, commit):
    """Left: the real-time factor by stage and thread count against the
    goal of 1. Right: where a correction's time goes, per thread count."""
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    threads = sorted({r["threads"] for r in rows})
    stages = [r["stage"] for r in rows if r["threads"] == threads[0]]
    width = 0.8 / len(threads)
    for k, n in enumerate(threads):
        factors = [r["real_time_factor"] for r in rows if r["threads"] == n]
        left.bar([i + k * width for i in range(len(stages))], factors,
                 width, label=f"{n} thread(s)")
    left.axhline(1.0, color="k", linestyle="--", label="real time (goal)")
    left.set_yscale("log")
    left.set_xticks([i + 0.4 - width / 2 for i in range(len(stages))])
    left.set_xticklabels(stages)
    left.set_ylabel("real-time factor (simulated / wall)")
    left.legend(fontsize=8)
    left.set_title("IOL injection, default lens")
    wholes = [r for r in rows if r["stage"] == "stages 1 to 3"]
    bottom = [0.0] * len(wholes)
    for part in PARTS:
        key = "ms_per_correction_" + part.replace(" ", "_")
        values = [r[key] for r in wholes]
        right.bar([str(r["threads"]) for r in wholes], values, 0.5,
                  bottom=bottom, label=part)
        bottom = [b + v for b, v in zip(bottom, values)]
    right.set_xlabel("threads")
    right.set_ylabel("ms per Newton correction")
    right.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    right.set_title("where a correction's time goes")
    figure.suptitle(f"{machine}, {commit}", fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    print("wrote", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--coshell", required=True)
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()
    binary = os.path.abspath(args.coshell)
    machine, commit = machine_and_commit()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for threads in args.threads:
            rows += measure(binary, threads, work)
    fields = list(rows[-1])
    write_csv(os.path.join(OUT, "iol_real_time.csv"), rows,
              [f"machine: {machine}; commit {commit}",
               "prm/iol/injection.prm, default lens, stages 1 to 3 "
               "(Stage 4 off), VTU off; newton_corrections counts failed "
               "attempts too; ms_per_correction_*: the stages' time "
               "stepping split by part over all their corrections"],
              fields)
    plot(rows, os.path.join(OUT, "iol_real_time.png"), machine, commit)


if __name__ == "__main__":
    main()
