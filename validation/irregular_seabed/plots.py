"""The figures of validation/irregular_seabed: positions (Fig. 19), tensions (Fig. 20), the seeds and a
3D view."""

from pathlib import Path

import numpy as np

from cablefem.geometry import TriangulatedSurface

from validation.irregular_seabed.model import EXTENT, METHODS, MOTION, PAPER, SNAPSHOT_T

COLOURS = {"general": "tab:blue", "inclined": "tab:green", "horizontal": "tab:red"}
LABELS = {"general": "general (triangulated, vertex normals)", "inclined": "inclined (least-squares plane)",
          "horizontal": "horizontal (z-bar)"}


def make_figures(results, target):
    """Fig. 19-, Fig. 20-like PNGs, the seed summary and a 3-D render; returns their names."""
    import matplotlib

    matplotlib.use("Agg")
    target.mkdir(parents=True, exist_ok=True)
    entry = next(e for e in results["seeds"] if e["seed"] == results["primary_seed"])
    names = [figure_positions(entry, target / "fig19_positions.png"),
             figure_tensions(entry, target / "fig20_tensions.png"),
             figure_seeds(results, target / "seeds.png")]
    try:
        names.append(render_3d(entry, target / "surface_3d.png"))
    except Exception as failure:  # no OpenGL context: the PNGs above are still written
        print(f"3-D render skipped: {type(failure).__name__}: {failure}")
    return [Path(n).name for n in names]


def figure_positions(entry, png):
    """Fig. 19: the cut y = 0 of the seabed models and the three lines at t = 6 s, and a zoom."""
    import matplotlib.pyplot as plt

    grid, runs = entry["_grid"], entry["methods"]
    models = {"inclined": grid.least_squares_plane(), "horizontal": grid.mean_depth_horizontal()}
    x = np.linspace(EXTENT[0][0], 20.0, 1601)
    cut = np.column_stack([x, np.zeros_like(x)])
    general = TriangulatedSurface(*grid.surface())
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.2), gridspec_kw={"width_ratios": [1.3, 1]})
    done = [m for m in METHODS if runs[m].get("completed")]
    tds = [runs[m]["touchdown_x_m"] for m in done]
    zoom = (min(tds) - 60.0, max(tds) + 60.0) if tds else (-300.0, -100.0)
    for ax in axes:
        ax.plot(x, general.elevation(cut), color=COLOURS["general"], lw=1.0, alpha=0.55, label="seabed, irregular (y = 0)")
        for m, bed in models.items():
            ax.plot(x, bed.elevation(cut), color=COLOURS[m], lw=1.0, ls="--", alpha=0.7,
                    label=f"seabed, {m} (y = 0)")
        for m in done:
            p = runs[m]["_series"]["snapshot"]
            ax.plot(p[:, 0], p[:, 2], "o-", color=COLOURS[m], ms=2.5, lw=1.6,
                    label=f"line, {LABELS[m]}")
            ax.plot(runs[m]["touchdown_x_m"], np.interp(runs[m]["touchdown_x_m"], p[:, 0], p[:, 2]),
                    "v", color=COLOURS[m], ms=10, mec="k")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]")
        ax.grid(True, alpha=0.3)
    axes[0].set_xlim(EXTENT[0][0], 25)
    axes[0].legend(fontsize=8, loc="upper left")
    axes[1].set_xlim(*zoom)
    z_zoom = [general.elevation(np.array([[zoom[0], 0.0], [zoom[1], 0.0]]))]
    low = min(np.min(z_zoom), *(bed.elevation(np.array([[zoom[0], 0.0], [zoom[1], 0.0]])).min()
                                 for bed in models.values()))
    axes[1].set_ylim(low - 6.0, low + 24.0)
    axes[1].set_title("zoom near the touchdown points (triangles)")
    t = runs[done[0]]["snapshot_t_s"] if done else SNAPSHOT_T
    axes[0].set_title(f"Fig. 19-like: line nodes at t = {t:g} s, seed {entry['seed']} (x-z view; seabed cut y = 0)")
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    plt.close(fig)
    return png


def figure_tensions(entry, png):
    """Fig. 20: dynamic (total minus its mean) and total fairlead tension of the three models."""
    import matplotlib.pyplot as plt

    runs = entry["methods"]
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.8))
    for m in METHODS:
        if not runs[m].get("completed"):
            continue
        s = runs[m]["_series"]
        axes[0].plot(s["t"], (s["fairlead_tension"] - runs[m]["mean_N"]) / 1e6, color=COLOURS[m], lw=1.2,
                     label=f"{m}: peak {runs[m]['dynamic_peak_N'] / 1e6:.2f} MN")
        axes[1].plot(s["t"], s["fairlead_tension"] / 1e6, color=COLOURS[m], lw=1.2,
                     label=f"{m}: peak {runs[m]['total_peak_N'] / 1e6:.2f} MN")
    for m in METHODS:
        axes[0].axhline(PAPER["dynamic_peak_N"][m] / 1e6, color=COLOURS[m], ls=":", lw=1)
        axes[1].axhline(PAPER["total_peak_N"][m] / 1e6, color=COLOURS[m], ls=":", lw=1)
    for ax, title in zip(axes, ("dynamic tension T - mean(T)", "total tension T")):
        ax.axvspan(0, MOTION.ramp, color="0.9", zorder=0)
        ax.axvline(SNAPSHOT_T, color="0.5", lw=0.8)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("fairlead tension [MN]")
        ax.set_title(f"Fig. 20-like, seed {entry['seed']}: {title}\n(dotted: the paper's peaks; grey: ramp)",
                     fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    plt.close(fig)
    return png


def figure_seeds(results, png):
    """Dynamic and total peaks and touchdown x of the three models for every seed."""
    import matplotlib.pyplot as plt

    seeds = results["seeds"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    keys = (("dynamic_peak_N", 1e6, "dynamic peak [MN]"), ("total_peak_N", 1e6, "total peak [MN]"),
            ("touchdown_x_m", 1.0, f"touchdown x at t = {SNAPSHOT_T:g} s [m]"))
    for ax, (key, scale, label) in zip(axes, keys):
        for k, m in enumerate(METHODS):
            values = [e["methods"][m].get(key, np.nan) / scale if e["methods"][m].get("completed") else np.nan
                      for e in seeds]
            ax.plot(np.arange(len(seeds)) + (k - 1) * 0.12, values, "o", color=COLOURS[m], ms=7, label=m)
            if key in ("dynamic_peak_N", "total_peak_N"):
                ax.axhline(PAPER[key][m] / scale, color=COLOURS[m], ls=":", lw=1)
        ax.set_xticks(range(len(seeds)), [f"seed {e['seed']}" for e in seeds])
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[0].set_title("dotted: the paper's values", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    plt.close(fig)
    return png


def render_3d(entry, png, exaggeration=4.0, strip=40.0):
    """pyvista render (z exaggerated) at t = 6 s: left, the irregular surface and the general
    line; right, the surface see-through, the two planes as strips along y = 0 and the three lines."""
    import pyvista

    pyvista.OFF_SCREEN = True
    grid, runs = entry["_grid"], entry["methods"]
    scale = np.array([1.0, 1.0, exaggeration])
    gx, gy = np.meshgrid(grid.x, grid.y)
    surface = pyvista.StructuredGrid(gx, gy, grid.z * exaggeration)
    surface["elevation [m]"] = grid.z.ravel(order="F")
    (x0, x1), _ = EXTENT
    plotter = pyvista.Plotter(off_screen=True, shape=(1, 2), window_size=(2000, 900), border=False)
    # looking from the anchor's side, south-west and above, at the middle of the line
    camera = [(-1100.0, -900.0, 300.0), (-300.0, 0.0, -90.0 * exaggeration), (0.0, 0.0, 1.0)]
    for column in (0, 1):
        plotter.subplot(0, column)
        plotter.set_background("white")
        plotter.add_mesh(surface.copy(), scalars="elevation [m]", cmap="gist_earth", clim=(grid.z.min(), grid.z.max()),
                         opacity=1.0 if column == 0 else 0.35, show_scalar_bar=column == 0,
                         scalar_bar_args={"title": "seabed elevation [m]", "color": "black", "vertical": True,
                                          "position_x": 0.06, "position_y": 0.25,
                                          "title_font_size": 14, "label_font_size": 12, "fmt": "%.0f"})
        shown = ("general",) if column == 0 else METHODS
        if column == 1:
            for m in ("inclined", "horizontal"):
                bed = grid.least_squares_plane() if m == "inclined" else grid.mean_depth_horizontal()
                corners = np.array([[x0, -strip], [x1, -strip], [x1, strip], [x0, strip]], dtype=float)
                quad = np.column_stack([corners, bed.elevation(corners)]) * scale
                plotter.add_mesh(pyvista.PolyData(quad, faces=[4, 0, 1, 2, 3]), color=COLOURS[m][4:],
                                 opacity=0.45)
        for m in shown:
            if runs[m].get("completed"):
                points = runs[m]["_series"]["snapshot"] * scale
                plotter.add_mesh(pyvista.lines_from_points(points), color=COLOURS[m][4:], line_width=6)
        plotter.camera_position = camera
        plotter.reset_camera()
        plotter.camera.zoom(1.3)
        text = ("irregular seabed (diamond-square) and the line on it, general projection" if column == 0 else
                "see-through: least-squares plane (green) and z-bar plane (red) strips; lines of the three models")
        plotter.add_text(f"{text}\nseed {entry['seed']}, t = {SNAPSHOT_T:g} s, z x {exaggeration:g}",
                         font_size=11, color="black")
        if column == 1:  # a legend of coloured words (add_legend's box is clipped in subplots)
            for k, m in enumerate(METHODS):
                plotter.add_text(f"line: {LABELS[m]}", position=(0.52, 0.2 - 0.05 * k), viewport=True,
                                 font_size=11, color=COLOURS[m][4:])
    plotter.screenshot(str(png))
    plotter.close()
    return png
