"""Starting shapes of a static solve: where Newton begins (desire2023 Sec. 2.3).

Newton starts from a shape close to the answer and never from the straight chord, which converges
to the inverse catenary (desire2023 Fig. 5). Three shapes, by what the line is:

- **A line that needs its length** (taut, or touching down with a horizontal pull): the elastic
  catenary in the vertical plane of anchor and fairlead, on the seabed's slope when the anchor lies
  on a plane (``cablefem.statics.catenary``), lifted onto the seabed where it would be buried.
- **A line longer than it needs** (the catenary's slack regime, H = 0: more than enough to hang from
  the fairlead to the seabed and lie to the anchor, or anchor and fairlead at one point): on a
  frictionless seabed the surplus lies slack with zero tension in any shape. It is laid here as
  the physics allows and without two points at one place: the line drops vertically from an end
  above the seabed to the seabed, lies along a circular arc in the seabed's plane from the foot
  under the anchor to the foot under the fairlead, and rises vertically to the fairlead, each
  vertical part stretched by its own weight. The arc is at most a half circle over the feet
  (a full circle when the feet coincide, of circumference ``LOOP_FRACTION`` of the line); what
  it cannot hold is spread evenly along it as slack (a chain's links lie bunched: strain < 0,
  no force). Newton then only settles the ends: the lying part is already in equilibrium.
- **A buoyant line** (mean submerged weight < 0): the inverted catenary, hanging upwards, which is
  the catenary of the weight's magnitude mirrored in z.
- **A line with one free end** that hangs from its held end (``cablefem.statics.hang``): straight
  down, each piece stretched by what hangs below it, onto the seabed where it reaches it; the free
  end where the hang puts it, not where the scene gives it. A stiff cantilever, a bending line
  clamped at its held end whose load bends it little (``CANTILEVER``), starts straight along its
  clamp instead: its unloaded shape, from which Newton bends it in a few iterations, where from the
  hang it would have to swing the beam up through its clamp (MoorDyn's BeamCantilevered.txt at 38
  Hermite elements converged from the hang to a beam folded back at its clamp).

``initial_shape`` also says whether it laid out slack line: statics then skips the compressive
start (``cablefem.statics.newton``), which would push slack elements straight.
"""

import math

import numpy as np

from cablefem.fem import clamp
from cablefem.statics.catenary import elastic_catenary, inclined_catenary
from cablefem.geometry import Plane
from cablefem.statics.hang import free_end, free_hang, hanging_tension
from cablefem.model.line import Line
from cablefem.loads.gravity import submerged_fraction

#: circumference of the loop, as a fraction of the line, that the lying part takes when the feet
#: under anchor and fairlead coincide
LOOP_FRACTION = 0.1
#: a mean submerged weight below this fraction of the dry weight counts as neutral: the straight
#: chord is the start
NEUTRAL = 1e-9
#: a clamped bending line with one free end starts straight along its clamp when T L^2 / (3 EI) is
#: below this (T: the weight and points hanging from the clamp, EI the least along the line): the
#: small-deflection slope at the free end of a cantilever carrying T at its tip, in radians
CANTILEVER = 1.0


def mean_weight(line, environment):
    """Length-weighted mean submerged weight [N/m] and series axial stiffness EA [N] of a line."""
    pieces = np.array([seg.length for seg in line.segments])
    length = float(pieces.sum())
    weights = [seg.type.submerged_weight(environment.water_density, environment.gravity)
               for seg in line.segments]
    EA = float(length / np.sum(pieces / [seg.type.EA for seg in line.segments]))
    return float(pieces @ weights / length), EA


def initial_shape(system):
    """Starting state X (N, 3) of a static solve of ``system`` and whether it lays slack line."""
    line, fem = system.line, system.fem
    weight, EA = mean_weight(line, system.environment)
    hang = _hang(system)
    positions, slack = (hang, False) if hang is not None else _shape(system, weight, EA)
    X = fem.interpolate(positions)
    _rest_on_seabed(system, X, max(weight, 0.0))
    for dof, end, held in zip(fem.end_dofs, (line.anchor, line.fairlead), line.prescribed):
        if held or hang is None:  # a free end that hangs stays where the hang puts it
            X[dof] = end
    clamp.satisfy(system.clamps, X)
    return X, slack


def hangs(system):
    """Whether the start of ``system`` is the hang of a line with one free end (``free_hang``)."""
    return _hang(system) is not None


def _hang(system):
    """The hang (or rise) of a line with one free end (``free_hang``), or None. A line that bends
    rises straight: a float on a hinge stands above it (tripod.txt's), where lying along the level
    it floats at would bend it through a right angle at the start."""
    level = float_level(system.weight)
    line = system.line
    straight = _cantilever(system)
    if straight is not None:
        return straight
    if np.isfinite(level) and any(seg.type.EI > 0.0 for seg in line.segments):
        held = line.anchor if free_end(line) == 1 else line.fairlead
        level = max(level, float(held[2]) + 2.0 * line.unstretched_length)
    return free_hang(line, system.seabed, system.environment, level)


def _cantilever(system):
    """Positions (a function of arc length) of a stiff cantilever's start straight along its clamp
    (``CANTILEVER``), or None: a line that does not bend, has no free end, or is not clamped at its
    held end."""
    line = system.line
    free = free_end(line)
    if free is None or line.tangents[1 - free] is None:
        return None
    EI = min(seg.type.EI for seg in line.segments)
    if EI <= 0.0:
        return None
    _, below = hanging_tension(line, system.environment)
    length = line.unstretched_length
    if abs(below[0]) * length ** 2 / (3.0 * EI) >= CANTILEVER:
        return None
    direction = np.asarray(line.tangents[1 - free], dtype=float)
    direction = direction / np.linalg.norm(direction)
    held = line.anchor if free == 1 else line.fairlead
    along = 1.0 if free == 1 else -1.0  # r' points from the anchor to the fairlead

    def positions(s):
        u = np.asarray(s, dtype=float) if free == 1 else length - np.asarray(s, dtype=float)
        return held[None, :] + along * u[:, None] * direction[None, :]

    return positions


def _shape(system, weight, EA):
    """The start's positions (a function of arc length) and whether they lay slack line, for a line
    that does not hang from one end."""
    line, seabed = system.line, system.seabed
    dry = float(np.max(system.weight.dry))
    if weight > NEUTRAL * dry:
        positions = slack_layout(line, seabed, weight, EA, resting_sink(system, weight))
        if positions is not None:
            return positions, True
        return _catenary(line, seabed, weight, EA), False
    if weight < -NEUTRAL * dry:
        return _floating(line, system.weight, -weight, EA)
    return _chord(line), False


def _frame(line):
    """Unit horizontal direction u (3,) from anchor towards fairlead (x when they are above
    one another) and the horizontal span [m]."""
    chord = line.fairlead - line.anchor
    span = float(np.hypot(*chord[:2]))
    if span > 1e-9 * line.unstretched_length:
        return np.append(chord[:2] / span, 0.0), span
    return np.array([1.0, 0.0, 0.0]), 0.0


def _catenary(line, seabed, weight, EA):
    """Positions along the elastic catenary (a function of arc length (n,) -> (n, 3))."""
    anchor = line.anchor
    u, span = _frame(line)
    rise = float(line.fairlead[2] - anchor[2])
    length = line.unstretched_length
    on_seabed = abs(float(seabed.gap_only(anchor[None])[0])) <= 1e-6 * length
    if isinstance(seabed, Plane) and on_seabed:
        up = seabed.elevation((anchor[:2] + u[:2])[None])[0] - seabed.elevation(anchor[:2][None])[0]
        solution = inclined_catenary(span, rise, length, weight, np.arctan(up), EA)
    else:
        solution = elastic_catenary(span, rise, length, EA, weight, seabed=on_seabed)

    def positions(s):
        x, z = solution.profile(s)
        return anchor + x[:, None] * u + z[:, None] * np.array([0.0, 0.0, 1.0])

    return positions


def _floating(line, weight, lift, EA):
    """A buoyant line (mean lift ``lift`` [N/m] > 0): the shape a heavy line would take in the
    mirror image z -> 2 z_f - z, with the level z_f where it floats (``float_level``, no higher
    than the higher end) as the mirror's seabed: the slack layout floating along the surface
    when it is longer than it needs, else the inverted catenary, kept below z_f. Returns
    (positions, whether it lays slack line)."""
    level = max(float_level(weight), float(line.anchor[2]), float(line.fairlead[2]))
    mirror = np.array([1.0, 1.0, -1.0])
    shift = np.array([0.0, 0.0, 2.0 * level])
    mirrored = Line(line.name, shift + mirror * line.anchor, shift + mirror * line.fairlead, line.segments,
                    line.order, element=line.element)
    surface = Plane((0.0, 0.0, level), (0.0, 0.0, 1.0))
    positions = slack_layout(mirrored, surface, lift, EA)
    slack = positions is not None
    if positions is None:
        positions = _catenary(mirrored, surface, lift, EA)

    def floating(s):
        points = shift + mirror * positions(s)
        points[:, 2] = np.minimum(points[:, 2], level)
        return points

    return floating, slack


def float_level(weight):
    """Height z [m] (<= 0) of the centre of a floating cross-section: where the submerged fraction
    (``cablefem.loads.gravity``) carries the dry weight, for the element that floats highest;
    -inf if none floats."""
    floats = (weight.dry < weight.buoyancy)[:, 0]
    if not np.any(floats):
        return -np.inf
    fraction = (weight.dry / weight.buoyancy)[floats, 0]
    diameter = weight.diameter[floats, 0]
    low, high = -0.5 * diameter, 0.5 * diameter  # phi falls from 1 to 0 as z rises through the band
    for _ in range(60):
        mid = 0.5 * (low + high)
        below = submerged_fraction(mid, diameter)[0] > fraction
        low, high = np.where(below, mid, low), np.where(below, high, mid)
    return float(np.max(0.5 * (low + high)))


def _chord(line):
    """A neutrally buoyant line: the straight chord (it has no weight to sag)."""
    anchor, fairlead, length = line.anchor, line.fairlead, line.unstretched_length

    def positions(s):
        return anchor + (s / length)[:, None] * (fairlead - anchor)

    return positions


def _height(seabed, point):
    """Height [m] of ``point`` (3,) above the seabed along the vertical, and the seabed point below it."""
    foot = np.array([point[0], point[1], seabed.elevation(np.asarray(point[:2])[None])[0]])
    return float(point[2] - foot[2]), foot


def slack_hangs(line, seabed, weight, EA, sink=0.0):
    """(unstretched length of the vertical drop from the anchor to the seabed [m], of the rise from
    the seabed to the fairlead [m], the seabed points below anchor and fairlead (3,) each) when
    the line is longer than it needs (see the module docstring: longer than those two verticals
    plus the distance between their feet); None when it is not. ``weight`` [N/m] > 0, EA [N];
    ``sink`` [m]: the resting penetration, where a vertical part meets the lying line."""
    length = line.unstretched_length
    drop, bottom = _height(seabed, line.anchor)
    rise, top = _height(seabed, line.fairlead)
    if drop > 1e-6 * length:
        drop += sink
    if rise > 1e-6 * length:
        rise += sink
    if drop < -1e-6 * length or rise < -1e-6 * length:
        return None  # an end below the seabed: no layout to offer
    hang_a = _unstretched_hang(max(drop, 0.0), weight, EA)
    hang_f = _unstretched_hang(max(rise, 0.0), weight, EA)
    if length - hang_a - hang_f <= float(np.linalg.norm(top - bottom)) * (1.0 + 1e-9):
        return None
    return hang_a, hang_f, bottom, top


def slack_layout(line, seabed, weight, EA, sink=0.0):
    """Positions (a function of arc length) of a line longer than it needs (see the module
    docstring), or None when it is not (``slack_hangs``). ``weight`` [N/m] > 0, EA [N], ``sink``
    [m] the resting penetration."""
    hangs = slack_hangs(line, seabed, weight, EA, sink)
    if hangs is None:
        return None
    hang_a, hang_f, bottom, top = hangs
    length = line.unstretched_length
    lying = length - hang_a - hang_f
    arc = _Arc(bottom, top, lying, seabed)

    def positions(s):
        s = np.asarray(s, dtype=float)
        out = np.empty((s.size, 3))
        down = s <= hang_a
        up = s >= length - hang_f
        on = ~(down | up)
        out[down] = line.anchor - _hang_depth(s[down], weight, EA)[:, None] * [0.0, 0.0, 1.0]
        # the anchor's vertical: hang_depth counted from the anchor, stretched by the weight below
        out[on] = arc.at((s[on] - hang_a) / lying)
        out[up] = line.fairlead - _hang_depth(length - s[up], weight, EA)[:, None] * [0.0, 0.0, 1.0]
        return out

    return positions


def _unstretched_hang(height, weight, EA):
    """Unstretched length [m] of a vertical hang of ``height`` [m] that carries its own weight:
    height = l + w l^2 / (2 EA)."""
    if height <= 0.0:
        return 0.0
    return 2.0 * height / (1.0 + math.sqrt(1.0 + 2.0 * weight * height / EA))


def _hang_depth(l, weight, EA):
    """Depth [m] below its top of the point at unstretched distance l (n,) [m] down a vertical
    hang, stretched by the weight below it (an approximation the solve corrects: the top tension
    of each hang depends on its length, which is not known here)."""
    return l * (1.0 + 0.5 * weight * l / EA)


class _Arc:
    """A circular arc on the seabed from ``start`` to ``end`` (3,), bulging sideways (horizontally
    across the chord), of length at most a half circle over the chord (a loop of
    ``LOOP_FRACTION`` of the line when they coincide), holding ``length`` [m] of line."""

    def __init__(self, start, end, length, seabed):
        chord = end - start
        c = float(np.linalg.norm(chord))
        self.start, self.seabed = start, seabed
        along = chord / c if c > 1e-12 * length else np.array([1.0, 0.0, 0.0])
        side = np.cross([0.0, 0.0, 1.0], along)
        norm = float(np.linalg.norm(side))
        self.along = along
        self.side = side / norm if norm > 1e-12 else np.array([0.0, 1.0, 0.0])
        self.length = min(length, max(0.5 * math.pi * c, LOOP_FRACTION * length))
        self.chord = c
        self.angle = _central_angle(c / self.length) if self.length > c * (1.0 + 1e-12) else 0.0

    def at(self, fraction):
        """Points (n, 3) at fractions (n,) of the arc's length, lifted onto the seabed."""
        sigma = np.asarray(fraction, dtype=float) * self.length
        if self.angle == 0.0:
            x, y = sigma, np.zeros_like(sigma)
        else:
            radius = self.length / self.angle
            half = 0.5 * self.angle
            phase = 0.5 * math.pi + half - sigma / radius
            x = 0.5 * self.chord + radius * np.cos(phase)
            y = -radius * math.cos(half) + radius * np.sin(phase)
        points = self.start + x[:, None] * self.along + y[:, None] * self.side
        points[:, 2] = self.seabed.elevation(points[:, :2])
        return points


def _central_angle(ratio):
    """theta in (0, 2 pi] with 2 sin(theta / 2) / theta = ratio (chord / arc length) in [0, 1)."""
    if ratio <= 0.0:
        return 2.0 * math.pi
    low, high = 0.0, 2.0 * math.pi
    for _ in range(200):  # sin(x)/x falls monotonically on (0, pi]
        mid = 0.5 * (low + high)
        if 2.0 * math.sin(0.5 * mid) / mid > ratio:
            low = mid
        else:
            high = mid
    return 0.5 * (low + high)


def resting_sink(system, weight):
    """Penetration [m] at which the seabed carries a line of submerged weight ``weight`` [N/m]
    lying on a level bottom: w / (G_K d), with the stiffest element's G_K d (0 for a line in soil,
    which has no contact spring)."""
    return max(weight, 0.0) / _ground_stiffness(system)


def _ground_stiffness(system):
    """The stiffest element's G_K d [N/m^2]; infinite without a contact load (a line in soil)."""
    return float(np.max(system.contact.stiffness)) if system.has("contact") else np.inf


def _rest_on_seabed(system, X, weight):
    """Lift the points of X (N, 3) that would be buried onto the seabed, each at the penetration
    that carries its weight, w n_z / (G_K d) [m] (in place). P3 and up: vertices only (the
    other rows are coefficients)."""
    fem, seabed = system.fem, system.seabed
    length = system.line.unstretched_length
    rows = slice(None) if fem.order <= 2 else slice(0, fem.n_vertices)
    points = X[rows]
    proj = seabed.project(points)
    resting = proj.gap <= 1e-9 * length
    sink = max(weight, 0.0) * proj.direction[:, 2] / _ground_stiffness(system)
    points[resting] = proj.closest[resting] - sink[resting][:, None] * proj.direction[resting]
    X[rows] = points
