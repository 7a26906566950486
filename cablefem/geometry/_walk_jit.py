"""The compiled walk of a triangulated surface: locate and project a line's points in one numba loop
(desire2023 Sec. 2.2.2.2, Eq. 6, 7, 10).

``project`` does per point what the numpy search of ``_search`` does for
all at once: from each point's start triangle (its triangle at the
remembered call, or the nearest centroid) ``_vertex_normal_jit.solve`` and
the walk to the neighbour across the most violated edge (at most
``WALK_STEPS`` steps) until a prism holds the point at its nearest root,
then ``_vertex_normal_jit.evaluate`` for every point. ``TriangulatedSurface``
calls it for its compiled path and hands its tables and warm start to
``cablefem.compiled.steps``, which calls it inside the compiled steps.

A point the walk does not place (held by no prism within the walk, or by a
prism only at a far root, beyond the mesh's edge at the last call, moved
farther than its triangle is large, or a cubic Halley does not settle) is
reported, and ``TriangulatedSurface`` places it with the numpy search.

``project`` takes its arrays in three named tuples, ``Surface``, ``Start``
and ``Result`` (``cablefem.compiled.steps`` nests them in its ``Projector``); what it
computes (``mode``) and the rows of its packed outputs are
``_vertex_normal_jit``'s, named here too for its callers.
"""

from collections import namedtuple

import numpy as np
from numba import njit

from cablefem.geometry._search import WALK_STEPS
from cablefem.geometry._vertex_normal_jit import (CLOSEST, DIRECTION, DIRECTION_GRADIENT, EVERYTHING, GAP,
    GAP_AND_DIRECTION, GAP_GRADIENT, GAP_ONLY, JIT, OUTPUTS, evaluate, is_inside, solve)

__all__ = ["CLOSEST", "DIRECTION", "DIRECTION_GRADIENT", "EVERYTHING", "GAP", "GAP_AND_DIRECTION", "GAP_GRADIENT",
           "GAP_ONLY", "OUTPUTS", "Result", "Start", "Surface", "project"]

#: ``project``'s arguments. The surface: ``triangle_table``'s rows (k, 30), the neighbour across
#: each edge (k, 3) (-1: none), ``warm_table``'s SAFE heights (k,) [m], the longest edges (k,) [m]
Surface = namedtuple("Surface", "rows neighbours safe size")
#: where the walk starts: the previous call's points (3, n) [m], their triangles (n,) (-1: none),
#: heights (n,) [m] (NaN: none) and whether no prism held them (n,)
Start = namedtuple("Start", "origin triangle h unheld")
#: what it finds and computes: triangles (n,) (-1: not placed), s, t, h (3, n), the packed outputs (19, n)
Result = namedtuple("Result", "triangle sth out")


@njit(inline="always", **JIT)
def _moved_beyond(xyz, origin, typical):
    """Whether a point of xyz (3, n) [m] moved farther than ``typical`` [m] in a coordinate from
    origin (3, n) [m] (or is NaN)."""
    for i in range(xyz.shape[1]):
        for c in range(3):
            if not abs(xyz[c, i] - origin[c, i]) <= typical:
                return True
    return False


@njit(inline="always", **JIT)
def _most_violated(s, t):
    """The edge (0, 1, 2: opposite the vertex of N_0 = 1 - s - t, N_1 = s, N_2 = t) across which
    the walk goes on: np.argmin of the N_i, the first NaN, else the first smallest."""
    lam0, lam1, lam2 = 1.0 - s - t, s, t
    if np.isnan(lam0):
        return 0
    if np.isnan(lam1):
        return 1
    if np.isnan(lam2):
        return 2
    k = 0
    if lam1 < lam0:
        k = 1
    if lam2 < (lam1 if k == 1 else lam0):
        k = 2
    return k


@njit(**JIT)
def project(xyz, surface, start, typical, search, mode, result):
    """Locate points xyz (3, n) [m] on ``surface`` (a ``Surface``) from the ``Start`` of a previous
    call, walking at most ``WALK_STEPS`` steps (a constant of the compiled loop), and evaluate them into
    ``result.out`` (19, n). Its Python and compiled callers pass the same types (the named tuples):
    numba compiles it once for both, where plain tuples from Python (0.5 us less to unbox each)
    compiled it twice (2.5 s more of a first run).

    With ``search``, writes each point's triangle (or -1: not placed, see the module docstring;
    also for points ``start.unheld`` or that moved farther than ``surface.size`` [m] of their
    triangle) into ``result.triangle`` (n,) and s, t, h into ``result.sth`` (3, n), and evaluates
    only if every point was placed; without, evaluates the given ``result.triangle`` and
    ``result.sth``. ``mode``: GAP_ONLY, GAP_AND_DIRECTION or EVERYTHING. Returns the number of
    points not placed, or -1 (and does nothing) if a point moved farther than ``typical`` [m]
    from ``start.origin``: then ``TriangulatedSurface._recall`` chooses where to start.
    """
    rows, neighbours, safe, size = surface
    origin, start_triangle, start_h, unheld = start
    triangle, sth, out = result
    n = xyz.shape[1]
    lost = 0
    if search:
        if _moved_beyond(xyz, origin, typical):  # not _recall's usual case
            return -1
        for i in range(n):
            x0, x1, x2 = xyz[0, i], xyz[1, i], xyz[2, i]
            current = start_triangle[i]
            found = -1
            moved = max(abs(x0 - origin[0, i]), abs(x1 - origin[1, i]), abs(x2 - origin[2, i]))
            if current >= 0 and not unheld[i] and moved <= size[current]:
                # the numpy search's walk (_search): to the neighbour across the most violated
                # edge until a prism holds the point at its nearest root (written out here:
                # as a function of its own it ran three times slower)
                previous, guess = -1, start_h[i]
                for step in range(WALK_STEPS + 1):
                    s, t, h, inside, smallest, ok = solve(x0, x1, x2, rows, current, guess, safe[current])
                    if not ok:
                        break
                    if inside and smallest:
                        found = current
                        sth[0, i], sth[1, i], sth[2, i] = s, t, h
                        break
                    ahead = neighbours[current, _most_violated(s, t)]
                    # ahead < 0: the mesh's edge (the numpy search redirects it or searches);
                    # back: the walk circles a corner; the last step: lost (the numpy search
                    # tries the nearest centroids); a far root: the numpy search weighs it
                    if ahead < 0 or ahead == previous or step == WALK_STEPS:
                        break
                    previous, current, guess = current, ahead, np.nan
            triangle[i] = found
            if found < 0:
                lost += 1
        if lost:
            return lost
    clamped = False  # as _vertex_normal: the edge rule's formulas for all if any is outside
    for i in range(n):
        if not is_inside(sth[0, i], sth[1, i]):
            clamped = True
            break
    for i in range(n):
        evaluate((xyz[0, i], xyz[1, i], xyz[2, i]), rows, triangle[i], (sth[0, i], sth[1, i], sth[2, i]), clamped,
                 mode, out, i)
    return 0
