"""The current at a point: uniform, or a depth profile U(z) (MoorDyn-C's ``Currents = 1``).

A ``CurrentProfile`` holds heights z_0 < z_1 < ... < z_k-1 [m] (z = 0 the still water surface) and
the current U_i (3,) [m/s] at each. Between two heights U is linear in z; below the lowest and above
the highest it keeps the end value, as MoorDyn-C interpolates its current grid
(``Util/Interp.hpp``: ``interp_factor`` clamps, ``lerp`` is a (1 - f) + b f). dU/dz is the slope of
the piece (zero beyond the ends; at a height z_i the piece below it), which the drag loads' tangents
need (``cablefem.loads.drag``, ``cablefem.loads.points``).

Both faces: ``CurrentProfile.at`` (numpy) and ``current_at`` (compiled, reading the fixed-size arrays
of a load's parameters: at most ``MAX_HEIGHTS`` heights, after dropping heights where the profile
is straight, which changes no value beyond round-off).
"""

from dataclasses import dataclass

import numpy as np
from numba import njit

from cablefem.errors import InputError

#: heights a profile may keep in the compiled parameters (each element's record holds them)
MAX_HEIGHTS = 32


def _straight(z, U, i):
    """Whether height i lies on the straight piece through its neighbours (round-off allowed)."""
    f = (z[i] - z[i - 1]) / (z[i + 1] - z[i - 1])
    line = U[i - 1] * (1.0 - f) + U[i + 1] * f
    return np.all(np.abs(line - U[i]) <= 1e-12 * max(1.0, float(np.abs(U).max())))


@dataclass(frozen=True)
class CurrentProfile:
    """Heights z (k,) [m], strictly increasing, and the current (k, 3) [m/s] at each (tuples, so that
    a scene stays hashable); ``source``: where it was read, for messages."""

    z: tuple
    velocity: tuple
    source: str = ""

    @classmethod
    def from_arrays(cls, z, velocity, key, source=""):
        """A checked profile from heights (k,) and velocities (k, 3) (or (k, 1), (k, 2): the missing
        components zero, as MoorDyn reads ux [uy [uz]]); InputError naming ``key`` otherwise."""
        z = np.asarray(z, dtype=float)
        velocity = np.asarray(velocity, dtype=float)
        if velocity.ndim == 1:
            velocity = velocity[:, None]
        if z.ndim != 1 or len(z) == 0 or velocity.shape[0] != len(z) or not 1 <= velocity.shape[1] <= 3:
            raise InputError(f"expected k heights and k velocities of 1 to 3 components, got {z.shape} "
                             f"heights and {velocity.shape} velocities", key=key)
        if not (np.all(np.isfinite(z)) and np.all(np.isfinite(velocity))):
            raise InputError("heights and velocities must be finite", key=key)
        bad = np.flatnonzero(np.diff(z) <= 0.0)
        if len(bad):
            raise InputError(f"heights must strictly increase (bottom first): z = {z[bad[0] + 1]:g} after "
                             f"z = {z[bad[0]]:g}", key=key)
        velocity = np.pad(velocity, ((0, 0), (0, 3 - velocity.shape[1])))
        keep = [0] + [i for i in range(1, len(z) - 1) if not _straight(z, velocity, i)] + [len(z) - 1]
        keep = sorted(set(keep))
        if len(keep) > MAX_HEIGHTS:
            raise InputError(f"{len(keep)} heights where the profile bends; cablefem keeps at most "
                             f"{MAX_HEIGHTS}: resample it to fewer heights", key=key)
        return cls(tuple(float(x) for x in z[keep]), tuple(tuple(float(c) for c in u) for u in velocity[keep]),
                   source)

    def arrays(self):
        """Heights (k,) and velocities (k, 3) as arrays."""
        return np.array(self.z), np.array(self.velocity).reshape(-1, 3)

    def at(self, z):
        """U (3, ...) [m/s] and dU/dz (3, ...) [1/s] at heights z (...) [m]."""
        heights, velocity = self.arrays()
        z = np.asarray(z, dtype=float)
        n = len(heights)
        if n == 1:
            U = np.broadcast_to(velocity[0].reshape((3,) + (1,) * z.ndim), (3,) + z.shape).copy()
            return U, np.zeros_like(U)
        i = np.clip(np.searchsorted(heights, z, side="left"), 1, n - 1)  # first height >= z
        width = heights[i] - heights[i - 1]
        f = (z - heights[i - 1]) / width
        below, above = z <= heights[0], z >= heights[-1]
        f = np.where(below, 0.0, np.where(above, 1.0, f))
        lower, upper = np.moveaxis(velocity[i - 1], -1, 0), np.moveaxis(velocity[i], -1, 0)
        U = lower * (1.0 - f) + upper * f
        slope = np.where(below | above, 0.0, (upper - lower) / width)
        return U, slope

    def params(self, count):
        """The compiled face's fields for ``count`` elements or points: number of heights (count,),
        heights (count, MAX_HEIGHTS) and velocities (count, MAX_HEIGHTS, 3), padded with zeros."""
        heights, velocity = self.arrays()
        n = len(heights)
        z = np.zeros(MAX_HEIGHTS)
        U = np.zeros((MAX_HEIGHTS, 3))
        z[:n], U[:n] = heights, velocity
        return {"profile_n": np.full(count, n, dtype=np.int64), "profile_z": np.tile(z, (count, 1)),
                "profile_u": np.tile(U, (count, 1, 1))}


#: the compiled parameters of a profile (a load with a current adds them to its LoadSpec)
PROFILE_FIELDS = (("profile_n", "i8"), ("profile_z", "f8", (MAX_HEIGHTS,)), ("profile_u", "f8", (MAX_HEIGHTS, 3)))


def no_profile(count):
    """The profile fields of a uniform current (no heights) for ``count`` elements or points."""
    return {"profile_n": np.zeros(count, dtype=np.int64), "profile_z": np.zeros((count, MAX_HEIGHTS)),
            "profile_u": np.zeros((count, MAX_HEIGHTS, 3))}


@njit(cache=True, _nrt=False)
def current_at(z, n, heights, velocity, U, slope):
    """The compiled face: U(z) into ``U`` (3,) and dU/dz into ``slope`` (3,) from a profile of ``n``
    heights (``CurrentProfile.at``)."""
    if n == 1 or z <= heights[0]:
        for a in range(3):
            U[a], slope[a] = velocity[0, a], 0.0
        return
    if z >= heights[n - 1]:
        for a in range(3):
            U[a], slope[a] = velocity[n - 1, a], 0.0
        return
    i = 1
    while z > heights[i]:
        i += 1
    width = heights[i] - heights[i - 1]
    f = (z - heights[i - 1]) / width
    for a in range(3):
        U[a] = velocity[i - 1, a] * (1.0 - f) + velocity[i, a] * f
        slope[a] = (velocity[i, a] - velocity[i - 1, a]) / width


@njit(cache=True, inline="always", _nrt=False)
def relative_water(ctx, n, uniform, heights, velocity, current, slope, w):
    """In waves: the water's velocity relative to the point, w = U(z) + u_w - v, into ``w`` (3,), with the
    current U (``uniform`` (3,) when ``n`` is 0, else the profile's) into ``current`` and dU/dz into
    ``slope`` (zero for a uniform current); u_w, v and z are the context's (``cablefem.compiled.kernels``)."""
    slope[0], slope[1], slope[2] = 0.0, 0.0, 0.0
    if n == 0:
        for a in range(3):
            current[a] = uniform[a]
    else:
        current_at(ctx.r[2], n, heights, velocity, current, slope)
    for a in range(3):
        w[a] = current[a] + ctx.water_u[a] - ctx.v[a]
