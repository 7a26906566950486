"""Model only what a scene needs: replace a gridded or triangulated seabed that is
flat by its plane (desire2023 Sec. 2.2.2: point-to-plane projection is cheaper,
Table 6), and the two flat stand-ins of an irregular seabed that desire2023
Sec. 5 compares with it (Fig. 18): the least-squares plane and the horizontal
plane at the mean depth.

Works on anything with a ``vertices`` (m, 3) attribute [m]: ``DepthGrid`` and
the triangulated surface.
"""

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.planes import Horizontal, Plane


def _points(points):
    points = np.asarray(points, dtype=float)
    if points.ndim != 2 or points.shape[1] != 3 or len(points) < 3 or not np.all(np.isfinite(points)):
        raise InputError(f"expected at least 3 finite points of shape (m, 3), got {points.shape}",
                         key="points")
    return points


def _fit(points):
    """Least-squares plane z = c + g_x (x - x_mean) + g_y (y - y_mean) through points (m, 3):
    the centroid (3,) and the gradient (g_x, g_y)."""
    centroid = points.mean(axis=0)
    centred = points - centroid
    gradient, _, rank, _ = np.linalg.lstsq(centred[:, :2], centred[:, 2], rcond=None)
    if rank < 2:
        raise InputError("the points lie on one vertical line or plane; no seabed plane fits them",
                         key="points")
    return centroid, gradient


def least_squares_plane(points):
    """The Plane z = a + b x + c y fitted to points (m, 3) [m] by least squares in z.

    Vertical least squares suits a seabed (a height field: the normal always
    points up); the plane passes through the centroid of the points.
    """
    centroid, (g_x, g_y) = _fit(_points(points))
    return Plane(centroid, [-g_x, -g_y, 1.0])


def mean_depth_horizontal(points):
    """The Horizontal seabed at the mean elevation of points (m, 3) [m] (desire2023 Sec. 5, z-bar)."""
    mean = float(_points(points)[:, 2].mean())
    if not mean < 0.0:
        raise InputError(f"the mean elevation {mean:g} m is not below the water surface z = 0",
                         key="points")
    return Horizontal(-mean)


def simplify(seabed, tolerance=1e-9, notes=None):
    """A Horizontal or Plane equal to seabed within tolerance x extent [m], else seabed itself.

    The extent is the diagonal of the bounding box of the seabed's vertices;
    the deviation is the largest distance of a vertex from the plane. One line
    saying what was chosen and the deviation is appended to notes (a list), if
    given. A plane replaces a grid everywhere: outside a DepthGrid, where the
    grid is clamped flat, the plane goes on sloping.
    """
    def say(line):
        if notes is not None:
            notes.append(line)
        return line

    if isinstance(seabed, Plane):
        say(f"seabed: kept {seabed.describe()} (already a plane)")
        return seabed
    vertices = getattr(seabed, "vertices", None)
    if vertices is None:
        say(f"seabed: kept {seabed.describe()} (no vertices to test for flatness)")
        return seabed
    if not (isinstance(tolerance, (int, float)) and np.isfinite(tolerance) and tolerance >= 0):
        raise InputError(f"must be a finite number >= 0, got {tolerance!r}", key="tolerance")
    vertices = _points(vertices)
    allowed = tolerance * float(np.linalg.norm(np.ptp(vertices, axis=0)))
    name = seabed.kind

    mean = vertices[:, 2].mean()
    level_deviation = float(np.max(np.abs(vertices[:, 2] - mean)))
    if level_deviation <= allowed and mean < 0.0:
        chosen = Horizontal(-mean)
        say(f"seabed: {name} is horizontal within {level_deviation:.3g} m "
            f"(tolerance {allowed:.3g} m): using {chosen.describe()}")
        return chosen

    centroid, (g_x, g_y) = _fit(vertices)
    chosen = Plane(centroid, [-g_x, -g_y, 1.0])
    deviation = float(np.max(np.abs((vertices - centroid) @ chosen.normal)))
    if deviation <= allowed:
        say(f"seabed: {name} is planar within {deviation:.3g} m "
            f"(tolerance {allowed:.3g} m): using {chosen.describe()}")
        return chosen
    say(f"seabed: kept {name}, {deviation:.3g} m from its least-squares plane "
        f"(tolerance {allowed:.3g} m)")
    return seabed


_simplest = simplify  # choose_seabed's argument of that name hides it


def choose_seabed(seabed, lines, simplify=True):
    """The seabed model a scene with ``lines`` uses, and one note (str) saying which and why (None
    for a plane: it is used as given, and ``describe`` says what it is).

    A plane is kept as given. With ``simplify``, a grid or mesh that is
    level or planar within 1e-9 of its extent becomes that Horizontal or Plane
    (``cablefem.geometry.simplify``; point-to-plane projection), anything else
    is kept (its general projection). A planar, sloping grid stays a grid when
    an anchor or fairlead lies outside it in plan: there the grid is clamped
    flat while its plane would go on sloping. ``simplify=False`` keeps the
    model as read, untested (cost studies).
    """
    if isinstance(seabed, Plane):
        return seabed, None
    if not simplify:
        return seabed, (f"seabed: {seabed.describe()}, kept as read (simplify = false: "
                        "not tested for flatness, general projection)")
    said = []
    chosen = _simplest(seabed, notes=said)
    note = said[-1] if said else f"seabed: kept {seabed.kind}"
    bounds = getattr(seabed, "bounds", None)
    if chosen is not seabed and not isinstance(chosen, Horizontal) and bounds is not None:
        (x0, x1), (y0, y1) = bounds
        ends = np.array([point for line in lines for point in (line.anchor, line.fairlead)])
        slack = 1e-9 * max(x1 - x0, y1 - y0)
        outside = ((ends[:, 0] < x0 - slack) | (ends[:, 0] > x1 + slack)
                   | (ends[:, 1] < y0 - slack) | (ends[:, 1] > y1 + slack))
        if outside.any():
            return seabed, (f"seabed: kept {seabed.describe()}: it is planar ({chosen.describe()}), "
                            "but a line end lies outside it in plan, where the grid is clamped flat "
                            "and the plane would go on sloping")
    if chosen is seabed:
        return seabed, f"{note}: using {seabed.describe()}"
    return chosen, f"{note} (point-to-plane projection)"
