"""Triangulated seabed with the continuous vertex-normal projection (desire2023 Sec. 2.2.2.2, Eq. 6, 7, 10).

The surface is the piecewise-linear triangulation itself; points are projected
along the vertex normals interpolated over each triangle (Orazi & Reggiani
2020), so the projection direction d_P (Eq. 6) and the gap d_G (Eq. 7) vary
continuously from triangle to triangle, as face normals do not. The algebra
of one triangle is in ``_vertex_normal``, the checks, orientation, adjacency
and (angle-weighted) vertex normals in ``_mesh``, the numpy search for the
triangle whose vertex-normal prism holds each point (the walk, the nearest
centroids, the edge rule beyond the mesh's edge) in ``_search``; this module
holds the surface, remembers its calls for warm starts and runs the compiled walk.

Paths (vectorised over points):

- Compiled (the default): ``_walk_jit.project`` does, per point in
  one numba loop, the start, the walk below and the evaluation, for every
  point the walk places (a prism holds it at its nearest root); the rest
  (cold starts the kd-tree seeds, far jumps, lost walks, far roots, points
  beyond the mesh's edge) take the numpy search (``_search``) from the same
  start, and the kernel evaluates them. Same answer as the numpy path to round-off
  (``compiled = False``; ``tests/test_projection_compiled.py``), ~15 us for
  the 80 points of a line instead of ~120 us: a line has ~100 points, so
  the numpy path's cost is its number of array calls, not their size.
- Warm (numpy path): when every point is still inside the triangle it held
  at the remembered call, at the cubic's nearest root,
  ``_vertex_normal.project_warm`` gives the projection in one fused pass.
  ``project(points, derivatives=False)`` leaves out the gradients.

- Start: the triangle each point had at a remembered call with as many
  points that lay nearby (Newton iterations and time steps of one line; up
  to 8 calls are remembered, so lines sharing a seabed keep their own), else
  the nearest centroid (scipy cKDTree). The last h seeds the cubic.
- Walk, nearest centroids and edge rule: ``_search``.
"""
import numpy as np

from cablefem.errors import InputError
from cablefem.geometry import _mesh, _vertex_normal as vn, _walk_jit as walk
from cablefem.geometry._search import PrismSearch
from cablefem.geometry.base import Projection, Seabed

#: calls remembered for warm starts (one per line sharing the seabed)
WARM_STATES = 8


class TriangulatedSurface(PrismSearch, Seabed):
    """Seabed given by vertices (m, 3) [m] and triangles (k, 3) of vertex indices, any winding."""

    kind = "mesh"
    #: project with the compiled walk (``_walk_jit``); False: the numpy search alone
    compiled = True

    def __init__(self, vertices, triangles):
        vertices, triangles = _mesh.checked_arrays(vertices, triangles)
        self.triangles, self.face_normals = _mesh.orient_up(vertices, triangles)
        self.vertices = vertices
        self.neighbours = _mesh.neighbours(self.triangles, len(vertices))
        self.vertex_normals = _mesh.vertex_normals(vertices, self.triangles, self.face_normals)
        self._table = vn.triangle_table(vertices, self.triangles, self.vertex_normals)
        self._rows = np.ascontiguousarray(self._table.T)  # one triangle's data contiguous, for jit
        self._across = np.ascontiguousarray(self.neighbours, dtype=np.int64)
        corners = vertices[self.triangles]
        self._centroids = corners.mean(axis=1)
        self._size = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2).max(axis=1)
        self._warm_table = None  # project_warm's rows, built at the first warm start
        self._walk_surface = None  # the compiled walk's tables, with their SAFE row
        self._typical = float(np.median(self._size))
        # recent calls (points, triangle, held by no prism, h, the rows project_warm gathered,
        # the points component-first): a Newton iteration or time step starts where the previous
        # one of the same line ended (several lines may share a seabed)
        self._states = []

    def locate(self, points):
        """Triangle (n,), barycentric s, t (n,) and height h [m] (n,) of points (n, 3) [m] (Eq. 10).

        Starts from a remembered call with as many points lying nearby (the
        previous Newton iteration or time step of the same line), else cold.
        """
        if self.compiled:  # the compiled walk, the numpy search where it does not place a point
            triangle, sth, _ = self._compiled(points, walk.GAP_ONLY)
            return triangle, sth[0].copy(), sth[1].copy(), sth[2].copy()
        points = _checked(points)
        return self._located(points, *self._recall(points))

    def _located(self, points, state, shift):
        """``locate`` from the remembered call ``state`` (or cold, None), which the points moved
        from by ``shift`` (n,) [m]."""
        if state is None:
            last = None
        else:
            if shift is None:  # _recall saw that no point moved far; which moved little?
                shift = np.abs(points - state[0]).max(axis=1)
            last = (state[1], state[2], state[3], shift <= self._size[state[1]])
        triangle, s, t, h, beyond = self._locate(points, self._table, self._nearest, last, self._below)
        self._remember(state, points, triangle, beyond, h)
        return triangle, s, t, h

    def _remember(self, state, points, triangle, beyond, h, gathered=None, xyz=None):
        """Keep this call (replacing the remembered ``state`` it started from) for the next ones,
        with the triangles' rows the fused path read (``vn.gather``), if it did; ``xyz``: the
        points' own component-first copy (3, n) the compiled path made (then ``points`` is its
        transpose), else the points are copied."""
        call = (points.copy() if xyz is None else points, triangle, beyond, h, gathered, xyz)
        if self._states and self._states[0] is state:  # the usual case: the same line again
            self._states[0] = call
            return
        others = [kept for kept in self._states if kept is not state]
        self._states = [call] + others[:WARM_STATES - 1]

    def reset(self):
        """Forget the remembered calls: the next projection starts cold (as the first one does)."""
        self._states = []

    def _recall(self, points):
        """The remembered call (points, triangle, unheld, h) whose points lie nearest to these
        (n, 3) [m], if on average within a typical triangle size, and how far each point moved
        from it (n,) [m] (largest coordinate change), None when no point moved farther than
        a typical triangle size; (None, None) if there is no such call."""
        same = [state for state in self._states if len(state[0]) == len(points)]
        if not same:
            return None, None
        # the usual case, one line moving a little: no per-point distances needed
        largest, nearest = min((np.abs(points - state[0]).max(), k) for k, state in enumerate(same))
        if largest <= self._typical:
            return same[nearest], None
        chosen, shift = None, np.inf
        for state in same:
            moved = np.abs(points - state[0]).max(axis=1)
            mean = moved.sum() / len(moved)
            if mean < shift:
                chosen, shift, distance = state, mean, moved
        if shift > self._typical:
            return None, None
        return chosen, distance

    def project(self, points, derivatives=True):
        """Projection of points (n, 3) [m] (``Seabed.project``); without ``derivatives`` its
        closest point and gradients may be None (a residual needs only d_G and d_P)."""
        if self.compiled:
            out = self._compiled(points, walk.EVERYTHING if derivatives else walk.GAP_AND_DIRECTION)[2]
            if not derivatives:
                return Projection(out[walk.GAP], out[walk.DIRECTION].T, None, None, None)
            return Projection(out[walk.GAP], out[walk.DIRECTION].T, out[walk.CLOSEST].T, out[walk.GAP_GRADIENT].T,
                              out[walk.DIRECTION_GRADIENT].reshape(3, 3, -1).transpose(2, 0, 1))
        points = _checked(points)
        state, shift = self._recall(points)
        warm = self._warm(points, state, derivatives)
        if warm is not None:
            return Projection(*warm[3:])
        triangle, s, t, h = self._located(points, state, shift)
        return Projection(*vn.evaluate(points, self._table, triangle, s, t, h))

    def gap_only(self, points):
        if self.compiled:
            return self._compiled(points, walk.GAP_ONLY)[2][walk.GAP]
        points = _checked(points)
        state, shift = self._recall(points)
        warm = self._warm(points, state, False)
        if warm is not None:
            return warm[3]
        triangle, s, t, _ = self._located(points, state, shift)
        return vn.gap(points, self._table, triangle, s, t)

    def _compiled(self, points, mode):
        """Triangle (n,), (s, t, h) (3, n) and the packed outputs (19, n) of ``_walk_jit.project``
        (``mode``: what it computes) for points (n, 3) [m], from the remembered call with as
        many points (the nearest, if several) or cold; the points the compiled walk does not
        place take the numpy search (``_locate``, from the same start)."""
        xyz = _checked(points).T.copy()  # component-first, and kept as the next call's start
        points = xyz.T
        n = len(points)
        same = [state for state in self._states if len(state[0]) == n]
        triangle, sth, out = np.empty(n, dtype=np.int64), np.empty((3, n)), np.empty((walk.OUTPUTS, n))
        result = walk.Result(triangle, sth, out)
        surface = self._walk_tables()
        lost = -1
        if len(same) == 1:  # one line on this seabed: the kernel sees whether it moved far
            state = same[0]
            start = walk.Start(*self._walk_from(state, points))
            lost = walk.project(xyz, surface, start, self._typical, True, mode, result)
        if lost < 0:  # several lines, or one that moved far: start as _located does
            state = self._recall(points)[0]
            start = walk.Start(*self._walk_from(state, points))
            lost = walk.project(xyz, surface, start, np.inf, True, mode, result)
        beyond = np.zeros(n, dtype=bool)
        if lost:  # the numpy search from the same start, for the points the walk left
            rows = np.flatnonzero(triangle < 0)
            last = None
            if state is not None:
                moved = np.abs(points[rows] - state[0][rows]).max(axis=1)
                last = (state[1][rows], state[2][rows], state[3][rows], moved <= self._size[state[1][rows]])
            found = self._locate(points[rows], self._table, self._nearest, last, self._below)
            triangle[rows], sth[0, rows], sth[1, rows], sth[2, rows], beyond[rows] = found
            walk.project(xyz, surface, start, np.inf, False, mode, result)
        self._remember(state, points, triangle, beyond, sth[2], xyz=xyz)
        return triangle, sth, out

    def walk_start(self, points):
        """What a compiled caller running ``_walk_jit.project`` itself needs for points (n, 3) [m]
        (``cablefem.compiled.steps``): the surface's tables (a ``_walk_jit.Surface``), its typical triangle
        size [m] and the warm start of the remembered call nearest to them (a ``_walk_jit.Start``:
        origin (3, n), triangles (n,), heights (n,), unheld (n,)), or a cold start from the nearest
        centroids. ``walk_end`` hands the last call back."""
        points = _checked(points)
        origin, triangle, h, unheld = self._walk_from(self._recall(points)[0], points)
        # copies: the caller's walk moves them on
        start = walk.Start(np.array(origin, dtype=float), np.array(triangle, dtype=np.int64),
                           np.array(h, dtype=float), np.array(unheld, dtype=bool))
        return self._walk_tables(), self._typical, start

    def _walk_from(self, state, points):
        """Where the compiled walk starts for points (n, 3) [m], the fields of a ``_walk_jit.Start``:
        origin (3, n), triangles (n,), heights (n,) and unheld (n,) of the remembered call
        ``state``, or, without one, cold from the nearest centroids with no height to start from."""
        if state is None:
            n = len(points)
            return (points.T, np.ascontiguousarray(self._nearest(points, 1)[:, 0]), np.full(n, np.nan),
                    np.zeros(n, dtype=bool))
        return _component_first(state), state[1], state[3], state[2]

    def _walk_tables(self):
        """The surface as the compiled walk reads it, a ``_walk_jit.Surface`` (the warm table's SAFE row
        made contiguous); built once."""
        if self._walk_surface is None:
            safe = np.ascontiguousarray(self._warm_tables()[vn.W_SAFE])
            self._walk_surface = walk.Surface(self._rows, self._across, safe, self._size)
        return self._walk_surface

    def walk_end(self, start):
        """Remember a compiled caller's last call: the ``_walk_jit.Start`` its walk moved on to
        (points (3, n) [m], their triangles (n,) and heights (n,) [m]), every point held (see
        ``walk_start``)."""
        xyz = np.array(start.origin, dtype=float)
        points = xyz.T
        self._remember(self._recall(points)[0], points, np.array(start.triangle), np.zeros(len(points), dtype=bool),
                       np.array(start.h, dtype=float), xyz=xyz)

    def _warm(self, points, state, derivatives):
        """``vn.project_warm`` of points (n, 3) [m] from the remembered call ``state``, kept as
        the next start when every point is still in its triangle; None otherwise."""
        if state is None:
            return None
        gathered = state[4]
        if gathered is None:  # the triangles changed since the fused path last read them
            gathered = vn.gather(self._table, self._warm_tables(), state[1])
        warm = vn.project_warm(points, gathered, state[3], derivatives)
        if warm is not None:
            self._remember(state, points, state[1], np.zeros(len(points), dtype=bool), warm[2], gathered)
        return warm

    def _warm_tables(self):
        """``vn.warm_table`` of this surface (32, k), built at the first warm start."""
        if self._warm_table is None:
            self._warm_table = vn.warm_table(self._table)
        return self._warm_table

    def elevation(self, xy):
        """Elevation z [m] (n,) of the triangulated surface below xy (n, 2) [m]; clamped beyond its edge."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        points = np.column_stack([xy, np.zeros(len(xy))])
        triangle, s, t, _, beyond = self._locate(points, self._vertical(), self._nearest_xy, None,
                                                 self._edge_triangle)
        lam = np.stack([1.0 - s - t, s, t])
        z = np.einsum("mi,im->m", self.vertices[self.triangles[triangle], 2], lam)
        if beyond.any():  # flat beyond the edge, at the nearest boundary point's elevation
            z[beyond] = self._nearest_edge(points[beyond])[1]
        return z

    def surface(self, bounds=None):
        """Vertices (m, 3) [m] and up-wound triangles (k, 3) of the faces that reach into
        bounds ((xmin, xmax), (ymin, ymax)) [m], all of them without bounds."""
        if bounds is None:
            return self.vertices.copy(), self.triangles.copy()
        (x0, x1), (y0, y1) = bounds
        corners = self.vertices[self.triangles]
        low, high = corners.min(axis=1), corners.max(axis=1)
        keep = (high[:, 0] >= x0) & (low[:, 0] <= x1) & (high[:, 1] >= y0) & (low[:, 1] <= y1)
        used, triangles = np.unique(self.triangles[keep], return_inverse=True)
        return self.vertices[used], triangles.reshape(-1, 3)

    def describe(self):
        low, high = self.vertices.min(axis=0), self.vertices.max(axis=0)
        return (f"triangulated surface, {len(self.vertices)} vertices, {len(self.triangles)} triangles, "
                f"x [{low[0]:g}, {high[0]:g}] y [{low[1]:g}, {high[1]:g}] z [{low[2]:g}, {high[2]:g}] m, "
                "vertex-normal projection")


def _component_first(state):
    """The points (3, n) [m] of a remembered call, C-contiguous."""
    return np.ascontiguousarray(state[0].T) if state[5] is None else state[5]


def _checked(points):
    """Points as a float array (n, 3) [m], or an InputError."""
    points = np.asarray(points, dtype=float)
    if points.ndim != 2 or points.shape[1] != 3:
        raise InputError(f"points must have shape (n, 3), got {points.shape}", key="points")
    return points
