"""The compiled face's scalar axial laws of ``cablefem.loads.rope`` at one point (numba): the table,
the viscoelastic rope's slow strain after a step, SYROPE's working curve and slow strain
(``cablefem.model.axial`` states the laws and where MoorDyn-C has them).

The slow strain e_1 obeys (BA + BA_D) de_1/dt = F(e, e_1) + BA_D de/dt; a step of size h takes it
by backward Euler from its committed value e_1n, R(e_1) = c (e_1 - e_1n) - F(e, e_1) - BA_D de/dt = 0
with c = (BA + BA_D) / h, and c = 0 in statics: the slow strain relaxed to the strain (de_1/dt = 0).
Each solver returns e_1, the mean tension T_m (the slow spring's), dT_m/de_1 and dR/de_1, from
which the caller takes the derivatives by the implicit function theorem.
"""

import math

import numpy as np
from numba import njit

from cablefem.model.axial import WORKING_ROWS

TABLE, VISCOELASTIC, SYROPE = 1, 2, 3
LINEAR, QUADRATIC, EXP = 1, 2, 3


@njit(cache=True, _nrt=False)
def segment(xs, n, x):
    """The row k (0 <= k <= n - 2) of the segment of the sorted xs[:n] holding x (the first or the
    last one outside them)."""
    lo, hi = 0, n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    return lo


@njit(cache=True, _nrt=False)
def table(xs, ys, n, x):
    """y(x) on the rows xs, ys [:n], straight beyond the ends, and its slope dy/dx."""
    k = segment(xs, n, x)
    slope = (ys[k + 1] - ys[k]) / (xs[k + 1] - xs[k])
    return ys[k] + slope * (x - xs[k]), slope


@njit(cache=True, _nrt=False)
def damping(q, rate):
    """The damping tension T_d [N] at the strain rate ``rate`` [1/s] and dT_d/drate: BA rate, or the
    damping table (mirrored for a table of positive rates, ``q.mirror``)."""
    if q.damping_rows == 0:
        return q.BA * rate, q.BA
    if q.mirror and rate < 0.0:
        value, slope = table(q.rate, q.force, q.damping_rows, -rate)
        return -value, slope
    return table(q.rate, q.force, q.damping_rows, rate)


@njit(cache=True, _nrt=False)
def _dynamic(q, e1):
    """The fast spring EA_2 [N] and dEA_2/de_1 where the mean tension EA_1 e_1 sets it (EA_2 =
    alpha + beta T_mean solved with EA_1 = EA_2 EA_s / (EA_2 - EA_s): the larger root of
    EA_2^2 - B EA_2 + alpha EA_s = 0, B = EA_s + alpha + beta EA_s e_1; alpha below zero e_1)."""
    if q.beta == 0.0 or e1 <= 0.0:
        return q.alpha, 0.0
    B = q.static + q.alpha + q.beta * q.static * e1
    root = math.sqrt(B * B - 4.0 * q.alpha * q.static)
    return 0.5 * (B + root), 0.5 * q.beta * q.static * (1.0 + B / root)


@njit(cache=True, _nrt=False)
def _viscoelastic_residual(q, e, rate, e1n, c, e1):
    """R(e_1), dR/de_1, T_m and dT_m/de_1 of the viscoelastic rope."""
    fast, dfast = _dynamic(q, e1)
    slow = fast * q.static / (fast - q.static)
    dslow = -q.static * q.static / ((fast - q.static) * (fast - q.static)) * dfast
    residual = c * (e1 - e1n) - fast * e + (slow + fast) * e1 - q.BA_D * rate
    return residual, c + dfast * (e1 - e) + dslow * e1 + slow + fast, slow * e1, slow + dslow * e1


@njit(cache=True, _nrt=False)
def viscoelastic(q, e, rate, e1n, c):
    """The slow strain e_1 after the step (safeguarded Newton from e_1n: R rises with e_1), T_m,
    dT_m/de_1 and dR/de_1."""
    e1 = e1n
    lo, hi = -np.inf, np.inf
    R, dR, Tm, dTm = _viscoelastic_residual(q, e, rate, e1n, c, e1)
    scale = q.alpha * (abs(e) + abs(e1n)) + q.BA_D * abs(rate) + 1e-300
    for _ in range(60):
        if R > 0.0:
            hi = min(hi, e1)
        else:
            lo = max(lo, e1)
        if abs(R) <= 1e-15 * scale:
            break
        trial = e1 - R / dR
        if not lo < trial < hi:  # outside the bracket: bisect (or step out of an open side)
            trial = 0.5 * (lo + hi) if math.isfinite(lo) and math.isfinite(hi) else trial
        if trial == e1:
            break
        e1 = trial
        R, dR, Tm, dTm = _viscoelastic_residual(q, e, rate, e1n, c, e1)
    return e1, Tm, dTm, dR


@njit(cache=True, _nrt=False)
def working_rows(q, peak, x, y, z):
    """SYROPE's curve below and above the highest mean tension ``peak`` into x, y, z (rows (strain,
    tension, slow strain)): the working curve of ``peak`` (WORKING_ROWS rows, as MoorDyn-C tabulates
    it), then the original working curve's rows above it (their slow strains above the working
    curve's top), or one row on its last slope if none is. Returns the number of rows."""
    n = q.rows
    eps_max = table(q.y, q.x, n, peak)[0]
    eps_0 = q.x[0]
    if q.form == LINEAR and q.k1 >= 1.0:
        eps_min = eps_max - peak / q.k1
    else:
        eps_min = eps_0 + q.k1 * (eps_max - eps_0)
    for i in range(WORKING_ROWS):
        xi = i / (WORKING_ROWS - 1.0)
        x[i] = eps_min + (eps_max - eps_min) * xi
        if q.form == LINEAR:
            y[i] = peak * xi
        elif q.form == QUADRATIC:
            y[i] = peak * xi * (q.k2 * xi + (1.0 - q.k2))
        else:
            y[i] = peak * (1.0 - math.exp(q.k2 * xi)) / (1.0 - math.exp(q.k2))
        z[i] = _slow(q, x[i], y[i])
    m = WORKING_ROWS
    for j in range(n):
        if q.y[j] > peak and q.z[j] > z[m - 1]:
            x[m], y[m], z[m] = q.x[j], q.y[j], q.z[j]
            m += 1
    if m == WORKING_ROWS:  # above the original curve's last row: its last slope on
        top = 2.0 * peak
        x[m], y[m] = table(q.y, q.x, n, top)[0], top
        z[m] = _slow(q, x[m], y[m])
        m += 1
    return m


@njit(cache=True, _nrt=False)
def _slow(q, x, y):
    """The slow strain z = x - ln(1 + beta y / alpha) / beta of a point (x, y) of a curve."""
    if q.beta == 0.0:
        return x - y / q.alpha
    return x - math.log1p(q.beta * y / q.alpha) / q.beta


@njit(cache=True, _nrt=False)
def curve_at(x, y, z, m, e1):
    """T_m and x at the slow strain e_1 on the curve rows x, y, z [:m], and their slopes in e_1
    (below the first row: zero tension, x = e_1)."""
    if e1 <= z[0]:
        return 0.0, e1, 0.0, 1.0
    k = segment(z, m, e1)
    dz = z[k + 1] - z[k]
    sy, sx = (y[k + 1] - y[k]) / dz, (x[k + 1] - x[k]) / dz
    return y[k] + sy * (e1 - z[k]), x[k] + sx * (e1 - z[k]), sy, sx


@njit(cache=True, _nrt=False)
def _syrope_residual_at(q, e, rate, e1n, c, x, y, z):
    """R at a row (x, y, z) of the curve."""
    return c * (z - e1n) - (e - x) * (q.alpha + q.beta * y) - q.BA_D * rate


@njit(cache=True, _nrt=False)
def syrope(q, e, rate, e1n, c, x, y, z, m):
    """SYROPE's slow strain e_1 after the step on the curve rows x, y, z [:m] (``working_rows``):
    R(e_1) = c (e_1 - e_1n) - (e - x(e_1)) (alpha + beta T_m(e_1)) - BA_D rate is quadratic on each
    segment, so the root is found exactly on the segment where R changes sign (below the first row
    the curve runs at zero tension with x = z). Returns e_1, T_m, dT_m/de_1 and dR/de_1."""
    if _syrope_residual_at(q, e, rate, e1n, c, x[0], y[0], z[0]) > 0.0:  # below: T_m = 0, x = e_1
        e1 = (c * e1n + q.alpha * e + q.BA_D * rate) / (c + q.alpha)
        return e1, 0.0, 0.0, c + q.alpha
    lo, hi = 0, m - 1
    if _syrope_residual_at(q, e, rate, e1n, c, x[hi], y[hi], z[hi]) <= 0.0:
        lo = m - 2  # beyond the last row: its segment carried on
    else:
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if _syrope_residual_at(q, e, rate, e1n, c, x[mid], y[mid], z[mid]) <= 0.0:
                lo = mid
            else:
                hi = mid
    k = lo
    dz = z[k + 1] - z[k]
    sx, sy = (x[k + 1] - x[k]) / dz, (y[k + 1] - y[k]) / dz
    a2 = q.beta * sx * sy
    a1 = c + sx * (q.alpha + q.beta * y[k]) - (e - x[k]) * q.beta * sy
    a0 = _syrope_residual_at(q, e, rate, e1n, c, x[k], y[k], z[k])
    u = -2.0 * a0 / (a1 + math.sqrt(max(a1 * a1 - 4.0 * a2 * a0, 0.0)))
    return z[k] + u, y[k] + sy * u, sy, 2.0 * a2 * u + a1
