"""Looking at results without ParaView: tension plots (matplotlib) and 3-D views (pyvista).

Both libraries are imported inside the functions, so the solver never pulls
in plotting.
"""

import csv
import os

import numpy as np

from cablefem.errors import InputError
from cablefem.io.vtk import read_collection


def read_tensions(out_dir):
    """Columns of a run's tensions.csv as a dict of arrays (``t`` and the tension columns)."""
    path = os.path.join(out_dir, "tensions.csv")
    if not os.path.isfile(path):
        raise InputError("no tensions.csv here: is this the output folder of `cablefem run`?", file=out_dir)
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            rows = list(csv.reader(handle))
        header, values = rows[0], np.array(rows[1:], dtype=float).reshape(-1, len(rows[0]))
    except (ValueError, IndexError, csv.Error) as error:  # UnicodeDecodeError is a ValueError
        reason = " ".join(str(error).split()) or "empty"
        raise InputError(f"not a tensions table of `cablefem run` ({reason})", file=path) from None
    return {name: values[:, k] for k, name in enumerate(header)}


def plot_tensions(out_dir, png=None):
    """Fairlead and anchor tension [N] against time of a run, as a PNG; returns its path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = read_tensions(out_dir)
    png = png or os.path.join(out_dir, "tensions.png")
    fig, ax = plt.subplots(figsize=(8, 4))
    for name, values in data.items():
        if name.endswith("fairlead_tension") or name.endswith("anchor_tension"):
            ax.plot(data["t"], values / 1e3, label=name.replace("_", " "))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("tension [kN]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)
    return png


def load_run(out_dir):
    """(times (k,), list of pyvista meshes of the line frames, pyvista seabed mesh) of a run."""
    import pyvista

    pvd = [f for f in os.listdir(out_dir) if f.endswith(".pvd")]
    if not pvd:
        raise InputError("no .pvd collection here", file=out_dir)
    times, frames = read_collection(os.path.join(out_dir, pvd[0]))
    seabed = os.path.join(out_dir, "seabed.vtu")
    return times, [pyvista.read(f) for f in frames], pyvista.read(seabed) if os.path.isfile(seabed) else None


def render_frame(out_dir, index=-1, png=None, scalars="tension"):
    """Render one frame of a run (line coloured by ``scalars`` over the seabed) to a PNG."""
    import pyvista

    pyvista.OFF_SCREEN = True
    times, frames, seabed = load_run(out_dir)
    png = png or os.path.join(out_dir, f"frame_{index % len(frames):05d}.png")
    plotter = pyvista.Plotter(off_screen=True, window_size=(1200, 600))
    _draw(plotter, frames[index], seabed, scalars)
    plotter.add_text(f"t = {times[index]:.2f} s", font_size=10)
    plotter.screenshot(png)
    plotter.close()
    return png


def write_animation(out_dir, path=None, scalars="tension", fps=10):
    """Write a GIF of all frames of a run (line over the seabed); returns its path."""
    import pyvista

    pyvista.OFF_SCREEN = True
    times, frames, seabed = load_run(out_dir)
    path = path or os.path.join(out_dir, "animation.gif")
    plotter = pyvista.Plotter(off_screen=True, window_size=(1000, 500))
    plotter.open_gif(path, fps=fps)
    limits = [min(f[scalars].min() for f in frames), max(f[scalars].max() for f in frames)]
    for t, frame in zip(times, frames):
        plotter.clear()
        _draw(plotter, frame, seabed, scalars, limits)
        plotter.add_text(f"t = {t:.2f} s", font_size=10)
        plotter.write_frame()
    plotter.close()
    return path


def _draw(plotter, frame, seabed, scalars, limits=None):
    if seabed is not None:
        plotter.add_mesh(seabed, color="tan", opacity=0.6)
    plotter.add_mesh(frame, scalars=scalars, line_width=4, clim=limits, cmap="viridis")
    plotter.view_xz()
    plotter.camera.elevation = 20
