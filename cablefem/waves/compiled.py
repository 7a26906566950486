"""The compiled face of the wave kinematics (numba): ``water_at`` is ``cablefem.waves.airy.kinematics``
at one point, for the load kernels (``cablefem.compiled.kernels`` fills the point's context with it).

A sea enters the compiled code as a ``Water`` tuple of arrays (``water_of``): its kind (``NONE``: no
waves, the tuple every line without waves gets; ``COMPONENTS``), its settings (depth, stretching,
ramp), its components (m, 7: A, omega, k, cos beta, sin beta, phi, 1 / (1 - e^{-2kh})) and a
scratch row per component (cos theta, sin theta of the first pass, read by the second).
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
AMPLITUDE, OMEGA, NUMBER, COS, SIN, PHASE, SCALE = range(7)

Water = namedtuple("Water", "kind settings components scratch")


def no_water():
    """The Water of a line without waves (kind NONE, empty arrays of the same types)."""
    return Water(NONE, np.zeros(3), np.zeros((0, 7)), np.zeros((0, 2)))


def water_of(sea):
    """The Water of a ``cablefem.waves.sea.Sea`` (None: no waves)."""
    if sea is None:
        return no_water()
    from cablefem.waves.sea import STRETCHING as CODES

    amplitude, omega, k, cos_b, sin_b, phase = sea.arrays
    with np.errstate(divide="ignore"):
        scale = np.where(k > 0.0, 1.0 / (1.0 - np.exp(-2.0 * k * sea.depth)), 0.0)
    components = np.ascontiguousarray(np.stack((amplitude, omega, k, cos_b, sin_b, phase, scale), axis=1))
    settings = np.array([sea.depth, float(CODES.index(sea.stretching)), sea.ramp])
    return Water(COMPONENTS, settings, components, np.zeros((len(amplitude), 2)))


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
    for j in range(comps.shape[0]):
        c, s, k, w = comps[j, COS], comps[j, SIN], comps[j, NUMBER], comps[j, OMEGA]
        first = np.exp(k * zs)
        second = np.exp(-k * (zs + 2.0 * depth))
        speed = comps[j, AMPLITUDE] * w * comps[j, SCALE]
        P, Q = speed * (first + second), speed * (first - second)
        cs, sn = scratch[j, 0], scratch[j, 1]
        Pc, Qs = P * cs, Q * sn
        u[0] += Pc * c
        u[1] += Pc * s
        u[2] += Qs
        a[0] += w * P * sn * c
        a[1] += w * P * sn * s
        a[2] -= w * Q * cs
        if not gradients:
            continue
        # theta-derivatives times k along the heading e = (c, s, 0); z'-derivatives times k
        hu, vu, ha, va = -k * P * sn, k * Q * cs, k * w * P * cs, k * w * Q * sn
        du[0, 0] += hu * c * c
        du[0, 1] += hu * c * s
        du[1, 0] += hu * s * c
        du[1, 1] += hu * s * s
        du[2, 0] += vu * c
        du[2, 1] += vu * s
        da[0, 0] += ha * c * c
        da[0, 1] += ha * c * s
        da[1, 0] += ha * s * c
        da[1, 1] += ha * s * s
        da[2, 0] += va * c
        da[2, 1] += va * s
        uzx += vu * c
        uzy += vu * s
        uzz += k * P * sn
        azx += va * c
        azy += va * s
        azz -= k * w * P * cs
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
    return eta, z <= eta
