"""Real roots of the vertex-normal projection's cubic in h (desire2023 Sec. 2.2.2.2, Eq. 10).

``_vertex_normal`` reduces the projection of a point onto a triangle's prism to a cubic
c0 + c1 h + c2 h^2 + c3 h^3 = 0 in the height h; this module solves many of them at once,
vectorised: Halley's iteration from the small root of the quadratic part or from the last
call's h, deflation and a stable quadratic for the other two roots (``polish``: one Newton step
on each), companion-matrix eigenvalues where Halley has not settled. ``_vertex_normal_jit``
holds the same steps for one point, compiled.
"""

import numpy as np


def _halley(c, h):
    """One Halley step for the cubics c = (c0, c1, 2 c2, 3 c3, 6 c3), each (m,), from h (m,) [m], and whether
    the step was below 1e-8 |h| + 1e-13 m: converging cubically, the new h is then right to round-off."""
    c0, c1, c2x2, c3x3, c3x6 = c
    df = (c3x3 * h + c2x2) * h + c1
    f = (((c3x3 * h + 1.5 * c2x2) * h + 3.0 * c1) * h + 3.0 * c0)  # 3 f
    step = 2.0 * f * df / (6.0 * df * df - f * (c3x6 * h + c2x2))
    step[~np.isfinite(step)] = 0.0
    return h - step, np.abs(step) <= 1e-8 * np.abs(h) + 1e-13


def cubic_roots(c0, c1, c2, c3, start=None):
    """Real roots (3, m) of c0 + c1 h + c2 h^2 + c3 h^3 (coefficients (m,)), NaN where complex or absent.

    The first is the root Halley's iteration reaches from ``start`` (m,) (the
    previous call's h) or else the small root of the quadratic part, whose
    relative error is of the order of (h / curvature radius)^2; the other two
    come from deflation. Call under np.errstate(all="ignore").
    """
    scaled = (c0, c1, 2.0 * c2, 3.0 * c3, 6.0 * c3)
    if start is None:  # the small root of c0 + c1 h + c2 h^2 (-c0/c1 when c2 = 0)
        h = -2.0 * c0 / (c1 + np.copysign(np.sqrt(c1 * c1 - 4.0 * c0 * c2), c1))
        h = np.where(np.isfinite(h), h, -c0 / c1)
        h[~np.isfinite(h)] = 0.0
    else:
        h = start
    for _ in range(4):
        h, settled = _halley(scaled, h)
        if settled.all():
            break
    stuck = np.flatnonzero(~settled)
    if len(stuck):  # a few more steps where the start was poor, eigenvalues where that fails
        hs, cs = h[stuck], tuple(x[stuck] for x in scaled)
        for _ in range(8):
            hs, settled = _halley(cs, hs)
        h[stuck] = hs
        stuck = stuck[~settled]
    # deflate c(h) = (h - h_1)(c3 h^2 + B h + C), then the quadratic without cancellation
    big_b = c2 + c3 * h
    big_c = c1 + big_b * h
    q = -0.5 * (big_b + np.copysign(np.sqrt(big_b * big_b - 4.0 * c3 * big_c), big_b))
    roots = np.stack([h, q / c3, big_c / q])
    roots[~np.isfinite(roots)] = np.nan
    if len(stuck):
        roots[:, stuck] = _companion_roots(np.stack([c0, c1, c2, c3], axis=1)[stuck]).T
    return roots


def polish(c, h):
    """One Newton step on the cubics c (4, ...) from roots h (...) found by deflation."""
    c0, c1, c2, c3 = c
    f = ((c3 * h + c2) * h + c1) * h + c0
    df = (3.0 * c3 * h + 2.0 * c2) * h + c1
    return np.where(df != 0.0, h - f / df, h)


def _companion_roots(coefficients):
    """Real roots (m, 3) of the few cubics (m, 4) [c0..c3] Halley did not settle, by eigenvalues."""
    roots = np.full((len(coefficients), 3), np.nan)
    scale = np.abs(coefficients).max(axis=1)
    todo = np.ones(len(coefficients), dtype=bool)
    for degree in (3, 2, 1):  # drop vanishing leading coefficients
        lead = coefficients[:, degree]
        rows = np.flatnonzero((np.abs(lead) > 1e-14 * scale) & todo)
        todo[rows] = False
        if len(rows) == 0:
            continue
        companion = np.zeros((len(rows), degree, degree))
        companion[:, 0, :] = -coefficients[rows, degree - 1::-1] / lead[rows, None]
        companion[:, np.arange(1, degree), np.arange(degree - 1)] = 1.0
        eig = np.linalg.eigvals(companion)
        real = np.abs(eig.imag) <= 1e-9 * np.maximum(1.0, np.abs(eig.real))
        found = np.where(real, eig.real, np.nan)
        order = np.argsort(np.where(real, np.abs(eig.real), np.inf), axis=1)
        roots[rows, :degree] = np.take_along_axis(found, order, axis=1)
    return roots
