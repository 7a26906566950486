"""Airy kinematics written out from the textbook (Dean & Dalrymple 1991, Table 4.1), independently
of ``cablefem.waves``: cosh and sinh as they are written, the wave number from scipy's root finder,
the stretched height from its definition. The study compares cablefem's kinematics with these."""

from functools import lru_cache

import numpy as np
from scipy.optimize import brentq


@lru_cache(maxsize=None)
def wave_number(omega, depth, gravity):
    """k [1/m] of omega^2 = g k tanh(k h), by bracketing (brentq)."""
    return brentq(lambda k: gravity * k * np.tanh(k * depth) - omega ** 2, 1e-12, 10.0 * omega ** 2 / gravity + 10.0,
                  xtol=1e-15, rtol=1e-15)


def sea_at(components, depth, gravity, stretching, point, t):
    """eta, u (3,), a (3,) at ``point`` (3,) and time t of components [(A, omega, beta, phi), ...]."""
    x, y, z = point
    parts = []
    for A, omega, beta, phi in components:
        k = wave_number(omega, depth, gravity)
        parts.append((A, omega, k, beta, k * (x * np.cos(beta) + y * np.sin(beta)) - omega * t + phi))
    eta = sum(A * np.cos(theta) for A, _, _, _, theta in parts)
    if stretching == "wheeler":
        zs = min(depth * (z - eta) / (depth + eta), 0.0)
    elif stretching == "vertical":
        zs = min(z, 0.0)
    else:
        zs = z
    zs = max(zs, -depth)
    u, a = np.zeros(3), np.zeros(3)
    for A, omega, k, beta, theta in parts:
        ch = np.cosh(k * (zs + depth)) / np.sinh(k * depth)
        sh = np.sinh(k * (zs + depth)) / np.sinh(k * depth)
        heading = np.array([np.cos(beta), np.sin(beta), 0.0])
        u += A * omega * ch * np.cos(theta) * heading + np.array([0.0, 0.0, A * omega * sh * np.sin(theta)])
        a += A * omega ** 2 * ch * np.sin(theta) * heading - np.array([0.0, 0.0, A * omega ** 2 * sh * np.cos(theta)])
    return eta, u, a
