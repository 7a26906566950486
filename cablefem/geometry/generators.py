"""Seabed generators: uniform slopes, the flat-slope-flat steps of the desire2023
flume (Sec. 4.1, Figs. 10-11) and the diamond-square fractal seabed of
desire2023 Sec. 5 (Fig. 18), each as a ``DepthGrid`` (angles in radians,
lengths in metres, z up, the still water surface at z = 0).

The flume steps are a reconstruction: the paper gives their angles and which
corner the line works against, not their coordinates. Every assumption is
listed in ``flume_step`` and in docs/seabeds.md.
"""

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.grid import DepthGrid

#: desire2023 Sec. 4.1 / Fig. 10-11: Froude scale of the flume tests
FLUME_SCALE = 75.0
#: the COCOTSU flume is 2 m wide (model scale) -> 150 m at prototype scale
FLUME_WIDTH = 2.0 * FLUME_SCALE
#: x range of the flume grids [m]: the anchor (x ~ -600 m for the 635 m line of
#: Table 5) with 100 m to spare, to the fairlead's largest surge (+17.5 m) with
#: 80 m to spare; outside, the grid is clamped, which continues the flat floors.
FLUME_X_RANGE = (-700.0, 100.0)
#: kind -> (slope angle [deg], which corner is placed, x of that corner [m])
FLUME_STEPS = {
    "gentle": (4.0, "foot", -260.0),   # the concave bottom corner, anchor side of touchdown
    "steep": (19.0, "top", -200.0),    # the convex top corner, which the line bends over
}


def _positive(value, name, upper=np.inf):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not (0.0 < value < upper):
        raise InputError(f"must be a number in (0, {upper:g}), got {value!r}", key=name)
    return float(value)


def _bounds(extent, name="extent"):
    try:
        (x0, x1), (y0, y1) = extent
        x0, x1, y0, y1 = (float(v) for v in (x0, x1, y0, y1))
    except (TypeError, ValueError):
        raise InputError(f"expected ((xmin, xmax), (ymin, ymax)) [m], got {extent!r}", key=name) from None
    if not (np.all(np.isfinite([x0, x1, y0, y1])) and x1 > x0 and y1 > y0):
        raise InputError(f"expected finite ((xmin, xmax), (ymin, ymax)) with max > min, got {extent!r}",
                         key=name)
    return (x0, x1), (y0, y1)


def slope(angle, azimuth=0.0, depth=100.0, extent=((-1000.0, 1000.0), (-1000.0, 1000.0)), nodes=2):
    """Uniform slope rising at angle [rad] towards azimuth [rad], z = -depth [m] at x = y = 0,
    as a DepthGrid of nodes x nodes over extent ((xmin, xmax), (ymin, ymax)) [m].

    Same convention as ``Plane.from_slope``: azimuth 0 rises towards +x, pi/2
    towards +y. housner2022's 12.5 % grade is angle = arctan(0.125). The grid
    is exact for any nodes >= 2 (a bilinear patch of a plane is the plane);
    outside the extent it is clamped flat.
    """
    if isinstance(angle, bool) or not isinstance(angle, (int, float, np.integer, np.floating)) \
            or not abs(angle) < np.pi / 2:
        raise InputError(f"must be a number of radians in (-pi/2, pi/2), got {angle!r}", key="angle")
    depth = _positive(depth, "depth")
    (x0, x1), (y0, y1) = _bounds(extent)
    if isinstance(nodes, bool) or not isinstance(nodes, (int, np.integer)) or nodes < 2:
        raise InputError(f"must be an integer >= 2, got {nodes!r}", key="nodes")
    x, y = np.linspace(x0, x1, nodes), np.linspace(y0, y1, nodes)
    gx, gy = np.meshgrid(x, y)
    rise = np.tan(angle) * (gx * np.cos(azimuth) + gy * np.sin(azimuth))
    return DepthGrid(x, y, -depth + rise)


def step(angle, foot, rise, depth=100.0, x_range=FLUME_X_RANGE, width=FLUME_WIDTH):
    """Flat-slope-flat step across x: z = -depth [m] for x <= foot [m], rising at angle [rad]
    by rise [m], then flat; uniform in y over width [m] centred on y = 0, as a DepthGrid.

    The grid has a node line on each corner, so it is the exact piecewise-plane
    profile: a concave corner at x = foot, a convex one at x = foot + rise / tan(angle).
    """
    angle = _positive(angle, "angle", np.pi / 2)
    rise, depth, width = _positive(rise, "rise"), _positive(depth, "depth"), _positive(width, "width")
    if rise >= depth:
        raise InputError(f"the step top would be at or above the water surface (rise {rise:g} m, "
                         f"depth {depth:g} m)", key="rise")
    top = foot + rise / np.tan(angle)
    x0, x1 = x_range
    if not (x0 < foot and top < x1):
        raise InputError(f"the step from x = {foot:g} to {top:g} m must lie inside x_range {x_range}",
                         key="x_range")
    x = np.array([x0, foot, top, x1], dtype=float)
    profile = np.array([-depth, -depth, rise - depth, rise - depth])
    return DepthGrid(x, [-width / 2, width / 2], np.vstack([profile, profile]))


def flume_step(kind, depth=100.0, rise=12.0):
    """The desire2023 flume seabed kind ("flat", "gentle" 4 deg, "steep" 19 deg) at prototype
    scale 1:75, as a DepthGrid [m]; origin at the fairlead's projection on the surface.

    The paper gives the angles, the flume (56 m x 2 m, 1.8-2.5 m deep at model
    scale), the line (Table 5: 635 m) and which corner dominates each test
    (Sec. 4.1: the gentle step's bottom concave corner, the steep step's top
    convex corner); the rest is assumed (docs/seabeds.md has the reasoning):

    - The step rises towards the fairlead (x > 0): the paper's tensions fall
      from flat to gentle to steep (Figs. 12-17) because more of the line
      lies on the seabed, i.e. the seabed below the suspended line is
      shallower.
    - depth = 100 m on the anchor side (1.33 m at model scale), the depth of
      the built-in scene, with the anchor at x ~ -595 m: a static check of
      the 635 m line on the flat floor gives 2.56 MN at the quasi-static
      minimum surge (x = 12.5 m) where Fig. 12 shows ~2.5 MN.
    - rise = 12 m (0.16 m at model scale) for both steps, so they differ in
      length (172 m vs 35 m) and location, as the paper says they do.
    - gentle: the concave foot at x = -260 m, anchor side of the touchdown,
      top at x = -88 m: the line lies into the foot and up the slope
      (touchdown -214 to -162 m for surge 12.5-17.5 m); 2.22 MN static at
      x = 12.5 m, Fig. 14 ~2.2 MN.
    - steep: the convex top at x = -200 m, foot at x = -235 m: the line
      bends over the top edge onto the plateau (touchdown ~ -160 m); 2.00 MN
      static at x = 12.5 m, Fig. 16 ~2.0 MN.
    - uniform across the flume: 150 m wide (2 m model), x from -700 to 100 m;
      the grid is clamped outside, which continues both flat floors.
    """
    if kind == "flat":
        depth = _positive(depth, "depth")
        x0, x1 = FLUME_X_RANGE
        return DepthGrid([x0, x1], [-FLUME_WIDTH / 2, FLUME_WIDTH / 2], np.full((2, 2), -depth))
    if kind not in FLUME_STEPS:
        raise InputError(f"unknown flume seabed {kind!r}; expected flat, gentle or steep", key="kind")
    degrees, corner, where = FLUME_STEPS[kind]
    angle = np.radians(degrees)
    rise = _positive(rise, "rise")
    foot = where if corner == "foot" else where - rise / np.tan(angle)
    return step(angle, foot, rise, depth)


def _neighbour_mean(height, rows, cols, half):
    """Mean of the existing neighbours at distance half (N, S, E, W) of the nodes rows x cols
    of the square array height (the square step of diamond-square; 3 neighbours on an edge)."""
    size = height.shape[0]
    r, c = np.meshgrid(rows, cols, indexing="ij")
    total = np.zeros(r.shape)
    found = np.zeros(r.shape)
    for dr, dc in ((-half, 0), (half, 0), (0, -half), (0, half)):
        rr, cc = r + dr, c + dc
        ok = (rr >= 0) & (rr < size) & (cc >= 0) & (cc < size)
        total += np.where(ok, height[np.clip(rr, 0, size - 1), np.clip(cc, 0, size - 1)], 0.0)
        found += ok
    return total / found


def fractal_heights(n, smoothness, amplitude, rng):
    """Diamond-square heights (2^n + 1, 2^n + 1) [m] from the numpy Generator rng.

    Convention: corners uniform in [-amplitude, amplitude]; the displacements
    of subdivision level k = 1..n are uniform in [-a_k, a_k] with
    a_k = amplitude * 2^(-k (1 - smoothness)), i.e. Hurst exponent
    H = 1 - smoothness, so smoothness near 0 is smooth (displacements halve per
    level) and near 1 is rough (they do not shrink), as desire2023 Sec. 5
    describes Kaya's parameter ("the closer it is to 0, the smoother").
    Each level draws the diamond step's centres, then the square step's
    edge midpoints (rows 0, step, ... first), in row-major order.
    """
    size = 2 ** n + 1
    height = np.zeros((size, size))
    corner = np.ix_([0, size - 1], [0, size - 1])
    height[corner] = rng.uniform(-amplitude, amplitude, (2, 2))
    span = size - 1
    for level in range(1, n + 1):
        half = span // 2
        scale = amplitude * 2.0 ** (-level * (1.0 - smoothness))
        centres = 0.25 * (height[:-1:span, :-1:span] + height[span::span, :-1:span]
                          + height[:-1:span, span::span] + height[span::span, span::span])
        height[half::span, half::span] = centres + rng.uniform(-scale, scale, centres.shape)
        for rows, cols in ((np.arange(0, size, span), np.arange(half, size, span)),
                           (np.arange(half, size, span), np.arange(0, size, span))):
            mean = _neighbour_mean(height, rows, cols, half)
            height[np.ix_(rows, cols)] = mean + rng.uniform(-scale, scale, mean.shape)
        span = half
    return height


def diamond_square(n, smoothness=0.3, amplitude=10.0, seed=0,
                   extent=((-700.0, 100.0), (-400.0, 400.0)), mean_depth=93.5, tilt=(0.0, 0.0)):
    """Irregular seabed of desire2023 Sec. 5 (Fig. 18): a diamond-square fractal on
    (2^n + 1)^2 nodes over extent ((xmin, xmax), (ymin, ymax)) [m], as a DepthGrid.

    smoothness in [0, 1] (0.3 in the paper; convention in ``fractal_heights``),
    amplitude [m] the half-range of the corner heights, seed the numpy
    Generator seed (same seed, same seabed). The fractal's own least-squares
    plane is removed and replaced by the requested one, so that the nodes'
    mean elevation is exactly -mean_depth [m] (Fig. 18's z-bar = -93.5 m) and
    their least-squares plane has gradient tilt = (dz/dx, dz/dy) [m/m].
    ``least_squares_plane()`` and ``mean_depth_horizontal()`` of the result
    give the paper's two flat stand-ins.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 1 <= n <= 12:
        raise InputError(f"must be an integer from 1 to 12 (2^n + 1 nodes a side), got {n!r}", key="n")
    if isinstance(smoothness, bool) or not isinstance(smoothness, (int, float, np.floating)) \
            or not 0.0 <= smoothness <= 1.0:
        raise InputError(f"must be a number in [0, 1], got {smoothness!r}", key="smoothness")
    if not (isinstance(amplitude, (int, float, np.floating)) and 0.0 <= amplitude < np.inf):
        raise InputError(f"must be a finite number >= 0, got {amplitude!r}", key="amplitude")
    mean_depth = _positive(mean_depth, "mean_depth")
    tilt = np.asarray(tilt, dtype=float)
    if tilt.shape != (2,) or not np.all(np.isfinite(tilt)):
        raise InputError(f"expected (dz/dx, dz/dy), got {tilt.tolist()}", key="tilt")
    (x0, x1), (y0, y1) = _bounds(extent)

    height = fractal_heights(n, float(smoothness), float(amplitude), np.random.default_rng(seed))
    x, y = np.linspace(x0, x1, 2 ** n + 1), np.linspace(y0, y1, 2 ** n + 1)
    dx, dy = np.meshgrid(x - x.mean(), y - y.mean())
    basis = np.column_stack([np.ones(dx.size), dx.ravel(), dy.ravel()])
    fitted, *_ = np.linalg.lstsq(basis, height.ravel(), rcond=None)
    detrended = height - (basis @ fitted).reshape(height.shape)
    return DepthGrid(x, y, detrended - mean_depth + tilt[0] * dx + tilt[1] * dy)


def triangulated_step(grid, band=2.0, spacing=25.0):
    """A ``TriangulatedSurface`` of a step DepthGrid (uniform in y) for the vertex-normal projection.

    Vertex normals average the faces around a vertex, so the direction d_P turns
    continuously across each corner (desire2023 Sec. 2.2.2.2) over the faces touching
    it: extra node lines at the corners +- ``band`` [m] keep that turn within the band,
    and the flat floors are split every ``spacing`` [m].
    """
    from cablefem.geometry.planes import _grid_triangles
    from cablefem.geometry.triangulated import TriangulatedSurface

    corners = grid.x[1:-1]
    regular = np.arange(grid.x[0], grid.x[-1] + spacing, spacing)
    x = np.unique(np.concatenate([grid.x, corners - band, corners + band,
                                  regular[(regular > grid.x[0]) & (regular < grid.x[-1])]]))
    keep = np.concatenate([[True], np.diff(x) > 1e-6])
    x = x[keep]
    y = grid.y
    X, Y = np.meshgrid(x, y)
    xy = np.column_stack([X.ravel(), Y.ravel()])
    vertices = np.column_stack([xy, grid.elevation(xy)])
    return TriangulatedSurface(vertices, _grid_triangles(len(x), len(y)))
