"""Prescribed fairlead motions: fixed, harmonic, circular and tabulated (docs/scene.md, [motion]).

A motion gives the displacement of the fairlead from its scene position, and
its velocity and acceleration, at time t; a table's rows are joined by a
quintic spline (velocity and acceleration are its derivatives, ``table_spline``). The whole displacement (offset
included) is scaled by the smoothstep ramp S(u) = 3u^2 - 2u^3, u = t/ramp,
so a run starts at rest from the static solution of the undisplaced scene;
the velocity and acceleration follow by the product rule.
"""

import numpy as np

_PLANE_AXES = {"xy": (0, 1), "xz": (0, 2), "yz": (1, 2), "yx": (1, 0), "zx": (2, 0), "zy": (2, 1)}


def _ramp(t, ramp):
    """Smoothstep S(t/ramp) and its first two time derivatives at the times t (n,)."""
    if ramp <= 0.0 or t.min() >= ramp:
        return np.ones_like(t), np.zeros_like(t), np.zeros_like(t)
    u = np.minimum(np.maximum(t / ramp, 0.0), 1.0)
    inside = (t > 0.0) & (t < ramp)
    return (3 * u**2 - 2 * u**3, np.where(inside, (6 * u - 6 * u**2) / ramp, 0.0),
            np.where(inside, (6 - 12 * u) / ramp**2, 0.0))


def _raw(motion, t):
    """Unramped displacement, velocity, acceleration (n, 3) of ``motion`` at the times t (n,) [s]."""
    kind = motion.kind
    zero = np.zeros((t.size, len(motion.offset)))
    if kind == "fixed":
        return zero, zero, zero
    if kind in ("harmonic", "circular"):
        omega = 2.0 * np.pi / motion.period
        offset = np.asarray(motion.offset, dtype=float)
        if len(motion.phase):  # per component [rad]
            angle = omega * t[:, None] + np.asarray(motion.phase, dtype=float)
            s, c = np.sin(angle), np.cos(angle)
        else:
            s, c = np.sin(omega * t)[:, None], np.cos(omega * t)[:, None]
        if kind == "harmonic":
            amplitude = np.asarray(motion.amplitude, dtype=float)
            return offset + amplitude * s, amplitude * omega * c, -amplitude * omega**2 * s
        i, j = _PLANE_AXES[motion.plane]
        d, v, a = zero.copy(), zero.copy(), zero.copy()
        R = motion.radius
        d[:, i], d[:, j] = R * s[:, 0], R * c[:, 0]
        v[:, i], v[:, j] = R * omega * c[:, 0], -R * omega * s[:, 0]
        a[:, i], a[:, j] = -R * omega**2 * s[:, 0], -R * omega**2 * c[:, 0]
        return offset + d, v, a
    if kind == "table":
        return table_kinematics(motion, t)
    raise ValueError(f"unknown motion kind {kind!r}")


def table_kinematics(motion, t):
    """Positions from a table, smooth between its rows (``table_spline``; with ``interpolation =
    "linear"`` straight lines, ``_linear``), their first and second time derivatives, at the times
    t (n,); before the first row and after the last the fairlead stays there (velocity and
    acceleration zero)."""
    if motion.interpolation == "linear":
        return _linear(np.asarray(motion.times, dtype=float), np.asarray(motion.positions, dtype=float), t)
    times, spline = table_spline(motion)
    inside = np.clip(t, times[0], times[-1])
    d, v, a = spline(inside), spline(inside, 1), spline(inside, 2)
    outside = (t < times[0]) | (t > times[-1])
    v[outside], a[outside] = 0.0, 0.0
    return d, v, a


def _linear(times, positions, t):
    """Piecewise-linear positions from a table, their slopes, and zero accelerations (held at the
    ends), at the times t (n,): the velocity jumps at every row (a dead stop, on purpose)."""
    k = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2)
    slope = (positions[k + 1] - positions[k]) / (times[k + 1] - times[k])[:, None]
    before, after = t <= times[0], t >= times[-1]
    slope[before | after] = 0.0
    d = positions[k] + (t - times[k])[:, None] * slope
    d[before], d[after] = positions[0], positions[-1]
    return d, slope, np.zeros_like(d)


#: degree of the spline through a motion table's rows: quintic (C4; for a row spacing h the
#: positions' error is O(h^6), the accelerations' O(h^4)). A cubic spline (C2, accelerations O(h^2))
#: was measured first: the flume's 5 m / 6 s harmonic surge as a table of 0.5 s rows, 18 s,
#: gave a largest fairlead tension 0.29 % below the harmonic run's and a largest step-to-step jump
#: 1.9 % above it (the snap's, its accelerations 2 % off); the quintic 0.012 % and 0.009 % below
#: (tests/test_motion_table.py). Linear rows with zero acceleration had 82 % and 17x.
TABLE_DEGREE = 5

_SPLINES = {}  # id(motion) -> (motion, its times, its spline): a table's spline is built once


def table_spline(motion):
    """(times (k,), spline) of a table motion: scipy's ``make_interp_spline`` through its rows,
    ``TABLE_DEGREE`` or the highest odd degree its rows allow (cubic with 4 or 5 rows, linear with
    2 or 3), with scipy's not-a-knot ends; ``spline(t, n)`` is its n-th derivative. Built once per
    motion."""
    hit = _SPLINES.get(id(motion))
    if hit is None or hit[0] is not motion:
        from scipy.interpolate import make_interp_spline

        times = np.asarray(motion.times, dtype=float)
        degree = min(TABLE_DEGREE, len(times) - 1)
        degree -= degree % 2 == 0  # odd: the rows are the knots
        if len(_SPLINES) > 32:  # many scenes in one process (a sweep's worker): keep a few
            _SPLINES.clear()
        spline = make_interp_spline(times, np.asarray(motion.positions, dtype=float), k=degree, axis=0)
        hit = _SPLINES[id(motion)] = (motion, times, spline)
    return hit[1], hit[2]


def body_motion(motion, t):
    """A coupled body's ramped displacement (x, y, z [m], roll, pitch, yaw [rad]), velocity and
    acceleration at time t: each (6,), or (n, 6) for times (n,) (``fairlead_motion`` with six
    components; harmonic components may have phases)."""
    return fairlead_motion(motion, t)


def fairlead_motion(motion, t):
    """Ramped displacement [m], velocity [m/s] and acceleration [m/s^2] at time t [s]: each (3,)
    for a scalar t, (n, 3) for times t (n,)."""
    times = np.array(t, dtype=float, ndmin=1)
    d, v, a = _raw(motion, times)
    S, dS, ddS = _ramp(times, motion.ramp)
    S, dS, ddS = S[:, None], dS[:, None], ddS[:, None]
    d, v, a = S * d, S * v + dS * d, S * a + 2 * dS * v + ddS * d
    return (d[0], v[0], a[0]) if np.ndim(t) == 0 else (d, v, a)


class FairleadPath:
    """The fairlead's prescribed path: path(t) -> (position, velocity, acceleration), each (3,);
    path.positions(times) -> positions (m, 3), in one vectorised call."""

    def __init__(self, motion, fairlead):
        self.motion = motion
        self.fairlead = np.asarray(fairlead, dtype=float)

    def __call__(self, t):
        d, v, a = fairlead_motion(self.motion, t)
        return self.fairlead + d, v, a

    def positions(self, times):
        return self.fairlead + fairlead_motion(self.motion, times)[0]
