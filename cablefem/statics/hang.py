"""The start shape of a line with one free end: where it hangs (a pendulum's line, a lifted mass,
a string ending at a free point that nothing else holds; ``cablefem.statics.start_shape``).

In statics there is no drag, so a line whose only support is one prescribed end carries nothing
sideways: its weight and the weight of its points (clump weights, the mass on its free end) hang
straight down from that end, each piece stretched by the tension of what hangs below it,
T(u) = int_u^L w du' + sum of the points' weights below u (u the unstretched distance from the
held end, w the submerged weight per length). That is the equilibrium itself when the line does
not reach the seabed (Newton then only removes the round-off). Where it would reach the seabed the
rest of it lies on the seabed from the foot of the hang, downhill (on a level seabed towards where
the scene puts the free end): a start from which Newton slides the lying part to its rest; or, when
the points on its free end carry more than the line weighs, straight from the held end to where
the end rests downhill at the hang's length (a weightless line holding a mass on a slope). A line
whose every part is pulled up by what lies beyond it (a tether to a float) rises the same way, in
the mirror of the level where its buoyant part floats, and lies along that level.

The given position of the free end plays no part: MoorDyn's files put a free point anywhere, and a
start at the given point with the line's points carried by continuation from none is a mechanism
(a weightless line with nothing on its free end swings freely), which Newton cannot solve.
"""

from dataclasses import replace

import numpy as np

from cablefem.geometry import Plane

#: the horizontal distance [m] over which the seabed's downhill direction is measured, as a
#: fraction of the line's length
SLOPE_STEP = 1e-3


def free_end(line):
    """Which end of ``line`` is free (0 anchor, 1 fairlead) when exactly one is, else None."""
    if line.prescribed == (True, False):
        return 1
    if line.prescribed == (False, True):
        return 0
    return None


def hanging_tension(line, environment):
    """(pieces, T) of a line hanging from its held end: per segment from the held end, its
    (start u [m], length [m], submerged weight w [N/m], EA [N]) and the tension T [N] just below its
    start (what hangs below: the segments' weight and the points' weight less their buoyancy)."""
    rho, g = environment.water_density, environment.gravity
    segments = list(line.segments)
    joints = {k: joint for k, joint in line.joints}
    bounds = list(range(len(segments) + 1))  # boundary k: between segments k - 1 and k
    if free_end(line) == 0:  # hang from the fairlead: walk the segments backwards
        segments, bounds = segments[::-1], bounds[::-1]
    weights = [seg.type.submerged_weight(rho, g) for seg in segments]
    point = [0.0 if b not in joints else joints[b].mass * g - rho * g * joints[b].volume for b in bounds]
    below = np.zeros(len(segments))  # tension just below the start of each segment
    total = point[-1]
    for i in range(len(segments) - 1, -1, -1):
        total += weights[i] * segments[i].length
        below[i] = total
        total += point[i] if i > 0 else 0.0  # the held end's own point loads its support, not the line
    starts = np.concatenate([[0.0], np.cumsum([seg.length for seg in segments])[:-1]])
    pieces = [(starts[i], seg.length, weights[i], seg.type.EA) for i, seg in enumerate(segments)]
    return pieces, below


def free_hang(line, seabed, environment, level=-np.inf):
    """Positions (a function of arc length s (n,) -> (n, 3)) of ``line`` hanging from its held end
    (the module docstring), or rising from it when all below each point pulls up, to ``level``
    [m] where its buoyant part floats (``start_shape.float_level``) and along it; None when it
    does neither: both or neither end held, a pull both ways, the held end on or below the seabed
    (or above the level)."""
    free = free_end(line)
    if free is None:
        return None
    pieces, below = hanging_tension(line, environment)
    if _pulls(pieces, below):
        return _hang(line, seabed, free, pieces, below)
    up = [(start, piece, -w, EA) for start, piece, w, EA in pieces]
    if not (_pulls(up, -below) and np.isfinite(level)):
        return None
    mirror, shift = np.array([1.0, 1.0, -1.0]), np.array([0.0, 0.0, 2.0 * level])
    mirrored = replace(line, anchor=shift + mirror * line.anchor, fairlead=shift + mirror * line.fairlead)
    positions = _hang(mirrored, Plane((0.0, 0.0, level), (0.0, 0.0, 1.0)), free, up, -below)
    return None if positions is None else (lambda s: shift + mirror * positions(s))


def _pulls(pieces, below):
    """Whether every point of the line is pulled down by what hangs below it (``hanging_tension``)."""
    lowest = [T - w * length for (_, length, w, _), T in zip(pieces, below)]  # the tension at each segment's end
    return below[0] > 0.0 and min(np.min(below), np.min(lowest)) >= 0.0


def _hang(line, seabed, free, pieces, below):
    """Positions (a function of arc length) of the hang (``free_hang``), or None with the held end
    on or below the seabed."""
    top = line.fairlead if free == 0 else line.anchor
    given = line.anchor if free == 0 else line.fairlead
    length = line.unstretched_length
    height = float(top[2] - seabed.elevation(top[:2][None])[0])
    if height <= 1e-9 * length:
        return None

    def depth(u):
        """Depth below the held end [m] of the points at distance u (n,) [m] down the hang."""
        out = np.zeros_like(u)
        for (start, piece, w, EA), T in zip(pieces, below):
            d = np.clip(u - start, 0.0, piece)
            out += d + (T * d - 0.5 * w * d * d) / EA
        return out

    reach = _reach(depth, height, length)
    lie = _downhill(seabed, top, given, length)
    if reach < length and below[0] >= 2.0 * sum(max(w, 0.0) * piece for _, piece, w, _ in pieces):
        return _taut(seabed, top, lie, float(depth(np.array([length]))[0]), free, length)

    def positions(s):
        u = np.asarray(s, dtype=float) if free == 1 else length - np.asarray(s, dtype=float)
        out = np.repeat(top[None, :], u.size, axis=0)
        hanging = u <= reach
        out[hanging, 2] -= depth(u[hanging])
        lying = ~hanging
        out[lying, :2] += (u[lying] - reach)[:, None] * lie
        out[lying, 2] = seabed.elevation(out[lying, :2])
        return out

    return positions


def _taut(seabed, top, lie, stretched, free, length):
    """Positions (a function of arc length) of a line held taut by the points on its free end,
    which rests on the seabed: straight from ``top`` (3,) to the point downhill (``lie`` (2,)) at
    the hang's stretched length ``stretched`` [m] from it."""
    def end(t):
        xy = top[:2] + t * lie
        return np.array([xy[0], xy[1], seabed.elevation(xy[None])[0]])

    low, high = 0.0, stretched
    for _ in range(80):  # the distance from the top grows as the end moves downhill
        mid = 0.5 * (low + high)
        low, high = (mid, high) if np.linalg.norm(end(mid) - top) < stretched else (low, mid)
    bottom = end(low)

    def positions(s):
        u = np.asarray(s, dtype=float) if free == 1 else length - np.asarray(s, dtype=float)
        return top + (u / length)[:, None] * (bottom - top)

    return positions


def _reach(depth, height, length):
    """The distance [m] down the hang at which it meets the seabed ``height`` [m] below the held
    end (``length`` when it does not)."""
    if depth(np.array([length]))[0] <= height:
        return length
    low, high = 0.0, length
    for _ in range(80):  # depth rises monotonically with u
        mid = 0.5 * (low + high)
        low, high = (mid, high) if depth(np.array([mid]))[0] < height else (low, mid)
    return low


def _downhill(seabed, top, given, length):
    """The horizontal unit direction (2,) downhill on the seabed below ``top`` (3,); on a level
    seabed towards ``given`` (3,) (x when it is straight below)."""
    h = SLOPE_STEP * length
    xy = top[:2] + h * np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])
    z = seabed.elevation(xy)
    slope = -np.array([z[0] - z[1], z[2] - z[3]]) / (2.0 * h)
    norm = float(np.linalg.norm(slope))
    if norm > 1e-6:
        return slope / norm
    towards = given[:2] - top[:2]
    norm = float(np.linalg.norm(towards))
    return towards / norm if norm > 1e-9 * length else np.array([1.0, 0.0])
