"""A current given on a grid in x, y, z and time (MoorDyn-C's ``Currents 2`` and ``5``), interpolated as
MoorDyn-C interpolates it (``Waves.cpp`` ``CurrentGrid::getCurrentKin``, ``Util/Interp.hpp``): the numpy
face; ``cablefem.waves.compiled`` has the compiled one.

The grid holds the velocity U (nx, ny, nz, nt, 3) [m/s] at the axes' points x (nx,), y (ny,), z (nz,)
[m] and at the times i dt, i = 0 .. nt - 1 (MoorDyn-C resamples a file's times onto that clock, dt the
smallest interval of the file). In each space axis the interpolation is linear between the two points
around the coordinate and holds the end values beyond the axis (an axis of one point is constant). In
time it takes the interval [i dt, (i + 1) dt) of i = floor(t / dt) and the upper point i + 1, counted
modulo nt (``while (it > nt - 1) it -= nt``): the record repeats with period nt dt, and over its last
interval [(nt - 1) dt, nt dt) the velocity is the first sample's. The heights are not stretched with
the waves (MoorDyn-C: "TODO - current stretching?"), and the current's acceleration is zero, as
MoorDyn-C sets it (its "TODO: approximate fluid accelerations"): the current drags, and its time
variation adds no fluid inertia.

The velocity is piecewise multilinear in x, y and z, so its gradient dU/dx (n, 3, 3) is exact within a
cell (the Morison load's tangent) and jumps across cell faces.
"""

from dataclasses import dataclass
from itertools import product

import numpy as np


@dataclass(frozen=True, eq=False)
class CurrentGrid:
    """The axes x, y, z (each (k,), increasing) [m], the clock's step ``dt`` [s] and the velocity (nx,
    ny, nz, nt, 3) [m/s]; ``kind`` (what it was read from) and ``source`` (its file)."""

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    dt: float
    velocity: np.ndarray
    kind: str = "grid"
    source: str = ""

    def at(self, points, t, gradients=False):
        """The velocity (n, 3) [m/s] at points (n, 3) [m] and time t [s] (a number or (n,)); with
        ``gradients`` also dU/dx (n, 3, 3), [i, j] = d U_i / d x_j."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        n = len(points)
        axes = [factors(axis, points[:, j]) for j, axis in enumerate((self.x, self.y, self.z))]
        upper, fraction = time_factors(self.dt, self.velocity.shape[3], np.broadcast_to(t, (n,)))
        lower = np.maximum(upper - 1, 0)
        U = np.zeros((n, 3))
        G = np.zeros((n, 3, 3)) if gradients else None
        for corner in product((0, 1), repeat=3):
            index, weight, slope = [], np.ones(n), np.ones((n, 3))
            for j, ((hi, f, df), c) in enumerate(zip(axes, corner)):
                index.append(hi if c else np.maximum(hi - 1, 0))
                w, dw = (f, df) if c else (1.0 - f, -df)
                slope *= np.where(np.arange(3) == j, dw[:, None], w[:, None])
                weight = weight * w
            value = (self.velocity[index[0], index[1], index[2], lower] * (1.0 - fraction)[:, None]
                     + self.velocity[index[0], index[1], index[2], upper] * fraction[:, None])
            U += weight[:, None] * value
            if gradients:
                G += value[:, :, None] * slope[:, None, :]
        return U, G

    def describe(self):
        """What the grid is, for summary.json."""
        return {"kind": self.kind, "grid_points": list(self.velocity.shape[:4]), "dt": self.dt,
                **({"source": self.source} if self.source else {})}


def factors(axis, x):
    """MoorDyn-C's ``interp_factor`` at coordinates x (n,) on ``axis`` (k,): the upper point's index
    (n,), the fraction f (n,) towards it, and df/dx (n,) [1/m] (0 where the end values are held)."""
    n, k = len(x), len(axis)
    if k == 1:
        return np.zeros(n, dtype=np.int64), np.zeros(n), np.zeros(n)
    upper = np.clip(np.searchsorted(axis, x, side="left"), 1, k - 1)
    width = axis[upper] - axis[upper - 1]
    fraction, slope = (x - axis[upper - 1]) / width, 1.0 / width
    below, above = x <= axis[0], x >= axis[-1]
    beyond = below | above
    upper = np.where(below, 1, np.where(above, k - 1, upper))
    return upper, np.where(below, 0.0, np.where(above, 1.0, fraction)), np.where(beyond, 0.0, slope)


def time_factors(dt, nt, t):
    """The upper sample's index (n,) and the fraction (n,) towards it at times t (n,) [s] (the module
    docstring: the record repeats with period nt dt)."""
    if nt == 1:
        return np.zeros(len(t), dtype=np.int64), np.zeros(len(t))
    q = np.maximum(np.asarray(t, dtype=float), 0.0) / dt
    whole = np.floor(q)
    return (whole.astype(np.int64) + 1) % nt, q - whole
