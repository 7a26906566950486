"""The numpy search of a triangulated surface: the triangle whose vertex-normal prism holds each point
(desire2023 Sec. 2.2.2.2, Eq. 10; no per-node sorted list as in desire2023; vectorised over points).

``TriangulatedSurface`` derives from ``PrismSearch``; its compiled walk
(``_walk_jit``) leaves here the points it does not place, and the
``compiled = False`` path and ``elevation`` search here alone.

- Start: the triangle each point had at a remembered call (``TriangulatedSurface``
  keeps them), else the nearest centroid (scipy cKDTree). The last h seeds the cubic.
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

The triangle below a point in plan is the same search on the table with vertical normals.
"""

import numpy as np

from cablefem.geometry import _vertex_normal as vn

#: walk steps from the start triangle, and nearest centroids tried after them
WALK_STEPS = 8
NEAREST_CANDIDATES = 8
#: a point held by no prism (far above rough ground, where the prisms cross) that is still
#: more than FAR x its triangle's longest edge away at the next call skips the search
FAR = 3.0


class PrismSearch:
    """The search of ``TriangulatedSurface``, its base: reads its ``vertices`` (m, 3) [m], up-wound
    ``triangles`` (k, 3), ``neighbours`` (k, 3), ``_centroids`` (k, 3) [m] and longest edges
    ``_size`` (k,) [m]; builds its kd-trees, vertical table and boundary edges on first use."""

    _convex = _tree = _tree_xy = _vertical_table = _edges = _edge_tree = None

    @property
    def convex_footprint(self):
        """Whether the plan view of the mesh is convex (as a Delaunay triangulation's is)."""
        if self._convex is None:
            corner = self.vertices[self.triangles][:, :, :2]
            u, w = corner[:, 1] - corner[:, 0], corner[:, 2] - corner[:, 0]
            area = 0.5 * np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]).sum()
            from scipy.spatial import ConvexHull  # here, not at import: ~0.07 s of start-up

            hull = ConvexHull(self.vertices[np.unique(self.triangles), :2]).volume
            self._convex = bool(abs(hull - area) <= 1e-9 * hull)
        return self._convex

    def _nearest(self, points, k):
        """Indices (n, k) of the k triangles whose centroids are nearest to points (n, 3) [m]."""
        if self._tree is None:
            from scipy.spatial import cKDTree  # on first use: a run on a plane never needs it

            self._tree = cKDTree(self._centroids)
        _, index = self._tree.query(points, k=min(k, len(self.triangles)))
        return index.reshape(len(points), -1)

    def _nearest_xy(self, points, k):
        """Indices (n, k) of the k triangles whose centroids are nearest in plan to points (n, 3) [m]."""
        if self._tree_xy is None:
            from scipy.spatial import cKDTree

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
        found = _Found(current, first)
        redirect = self._walk(points, table, last, current, first, found)
        lost = np.flatnonzero(~found.held & ~redirect)
        if len(lost):  # the nearest centroids, all in one block (k, lost)
            _try_centroids(points, table, nearest(points[lost], NEAREST_CANDIDATES).T, lost, found)
        return found.settled(points, table, fallback, current)

    def _walk(self, points, table, last, current, result, found):
        """``_locate``'s walk from the triangles ``current`` (n,) (moved on in place) and their
        ``vn.solve`` ``result``: to the neighbour across the most violated edge, at most WALK_STEPS
        steps, each prism that holds a point kept in ``found``. Returns which points (n,) go to
        the fallback (stopped at the edge of a convex footprint; unheld at ``last``, still so and
        beyond the edge in plan or FAR away)."""
        n = len(points)
        previous, redirect = np.full(n, -1), np.zeros(n, dtype=bool)
        todo = np.arange(n)
        for step in range(WALK_STEPS + 1):
            si, ti, hi, inside, lam, smallest = result
            tried = current[todo]
            found.take(todo, tried, si, ti, hi, inside & smallest, inside & ~smallest)
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
        return redirect

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
            from scipy.spatial import cKDTree

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


class _Found:
    """What ``_locate`` holds for each of n points: its triangle, s, t, h (n,), whether a prism
    holds it at its nearest root (n,), and a candidate prism that holds it at a far root only
    (its near root is outside: kept while nearer prisms are looked for), -1 if none, with its
    s, t, h (n,)."""

    def __init__(self, current, first):
        n = len(current)
        self.triangle, self.s, self.t, self.h = current.copy(), first[0].copy(), first[1].copy(), first[2].copy()
        self.held = np.zeros(n, dtype=bool)
        self.candidate = np.full(n, -1)
        self.far_s, self.far_t, self.far_h = np.zeros(n), np.zeros(n), np.zeros(n)

    def take(self, rows, triangles, si, ti, hi, near, far):
        """Keep the triangles (m,) and s, t, h (m,) found for the points ``rows`` (m,): where their
        prism holds them at the nearest root (``near`` (m,)), and as candidates where at a far
        one (``far`` (m,)) if they have none yet."""
        self.triangle[rows[near]], self.s[rows[near]], self.t[rows[near]], self.h[rows[near]] = (
            triangles[near], si[near], ti[near], hi[near])
        self.held[rows[near]] = True
        far = far & (self.candidate[rows] < 0)
        self.candidate[rows[far]], self.far_s[rows[far]], self.far_t[rows[far]], self.far_h[rows[far]] = (
            triangles[far], si[far], ti[far], hi[far])

    def settled(self, points, table, fallback, current):
        """``_locate``'s answer for points (n, 3) [m]: the points held nowhere at a nearest root take
        their candidate, those without one ``fallback``'s triangle (from ``current`` (n,)), its
        map continued; triangle, s, t, h and whether no prism holds the point (n,)."""
        held, candidate = self.held, self.candidate
        rest = np.flatnonzero(~held & (candidate >= 0))
        self.triangle[rest], self.s[rest], self.t[rest], self.h[rest] = (
            candidate[rest], self.far_s[rest], self.far_t[rest], self.far_h[rest])
        unheld = ~held & (candidate < 0)
        rest = np.flatnonzero(unheld)
        if len(rest):  # no prism holds them: the fallback's triangle, its map continued
            self.triangle[rest] = fallback(points[rest], current[rest])
            self.s[rest], self.t[rest], self.h[rest] = vn.solve(points[rest], table, self.triangle[rest])[:3]
        return self.triangle, self.s, self.t, self.h, unheld


def _try_centroids(points, table, candidates, lost, found):
    """For the points (n, 3) [m] ``lost`` (m,) by the walk, the first of their nearest centroids'
    triangles ``candidates`` (k, m) whose prism holds each, at its nearest root, else at a far
    one, into ``found`` (a ``_Found``); all in one block."""
    rows = np.broadcast_to(lost, candidates.shape).ravel()
    si, ti, hi, inside, _, smallest = vn.solve(points[rows], table, candidates.ravel())
    near, far = (x.reshape(candidates.shape) for x in (inside & smallest, inside & ~smallest))
    cols = np.arange(len(lost))
    for hits, is_near in ((near, True), (far, False)):  # the nearest centroid that holds it
        pick = np.argmax(hits, axis=0)
        flat = np.ravel_multi_index((pick, cols), candidates.shape)
        ok = hits[pick, cols]
        found.take(lost, candidates.ravel()[flat], si[flat], ti[flat], hi[flat], ok & is_near, ok & ~is_near)
