"""Triangulated seabed with the continuous vertex-normal projection (desire2023 Sec. 2.2.2.2, Eq. 6, 7, 10).

The surface is the piecewise-linear triangulation itself; points are projected
along the vertex normals interpolated over each triangle (Orazi & Reggiani
2020), so the projection direction d_P (Eq. 6) and the gap d_G (Eq. 7) vary
continuously from triangle to triangle, as face normals do not. The algebra
of one triangle is in ``_vertex_normal``, the checks, orientation, adjacency
and (angle-weighted) vertex normals in ``_mesh``; this module finds, for
each point, the triangle whose vertex-normal prism holds it.

Search (no per-node sorted list as in desire2023; vectorised over points):

- Compiled (the default): ``_vertex_normal_jit.project`` does, per point in
  one numba loop, the start, the walk below and the evaluation, for every
  point the walk places (a prism holds it at its nearest root); the rest
  (cold starts the kd-tree seeds, far jumps, lost walks, far roots, points
  beyond the mesh's edge) take the numpy search below from the same start,
  and the kernel evaluates them. Same answer as the numpy path to round-off
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
- Walk to the neighbour across the most violated edge, at most 8 steps; then
  the 8 nearest centroids, all at once. The first prism that holds the point
  is kept (within the focal distance of the surface's curvature the
  vertex-normal prisms do not overlap, so it is the only one); within it the
  real root of smallest |h|.
- Edge rule: a point no prism holds (beyond the mesh's edge, or far above
  ground so rough that the prisms cross) takes the triangle below it in
  plan, or beyond the edge the triangle of the nearest boundary edge in
  plan; that triangle's vertex-normal coordinates are clamped onto it
  (negative N_i dropped, the rest renormalised) and the surface goes on as
  the tangent plane there: d_P = n(s_c, t_c) / |n|, d_G = (p - P(s_c, t_c)) . d_P.
  Continuous where a prism is left, exact on a plane, derivatives exact; it
  is an extrapolation, poor more than a few triangles beyond the edge of a
  rough mesh, and d_P jumps where the nearest boundary edge changes.
  ``elevation`` is flat beyond the edge, at the nearest boundary point's z,
  as ``DepthGrid`` clamps.
"""

import numpy as np
from scipy.spatial import ConvexHull, cKDTree

from ..errors import InputError
from . import _mesh, _vertex_normal as vn, _vertex_normal_jit as jit
from .base import Projection, Seabed

#: walk steps from the start triangle, and nearest centroids tried after them
WALK_STEPS = 8
NEAREST_CANDIDATES = 8
#: a point held by no prism (far above rough ground, where the prisms cross) that is still
#: more than FAR x its triangle's longest edge away at the next call skips the search
FAR = 3.0
#: calls remembered for warm starts (one per line sharing the seabed)
WARM_STATES = 8


class TriangulatedSurface(Seabed):
    """Seabed given by vertices (m, 3) [m] and triangles (k, 3) of vertex indices, any winding."""

    kind = "mesh"
    #: project with the compiled walk (``_vertex_normal_jit``); False: the numpy search alone
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
        self._tree = None
        self._tree_xy = None
        self._vertical_table = None
        self._warm_table = None  # project_warm's rows, built at the first warm start
        self._safe = None  # their SAFE row, for the compiled path
        self._convex = None
        self._edges = self._edge_tree = None
        self._typical = float(np.median(self._size))
        # recent calls (points, triangle, held by no prism, h, the rows project_warm gathered,
        # the points component-first): a Newton iteration or time step starts where the previous
        # one of the same line ended (several lines may share a seabed)
        self._states = []

    @property
    def convex_footprint(self):
        """Whether the plan view of the mesh is convex (as a Delaunay triangulation's is)."""
        if self._convex is None:
            corner = self.vertices[self.triangles][:, :, :2]
            u, w = corner[:, 1] - corner[:, 0], corner[:, 2] - corner[:, 0]
            area = 0.5 * np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]).sum()
            hull = ConvexHull(self.vertices[np.unique(self.triangles), :2]).volume
            self._convex = bool(abs(hull - area) <= 1e-9 * hull)
        return self._convex

    def _nearest(self, points, k):
        """Indices (n, k) of the k triangles whose centroids are nearest to points (n, 3) [m]."""
        if self._tree is None:
            self._tree = cKDTree(self._centroids)
        _, index = self._tree.query(points, k=min(k, len(self.triangles)))
        return index.reshape(len(points), -1)

    def _nearest_xy(self, points, k):
        """Indices (n, k) of the k triangles whose centroids are nearest in plan to points (n, 3) [m]."""
        if self._tree_xy is None:
            self._tree_xy = cKDTree(self._centroids[:, :2])
        _, index = self._tree_xy.query(points[:, :2], k=min(k, len(self.triangles)))
        return index.reshape(len(points), -1)

    def _locate(self, points, table, nearest, last, fallback):
        """Triangle (n,), s, t, h (n,) and whether no prism holds the point (n,), for points (n, 3) [m].

        Starts from ``last`` (triangle, unheld, h, barely moved, each (n,), of
        a previous call) or the nearest centroid and walks to the neighbour
        across the most violated edge until a prism holds the point. A walk
        that stops at the mesh's edge (a violated edge without neighbour where
        it cannot go on, convex footprint), or a point that was unheld last
        time and is still beyond the edge in plan or FAR away, goes to
        ``fallback(points, start) -> triangles``; the rest try the 8 nearest
        centroids first.
        """
        n = len(points)
        if last is None:
            current = nearest(points, 1)[:, 0]
        else:  # a point that moved farther than its triangle is large starts afresh
            current = last[0].copy()
            moved = np.flatnonzero(~last[3])
            if len(moved):
                current[moved] = nearest(points[moved], 1)[:, 0]
        # most points stay in their triangle between calls, near their last h
        first = vn.solve(points, table, current, None if last is None else last[2])
        if (first[3] & first[5]).all():
            return current, first[0], first[1], first[2], np.zeros(n, dtype=bool)
        found, previous = current.copy(), np.full(n, -1)
        s, t, h = first[0].copy(), first[1].copy(), first[2].copy()
        held, redirect = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
        # a prism that holds a point only at a far root of its cubic (its near root is
        # outside) is kept as a candidate while nearer prisms are looked for
        candidate = np.full(n, -1)
        far_s, far_t, far_h = np.zeros(n), np.zeros(n), np.zeros(n)

        def take(rows, triangles, si, ti, hi, near, far):
            found[rows[near]], s[rows[near]], t[rows[near]], h[rows[near]] = (
                triangles[near], si[near], ti[near], hi[near])
            held[rows[near]] = True
            far = far & (candidate[rows] < 0)
            candidate[rows[far]], far_s[rows[far]], far_t[rows[far]], far_h[rows[far]] = (
                triangles[far], si[far], ti[far], hi[far])

        todo, result = np.arange(n), first
        for step in range(WALK_STEPS + 1):
            si, ti, hi, inside, lam, smallest = result
            tried = current[todo]
            take(todo, tried, si, ti, hi, inside & smallest, inside & ~smallest)
            inside &= smallest
            across = self.neighbours[tried]  # (m, 3)
            ahead = across[np.arange(len(todo)), np.argmin(lam, axis=1)]
            back = ahead == previous[todo]  # a walk that turns back circles a corner
            edge = ~inside & ((lam < -vn.INSIDE_TOLERANCE) & (across < 0)).any(axis=1)
            # convex: no other part of the mesh lies beyond a boundary edge
            stop = edge & ((ahead < 0) | back) & self.convex_footprint
            if step == 0 and last is not None:  # held by no prism last time, and still not
                unheld = ~inside & last[1] & last[3]
                far = unheld & (np.abs(hi) > FAR * self._size[current])
                stop |= far | self._still_beyond(points, current, unheld & ~far)
            redirect[todo[stop]] = True
            walking = ~inside & ~stop & (ahead >= 0) & ~back
            if step == WALK_STEPS or not walking.any():
                break
            todo = todo[walking]
            previous[todo] = current[todo]
            current[todo] = ahead[walking]
            result = vn.solve(points[todo], table, current[todo])
        lost = np.flatnonzero(~held & ~redirect)
        if len(lost):  # the nearest centroids, all in one block (k, lost)
            candidates = nearest(points[lost], NEAREST_CANDIDATES).T
            rows = np.broadcast_to(lost, candidates.shape).ravel()
            si, ti, hi, inside, _, smallest = vn.solve(points[rows], table, candidates.ravel())
            near, far = (x.reshape(candidates.shape) for x in (inside & smallest, inside & ~smallest))
            cols = np.arange(len(lost))
            for hits, is_near in ((near, True), (far, False)):  # the nearest centroid that holds it
                pick = np.argmax(hits, axis=0)
                flat = np.ravel_multi_index((pick, cols), candidates.shape)
                ok = hits[pick, cols]
                take(lost, candidates.ravel()[flat], si[flat], ti[flat], hi[flat], ok & is_near, ok & ~is_near)
        rest = np.flatnonzero(~held & (candidate >= 0))
        found[rest], s[rest], t[rest], h[rest] = candidate[rest], far_s[rest], far_t[rest], far_h[rest]
        unheld = ~held & (candidate < 0)
        rest = np.flatnonzero(unheld)
        if len(rest):  # no prism holds them: the fallback's triangle, its map continued
            found[rest] = fallback(points[rest], current[rest])
            s[rest], t[rest], h[rest] = vn.solve(points[rest], table, found[rest])[:3]
        return found, s, t, h, unheld

    def _still_beyond(self, points, triangle, candidates):
        """Which of the points (n, 3) [m] marked by candidates (n,) lie in plan beyond a
        boundary edge of their triangles (n,): they keep their edge-rule triangle."""
        rows = np.flatnonzero(candidates)
        if len(rows) == 0:
            return candidates
        lam = vn.solve(points[rows], self._vertical(), triangle[rows])[4]
        across = self.neighbours[triangle[rows]]
        still = candidates.copy()
        still[rows] = ((lam < -vn.INSIDE_TOLERANCE) & (across < 0)).any(axis=1)
        return still

    def locate(self, points):
        """Triangle (n,), barycentric s, t (n,) and height h [m] (n,) of points (n, 3) [m] (Eq. 10).

        Starts from a remembered call with as many points lying nearby (the
        previous Newton iteration or time step of the same line), else cold.
        """
        if self.compiled:  # the compiled walk, the numpy search where it does not place a point
            triangle, sth, _ = self._compiled(points, jit.GAP_ONLY)
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
            out = self._compiled(points, jit.EVERYTHING if derivatives else jit.GAP_AND_DIRECTION)[2]
            if not derivatives:
                return Projection(out[jit.GAP], out[jit.DIRECTION].T, None, None, None)
            return Projection(out[jit.GAP], out[jit.DIRECTION].T, out[jit.CLOSEST].T, out[jit.GAP_GRADIENT].T,
                              out[jit.DIRECTION_GRADIENT].reshape(3, 3, -1).transpose(2, 0, 1))
        points = _checked(points)
        state, shift = self._recall(points)
        warm = self._warm(points, state, derivatives)
        if warm is not None:
            return Projection(*warm[3:])
        triangle, s, t, h = self._located(points, state, shift)
        return Projection(*vn.evaluate(points, self._table, triangle, s, t, h))

    def gap_only(self, points):
        if self.compiled:
            return self._compiled(points, jit.GAP_ONLY)[2][jit.GAP]
        points = _checked(points)
        state, shift = self._recall(points)
        warm = self._warm(points, state, False)
        if warm is not None:
            return warm[3]
        triangle, s, t, _ = self._located(points, state, shift)
        return vn.gap(points, self._table, triangle, s, t)

    def _compiled(self, points, mode):
        """Triangle (n,), (s, t, h) (3, n) and the packed outputs (19, n) of ``jit.project``
        (``mode``: what it computes) for points (n, 3) [m], from the remembered call with as
        many points (the nearest, if several) or cold; the points the compiled walk does not
        place take the numpy search (``_locate``, from the same start)."""
        xyz = _checked(points).T.copy()  # component-first, and kept as the next call's start
        points = xyz.T
        n = len(points)
        same = [state for state in self._states if len(state[0]) == n]
        triangle, sth, out = np.empty(n, dtype=np.int64), np.empty((3, n)), np.empty((jit.OUTPUTS, n))
        safe = self._safe_radii()
        lost = -1
        if len(same) == 1:  # one line on this seabed: the kernel sees whether it moved far
            state = same[0]
            origin, start, unheld, start_h = self._walk_from(state, points)
            lost = jit.project(xyz, origin, start, start_h, unheld, self._rows, self._across, safe,
                               self._size, self._typical, WALK_STEPS, True, mode, triangle, sth, out)
        if lost < 0:  # several lines, or one that moved far: start as _located does
            state = self._recall(points)[0]
            origin, start, unheld, start_h = self._walk_from(state, points)
            lost = jit.project(xyz, origin, start, start_h, unheld, self._rows, self._across, safe,
                               self._size, np.inf, WALK_STEPS, True, mode, triangle, sth, out)
        beyond = np.zeros(n, dtype=bool)
        if lost:  # the numpy search from the same start, for the points the walk left
            rows = np.flatnonzero(triangle < 0)
            last = None
            if state is not None:
                moved = np.abs(points[rows] - state[0][rows]).max(axis=1)
                last = (state[1][rows], state[2][rows], state[3][rows], moved <= self._size[state[1][rows]])
            found = self._locate(points[rows], self._table, self._nearest, last, self._below)
            triangle[rows], sth[0, rows], sth[1, rows], sth[2, rows], beyond[rows] = found
            jit.project(xyz, origin, start, start_h, unheld, self._rows, self._across, safe,
                        self._size, np.inf, WALK_STEPS, False, mode, triangle, sth, out)
        self._remember(state, points, triangle, beyond, sth[2], xyz=xyz)
        return triangle, sth, out

    def walk_start(self, points):
        """What a compiled caller running ``_vertex_normal_jit.project`` itself needs for points
        (n, 3) [m] (``cablefem.march``): the surface's tables (rows, neighbours, safe radii,
        triangle sizes, typical size) and the warm start of the remembered call nearest to them
        (origin (3, n), start triangles (n,), unheld (n,), heights (n,)), or a cold start from
        the nearest centroids. ``walk_end`` hands the last call back."""
        points = _checked(points)
        origin, start, unheld, start_h = self._walk_from(self._recall(points)[0], points)
        # copies: the caller's walk moves them on
        warm = (np.array(origin, dtype=float), np.array(start, dtype=np.int64), np.array(unheld, dtype=bool),
                np.array(start_h, dtype=float))
        return (self._rows, self._across, self._safe_radii(), self._size, self._typical) + warm

    def _walk_from(self, state, points):
        """Where the compiled walk starts for points (n, 3) [m]: origin (3, n), triangles (n,),
        unheld (n,) and heights (n,) of the remembered call ``state``, or, without one, cold from
        the nearest centroids with no height to start from."""
        if state is None:
            n = len(points)
            return points.T, self._nearest(points, 1)[:, 0], np.zeros(n, dtype=bool), np.full(n, np.nan)
        return _component_first(state), state[1], state[2], state[3]

    def _safe_radii(self):
        """The warm table's SAFE row (k,), contiguous, for the compiled walk; built once."""
        if self._safe is None:
            self._safe = np.ascontiguousarray(self._warm_tables()[vn.W_SAFE])
        return self._safe

    def walk_end(self, xyz, triangle, h):
        """Remember a compiled caller's last call: points xyz (3, n) [m] found in ``triangle``
        (n,) at heights h (n,) [m], every point held (see ``walk_start``)."""
        xyz = np.array(xyz, dtype=float)
        points = xyz.T
        self._remember(self._recall(points)[0], points, np.array(triangle), np.zeros(len(points), dtype=bool),
                       np.array(h, dtype=float), xyz=xyz)

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

    def _below(self, points, start=None):
        """Triangle (n,) below points (n, 3) [m] in plan, or the nearest one beyond the mesh's edge.

        Unique (but on shared edges): the vertical prisms do not overlap.
        """
        last = None if start is None else (start, np.zeros(len(start), dtype=bool), np.zeros(len(start)),
                                           np.zeros(len(start), dtype=bool))
        return self._locate(points, self._vertical(), self._nearest_xy, last, self._edge_triangle)[0]

    def _edge_triangle(self, points, start=None):
        """Triangle (n,) of the boundary edge nearest in plan to points (n, 3) [m] (the edge rule)."""
        return self._nearest_edge(points)[0]

    def _nearest_edge(self, points):
        """Triangle (n,) and elevation z [m] (n,) of the nearest point in plan on the mesh's
        boundary, for points (n, 3) [m]."""
        if self._edges is None:
            triangle, corner = np.nonzero(self.neighbours < 0)
            ends = self.vertices[self.triangles[triangle[:, None], (corner[:, None] + [1, 2]) % 3]]
            self._edges = (triangle, ends)
            self._edge_tree = cKDTree(ends[:, :, :2].mean(axis=1))
        triangle, ends = self._edges
        _, index = self._edge_tree.query(points[:, :2], k=min(NEAREST_CANDIDATES, len(triangle)))
        index = index.reshape(len(points), -1)
        a, b = ends[index, 0], ends[index, 1]  # (n, k, 3)
        ab, ap = (b - a)[..., :2], points[:, None, :2] - a[..., :2]
        along = np.clip(np.einsum("nkc,nkc->nk", ap, ab) / np.einsum("nkc,nkc->nk", ab, ab), 0.0, 1.0)
        distance = np.linalg.norm(ap - along[:, :, None] * ab, axis=2)
        # beyond a corner both edges end nearest at the corner: take the one whose line is farther
        line = np.abs(ab[..., 0] * ap[..., 1] - ab[..., 1] * ap[..., 0]) / np.linalg.norm(ab, axis=2)
        pick = np.argmin(distance - 1e-9 * line, axis=1)
        rows = np.arange(len(points))
        z = a[rows, pick, 2] + along[rows, pick] * (b[rows, pick, 2] - a[rows, pick, 2])
        return triangle[index[rows, pick]], z

    def _vertical(self):
        """The triangle table with vertical normals: projection straight down, for elevations."""
        if self._vertical_table is None:
            up = np.tile([0.0, 0.0, 1.0], (len(self.vertices), 1))
            self._vertical_table = vn.triangle_table(self.vertices, self.triangles, up)
        return self._vertical_table

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
