"""Prescribed fairlead motions: fixed, harmonic, circular and tabulated (DESIGN.md [motion]).

A motion gives the displacement of the fairlead from its scene position, and
its velocity and acceleration, at time t. The whole displacement (offset
included) is scaled by the smoothstep ramp S(u) = 3u^2 - 2u^3, u = t/ramp,
so a run starts at rest from the static solution of the undisplaced scene;
the velocity and acceleration follow by the product rule.
"""

import numpy as np

_PLANE_AXES = {"xy": (0, 1), "xz": (0, 2), "yz": (1, 2), "yx": (1, 0), "zx": (2, 0), "zy": (2, 1)}


def _ramp(t, ramp):
    """Smoothstep S(t/ramp) and its first two time derivatives."""
    if ramp <= 0.0 or t >= ramp:
        return 1.0, 0.0, 0.0
    if t <= 0.0:
        return 0.0, 0.0, 0.0
    u = t / ramp
    return 3 * u**2 - 2 * u**3, (6 * u - 6 * u**2) / ramp, (6 - 12 * u) / ramp**2


def _raw(motion, t):
    """Unramped displacement, velocity, acceleration (3,) of ``motion`` at time t [s]."""
    kind = motion.kind
    zero = np.zeros(3)
    if kind == "fixed":
        return zero, zero, zero
    if kind in ("harmonic", "circular"):
        omega = 2.0 * np.pi / motion.period
        if kind == "harmonic":
            amplitude = np.asarray(motion.amplitude, dtype=float)
            offset = np.asarray(motion.offset, dtype=float)
            s, c = np.sin(omega * t), np.cos(omega * t)
            return offset + amplitude * s, amplitude * omega * c, -amplitude * omega**2 * s
        i, j = _PLANE_AXES[motion.plane]
        d, v, a = zero.copy(), zero.copy(), zero.copy()
        offset = np.asarray(motion.offset, dtype=float)
        R = motion.radius
        s, c = np.sin(omega * t), np.cos(omega * t)
        d[i], d[j] = R * s, R * c
        v[i], v[j] = R * omega * c, -R * omega * s
        a[i], a[j] = -R * omega**2 * s, -R * omega**2 * c
        return offset + d, v, a
    if kind == "table":
        return _table(motion.times, motion.positions, t)
    raise ValueError(f"unknown motion kind {kind!r}")


def _table(times, positions, t):
    """Piecewise-linear position from a table, its slope, and zero acceleration (held at the ends)."""
    if t <= times[0]:
        return positions[0].copy(), np.zeros(3), np.zeros(3)
    if t >= times[-1]:
        return positions[-1].copy(), np.zeros(3), np.zeros(3)
    k = int(np.searchsorted(times, t, side="right")) - 1
    h = times[k + 1] - times[k]
    slope = (positions[k + 1] - positions[k]) / h
    return positions[k] + (t - times[k]) * slope, slope, np.zeros(3)


def fairlead_motion(motion, t):
    """Ramped displacement [m], velocity [m/s] and acceleration [m/s^2] (each (3,)) at time t [s]."""
    d, v, a = _raw(motion, t)
    S, dS, ddS = _ramp(t, motion.ramp)
    return S * d, S * v + dS * d, S * a + 2 * dS * v + ddS * d
