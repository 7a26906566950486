"""Looking at results without ParaView: tension plots (matplotlib) and pictures of a run's frames
(pyvista, off screen; ``cablefem render``).

A picture shows the line(s) coloured by one of the frames' arrays (docs/outputs.md) over the
seabed near them, in a parallel projection framed on all the run's frames (so that pictures of
one run line up), with a colour bar naming the quantity and its unit, one colour range for the
whole run by default, and the scene and time as its title. Both libraries are imported inside the
functions, so the solver never pulls in plotting.
"""

import csv
import json
import os

import numpy as np

from cablefem.errors import InputError
from cablefem.io.vtk import read_collection

#: the frames' arrays as pictures show them: label, unit and factor from the SI value to that unit
#: (vectors are shown by their magnitude)
QUANTITIES = {
    "tension": ("tension", "kN", 1e-3),
    "strain": ("axial strain", "-", 1.0),
    "velocity": ("speed", "m/s", 1.0),
    "seabed_gap": ("seabed gap", "m", 1.0),
    "contact_force": ("seabed contact force", "kN/m", 1e-3),
    "soil_reaction": ("soil reaction", "kN/m", 1e-3),
    "soil_slip": ("soil slip", "m", 1.0),
    "curvature": ("curvature", "1/m", 1.0),
    "bending_moment": ("bending moment", "kN m", 1e-3),
}

#: named views: the direction from the focal point to the camera and the screen's up, both
#: before normalisation ("side": along -y, 20 deg above the horizon)
VIEWS = {"side": ((0.0, -np.cos(np.radians(20.0)), np.sin(np.radians(20.0))), (0.0, 0.0, 1.0)),
         "top": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
         "iso": ((0.6, -1.0, 0.7), (0.0, 0.0, 1.0))}

#: the picture's bands above and below the scene [px]: the title, and the colour bar with its label
TITLE_BAND, BAR_BAND = 60, 120

#: the colour map of every picture (perceptually uniform, readable in grey)
CMAP = "viridis"


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


def plot_tensions(out_dir, png=None, elevation=False):
    """Fairlead and anchor tension [N] against time of a run, as a PNG; with ``elevation`` (a run in
    waves) the elevation at the origin [m] above them, on the same time axis; returns its path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = read_tensions(out_dir)
    if elevation and "eta" not in data:
        raise InputError("no elevation in tensions.csv: the run had no [waves]", file=out_dir)
    png = png or os.path.join(out_dir, "tensions.png")
    if elevation:
        fig, (top, ax) = plt.subplots(2, 1, figsize=(8, 6), sharex=True, gridspec_kw={"height_ratios": [1, 2]})
        top.plot(data["t"], data["eta"], color="tab:blue")
        top.set_ylabel("elevation at the origin [m]")
        top.grid(True, alpha=0.3)
    else:
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


def collection(out_dir):
    """The path of a run's .pvd in ``out_dir``: the one of the scene its summary.json names, else
    the only one there; InputError otherwise."""
    if not os.path.isdir(out_dir):
        raise InputError("no such folder", file=out_dir)
    found = sorted(f for f in os.listdir(out_dir) if f.endswith(".pvd"))
    if len(found) > 1 and "waves.pvd" in found:  # a run in waves: the free surface's collection
        found.remove("waves.pvd")
    try:
        with open(os.path.join(out_dir, "summary.json"), encoding="utf-8") as handle:
            named = f"{json.load(handle)['scene']}.pvd"
    except (OSError, ValueError, KeyError, TypeError):
        named = None
    if named in found:
        return os.path.join(out_dir, named)
    if len(found) != 1:
        raise InputError("no .pvd collection here: is this the output folder of `cablefem run`?" if not found
                         else f"several .pvd collections here ({', '.join(found)}) and no summary.json naming "
                         "one", file=out_dir)
    return os.path.join(out_dir, found[0])


def load_run(out_dir):
    """(times (k,), list of pyvista meshes of the line frames, pyvista seabed mesh or None) of a run."""
    import pyvista

    times, frames = read_collection(collection(out_dir))
    seabed = os.path.join(out_dir, "seabed.vtu")
    return times, [pyvista.read(f) for f in frames], pyvista.read(seabed) if os.path.isfile(seabed) else None


def render_frame(out_dir, index=-1, png=None, scalars="tension", clim=None, camera="side", size=None):
    """Render frame ``index`` of a run to a PNG (``render_run``); returns its path (default
    OUT/<scene>_NNNNN.png)."""
    return render_run(out_dir, frames=[index], png=png, scalars=scalars, clim=clim, camera=camera, size=size)[0]


def load_surface(out_dir):
    """The free surface's frames of a run in waves (a list of pyvista meshes, one per line frame:
    ``cablefem.runs.surface``), or None."""
    import pyvista

    path = os.path.join(out_dir, "waves.pvd")
    if not os.path.isfile(path) or collection(out_dir) == path:
        return None
    return [pyvista.read(f) for f in read_collection(path)[1]]


def render_run(out_dir, frames=None, png=None, png_dir=None, animation=None, scalars="tension", clim=None,
               camera="side", size=None, fps=10):
    """Pictures of a run's frames ``frames`` (indices, negative from the end; default all): one PNG
    each (``png`` for a single frame, else ``png_dir``/<scene>_NNNNN.png, default OUT; rendering all
    frames first removes such pictures of an earlier render) or, with ``animation`` (.gif, or .mp4
    with imageio-ffmpeg), one animation through imageio. The line is coloured by the frames' array
    ``scalars`` (``QUANTITIES``) over ``clim`` (low, high) [the array's SI unit; default the range
    over all the run's frames], seen from ``camera`` ("side", "top", "iso", or a pyvista camera
    position [(position), (focal point), (view up)]); ``size`` (width, height) of a picture [px]
    (default 1600 wide, as tall as the framed scene needs). Returns the paths written."""
    times, meshes, seabed = load_run(out_dir)
    surface = load_surface(out_dir)
    name = os.path.splitext(os.path.basename(collection(out_dir)))[0]
    picked = _frame_indices(frames, len(meshes), out_dir)
    meshes = [_parts(mesh) for mesh in meshes]  # (the lines, the network's points, its bodies' segments)
    values = [_values(lines, scalars, out_dir) for lines, _, _ in meshes]
    label, unit, factor = QUANTITIES.get(scalars, (scalars.replace("_", " "), "", 1.0))
    label = f"{label} [{unit}]" if unit else label
    limits = _limits(values if clim is None else None, clim, factor)
    seabed = _near(seabed, [m for parts in meshes for m in parts])
    framed = [m.points for parts in meshes for m in parts if m is not None]
    view = _View(camera, framed + ([seabed.points] if seabed is not None else []), size)

    def picture(k):
        scene = view.scene(seabed, meshes[k], values[k] * factor, limits, None if surface is None else surface[k])
        return _picture(scene, f"{name}, t = {times[k]:.2f} s", label, limits, view.metres_per_pixel())

    try:
        if animation is not None:
            return [_animate(animation, [picture(k) for k in picked], fps)]
        if png is not None and len(picked) != 1:
            raise InputError("a PNG file name is for one frame; give a folder for several", key="png")
        folder = png_dir or out_dir
        if png is None:
            from cablefem.io.output import prepare_folder

            folder = prepare_folder(folder)
            if frames is None:  # every frame: no picture of an earlier render stays among them
                for path in picture_files(folder, name):
                    os.unlink(path)
        paths = [png] if png is not None else [os.path.join(folder, f"{name}_{k:05d}.png") for k in picked]
        for path, k in zip(paths, picked):
            _write_image(path, picture(k))
        return paths
    finally:
        view.close()


def picture_files(folder, name):
    """The pictures of a run's frames in ``folder`` as ``render_run`` names them: <name>_NNNNN.png."""
    import re

    pattern = re.compile(re.escape(name) + r"_[0-9]{5,}\.png")
    with os.scandir(folder) as entries:
        return sorted(e.path for e in entries if not e.is_dir(follow_symlinks=False) and pattern.fullmatch(e.name))


def _parts(mesh):
    """A frame's lines, the network's named points and its bodies' segments (cell data ``network``
    0, 1, 2; docs/outputs.md), each a pyvista mesh (the last two None without them)."""
    if "network" not in mesh.cell_data:
        return mesh, None, None
    kind = np.asarray(mesh.cell_data["network"])
    return tuple(mesh.extract_cells(np.flatnonzero(kind == k)) if np.any(kind == k) else None for k in range(3))


def _frame_indices(frames, count, out_dir):
    """The frames' indices (list) in 0 .. count - 1; InputError naming one that is not there."""
    picked = list(range(count)) if frames is None else [int(k) for k in frames]
    for k in picked:
        if not -count <= k < count:
            raise InputError(f"no frame {k}: the run wrote {count} frames (0 to {count - 1}, or -1 for the last)",
                             key="frame", file=out_dir)
    return [k % count for k in picked]


def _values(mesh, scalars, out_dir):
    """The point array ``scalars`` of a frame (n,), a vector's magnitude; InputError listing the
    arrays if it has none of that name."""
    if scalars not in mesh.point_data:
        raise InputError(f"no array '{scalars}' in the frames; they have {', '.join(mesh.point_data.keys())}",
                         key="scalars", file=out_dir)
    values = np.asarray(mesh.point_data[scalars], dtype=float)
    return np.linalg.norm(values, axis=1) if values.ndim == 2 else values


def _limits(values, clim, factor):
    """The colour range in the shown unit: ``clim`` (SI) scaled, or the range over ``values``."""
    if values is None:
        try:
            lo, hi = (float(x) for x in clim)
        except (TypeError, ValueError):
            lo = hi = float("nan")
    else:
        lo, hi = min(float(v.min()) for v in values), max(float(v.max()) for v in values)
    if not lo <= hi:
        raise InputError(f"the colour range must be two numbers, low to high, got {clim}", key="clim")
    if hi == lo:  # a constant field: a range around it
        lo, hi = lo - 0.5 * (abs(lo) or 1.0), hi + 0.5 * (abs(hi) or 1.0)
    return lo * factor, hi * factor


def _near(seabed, meshes, margin=0.05):
    """The seabed within the plan extent of ``meshes`` (None among them ignored), widened by
    ``margin`` of its largest side."""
    if seabed is None or seabed.n_cells == 0:
        return None
    points = np.vstack([m.points for m in meshes if m is not None])
    lo, hi = points.min(axis=0), points.max(axis=0)
    pad = margin * float(max(hi[0] - lo[0], hi[1] - lo[1], 1.0))
    z0, z1 = seabed.bounds[4], seabed.bounds[5]
    box = (lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad, z0 - 1.0, z1 + 1.0)
    clipped = seabed.clip_box(box, invert=False)
    return clipped if clipped.n_cells else None


class _View:
    """An off-screen pyvista picture framed on ``points`` (list of (n, 3)): a parallel projection
    along a named view fitted to them, or a given camera; ``size`` (width, height) of the whole
    picture [px], the scene taking what the title and the colour bar leave."""

    def __init__(self, camera, points, size):
        points = np.vstack(points)
        self.named = isinstance(camera, str)
        if self.named and camera not in VIEWS:
            raise InputError(f"unknown camera '{camera}'; views: {', '.join(VIEWS)}, or a camera position",
                             key="camera")
        if self.named:
            back, up = (np.asarray(v, dtype=float) for v in VIEWS[camera])
            self.back = back / np.linalg.norm(back)
            right = np.cross(up, self.back)
            self.right = right / np.linalg.norm(right)
            self.up = np.cross(self.back, self.right)
            x, y = points @ self.right, points @ self.up
            self.span = (float(np.ptp(x)) or 1.0, float(np.ptp(y)) or 1.0)
            self.centre = (0.5 * (x.min() + x.max()), 0.5 * (y.min() + y.max()), float(np.mean(points @ self.back)))
            self.depth = float(np.linalg.norm(np.ptp(points, axis=0))) or 1.0
        self.camera = camera
        width = 1600 if size is None else int(size[0])
        if size is not None:
            scene = int(size[1]) - TITLE_BAND - BAR_BAND
        elif self.named:  # the scene's own aspect (with 4 % to spare), between 300 and 1200 px
            scene = int(np.clip(width * 1.04 * self.span[1] / self.span[0], 300, 1200))
        else:
            scene = 600
        if width < 400 or scene < 100:
            raise InputError(f"a picture of {size[0]} x {size[1]} px is too small: at least "
                             f"400 x {100 + TITLE_BAND + BAR_BAND}", key="size")
        self.size = (width, scene)
        self.plotter = None

    def scene(self, seabed, parts, values, limits, surface=None):
        """The scene's picture (height, width, 3): the frame's ``parts`` (``_parts``), its lines
        coloured by ``values``, its points black and its bodies' segments grey, over ``seabed``
        (the seabed and the camera set on the first call; ``close`` when done), under the free
        ``surface`` of a run in waves (blue, translucent)."""
        import pyvista

        if self.plotter is None:
            pyvista.OFF_SCREEN = True
            self.plotter = pyvista.Plotter(off_screen=True, window_size=self.size)
            self.plotter.set_background("white")
            if seabed is not None:
                self.plotter.add_mesh(seabed, color="tan", opacity=0.55, smooth_shading=True)
        lines, points, bodies = parts
        shown = lines.copy()
        shown.point_data["shown"] = values
        self.plotter.add_mesh(shown, scalars="shown", clim=limits, cmap=CMAP, line_width=7, name="line",
                              render_lines_as_tubes=True, lighting=False, show_scalar_bar=False)
        for part, name, style in ((bodies, "bodies", dict(color="grey", line_width=4)),
                                  (points, "points", dict(color="black", point_size=14,
                                                          render_points_as_spheres=True))):
            if part is not None:
                self.plotter.add_mesh(part, name=name, lighting=False, **style)
        if surface is not None:
            self.plotter.add_mesh(surface, name="surface", color="steelblue", opacity=0.35, smooth_shading=True)
        self._place(self.plotter)
        return self.plotter.screenshot(return_img=True)

    def close(self):
        if self.plotter is not None:
            self.plotter.close()
            self.plotter = None

    def metres_per_pixel(self):
        """The scene's scale [m/px] across the picture (parallel projection), None for a given camera."""
        if not self.named:
            return None
        width, height = self.size
        return 2.0 * self._scale() / height

    def _scale(self):
        """Half the picture's height [m]: the framed points fit it with 4 % to spare."""
        width, height = self.size
        return 0.52 * max(self.span[1], self.span[0] * height / width)

    def _place(self, plotter):
        if not self.named:
            plotter.camera_position = self.camera
            return
        camera = plotter.camera
        focal = self.centre[0] * self.right + self.centre[1] * self.up + self.centre[2] * self.back
        camera.parallel_projection = True
        camera.focal_point = focal
        camera.position = focal + 2.0 * self.depth * self.back
        camera.up = self.up
        camera.parallel_scale = self._scale()
        camera.clipping_range = (0.5 * self.depth, 4.0 * self.depth)


def _picture(scene, title, label, limits, metres_per_pixel=None):
    """The whole picture (height, width, 3): the scene's image under its title, over a horizontal
    colour bar (matplotlib: round ticks, the quantity and its unit as its label) and, with the
    scene's ``metres_per_pixel`` across it, a scale bar of a round length beside the colour bar."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    height, width = scene.shape[:2]
    total, dpi = height + TITLE_BAND + BAR_BAND, 100
    fig = plt.figure(figsize=(width / dpi, total / dpi), dpi=dpi)
    ax = fig.add_axes((0.0, BAR_BAND / total, 1.0, height / total))
    ax.imshow(scene, interpolation="nearest")
    ax.set_axis_off()
    bar = fig.add_axes((0.3, 0.55 * BAR_BAND / total, 0.4, 0.2 * BAR_BAND / total))
    fig.colorbar(ScalarMappable(Normalize(*limits), cmap=CMAP), cax=bar, orientation="horizontal")
    bar.set_xlabel(label, fontsize=15)
    bar.tick_params(labelsize=13)
    fig.text(0.5, 1.0 - 0.5 * TITLE_BAND / total, title, ha="center", va="center", fontsize=18)
    if metres_per_pixel:
        length = _round_length(0.15 * width * metres_per_pixel)
        y = 0.65 * BAR_BAND / total
        fig.add_artist(plt.Line2D([0.04, 0.04 + length / metres_per_pixel / width], [y, y], color="black", lw=3))
        fig.text(0.04, y - 0.12 * BAR_BAND / total, f"{length:g} m", ha="left", va="top", fontsize=13)
    fig.canvas.draw()
    image = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    plt.close(fig)
    return image


def _round_length(at_most):
    """The largest 1, 2 or 5 times a power of ten not above ``at_most`` (> 0)."""
    power = 10.0 ** np.floor(np.log10(at_most))
    return max(step * power for step in (1.0, 2.0, 5.0) if step * power <= at_most)


def _write_image(path, image):
    """A PNG at ``path``, whole or not at all (``cablefem.io.output.replace_into``)."""
    import imageio.v3 as iio

    from cablefem.io.output import replace_into

    replace_into(lambda tmp: iio.imwrite(tmp, image, extension=".png"), path)


def _animate(path, images, fps):
    """One animation file of ``images`` at ``fps`` frames a second through imageio; its path."""
    import imageio.v3 as iio

    from cablefem.io.output import prepare_file, replace_into

    extension = os.path.splitext(path)[1].lower()
    if extension not in (".gif", ".mp4"):
        raise InputError("an animation is a .gif (or an .mp4, with imageio-ffmpeg installed)", key="animation")
    prepare_file(path)
    options = {"duration": 1000.0 / fps, "loop": 0} if extension == ".gif" else {"fps": fps}
    try:
        replace_into(lambda tmp: iio.imwrite(tmp, images, extension=extension, **options), path)
    except (ImportError, ValueError) as error:  # no writer for the format here (mp4 without imageio-ffmpeg)
        raise InputError(f"cannot write {extension}: {' '.join(str(error).split())}", key="animation") from None
    return path
