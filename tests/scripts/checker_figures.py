"""The pictures the test checkers draw when asked (--figures, --figure,
--plot): matplotlib charts of a run's CSV files and pictures of its VTU
series through doc/scripts/render_vtu.py. Nothing here asserts anything;
a checker imports this module only when it is asked for figures, so that
its checks never depend on drawing. Each function returns True when its
pictures were written."""
import os
import subprocess
import sys

import numpy as np

from coshell_checks import column

RENDER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                      "doc", "scripts", "render_vtu.py")


def render(arguments):
    """doc/scripts/render_vtu.py with these arguments; True if it drew."""
    command = [sys.executable, RENDER] + arguments
    print("rendering:", " ".join(command), flush=True)
    return subprocess.run(command).returncode == 0


def pyplot():
    """matplotlib's pyplot on the Agg backend (no display)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def compression_chart(rows, path):
    """check_compression.py --plot: the clamp force, the optic's
    decentration and axial displacement against the compressed diameter
    (rows of compression.csv as tuples)."""
    plt = pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    diameters = [r[1] for r in rows]
    left.plot(diameters, [r[2] for r in rows], "o-", ms=3)
    left.set_xlabel("compressed diameter (mm)")
    left.set_ylabel("clamp force (mN)")
    left.invert_xaxis()
    left.grid(alpha=0.3)
    right.plot(diameters, [r[4] for r in rows], label="axial displacement (mm)")
    right.plot(diameters, [r[3] for r in rows], label="decentration (mm)")
    right.set_xlabel("compressed diameter (mm)")
    right.invert_xaxis()
    right.legend()
    right.grid(alpha=0.3)
    fig.suptitle("ISO 11979-3 compression of the C-loop lens (E = 1 MPa)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def fold_kinematics_chart(path, runs, line_stretch):
    """check_fold_kinematics.py --figure: the optic line's stretch and the
    largest membrane strain against time, one curve per formulation
    ('runs': formulation -> time_history.csv rows)."""
    plt = pyplot()
    figure, (left, right) = plt.subplots(1, 2, figsize=(9, 3.6))
    for formulation, rows in runs.items():
        t = [float(r["time"]) for r in rows]
        left.plot(t, [100 * line_stretch(r) for r in rows], label=formulation)
        right.plot(t, [100 * float(r["max_membrane_strain"]) for r in rows],
                   label=formulation)
    left.set_xlabel("time (s)")
    left.set_ylabel("stretch of the optic's line rim-centre-rim (%)")
    right.set_xlabel("time (s)")
    right.set_ylabel("largest membrane strain (%)")
    for axes in (left, right):
        axes.grid(True, alpha=0.3)
        axes.legend()
    figure.suptitle("IOL fold by the cartridge's wings: co-rotational "
                    "against linear kinematics")
    figure.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return True


def injection_history(args, history, time, displacement, push, chord):
    """check_injection.py --figures: injection_history.png, over stages 1
    to 3 (the settling's long, quiet tail would squeeze them) the plunger
    force, the optic's width, the largest strains and the energies; over
    the whole run the optic's decentration and tilt, which come to rest
    in stage 4. And plunger_force.png."""
    plt = pyplot()
    os.makedirs(args.figures, exist_ok=True)
    t, stage = column(history, "time"), column(history, "stage")
    surgical = stage <= 3
    figure, axes = plt.subplots(3, 2, figsize=(11, 10))
    axes[0, 0].plot(time[time <= t[surgical].max()],
                    1e3 * push[time <= t[surgical].max()])
    axes[0, 0].set(xlabel="time (s)", ylabel="plunger force (mN)")
    axes[0, 1].plot(t[surgical], chord[surgical],
                    label="optic width across the axis")
    axes[0, 1].axhline(2 * args.nozzle_radius, ls="--", color="k",
                       label="nozzle inner diameter")
    axes[0, 1].set(xlabel="time (s)", ylabel="mm")
    axes[0, 1].legend(fontsize=8)
    for name in ("max_membrane_strain", "max_bending_strain",
                 "max_surface_strain"):
        if name in history[0]:
            axes[1, 0].plot(t[surgical], 100 * column(history, name)[surgical],
                            label=name.replace("_", " "))
    axes[1, 0].set(xlabel="time (s)", ylabel="largest strain (%)")
    axes[1, 0].legend(fontsize=8)
    for name in ("strain_energy", "dissipated_energy", "contact_energy"):
        axes[1, 1].plot(t[surgical], column(history, name)[surgical],
                        label=name.replace("_", " "))
    axes[1, 1].set(xlabel="time (s)", ylabel="N mm")
    axes[1, 1].legend(fontsize=8)
    optic_pose_chart(axes[2], t, history, stage >= 3)
    figure.suptitle(f"IOL injection: {os.path.basename(args.prm)} (stages "
                    "1 to 3 above; deploy and settling below)")
    figure.tight_layout()
    figure.savefig(os.path.join(args.figures, "injection_history.png"),
                   dpi=110)
    plt.close(figure)
    plunger_force_chart(plt, args, displacement, push)
    return True


def optic_pose_chart(axes, t, history, released):
    """The optic's decentration and tilt against the bag's axis from its
    release (the 'released' rows): how it comes to rest."""
    axes[0].plot(t[released], column(history, "optic_decentration")[released])
    axes[0].set(xlabel="time (s)", ylabel="optic decentration (mm)")
    axes[1].plot(t[released], column(history, "optic_tilt")[released])
    axes[1].set(xlabel="time (s)", ylabel="optic tilt (degrees)")
    for ax in axes:
        ax.grid(alpha=0.3)


def plunger_force_chart(plt, args, displacement, push):
    """plunger_force.csv's picture: the force against the travel, the
    curve an injector is characterized by."""
    figure, axes = plt.subplots(figsize=(7, 4))
    axes.plot(displacement, 1e3 * push)
    axes.set(xlabel="plunger travel since t = 0 (mm; back out after the "
             "stroke)", ylabel="plunger force on the lens (mN)",
             title=f"plunger_force.csv: {os.path.basename(args.prm)}")
    figure.tight_layout()
    figure.savefig(os.path.join(args.figures, "plunger_force.png"), dpi=110)
    plt.close(figure)


def sequence_panels(history, times, args):
    """The injection sequence's panels, (time of a frame written, label):
    the stages' ends and the optic's way through the nozzle, each at the
    nearest frame; a frame two events share is drawn once."""
    t, stage = column(history, "time"), column(history, "stage")
    centre_x = column(history, "optic_ux")

    def first(passed):
        return t[np.argmax(passed)] if passed.any() else None
    deploy = t[stage == 3]
    events = [
        (t[0], "fold: the wings close"),
        (t[stage == 1].max(), "fold: folded, rod out"),
        (first(centre_x > args.nozzle_start), "push: optic enters the nozzle"),
        (first(centre_x > 0.5 * (args.nozzle_start + args.nozzle_tip)),
         "push: optic in the nozzle"),
        (first(centre_x > args.nozzle_tip), "push: optic out of the tip"),
        (t[stage == 2].max(), "push: plunger at the tip"),
        (deploy[len(deploy) // 4] if len(deploy) else None, "deploy: opening"),
        (t[-1], "settle: at rest in the bag" if (stage == 4).any()
         else "deploy: the end")]
    panels = {}
    for when, label in events:
        if when is not None:
            panels.setdefault(float(times[np.argmin(abs(times - when))]),
                              label)
    return sorted(panels.items())


def injection_pictures(args, history, frames):
    """check_injection.py --figures: the paper's Fig. 4 (the folded lens,
    when the optic's centre is deepest in the nozzle) and the sequence,
    each panel named by its stage and event."""
    t = column(history, "time")
    centre_x = column(history, "optic_ux")
    times = np.array([f.time for f in frames])
    in_nozzle = (centre_x > args.nozzle_start) & (centre_x < args.nozzle_tip)
    folded_time = t[in_nozzle][len(t[in_nozzle]) // 2] if in_nozzle.any() \
        else t[np.argmax(centre_x)]
    pvd = os.path.join(args.output, "solution.pvd")
    panels = sequence_panels(history, times, args)
    folded = float(times[np.argmin(abs(times - folded_time))])
    drawn = [
        render(["--pvd", pvd, "--times", str(folded), "--out",
                os.path.join(args.output, "folded"), "--view", "20", "-150",
                "--fit", "shell", "--edges", "--title",
                f"folded lens in the nozzle, t = {folded:.3g} s"]),
        render(["--pvd", pvd, "--times"] + [repr(x) for x, _ in panels] +
               ["--labels"] + [label for _, label in panels] +
               ["--out", os.path.join(args.output, "sequence"), "--montage",
                os.path.join(args.figures, "injection_sequence.png"),
                "--view", "35", "-100", "--fit", "shell"]),
    ]
    index = int(np.argmin(abs(times - folded)))
    source = os.path.join(args.output, f"folded-{index:04d}.png")
    if os.path.exists(source):
        os.replace(source, os.path.join(args.figures, "folded_in_nozzle.png"))
    return all(drawn)


def folded_lens_pictures(figures, frame):
    """check_injection.py --fold-only with --figures: the folded lens of
    'frame' (the last written), plain and coloured by surface strain."""
    os.makedirs(figures, exist_ok=True)
    title = f"folded lens, t = {frame.time:.3g} s"
    common = ["--vtu", frame.shell_file, "--view", "20", "-150", "--fit",
              "shell", "--edges"]
    return all([
        render(common + ["--out", os.path.join(figures, "folded_lens.png"),
                         "--title", title]),
        render(common + ["--out", os.path.join(figures,
                                               "folded_lens_strain.png"),
                         "--color-by", "surface_strain", "--title",
                         title + ", largest principal strain at either "
                         "surface"])])


def tuck_pictures(args, tucked_at, end, bent):
    """check_tuck.py --figures: the tucked lens and its strain, the bent
    lens (with a bend) and the sequence."""
    os.makedirs(args.figures, exist_ok=True)
    pvd = os.path.join(args.output, "solution.pvd")
    common = ["--pvd", pvd, "--fit", "shell", "--obstacle-alpha", "0.25",
              "--no-axes"]

    def picture(time, name, title, *extra):
        # One time drawn as a one-picture montage: the file's name is fixed.
        return render(common + [
            "--times", str(time), "--view", "35", "-60", "--edges",
            *extra, "--out", os.path.join(args.figures, name),
            "--montage", os.path.join(args.figures, name + ".png"),
            "--title", title.format(time)])

    drawn = [picture(tucked_at, "tucked_lens",
                     "haptics tucked onto the optic, t = {:.3g} s"),
             picture(tucked_at, "tucked_lens_strain",
                     "surface strain of the tucked lens, t = {:.3g} s",
                     "--color-by", "surface_strain")]
    if bent:
        drawn.append(picture(end, "bent_lens", "the optic bent around the "
                             "tucked haptics, t = {:.3g} s"))
        drawn.append(picture(end, "bent_lens_end_on", "the bent lens seen "
                             "along its fold, t = {:.3g} s",
                             "--view", "0", "-90"))
        times = [tucked_at / 3, 2 * tucked_at / 3, tucked_at,
                 (tucked_at + end) / 2, end]
    else:
        times = [end * k / 5 for k in range(1, 6)]
    drawn.append(render(common + [
        "--times", *map(str, times), "--view", "35", "-60",
        "--out", os.path.join(args.figures, "tuck"),
        "--montage", os.path.join(args.figures, "tuck_sequence.png"),
        "--montage-columns", "5"]))
    return all(drawn)


def lens_pictures(args, first_vtu, cells):
    """check_iol_figures.py: the reference mesh (the paper's Fig. 3)
    coloured by thickness and the compression sequence. Returns
    {png: drawn}."""
    os.makedirs(args.figures, exist_ok=True)
    mesh_png = os.path.join(args.figures, "lens_mesh.png")
    sequence_png = os.path.join(args.figures, "compression_sequence.png")
    return {
        mesh_png: render(["--vtu", first_vtu, "--out", mesh_png,
                          "--warp-scale", "0", "--edges", "--color-by",
                          "thickness", "--view", "90", "-90",
                          "--no-obstacles", "--title",
                          f"the lens, {cells} triangles (paper: "
                          f"{args.paper_triangles})"]),
        sequence_png: render(["--pvd", os.path.join(args.output,
                                                    "solution.pvd"),
                              "--all", "--out",
                              os.path.join(args.output, "compression"),
                              "--montage", sequence_png, "--color-by",
                              "displacement_magnitude", "--view", "60",
                              "-90"]),
    }
