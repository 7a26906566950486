"""Mooring networks: points, rigid bodies and the lines between them (issue 18; docs/scene.md).

Data: a ``Point`` is fixed, coupled (it follows the scene's [motion], as a fairlead does) or free,
with a mass, a volume, a drag area and an added-mass coefficient (MoorDyn's points), and may be
attached to a ``Body``; a ``Body`` is fixed, coupled (a prescribed six-degree-of-freedom motion)
or free (mass, inertia, volume, a centre of gravity and a steady external load). A line names the
points at its two ends (``Line.ends``); a line without names keeps today's meaning: a fixed
anchor and a fairlead that follows [motion].

Rotations are MoorDyn-C's (measured with its library, ``tests/test_network.py``): a point at
r_local in a body's frame is at r + R r_local with R = Rx(roll) Ry(pitch) Rz(yaw), the angles
about the x, y', z'' axes, each positive by the right-hand rule: roll turns +y towards +z, pitch
+z towards +x, yaw +x towards +y.

Topology (``strings``): lines joined through free points that join exactly two line ends (a
clump weight, a buoy, a connector in series) are one finite element line, a *string*, with the
point as a ``Joint`` at the vertex between them: one banded block, solved as one line. Where one
of the two lines bends (Hermite elements) the point is a hinge, as MoorDyn's points are: the lines
share its position, not their tangents, so each is a string of its own and the point a junction
(a welded joint is one line of several segments). A free point at the end of one line only is a
free end of its string. What remains are the string ends
at fixed and coupled points and at points of fixed and coupled bodies (prescribed paths,
``EndPath``), and the *coupling* unknowns: free points where three or more line ends meet (or
two, at a hinge) and free bodies, which ``cablefem.statics.network`` solves for in statics and
``cablefem.dynamics.body_group`` steps in a run.
"""

import math
from dataclasses import dataclass, field, replace

import numpy as np

from cablefem.errors import InputError
from cablefem.model.clamps import check_clamps_do_not_turn, check_no_free_body_clamps
from cablefem.model.line import Joint, Line
from cablefem.model.motion import FairleadPath, body_motion

KINDS = ("fixed", "coupled", "free")


def _vector(value, size, key):
    """A finite float vector of ``size`` entries, or an InputError naming ``key``."""
    try:
        vector = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"expected {size} numbers, got {value!r}", key=key) from None
    if vector.shape != (size,) or not np.all(np.isfinite(vector)):
        raise InputError(f"expected {size} finite numbers, got {value!r}", key=key)
    return vector


def _kind(value, key):
    if value not in KINDS:
        raise InputError(f"must be one of {', '.join(KINDS)}, got {value!r}", key=key)
    return value


@dataclass(frozen=True)
class Point:
    """A point of a network. ``position`` [m]: in the scene's frame, or on a body in the body's
    frame relative to its reference point; for a free point the start of its search. ``force``
    (3,) [N]: a steady external force on a free point or a point of a free body (MoorDyn's FX FY
    FZ; a fixed or coupled point's motion is given, and a force on it changes nothing)."""

    name: str
    kind: str
    position: np.ndarray
    mass: float = 0.0
    volume: float = 0.0
    CdA: float = 0.0
    Ca: float = 0.0
    body: str | None = None
    force: np.ndarray = field(default_factory=lambda: np.zeros(3))

    def __post_init__(self):
        object.__setattr__(self, "kind", _kind(self.kind, f"points.{self.name}.kind"))
        object.__setattr__(self, "position", _vector(self.position, 3, f"points.{self.name}.position"))
        object.__setattr__(self, "force", _vector(self.force, 3, f"points.{self.name}.force"))
        self.joint  # the same checks

    @property
    def joint(self):
        """The point's mass, volume, drag, added mass and external force as a ``Joint`` of a line."""
        return Joint(self.name, self.mass, self.volume, self.CdA, self.Ca, tuple(self.force))


@dataclass(frozen=True)
class Body:
    """A rigid body: reference point ``position`` (x, y, z) [m] and ``rotation`` (roll, pitch, yaw)
    [rad] at rest; ``motion`` of a coupled body (a ``Motion`` of six components: x, y, z [m], roll,
    pitch, yaw [rad], added to the rest values); a free body's ``mass`` [kg], principal moments of
    ``inertia`` (3,) [kg m^2] about its centre of gravity ``cg`` (3,) [m, body frame], displaced
    ``volume`` [m^3] acting at its centre of buoyancy ``cb`` (3,) [m, body frame] (the volume at the
    reference point's z = 0; MoorPy's rM may stand for cb: buoyancy there gives the metacentric
    restoring moment), the ``waterplane_area`` [m^2] whose heave restoring force is
    -rho g A_wp z (MoorPy's AWP), and the steady external ``force`` (3,) [N] and ``moment`` (3,)
    [N m, about the reference point] of an offset study; in a run its drag areas ``CdA`` (6,) [m^2]
    (surge, sway, heave, then roll, pitch, yaw, in body axes: MoorDyn-C's drag 0.5 rho CdA |u| u on
    the reference point's velocity relative to the current, and on the angular velocity) and added
    mass coefficients ``Ca`` (6,) [-] (MoorDyn-C's rho V Ca about the reference point, body axes).
    ``rod``: the ``cablefem.model.rod.Rod`` that a free or pinned rod's body is (its own loads in
    place of mass, volume and waterplane: ``cablefem.model.rod.rod_body``); ``rods``: the rods fixed
    on the body, ends in its frame."""

    name: str
    kind: str
    position: np.ndarray
    rotation: np.ndarray = field(default_factory=lambda: np.zeros(3))
    mass: float = 0.0
    inertia: np.ndarray = field(default_factory=lambda: np.zeros(3))
    cg: np.ndarray = field(default_factory=lambda: np.zeros(3))
    volume: float = 0.0
    cb: np.ndarray = field(default_factory=lambda: np.zeros(3))
    waterplane_area: float = 0.0
    force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    moment: np.ndarray = field(default_factory=lambda: np.zeros(3))
    motion: object = None
    rod: object = None
    rods: tuple = ()
    CdA: np.ndarray = field(default_factory=lambda: np.zeros(6))
    Ca: np.ndarray = field(default_factory=lambda: np.zeros(6))

    def __post_init__(self):
        key = f"bodies.{self.name}"
        object.__setattr__(self, "kind", _kind(self.kind, f"{key}.kind"))
        for name in ("position", "rotation", "inertia", "cg", "cb", "force", "moment"):
            object.__setattr__(self, name, _vector(getattr(self, name), 3, f"{key}.{name}"))
        for name in ("CdA", "Ca"):
            value = getattr(self, name)
            if isinstance(value, (int, float)) and not isinstance(value, bool):  # one number for all six
                value = [value] * 6
            value = _vector(value, 6, f"{key}.{name}")
            if np.any(value < 0.0):
                raise InputError(f"must be >= 0, got {value.tolist()}", key=f"{key}.{name}")
            object.__setattr__(self, name, value)
        for name in ("mass", "volume", "waterplane_area"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
                raise InputError(f"must be a number >= 0, got {value!r}", key=f"{key}.{name}")
        if self.kind == "free":
            if self.mass <= 0.0:
                raise InputError("a free body needs a mass > 0", key=f"{key}.mass")
            if np.any(self.inertia <= 0.0):
                raise InputError(f"a free body needs three moments of inertia > 0 (its inertia matrix is "
                                 f"singular otherwise), got {self.inertia.tolist()}", key=f"{key}.inertia")


# ------------------------------------------------------------------------------------ rotations
def _axis(angle, axis):
    """The rotation matrix about ``axis`` (0, 1, 2) by ``angle`` (n,) and its first and second
    derivatives with respect to the angle, each (n, 3, 3)."""
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    R, dR, ddR = (np.zeros((len(angle), 3, 3)) for _ in range(3))
    R[:, axis, axis] = 1.0
    R[:, i, i], R[:, j, j], R[:, i, j], R[:, j, i] = c, c, -s, s
    dR[:, i, i], dR[:, j, j], dR[:, i, j], dR[:, j, i] = -s, -s, -c, c
    ddR[:, i, i], ddR[:, j, j], ddR[:, i, j], ddR[:, j, i] = -c, -c, s, -s
    return R, dR, ddR


def rotation(angles):
    """R = Rx(roll) Ry(pitch) Rz(yaw) (MoorDyn-C's convention) for angles (3,) or (n, 3) [rad]:
    (3, 3) or (n, 3, 3)."""
    return rotation_rates(angles)[0]


def rotation_rates(angles, rates=None, accelerations=None):
    """R (n, 3, 3) at ``angles`` (n, 3) [rad] and, given the angles' rates (n, 3) [rad/s] and
    accelerations (n, 3) [rad/s^2], its time derivatives dR/dt and d2R/dt2 (chain rule through
    the three factors)."""
    angles = np.asarray(angles, dtype=float)
    single = angles.ndim == 1
    angles = np.atleast_2d(angles)
    factors = [_axis(angles[:, k], k) for k in range(3)]
    R = factors[0][0] @ factors[1][0] @ factors[2][0]
    if rates is None:
        return (R[0] if single else R), None, None
    w = np.atleast_2d(np.asarray(rates, dtype=float))
    wd = np.atleast_2d(np.asarray(accelerations, dtype=float))

    def product(orders):  # the product of the factors each differentiated orders[k] times
        out = factors[0][orders[0]]
        for k in (1, 2):
            out = out @ factors[k][orders[k]]
        return out

    dR = sum(product([1 if k == m else 0 for k in range(3)]) * w[:, m, None, None] for m in range(3))
    ddR = sum(product([1 if k == m else 0 for k in range(3)]) * wd[:, m, None, None] for m in range(3))
    for m in range(3):
        for n in range(3):
            orders = [0, 0, 0]
            orders[m] += 1
            orders[n] += 1
            ddR = ddR + product(orders) * (w[:, m] * w[:, n])[:, None, None]
    if single:
        return R[0], dR[0], ddR[0]
    return R, dR, ddR


# ------------------------------------------------------------------------------- end paths
class FixedPath:
    """A prescribed end that stays at ``position`` (3,) [m]: path(t) -> (position, 0, 0)."""

    def __init__(self, position):
        self.position = np.asarray(position, dtype=float)

    def __call__(self, t):
        return self.position.copy(), np.zeros(3), np.zeros(3)

    def positions(self, times):
        return np.broadcast_to(self.position, (len(np.atleast_1d(times)), 3)).copy()


class BodyPointPath:
    """A point at ``local`` (3,) [m] in the frame of a fixed or coupled ``body``: its position,
    velocity and acceleration r + R p, v + dR/dt p, a + d2R/dt2 p as the body moves."""

    def __init__(self, body, local):
        self.body = body
        self.local = np.asarray(local, dtype=float)

    def states(self, times):
        """Positions, velocities and accelerations (n, 3) at ``times`` (n,)."""
        times = np.atleast_1d(np.asarray(times, dtype=float))
        body = self.body
        if body.kind == "coupled" and body.motion is not None:
            d, v, a = body_motion(body.motion, times)
        else:
            d = v = a = np.zeros((len(times), 6))
        R, dR, ddR = rotation_rates(body.rotation + d[:, 3:], v[:, 3:], a[:, 3:])
        p = self.local
        return (body.position + d[:, :3] + R @ p, v[:, :3] + dR @ p, a[:, :3] + ddR @ p)

    def __call__(self, t):
        x, v, a = self.states(np.array([t]))
        return x[0], v[0], a[0]

    def positions(self, times):
        return self.states(times)[0]


def end_path(scene, name, at):
    """The path of a prescribed line end at point ``name`` of ``scene`` (None: the line's own end
    at ``at``, a legacy fairlead following [motion]); None for a fixed end that is not on a body
    (the integrators' default: in place)."""
    if name is None:
        return FairleadPath(scene.motion, at)
    point = scene.points[name]
    if point.body is not None:
        return BodyPointPath(scene.bodies[point.body], point.position)
    if point.kind == "coupled":
        return FairleadPath(scene.motion, point.position)
    return None


def line_paths(scene, line):
    """(anchor path or None, fairlead path) of a line of ``scene``: the anchor end fixed in place
    unless it names a coupled point or a point of a body; the fairlead end follows [motion] unless
    it names a point (a fixed point: a ``FixedPath``)."""
    anchor_name, fairlead_name = line.ends
    anchor = None if anchor_name is None else end_path(scene, anchor_name, line.anchor)
    fairlead = end_path(scene, fairlead_name, line.fairlead)
    if fairlead is None:
        fairlead = FixedPath(line.fairlead)
    return anchor, fairlead


# ------------------------------------------------------------------------------------ strings
def _reversed(line):
    """The same line run from its fairlead end to its anchor end."""
    n = len(line.segments)
    return replace(line, anchor=line.fairlead, fairlead=line.anchor, segments=line.segments[::-1],
                   joints=tuple((n - k, joint) for k, joint in line.joints), prescribed=line.prescribed[::-1],
                   ends=line.ends[::-1], tangents=tuple(None if d is None else -d for d in line.tangents[::-1]))


#: which end of a string is its anchor: the lower rank (a fixed point first, a moving one last)
_RANK = {"fixed": 0, "junction": 1, "free": 2, "coupled": 3}


def _end_kind(points, bodies, name, count):
    """How a string ends at point ``name`` (None: a legacy end) joined by ``count`` line ends."""
    if name is None:
        return None
    point = points[name]
    if point.body is not None:
        return "junction" if bodies[point.body].kind == "free" else bodies[point.body].kind
    if point.kind == "free":
        return "free" if count == 1 else "junction"
    return point.kind


def strings(lines, points, bodies, where=lambda key: key):
    """The strings of a network (see the module docstring): ``lines`` (Line, each naming its end
    points or not) joined through the free ``points`` that join exactly two line ends, each string
    one ``Line`` with those points as joints, named 'a+b' after its lines, oriented with its most
    fixed end as its anchor; free ends and ends at coupling points are not prescribed."""
    at_point = {}
    for index, line in enumerate(lines):
        for end, name in enumerate(line.ends):
            if name is not None:
                if name not in points:
                    raise InputError(f"no point '{name}' in [points]", key=where(f"lines[{index}].ends"))
                at_point.setdefault(name, []).append((index, end))
    for name, point in points.items():
        if name not in at_point:
            raise InputError("no line uses this point", key=where(f"points.{name}"))
    check_no_free_body_clamps(lines, points, bodies, where)
    series = {name for name, ends in at_point.items()
              if points[name].kind == "free" and points[name].body is None and len(ends) == 2
              and not any(lines[index].hermite for index, _ in ends)}  # a point is a hinge on lines that bend
    used, out = set(), []
    for start in range(len(lines)):
        if start in used:
            continue
        chain = [(start, False)]  # (line index, reversed)
        used.add(start)
        for forward in (True, False):  # walk on from the fairlead end, then back from the anchor end
            index, flipped = chain[-1] if forward else chain[0]
            while True:
                line = lines[index]
                name = line.ends[(1 if forward else 0) ^ flipped]
                if name not in series:
                    break
                (other, end), = [e for e in at_point[name] if e[0] != index] or [(index, 0)]
                if other == index or other in used:
                    raise InputError(f"lines joined through free points form a loop at point '{name}'",
                                     key=where(f"lines[{other}]"))
                used.add(other)
                flip = (end == 1) if forward else (end == 0)  # enter each line at its anchor end
                chain.insert(len(chain) if forward else 0, (other, flip))
                index, flipped = other, flip
        out.append(_string([lines[i] if not f else _reversed(lines[i]) for i, f in chain], points, bodies,
                           at_point))
    return out


def _string(parts, points, bodies, at_point):
    """One string from its lines in order (each oriented along it), turned round so that its most
    fixed end is its anchor."""
    kinds = [_end_kind(points, bodies, name, len(at_point.get(name, ())))
             for name in (parts[0].ends[0], parts[-1].ends[1])]
    kinds = [kind or ("fixed", "coupled")[e] for e, kind in enumerate(kinds)]  # a line's own ends
    if _RANK[kinds[0]] > _RANK[kinds[1]]:
        parts, kinds = [_reversed(part) for part in parts[::-1]], kinds[::-1]
    segments, joints = [], []
    for k, line in enumerate(parts):
        offset = len(segments)
        segments.extend(line.segments)
        joints.extend((offset + b, j) for b, j in line.joints if 0 < b < len(line.segments))
        if k:  # the series point between this line and the one before
            joints.append((offset, points[line.ends[0]].joint))
    ends = (parts[0].ends[0], parts[-1].ends[1])
    n = len(segments)
    for e, (name, kind) in enumerate(zip(ends, kinds)):
        if kind == "free" and points[name].joint.loaded:  # a free end carries its point
            joints.append((0 if e == 0 else n, points[name].joint))
    prescribed = tuple(kind not in ("free", "junction") for kind in kinds)
    return Line("+".join(p.name for p in parts), parts[0].anchor, parts[-1].fairlead, tuple(segments),
                parts[0].order, joints=tuple(joints), prescribed=prescribed, ends=ends, element=parts[0].element,
                tangents=(parts[0].tangents[0], parts[-1].tangents[1]))


def coupling(lines, points, bodies):
    """The coupling unknowns of strings ``lines``: the junction points (free points joining two or
    more string ends: three or more, or two at a hinge) and the free bodies, as (points, bodies) name
    lists. A point on a free body is no junction, however many string ends meet there: the body's
    pose places it, and each of those ends is linked to the body alone."""
    junctions = sorted({name for line in lines for name, given in zip(line.ends, line.prescribed)
                        if name is not None and not given and points[name].body is None
                        and not _free_end(line, name, lines)})
    free_bodies = sorted(name for name, body in bodies.items() if body.kind == "free")
    return junctions, free_bodies


def _free_end(line, name, lines):
    """Whether ``name`` is a free end of ``line`` alone (no other string end there)."""
    return sum(end == name for other in lines for end in other.ends) == 1


def point_position(point, bodies):
    """Where ``point`` is at rest [m]: its position, or on a body r + R p."""
    if point.body is None:
        return point.position.copy()
    body = bodies[point.body]
    return body.position + rotation(body.rotation) @ point.position


def check_steppable(scene):
    """InputError for what a run cannot step: a clamp on a body that turns
    (``check_clamps_do_not_turn``). Junctions step in a ``cablefem.dynamics.group.Group`` and free
    bodies (free and pinned rods and bodies carrying rods among them) in a
    ``cablefem.dynamics.body_group`` step, with any integrator."""
    check_clamps_do_not_turn(scene)


def junction_ends(lines, points, bodies):
    """{junction: [(line index, end)]} of the strings ``lines`` (end 0: anchor, 1: fairlead)."""
    junctions, _ = coupling(lines, points, bodies)
    out = {name: [] for name in junctions}
    for k, line in enumerate(lines):
        for end, name in enumerate(line.ends):
            if name in out and not line.prescribed[end]:
                out[name].append((k, end))
    return out


def dynamic_lines(scene):
    """The scene's strings for a run: each junction's own point (its mass, volume, drag and added
    mass) rides as a joint at the end of the first string that ends there."""
    lines = list(scene.lines)
    for name, members in junction_ends(scene.lines, scene.points, scene.bodies).items():
        joint = scene.points[name].joint
        if members and joint.loaded:
            k, end = members[0]
            at = 0 if end == 0 else len(lines[k].segments)
            lines[k] = replace(lines[k], joints=lines[k].joints + ((at, joint),))
    return lines


def boundary_path(scene, line):
    """The fairlead end's prescribed path of ``line`` in ``scene``: a ``FairleadPath`` following
    [motion], or the path of the network point it names (``cablefem.model.network.line_paths``)."""
    if line.ends == (None, None):
        return FairleadPath(scene.motion, line.fairlead)
    return line_paths(scene, line)[1]


def anchor_path(scene, line):
    """The anchor end's prescribed path of ``line`` (None: fixed where the line has it)."""
    return None if line.ends[0] is None else line_paths(scene, line)[0]
