"""The vertex-normal projection's algebra for one point, compiled with numba (desire2023 Sec. 2.2.2.2, Eq. 6, 7, 10).

``_vertex_normal`` holds the algebra of one triangle as vectorised numpy; a
line has ~100 points, so there the cost of a projection is its ~60 numpy
calls, not the arithmetic. This module does the same for one point, for the
compiled walk of ``_walk_jit`` to call in its loop: ``solve``, the cubic in h
in a given triangle (Halley from the last h or the small root of the
quadratic part, deflation, a Newton polish of the other roots) and the real
root of smallest |h| inside the triangle; ``evaluate``, d_G, d_P, the
closest point and their exact derivatives (implicit function theorem on
J = [a, b, n]), with the edge rule's clamped foot where a point lies beyond
the triangle. Every step is ``_vertex_normal``'s, in the same order, with
two shortcuts that change nothing but round-off: a flat triangle's cubic is
linear (one root, -c0 / c1), and below the triangle's SAFE height
(``warm_table``) a root inside it is provably the nearest, so the other two
are not looked for. ``tests/test_projection_compiled.py`` checks that both
paths agree to round-off (1e-14 relative measured).

Shapes: component-first, as in ``_vertex_normal``: points (3, n) [m]; the
per-triangle table is ``triangle_table``'s transposed to rows (k, 30), so
that one triangle's data are contiguous; the outputs are packed in one
(19, n) array: d_G, d_P (3), closest point (3), d(d_G)/dp (3), d(d_P)/dp
(3 x 3, row a at 3 a). Their transposes are the (n, 3) and (n, 3, 3) views a
``Projection`` holds, and the component-first arrays that contact loads take.
"""

import numpy as np
from numba import njit

from cablefem.geometry._vertex_normal import INSIDE_TOLERANCE

#: rows of the packed output (OUTPUTS, n)
GAP, DIRECTION, CLOSEST = 0, slice(1, 4), slice(4, 7)
GAP_GRADIENT, DIRECTION_GRADIENT = slice(7, 10), slice(10, 19)
OUTPUTS = 19
#: what ``evaluate`` (and ``_walk_jit.project``) computes: the gap alone, with the direction, or everything
GAP_ONLY, GAP_AND_DIRECTION, EVERYTHING = 0, 1, 2
#: table columns (``_vertex_normal.triangle_table``'s rows)
_P0, _E1, _E2, _N0, _DN1, _DN2, _G0, _G1, _G2 = 0, 3, 6, 9, 12, 15, 18, 21, 24
_K1, _K2, _C3 = 27, 28, 29

JIT = {"cache": True, "error_model": "numpy"}  # numpy's float semantics: x / 0 is inf or NaN


@njit(**JIT)
def _halley(c0, c1, c2x2, c3x3, c3x6, h):
    """One Halley step from h and whether it settled (``_cubic._halley`` for one cubic)."""
    df = (c3x3 * h + c2x2) * h + c1
    f = ((c3x3 * h + 1.5 * c2x2) * h + 3.0 * c1) * h + 3.0 * c0
    step = 2.0 * f * df / (6.0 * df * df - f * (c3x6 * h + c2x2))
    if not np.isfinite(step):
        step = 0.0
    return h - step, abs(step) <= 1e-8 * abs(h) + 1e-13


@njit(**JIT)
def _polish(c0, c1, c2, c3, h):
    """One Newton step on the cubic from a root h found by deflation (``_cubic.polish``)."""
    f = ((c3 * h + c2) * h + c1) * h + c0
    df = (3.0 * c3 * h + 2.0 * c2) * h + c1
    return h - f / df if df != 0.0 else h


@njit(inline="always", **JIT)
def _edges_at(rows, k, h):
    """Edges a = e1 + h dn1 and b = e2 + h dn2 of triangle k of ``rows`` lifted to height h."""
    return (rows[k, _E1] + h * rows[k, _DN1], rows[k, _E1 + 1] + h * rows[k, _DN1 + 1],
            rows[k, _E1 + 2] + h * rows[k, _DN1 + 2], rows[k, _E2] + h * rows[k, _DN2],
            rows[k, _E2 + 1] + h * rows[k, _DN2 + 1], rows[k, _E2 + 2] + h * rows[k, _DN2 + 2])


@njit(inline="always", **JIT)
def _barycentric(rows, k, q0, q1, q2, h):
    """(s, t) of height h for the offset q = p - P_0 in the triangle k of ``rows`` (k, 30)
    (``_vertex_normal._barycentric``: the normal equations of q - h n_0 = s a + t b)."""
    a0, a1, a2, b0, b1, b2 = _edges_at(rows, k, h)
    r0, r1, r2 = q0 - h * rows[k, _N0], q1 - h * rows[k, _N0 + 1], q2 - h * rows[k, _N0 + 2]
    aa = a0 * a0 + a1 * a1 + a2 * a2
    bb = b0 * b0 + b1 * b1 + b2 * b2
    ab = a0 * b0 + a1 * b1 + a2 * b2
    qa = r0 * a0 + r1 * a1 + r2 * a2
    qb = r0 * b0 + r1 * b1 + r2 * b2
    gram = aa * bb - ab * ab
    scale = 1.0 / gram if gram > 1e-12 * aa * bb else np.nan  # a x b vanishing: a focal point
    return (qa * bb - qb * ab) * scale, (qb * aa - qa * ab) * scale


@njit(**JIT)
def is_inside(s, t):
    """``_vertex_normal._inside`` for one point (False for NaN)."""
    tol = -INSIDE_TOLERANCE
    return s >= tol and t >= tol and 1.0 - s - t >= tol


@njit(inline="always", **JIT)
def solve(x0, x1, x2, rows, k, start, safe):
    """``_vertex_normal._solve`` for one point (x0, x1, x2) [m] in the triangle k of ``rows``
    (k, 30), from the guess ``start`` [m] (NaN: none): s, t, h, inside, smallest, and whether
    the cubic settled (False where numpy would take companion eigenvalues: the numpy search
    places the point). ``safe`` [m]: the triangle's ``warm_table`` SAFE, a height below which
    a root inside the triangle is provably the nearest (the other two are not needed)."""
    q0, q1, q2 = x0 - rows[k, _P0], x1 - rows[k, _P0 + 1], x2 - rows[k, _P0 + 2]
    c0 = rows[k, _G0] * q0 + rows[k, _G0 + 1] * q1 + rows[k, _G0 + 2] * q2
    c1 = rows[k, _G1] * q0 + rows[k, _G1 + 1] * q1 + rows[k, _G1 + 2] * q2 - rows[k, _K1]
    c2 = rows[k, _G2] * q0 + rows[k, _G2 + 1] * q1 + rows[k, _G2 + 2] * q2 - rows[k, _K2]
    c3 = rows[k, _C3]
    if c2 == 0.0 and c3 == 0.0 and c1 != 0.0:  # a flat triangle (equal vertex normals): one root
        h = -c0 / c1
        s, t = _barycentric(rows, k, q0, q1, q2, h)
        return s, t, h, is_inside(s, t), True, True
    # _cubic.cubic_roots: Halley from the start or the small root of the quadratic part
    if np.isnan(start):
        h = -2.0 * c0 / (c1 + np.copysign(np.sqrt(c1 * c1 - 4.0 * c0 * c2), c1))
        if not np.isfinite(h):
            h = -c0 / c1
            if not np.isfinite(h):
                h = 0.0
    else:
        h = start
    c2x2, c3x3, c3x6 = 2.0 * c2, 3.0 * c3, 6.0 * c3
    settled = False
    for _ in range(4):
        h, settled = _halley(c0, c1, c2x2, c3x3, c3x6, h)
        if settled:
            break
    if not settled:  # a few more steps where the start was poor
        for _ in range(8):
            h, settled = _halley(c0, c1, c2x2, c3x3, c3x6, h)
        if not settled:
            return 0.0, 0.0, np.nan, False, False, False
    if abs(h) <= safe:
        s, t = _barycentric(rows, k, q0, q1, q2, h)
        if is_inside(s, t):
            return s, t, h, True, True, True
    # deflate c(h) = (h - h_1)(c3 h^2 + B h + C), then the quadratic without cancellation
    big_b = c2 + c3 * h
    big_c = c1 + big_b * h
    big_q = -0.5 * (big_b + np.copysign(np.sqrt(big_b * big_b - 4.0 * c3 * big_c), big_b))
    roots = (h if np.isfinite(h) else np.nan,
             big_q / c3 if np.isfinite(big_q / c3) else np.nan,
             big_c / big_q if np.isfinite(big_c / big_q) else np.nan)
    h = roots[0]
    s, t = _barycentric(rows, k, q0, q1, q2, h)
    inside = is_inside(s, t)
    closer = abs(roots[1]) < abs(h) or abs(roots[2]) < abs(h)
    if inside and not closer and not np.isnan(h):
        return s, t, h, True, True, True
    # the other real roots: the smallest |h| inside, else the smallest |h|
    nearest, pick = -1, -1
    nearest_size, pick_size = np.inf, np.inf
    best_s, best_t, best_h, best_in = np.nan, np.nan, np.nan, False
    near_s, near_t, near_h = np.nan, np.nan, np.nan
    for r in range(3):
        hr = roots[r] if r == 0 else _polish(c0, c1, c2, c3, roots[r])
        sr, tr = _barycentric(rows, k, q0, q1, q2, hr)
        size = np.inf if np.isnan(hr) else abs(hr)
        if nearest < 0 or size < nearest_size:  # np.argmin: the first of equal ones
            nearest, nearest_size = r, size
            near_s, near_t, near_h = sr, tr, hr
        if is_inside(sr, tr) and (pick < 0 or size < pick_size):
            pick, pick_size = r, size
            best_s, best_t, best_h, best_in = sr, tr, hr, True
    if pick < 0:
        return near_s, near_t, near_h, False, True, True
    return best_s, best_t, best_h, best_in, pick == nearest, True


@njit(inline="always", **JIT)
def _normal(rows, k, s, t):
    """n(s, t) = n_0 + s dn_1 + t dn_2 of the triangle k of ``rows`` (Eq. 10, not normalised)."""
    return (rows[k, _N0] + s * rows[k, _DN1] + t * rows[k, _DN2],
            rows[k, _N0 + 1] + s * rows[k, _DN1 + 1] + t * rows[k, _DN2 + 1],
            rows[k, _N0 + 2] + s * rows[k, _DN1 + 2] + t * rows[k, _DN2 + 2])


@njit(inline="always", **JIT)
def _lever(x, rows, k, s, t):
    """p - P(s, t) for the point x = (x0, x1, x2) [m] and the triangle k of ``rows``."""
    return (x[0] - (rows[k, _P0] + s * rows[k, _E1] + t * rows[k, _E2]),
            x[1] - (rows[k, _P0 + 1] + s * rows[k, _E1 + 1] + t * rows[k, _E2 + 1]),
            x[2] - (rows[k, _P0 + 2] + s * rows[k, _E1 + 2] + t * rows[k, _E2 + 2]))


@njit(inline="always", **JIT)
def _clamped_gap(x, rows, k, s, t):
    """``_vertex_normal.gap`` beyond the triangle: d_G [m] of x = (x0, x1, x2) [m] at the foot
    (s, t) clamped onto the triangle k of ``rows``."""
    l0, l1, l2 = max(1.0 - s - t, 0.0), max(s, 0.0), max(t, 0.0)
    total = l0 + l1 + l2
    s, t = l1 / total, l2 / total
    n0, n1, n2 = _normal(rows, k, s, t)
    v0, v1, v2 = _lever(x, rows, k, s, t)
    return (v0 * n0 + v1 * n1 + v2 * n2) / np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)


@njit(inline="always", **JIT)
def _clamped_foot(s, t, ds, dt):
    """The edge rule's foot (s_c, t_c), clamped onto the triangle, and its derivatives d(s_c, t_c)/dp
    (3 each) from those of (s, t), ds and dt (3 each)."""
    ds0, ds1, ds2 = ds
    dt0, dt1, dt2 = dt
    l0, l1, l2 = 1.0 - s - t, s, t
    total = max(l0, 0.0) + max(l1, 0.0) + max(l2, 0.0)
    f1, f2 = max(l1, 0.0) / total, max(l2, 0.0) / total
    on0, on1, on2 = l0 > 0.0, l1 > 0.0, l2 > 0.0
    k00, k01, k02 = (-ds0 - dt0, -ds1 - dt1, -ds2 - dt2) if on0 else (0.0, 0.0, 0.0)
    k10, k11, k12 = (ds0, ds1, ds2) if on1 else (0.0, 0.0, 0.0)
    k20, k21, k22 = (dt0, dt1, dt2) if on2 else (0.0, 0.0, 0.0)
    w0, w1, w2 = k00 + k10 + k20, k01 + k11 + k21, k02 + k12 + k22
    return (f1, f2, ((k10 - f1 * w0) / total, (k11 - f1 * w1) / total, (k12 - f1 * w2) / total),
            ((k20 - f2 * w0) / total, (k21 - f2 * w1) / total, (k22 - f2 * w2) / total))


@njit(inline="always", **JIT)
def _direction_gradient(rows, k, d, ds, dt, reciprocal, out, i):
    """d(d_P)/dp = (I - d d^T) dn / |n| into rows 10-18 of column i of out, with dn_a/dp_b =
    dn1_a ds_b + dn2_a dt_b (the triangle k of ``rows``, d = d_P, ds, dt = d(s, t)/dp, 3 each,
    ``reciprocal`` = 1 / |n|); returns d . dn (3)."""
    d0, d1, d2 = d
    ds0, ds1, ds2 = ds
    dt0, dt1, dt2 = dt
    m10, m11, m12 = rows[k, _DN1], rows[k, _DN1 + 1], rows[k, _DN1 + 2]
    m20, m21, m22 = rows[k, _DN2], rows[k, _DN2 + 1], rows[k, _DN2 + 2]
    u1 = d0 * m10 + d1 * m11 + d2 * m12  # d . dn1
    u2 = d0 * m20 + d1 * m21 + d2 * m22
    along0, along1, along2 = u1 * ds0 + u2 * dt0, u1 * ds1 + u2 * dt1, u1 * ds2 + u2 * dt2
    out[10, i] = (m10 * ds0 + m20 * dt0 - d0 * along0) * reciprocal
    out[11, i] = (m10 * ds1 + m20 * dt1 - d0 * along1) * reciprocal
    out[12, i] = (m10 * ds2 + m20 * dt2 - d0 * along2) * reciprocal
    out[13, i] = (m11 * ds0 + m21 * dt0 - d1 * along0) * reciprocal
    out[14, i] = (m11 * ds1 + m21 * dt1 - d1 * along1) * reciprocal
    out[15, i] = (m11 * ds2 + m21 * dt2 - d1 * along2) * reciprocal
    out[16, i] = (m12 * ds0 + m22 * dt0 - d2 * along0) * reciprocal
    out[17, i] = (m12 * ds1 + m22 * dt1 - d2 * along1) * reciprocal
    out[18, i] = (m12 * ds2 + m22 * dt2 - d2 * along2) * reciprocal
    return along0, along1, along2


@njit(inline="always", **JIT)
def _edge_rule_outputs(x, rows, k, s, t, d, ds, dt, out, i):
    """The edge rule's d_G = (p - P(s_c, t_c)) . d_P, closest point and d(d_G)/dp into column i of
    out (the direction's gradient already in it), for x = (x0, x1, x2) [m] at the clamped foot
    (s, t) of the triangle k of ``rows``, d = d_P, ds, dt = d(s_c, t_c)/dp (3 each)."""
    d0, d1, d2 = d
    ds0, ds1, ds2 = ds
    dt0, dt1, dt2 = dt
    v0, v1, v2 = _lever(x, rows, k, s, t)
    gap = v0 * d0 + v1 * d1 + v2 * d2
    out[GAP, i] = gap
    out[4, i], out[5, i], out[6, i] = x[0] - gap * d0, x[1] - gap * d1, x[2] - gap * d2
    e1d = rows[k, _E1] * d0 + rows[k, _E1 + 1] * d1 + rows[k, _E1 + 2] * d2
    e2d = rows[k, _E2] * d0 + rows[k, _E2 + 1] * d1 + rows[k, _E2 + 2] * d2
    out[7, i] = d0 + v0 * out[10, i] + v1 * out[13, i] + v2 * out[16, i] - e1d * ds0 - e2d * dt0
    out[8, i] = d1 + v0 * out[11, i] + v1 * out[14, i] + v2 * out[17, i] - e1d * ds1 - e2d * dt1
    out[9, i] = d2 + v0 * out[12, i] + v1 * out[15, i] + v2 * out[18, i] - e1d * ds2 - e2d * dt2


@njit(**JIT)
def evaluate(x, rows, k, sth, clamped, mode, out, i):
    """``_vertex_normal._evaluate`` (or, with ``mode`` GAP_ONLY, ``gap``) for the point x = (x0, x1,
    x2) [m] at sth = (s, t, h) of the triangle k of ``rows`` (k, 30), into column i of out (19, n);
    ``clamped``: the edge rule's foot."""
    x0, x1, x2 = x
    s, t, h = sth
    if clamped and (mode == GAP_ONLY or mode == GAP_AND_DIRECTION):
        if mode == GAP_ONLY:  # _vertex_normal.gap
            out[GAP, i] = _clamped_gap(x, rows, k, s, t)
            return
        mode = EVERYTHING  # beyond the edge numpy evaluates in full
    n0, n1, n2 = _normal(rows, k, s, t)
    if not clamped and mode != EVERYTHING:  # project_warm's lean outputs
        length = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
        out[GAP, i] = h * length
        if mode == GAP_AND_DIRECTION:
            out[1, i], out[2, i], out[3, i] = n0 / length, n1 / length, n2 / length
        return
    a0, a1, a2, b0, b1, b2 = _edges_at(rows, k, h)
    ab0, ab1, ab2 = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0
    det = ab0 * n0 + ab1 * n1 + ab2 * n2
    # rows of J^-1: d(s, t)/dp = (b x n, n x a) / det J
    inverse = 1.0 / det
    ds = ((b1 * n2 - b2 * n1) * inverse, (b2 * n0 - b0 * n2) * inverse, (b0 * n1 - b1 * n0) * inverse)
    dt = ((n1 * a2 - n2 * a1) * inverse, (n2 * a0 - n0 * a2) * inverse, (n0 * a1 - n1 * a0) * inverse)
    if clamped:  # the edge rule: the foot clamped onto the triangle, and its derivative
        s, t, ds, dt = _clamped_foot(s, t, ds, dt)
        n0, n1, n2 = _normal(rows, k, s, t)
    length = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    reciprocal = 1.0 / length
    d = (n0 * reciprocal, n1 * reciprocal, n2 * reciprocal)
    out[1, i], out[2, i], out[3, i] = d
    along0, along1, along2 = _direction_gradient(rows, k, d, ds, dt, reciprocal, out, i)
    if clamped:
        _edge_rule_outputs(x, rows, k, s, t, d, ds, dt, out, i)
        return
    # d_G = h |n|, p - r' = h n, dh/dp = (a x b) / det J
    out[GAP, i] = h * length
    out[4, i], out[5, i], out[6, i] = x0 - h * n0, x1 - h * n1, x2 - h * n2
    out[7, i] = length * ab0 * inverse + h * along0
    out[8, i] = length * ab1 * inverse + h * along1
    out[9, i] = length * ab2 * inverse + h * along2
