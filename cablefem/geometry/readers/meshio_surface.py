"""Seabed meshes in any surface format meshio reads (.stl, .obj, .ply, .off, .vtu, .vtk, .msh, ...).

Triangles are kept, quads split along their 0-2 diagonal and other polygons
fanned from their first corner; duplicate vertices (STL repeats every corner
per facet) are merged when bit-identical, and vertices no face uses are
dropped. The result is a ``TriangulatedSurface`` (desire2023 Sec. 2.2.2.2).
Every defect is an ``InputError`` naming the file: unreadable file, no
triangles, missing z, NaN coordinates, degenerate or repeated triangles, and
(from the surface) non-manifold edges, vertical faces and folds.
"""

import contextlib
import io
import warnings
from pathlib import Path

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.triangulated import TriangulatedSurface
from cablefem.geometry.readers import MAX_COORDINATE

#: meshio cell types that are surface polygons, and how to cut them into triangles
_FANS = {"triangle": [[0, 1, 2]], "quad": [[0, 1, 2], [0, 2, 3]]}


def _triangles(cells):
    """Triangles (k, 3) of the surface cell blocks of a meshio mesh; volume and line cells are ignored."""
    pieces = []
    for block in cells:
        data = np.asarray(block.data)
        if block.type in _FANS:
            pieces += [data[:, corners] for corners in _FANS[block.type]]
        elif block.type == "polygon" and data.ndim == 2 and data.shape[1] >= 3:
            pieces += [data[:, [0, k, k + 1]] for k in range(1, data.shape[1] - 1)]
    return np.concatenate(pieces).astype(np.int64) if pieces else np.zeros((0, 3), dtype=np.int64)


def merge_vertices(points, triangles):
    """Vertices (m', 3) without bit-identical duplicates or unused points, and triangles (k, 3) renumbered."""
    unique, inverse = np.unique(points, axis=0, return_inverse=True)
    triangles = inverse.reshape(-1)[triangles]
    used, renumbered = np.unique(triangles, return_inverse=True)
    return unique[used], renumbered.reshape(-1, 3)


def check_triangles(triangles):
    """Raise InputError for triangles (k, 3) that repeat a corner or repeat another triangle."""
    t = np.sort(triangles, axis=1)
    bad = np.flatnonzero((t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2]))
    if len(bad):
        raise InputError(f"triangle {bad[0]} is degenerate: it uses vertex {t[bad[0], 1]} twice "
                         f"({len(bad)} degenerate triangles)")
    _, first, counts = np.unique(t, axis=0, return_index=True, return_counts=True)
    if np.any(counts > 1):
        again = np.setdiff1d(np.arange(len(t)), first)[0]
        raise InputError(f"triangle {again} repeats an earlier triangle (vertices "
                         f"{triangles[again].tolist()}): the surface is doubled")


def read(path):
    """The TriangulatedSurface in the surface mesh file path (str or Path) [m]."""
    import meshio  # only when a mesh is read

    file = str(path)
    if not Path(path).is_file():
        raise InputError("no such file", file=file)
    chatter = io.StringIO()
    try:  # meshio prints, warns, and for some files calls sys.exit: keep all of that in
        with contextlib.redirect_stdout(chatter), contextlib.redirect_stderr(chatter), \
                warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mesh = meshio.read(file)
    except (Exception, SystemExit) as error:
        said = [line.strip() for line in (str(error) if isinstance(error, Exception) else chatter.getvalue())
                .splitlines() if line.strip()]
        detail = said[0] if said else type(error).__name__
        raise InputError(f"cannot read as a surface mesh ({detail})", file=file) from None
    points = np.asarray(mesh.points, dtype=float)
    triangles = _triangles(mesh.cells)
    try:
        if len(triangles) == 0:
            kinds = sorted({block.type for block in mesh.cells}) or ["none"]
            raise InputError(f"no triangles or quads in the file (cells: {', '.join(kinds)})")
        if points.ndim != 2 or points.shape[1] != 3:
            raise InputError(f"points must have x, y and z, got shape {points.shape}")
        bad = np.flatnonzero(~np.isfinite(points).all(axis=1))
        if len(bad):
            raise InputError(f"point {bad[0]} has a non-finite coordinate {points[bad[0]].tolist()} "
                             f"({len(bad)} such points)")
        beyond = np.flatnonzero(np.abs(points).max(axis=1) > MAX_COORDINATE)
        if len(beyond):
            raise InputError(f"point {beyond[0]} {points[beyond[0]].tolist()} lies beyond the sane limit "
                             f"of {MAX_COORDINATE:g} m (UTM northings reach 1e7 m)")
        if triangles.min() < 0 or triangles.max() >= len(points):
            raise InputError(f"a cell refers to point {triangles.max()}, but there are {len(points)}")
        points, triangles = merge_vertices(points, triangles)
        check_triangles(triangles)
        return TriangulatedSurface(points, triangles)
    except InputError as error:
        raise InputError(error.reason, file=file) from None
