"""The compiled face of the wave kinematics (numba): ``water_at`` is ``cablefem.waves.airy.kinematics``
at one point, for the load kernels (``cablefem.compiled.kernels`` fills the point's context with it).

Within a time step Newton evaluates the loads several times at one time, at positions that move
by little (from the predictor to the converged point). ``water_cached`` sums the components at a
point once per evaluation time and keeps its elevation, velocity, acceleration and their gradients
(the row of the point in the Water's ``cache``); later evaluations at that time take them to first
order in the point's displacement since, u(r) = u(r0) + du/dx (r - r0) (and a, eta alike), whose
tangent is exact. The approximation is second order in that displacement (~1e-6 m from a
predictor: ~(k dr)^2 ~ 1e-9 of the kinematics); it halves to thirds the sums a run does
(benchmarks/waves_cost.py), and the numpy face, the reference, sums at every evaluation.

A sea enters the compiled code as a ``Water`` tuple of arrays (``water_of``): its kind (``NONE``: no
waves, the tuple every line without waves gets; ``COMPONENTS``), its settings (depth, stretching,
ramp), its components (m, ``COLUMNS``: A, omega, k, cos beta, sin beta, phi, the velocity scale
A omega / (1 - e^{-2kh}), and cos^2 beta, cos beta sin beta, sin^2 beta) and a scratch row per
component (cos theta, sin theta of the first pass, read by the second), and a current grid's axes,
clock (dt, nt; nt = 0: none) and velocities (``cablefem.waves.grid``; ``_add_grid`` interpolates it
as its numpy face does, and adds it to the waves' velocity). (Writing the profile's
e^{-k(z' + 2h)} as e^{-2kh} / e^{kz'}, one exponential fewer, made a component ten times slower
here, 530 against 47 ns: kept as two exponentials.)
"""

from collections import namedtuple

import numpy as np
from numba import njit

#: kinds of compiled water
NONE, COMPONENTS = 0, 1
#: stretching codes (``cablefem.waves.sea.STRETCHING`` in order)
WHEELER, VERTICAL, UNSTRETCHED = 0, 1, 2
#: settings: depth [m], stretching code, ramp [s]
DEPTH, STRETCHING, RAMP = 0, 1, 2
#: the component columns
AMPLITUDE, OMEGA, NUMBER, COS, SIN, PHASE, SPEED, CC, CS, SS = range(10)
COLUMNS = 10

#: a point's row of the cache: the time it was summed at (NaN: never), the point r0 (3), eta, d eta/dx,
#: d eta/dy, u (3), a (3), du/dx (9, row-major), da/dx (9)
TIME, POINT, ETA, SLOPE, VELOCITY, ACCELERATION, DU, DA, CACHED = 0, 1, 4, 5, 7, 10, 13, 22, 31

#: a current grid's clock: its step dt [s] and its count of samples nt (0: no grid)
CLOCK_DT, CLOCK_COUNT = 0, 1

Water = namedtuple("Water", "kind settings components scratch cache grid_x grid_y grid_z grid_clock grid_u")


def _no_grid():
    """The grid fields of a Water without a current grid."""
    return np.zeros(1), np.zeros(1), np.zeros(1), np.array([1.0, 0.0]), np.zeros((1, 1, 1, 1, 3))


def _grid_of(grid):
    """The grid fields of a ``cablefem.waves.grid.CurrentGrid`` (None: none)."""
    if grid is None:
        return _no_grid()
    axes = tuple(np.ascontiguousarray(a, dtype=float) for a in (grid.x, grid.y, grid.z))
    clock = np.array([grid.dt, float(grid.velocity.shape[3])])
    return axes + (clock, np.ascontiguousarray(grid.velocity, dtype=float))


def no_water():
    """The Water of a line without waves (kind NONE, empty arrays of the same types)."""
    return Water(NONE, np.zeros(3), np.zeros((0, COLUMNS)), np.zeros((0, 2)), np.zeros((0, CACHED)), *_no_grid())


def water_of(sea, points=0):
    """The Water of a ``cablefem.waves.sea.Sea`` (None: no waves), with a cache of ``points`` rows (the
    evaluator's full quadrature points and vertices, ``water_cached``)."""
    if sea is None:
        return no_water()
    from cablefem.waves.sea import STRETCHING as CODES

    amplitude, omega, k, cos_b, sin_b, phase = sea.arrays
    with np.errstate(divide="ignore"):
        scale = np.where(k > 0.0, 1.0 / (1.0 - np.exp(-2.0 * k * sea.depth)), 0.0)
    columns = (amplitude, omega, k, cos_b, sin_b, phase, amplitude * omega * scale, cos_b * cos_b, cos_b * sin_b,
               sin_b * sin_b)
    components = np.ascontiguousarray(np.stack(columns, axis=1))
    settings = np.array([sea.depth, float(CODES.index(sea.stretching)), sea.ramp])
    cache = np.zeros((points, CACHED))
    cache[:, TIME] = np.nan
    return Water(COMPONENTS, settings, components, np.zeros((len(amplitude), 2)), cache, *_grid_of(sea.current))


@njit(cache=True, inline="always", _nrt=False)
def _ramp(t, ramp):
    """R(t), dR/dt of the smoothstep ramp (``Sea.ramp_factor``)."""
    if ramp <= 0.0:
        return 1.0, 0.0
    u = min(max(t / ramp, 0.0), 1.0)
    rate = 6.0 * u * (1.0 - u) / ramp if 0.0 < u < 1.0 else 0.0
    return u * u * (3.0 - 2.0 * u), rate


@njit(cache=True, _nrt=False)
def water_at(water, r, t, u, a, du, da, gradients):
    """Velocity u (3,), acceleration a (3,) of the water at point r (3,) [m] and time t [s], with
    ``gradients`` also du/dx and da/dx (3, 3), written into the arrays given; returns (eta, wet):
    the surface's elevation above the point and whether it is at or below it."""
    eta, _, _ = _sum(water, r, t, u, a, du, da, gradients)
    return eta, r[2] <= eta


@njit(cache=True, _nrt=False)
def water_cached(water, index, r, t, u, a, du, da):
    """``water_at`` with gradients at point ``index`` of the cache: summed at the first evaluation at
    time t, to first order in the displacement from that point after (the module docstring)."""
    row = water.cache[index]
    if row[TIME] != t:
        eta, gx, gy = _sum(water, r, t, u, a, du, da, True)
        row[TIME], row[ETA], row[SLOPE], row[SLOPE + 1] = t, eta, gx, gy
        for i in range(3):
            row[POINT + i], row[VELOCITY + i], row[ACCELERATION + i] = r[i], u[i], a[i]
            for j in range(3):
                row[DU + 3 * i + j], row[DA + 3 * i + j] = du[i, j], da[i, j]
        return eta, r[2] <= eta
    dx, dy, dz = r[0] - row[POINT], r[1] - row[POINT + 1], r[2] - row[POINT + 2]
    eta = row[ETA] + row[SLOPE] * dx + row[SLOPE + 1] * dy
    for i in range(3):
        u[i] = row[VELOCITY + i] + row[DU + 3 * i] * dx + row[DU + 3 * i + 1] * dy + row[DU + 3 * i + 2] * dz
        a[i] = row[ACCELERATION + i] + row[DA + 3 * i] * dx + row[DA + 3 * i + 1] * dy + row[DA + 3 * i + 2] * dz
        for j in range(3):
            du[i, j], da[i, j] = row[DU + 3 * i + j], row[DA + 3 * i + j]
    return eta, r[2] <= eta


@njit(cache=True, _nrt=False)
def _sum(water, r, t, u, a, du, da, gradients):
    """The sum over the components (``water_at``); returns eta and its slopes d eta/dx, d eta/dy."""
    comps, scratch, settings = water.components, water.scratch, water.settings
    depth, code = settings[DEPTH], int(settings[STRETCHING])
    R, Rd = _ramp(t, settings[RAMP])
    x, y, z = r[0], r[1], r[2]
    eta, gx, gy = 0.0, 0.0, 0.0
    for j in range(comps.shape[0]):
        c, s, k, A = comps[j, COS], comps[j, SIN], comps[j, NUMBER], comps[j, AMPLITUDE]
        theta = k * (x * c + y * s) - comps[j, OMEGA] * t + comps[j, PHASE]
        cs, sn = np.cos(theta), np.sin(theta)
        scratch[j, 0], scratch[j, 1] = cs, sn
        eta += A * cs
        gx -= A * k * c * sn
        gy -= A * k * s * sn
    eta, gx, gy = R * eta, R * gx, R * gy
    # the stretched height z' and dz'/dx (Zx, Zy, Zz)
    Zx, Zy, Zz = 0.0, 0.0, 1.0
    upper = 0.0 if code != UNSTRETCHED else np.inf
    if code == WHEELER:
        column = max(depth + eta, 1e-3 * depth)
        zs = depth * (z - eta) / column
        slope = -depth * (depth + z) / (column * column)
        Zx, Zy, Zz = slope * gx, slope * gy, depth / column
    else:
        zs = z
    if zs < -depth or zs > upper:
        zs = min(max(zs, -depth), upper)
        Zx, Zy, Zz = 0.0, 0.0, 0.0
    for i in range(3):
        u[i], a[i] = 0.0, 0.0
        if gradients:
            for j in range(3):
                du[i, j], da[i, j] = 0.0, 0.0
    uzx, uzy, uzz, azx, azy, azz = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0  # the z'-derivative sums
    hxx, hxy, hyy, vx, vy, axx, axy, ayy, bx, by = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    for j in range(comps.shape[0]):
        c, s, k, w = comps[j, COS], comps[j, SIN], comps[j, NUMBER], comps[j, OMEGA]
        first = np.exp(k * zs)
        second = np.exp(-k * (zs + 2.0 * depth))
        speed = comps[j, SPEED]
        P, Q = speed * (first + second), speed * (first - second)
        cs, sn = scratch[j, 0], scratch[j, 1]
        Pc, Qs, Ps, Qc = P * cs, Q * sn, w * P * sn, w * Q * cs
        u[0] += Pc * c
        u[1] += Pc * s
        u[2] += Qs
        a[0] += Ps * c
        a[1] += Ps * s
        a[2] -= Qc
        if not gradients:
            continue
        # theta-derivatives times k along the heading e = (c, s, 0); z'-derivatives times k
        hu, vu, ha, va = -k * P * sn, k * Q * cs, k * w * Pc, k * w * Qs
        hxx += hu * comps[j, CC]
        hxy += hu * comps[j, CS]
        hyy += hu * comps[j, SS]
        axx += ha * comps[j, CC]
        axy += ha * comps[j, CS]
        ayy += ha * comps[j, SS]
        vx += vu * c
        vy += vu * s
        bx += va * c
        by += va * s
        uzz += k * P * sn
        azz -= k * w * Pc
    if gradients:
        du[0, 0], du[0, 1], du[1, 0], du[1, 1], du[2, 0], du[2, 1] = hxx, hxy, hxy, hyy, vx, vy
        da[0, 0], da[0, 1], da[1, 0], da[1, 1], da[2, 0], da[2, 1] = axx, axy, axy, ayy, bx, by
        uzx, uzy, azx, azy = vx, vy, bx, by
    Z = (Zx, Zy, Zz)
    for i in range(3):
        ui = u[i]
        u[i] = R * ui
        a[i] = R * a[i] + Rd * ui
    if gradients:
        for j in range(3):
            du[0, j] += uzx * Z[j]
            du[1, j] += uzy * Z[j]
            du[2, j] += uzz * Z[j]
            da[0, j] += azx * Z[j]
            da[1, j] += azy * Z[j]
            da[2, j] += azz * Z[j]
        for i in range(3):
            for j in range(3):
                g = du[i, j]
                du[i, j] = R * g
                da[i, j] = R * da[i, j] + Rd * g
    if water.grid_clock[CLOCK_COUNT] > 0.0:  # a current on a grid: neither ramped nor stretched
        _add_grid(water, r, t, u, du, gradients)
    return eta, gx, gy


@njit(cache=True, inline="always", _nrt=False)
def _factor(axis, x):
    """MoorDyn-C's ``interp_factor`` (``cablefem.waves.grid.factors``) at x: the upper index, the
    fraction and its derivative d/dx."""
    k = axis.shape[0]
    if k == 1:
        return 0, 0.0, 0.0
    if x <= axis[0]:
        return 1, 0.0, 0.0
    if x >= axis[k - 1]:
        return k - 1, 1.0, 0.0
    i = 1
    while x > axis[i]:
        i += 1
    width = axis[i] - axis[i - 1]
    return i, (x - axis[i - 1]) / width, 1.0 / width


@njit(cache=True, _nrt=False)
def _add_grid(water, r, t, u, du, gradients):
    """Adds the current grid's velocity at point r and time t to u (3,), and with ``gradients`` its
    gradient to du (3, 3) (``cablefem.waves.grid``)."""
    ix, fx, dx = _factor(water.grid_x, r[0])
    iy, fy, dy = _factor(water.grid_y, r[1])
    iz, fz, dz = _factor(water.grid_z, r[2])
    nt = int(water.grid_clock[CLOCK_COUNT])
    it, ft = 0, 0.0
    if nt > 1:
        q = max(t, 0.0) / water.grid_clock[CLOCK_DT]
        whole = np.floor(q)
        it, ft = (int(whole) + 1) % nt, q - whole
    t0 = max(it - 1, 0)
    values = water.grid_u
    for cx in range(2):
        jx, wx, sx = (ix, fx, dx) if cx == 1 else (max(ix - 1, 0), 1.0 - fx, -dx)
        for cy in range(2):
            jy, wy, sy = (iy, fy, dy) if cy == 1 else (max(iy - 1, 0), 1.0 - fy, -dy)
            for cz in range(2):
                jz, wz, sz = (iz, fz, dz) if cz == 1 else (max(iz - 1, 0), 1.0 - fz, -dz)
                for i in range(3):
                    value = values[jx, jy, jz, t0, i] * (1.0 - ft) + values[jx, jy, jz, it, i] * ft
                    u[i] += wx * wy * wz * value
                    if gradients:
                        du[i, 0] += sx * wy * wz * value
                        du[i, 1] += wx * sy * wz * value
                        du[i, 2] += wx * wy * sz * value
