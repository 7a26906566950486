"""The figures of validation/flume: tensions.png, tensions_by_seabed.png, profiles.png and a pyvista
frame per seabed."""

import numpy as np

from cablefem.model.builtin import FLUME_MOTIONS, FLUME_SEABEDS

from validation.flume.cases import MN, MOTIONS, PAPER_LOWEST_PEAK, _motion_state
from validation.flume.report import _motion_words, _settings_words


def figures(results, out):
    """PNGs in ``out``: fairlead tension against time (3 x 2 panels), one period of each motion
    with the three seabeds overlaid, and the line's profile over each seabed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = {(c["seabed"], c["motion"]): c for c in results["cases"] if c.get("completed")}
    colours = {"flat": "tab:blue", "gentle": "tab:orange", "steep": "tab:green"}
    paths = [out / "tensions.png", out / "tensions_by_seabed.png", out / "profiles.png"]
    tensions_figure(plt, results, cases, colours).savefig(paths[0], dpi=110)
    by_seabed_figure(plt, cases, colours).savefig(paths[1], dpi=110)
    profiles_figure(plt, cases, colours).savefig(paths[2], dpi=110)
    plt.close("all")
    return paths


def tensions_figure(plt, results, cases, colours):
    """Fairlead tension against time, 3 seabeds x 2 motions."""
    fig, axes = plt.subplots(3, 2, figsize=(13, 10), sharex="col")
    legend = []
    for i, seabed in enumerate(FLUME_SEABEDS):
        for j, motion in enumerate(MOTIONS):
            ax = axes[i, j]
            c = cases.get((seabed, motion))
            if c is None:
                ax.text(0.5, 0.5, "failed", transform=ax.transAxes, ha="center")
                continue
            s = c["_series"]
            m = FLUME_MOTIONS[motion]
            surge = ax.twinx()  # behind ax: the shading and the surge under the tensions
            surge.axvspan(*c["window_s"], color="0.93", label="last two periods (statistics)")
            surge.axvspan(0, m.ramp, color="#fff2cc", label="ramp")
            surge.plot(s["t"], [_surge(motion, t) for t in s["t"]], color="0.6", lw=0.7, label="fairlead surge")
            surge.set_ylabel("fairlead surge [m]", color="0.45")
            surge.tick_params(axis="y", colors="0.45")
            ax.set_zorder(surge.get_zorder() + 1)
            ax.patch.set_visible(False)
            ax.plot(s["t"], s["fairlead_tension"] / MN, color=colours[seabed], lw=0.9, label="fairlead")
            ax.plot(s["t"], s["anchor_tension"] / MN, color="0.5", lw=0.8, ls="--", label="anchor")
            ax.plot(c["t_max_s"], c["max_N"] / MN, "v", color="k", ms=6)
            ax.plot(c["t_min_s"], c["min_N"] / MN, "^", color="k", ms=6)
            ax.annotate(f"max {c['max_N'] / MN:.2f} MN", (c["t_max_s"], c["max_N"] / MN),
                        textcoords="offset points", xytext=(-70, 2), fontsize=8)
            ax.annotate(f"min {c['min_N'] / MN:.2f} MN", (c["t_min_s"], c["min_N"] / MN),
                        textcoords="offset points", xytext=(-70, -12), fontsize=8)
            if motion == "quasi-static":
                ax.axhline(PAPER_LOWEST_PEAK[seabed] / MN, color="crimson", ls=":", lw=1.2,
                           label="paper's lowest peak (Sec. 4.2)")
            ax.set_title(f"{seabed} seabed, {motion} ({_motion_words(motion)})", fontsize=10)
            ax.set_ylabel("tension [MN]")
            ax.grid(True, alpha=0.3)
            ax.margins(y=0.15)
            if not legend:
                legend = [a.get_legend_handles_labels() for a in (ax, surge)]
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    if legend:
        fig.legend(legend[0][0] + legend[1][0], legend[0][1] + legend[1][1],
                   loc="lower center", ncol=7, fontsize=8, frameon=False)
    fig.suptitle("cablefem, desire2023 flume cases (prototype scale; cf. Figs. 12-17)\n"
                 f"{_settings_words(results['settings'])}",
                 fontsize=11)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    return fig


def by_seabed_figure(plt, cases, colours):
    """One period of each motion with the three seabeds overlaid."""
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    for ax, motion in zip(axes, MOTIONS):
        period = FLUME_MOTIONS[motion].period
        for seabed in FLUME_SEABEDS:
            c = cases.get((seabed, motion))
            if c is None:
                continue
            s = c["_series"]
            keep = s["t"] >= c["duration_s"] - period - 1e-9
            phase = (s["t"][keep] - (c["duration_s"] - period)) / period
            ax.plot(phase, s["fairlead_tension"][keep] / MN, color=colours[seabed], label=seabed)
        if motion == "quasi-static":
            for seabed in FLUME_SEABEDS:
                ax.axhline(PAPER_LOWEST_PEAK[seabed] / MN, color=colours[seabed], ls=":", lw=1)
        surge = ax.twinx()
        grid = np.linspace(0, 1, 200)
        surge.plot(grid, _motion_state(FLUME_MOTIONS[motion], grid * period)[0], color="0.6", lw=0.8)
        surge.set_ylabel("fairlead surge [m] (grey)", color="0.5")
        ax.set_xlabel("time in the last period, t / T")
        ax.set_ylabel("fairlead tension [MN]")
        ax.set_title(f"{motion}: the three seabeds over one period"
                     + ("  (dotted: paper's lowest peaks)" if motion == "quasi-static" else ""), fontsize=10)
        ax.set_zorder(surge.get_zorder() + 1)
        ax.patch.set_visible(False)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return fig


def profiles_figure(plt, cases, colours):
    """The line's profile over each seabed at its largest and smallest tension."""
    from cablefem.geometry.generators import flume_step

    fig, axes = plt.subplots(3, 2, figsize=(13, 9), sharex=True, sharey=True)
    x = np.linspace(-620.0, 30.0, 1301)
    for i, seabed in enumerate(FLUME_SEABEDS):
        bed = flume_step(seabed).elevation(np.column_stack([x, np.zeros_like(x)]))
        for j, motion in enumerate(MOTIONS):
            ax = axes[i, j]
            ax.fill_between(x, bed, -110, color="tan", alpha=0.6, label="seabed (y = 0)")
            c = cases.get((seabed, motion))
            if c is not None and "line_at_max" in c["_series"]:
                s = c["_series"]
                for key, label, style in (("line_at_max", f"at max tension {c['max_N'] / MN:.2f} MN", "-"),
                                          ("line_at_min", f"at min tension {c['min_N'] / MN:.2f} MN", "--")):
                    p = s[key]
                    ax.plot(p[:, 0], p[:, 2], style, color=colours[seabed], lw=1.3, label=label)
                ax.axvspan(c["touchdown_x_min_m"], c["touchdown_x_max_m"], color="k", alpha=0.12,
                           label=f"touchdown {c['touchdown_x_min_m']:.0f} .. {c['touchdown_x_max_m']:.0f} m")
            ax.set_ylim(-106, 2)
            ax.set_title(f"{seabed} seabed, {motion}", fontsize=10)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7, loc="upper left")
            if j == 0:
                ax.set_ylabel("z [m]")
    for ax in axes[-1]:
        ax.set_xlabel("x [m] (fairlead at x = 0 + surge)")
    fig.suptitle("line profile over the seabed (vertical scale exaggerated ~3x); shaded: touchdown range "
                 "over the last two periods", fontsize=11)
    fig.tight_layout()
    return fig


def render_frames(results, out, vertical_scale=3.0):
    """One pyvista frame per seabed: the quasi-static case at its lowest tension peak, the line
    coloured by tension [MN] over the seabed (vertical scale exaggerated), from the run's .pvd
    frames (``cablefem.post.load_run``). Returns the PNG paths."""
    import pyvista

    from cablefem.post import load_run

    pyvista.OFF_SCREEN = True
    paths = []
    for c in results["cases"]:
        if c["motion"] != "quasi-static" or not c.get("completed") or "frame_index_min" not in c["_series"]:
            continue
        times, frames, seabed = load_run(c["run_dir"])
        index = c["_series"]["frame_index_min"]
        line = frames[index].copy()
        line["tension [MN]"] = line["tension"] / MN
        plotter = pyvista.Plotter(off_screen=True, window_size=(1600, 700))
        if seabed is not None:
            plotter.add_mesh(seabed.clip_box((-640.0, 40.0, -80.0, 80.0, -200.0, 50.0), invert=False),
                             color="tan", opacity=0.8)
        plotter.add_mesh(line, scalars="tension [MN]", line_width=6, cmap="viridis",
                         scalar_bar_args={"title": "tension [MN]", "fmt": "%.2f", "n_labels": 5,
                                          "position_x": 0.06, "position_y": 0.72, "width": 0.4})
        plotter.set_scale(zscale=vertical_scale)
        plotter.view_xz()
        plotter.camera.elevation = 15
        plotter.camera.zoom(1.8)
        plotter.add_text(f"{c['seabed']} seabed, quasi-static, t = {times[index]:.1f} s: lowest tension peak, "
                         f"fairlead {c['lowest_peak_N'] / MN:.2f} MN, surge {c['surge_at_min_m']:.1f} m; "
                         f"vertical scale x{vertical_scale:g}; anchor at x = -595 m (left)", font_size=11)
        png = out / f"frame_{c['seabed']}.png"
        plotter.screenshot(str(png))
        plotter.close()
        paths.append(png)
    return paths


def _surge(motion, t):
    from cablefem.model.motion import fairlead_motion

    return float(fairlead_motion(FLUME_MOTIONS[motion], t)[0][0])
