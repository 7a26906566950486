"""Line model: line types and multi-segment lines over unstretched arc length.

A line runs from its anchor (s = 0) to its fairlead (s = L); each segment has
its own line type (chain, polyester rope, ...) and element count, and the
FEM mesh has nodes at the segment boundaries (desire2023 Sec. 2.1).
"""

import math
from dataclasses import dataclass, replace

import numpy as np

from cablefem.errors import InputError
from cablefem.model.axial import AxialLaw

#: Gauss points per element a line may ask for (``Line.quadrature_points``): 16 integrate the
#: touchdown's kink to ~4e-5 of the contact force, 8 to ~8e-5 (tests/test_quadrature_points.py);
#: each point costs a point of every full-point load
MAX_QUADRATURE_POINTS = 16
#: the element kinds of a line: Lagrange P1, P2, ... or the C1 cubic Hermite (``cablefem.fem.hermite``)
ELEMENTS = ("lagrange", "hermite")


def _positive(value, key, allow_zero=False):
    """A finite float > 0 (or >= 0); InputError naming the key otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise InputError(f"expected a number, got {value!r}", key=key)
    value = float(value)
    if not math.isfinite(value):
        raise InputError(f"must be finite, got {value}", key=key)
    if value < 0 or (value == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise InputError(f"must be {bound}, got {value:g}", key=key)
    return value


def _point(value, key):
    """A finite 3-vector as a float array of shape (3,)."""
    try:
        point = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"expected 3 numbers, got {value!r}", key=key) from None
    if point.shape != (3,):
        raise InputError(f"expected 3 numbers, got {value!r}", key=key)
    if not np.all(np.isfinite(point)):
        raise InputError(f"must be finite, got {value!r}", key=key)
    return point


@dataclass(frozen=True)
class LineType:
    """Material and hydrodynamic properties of one kind of line (SI units).

    ``diameter`` is the volume-equivalent diameter [m] used for buoyancy,
    drag and seabed contact; ``mass`` is the mass in air per unit unstretched
    length [kg/m]; ``EA`` the axial stiffness [N]; ``damping`` is beta [s] in
    T = EA (e + beta de/dt) (desire2023 Eq. 2), no tension at all where slack; with
    ``damping_when_slack``, MoorDyn-C's law T = EA (max(e, 0) + beta de/dt): the damping part acts in
    slack segments too (``cablefem.loads.tension``). ``nominal_diameter`` is the chain's bar
    diameter d_b [m] that the soil's resistance scales with (rui2025 Eq. 3; None: not given, and
    a scene with ``[soil]`` refuses it). ``axial``: another axial law (``cablefem.model.axial``: a
    strain-tension table, a viscoelastic rope, SYROPE; ``cablefem.loads.rope``), with ``EA`` its
    reference stiffness (``AxialLaw.reference_EA``) and its own damping (``damping`` 0). ``EI`` is
    the bending stiffness [N m^2] (``cablefem.loads.bending``; > 0 needs a line on Hermite elements).
    """

    name: str
    diameter: float
    mass: float
    EA: float
    damping: float = 0.0
    Cd_normal: float = 1.2
    Cd_tangential: float = 0.0
    Ca_normal: float = 1.0
    Ca_tangential: float = 0.0
    damping_when_slack: bool = False
    nominal_diameter: float | None = None
    axial: AxialLaw | None = None
    EI: float = 0.0

    def __post_init__(self):
        for key in ("diameter", "mass", "EA"):
            object.__setattr__(self, key, _positive(getattr(self, key), key))
        if self.nominal_diameter is not None:
            object.__setattr__(self, "nominal_diameter", _positive(self.nominal_diameter, "nominal_diameter"))
        for key in ("damping", "Cd_normal", "Cd_tangential", "Ca_normal", "Ca_tangential", "EI"):
            object.__setattr__(self, key, _positive(getattr(self, key), key, allow_zero=True))
        if not isinstance(self.damping_when_slack, (bool, np.bool_)):
            raise InputError(f"expected true or false, got {self.damping_when_slack!r}", key="damping_when_slack")
        if self.axial is not None and self.damping != 0.0:
            raise InputError("with a nonlinear or viscoelastic EA the internal damping is BA [N s] (and BA_dynamic), "
                             "not beta", key="damping")

    @property
    def area(self):
        """Volume-equivalent cross-section area [m^2]."""
        return math.pi * self.diameter**2 / 4.0

    def submerged_weight(self, water_density, gravity):
        """Weight in water per unit unstretched length [N/m] (negative: buoyant)."""
        return (self.mass - water_density * self.area) * gravity


@dataclass(frozen=True)
class Segment:
    """A stretch of one line type: unstretched ``length`` [m] over ``elements`` elements;
    ``syrope``: the highest and the present mean tension (Tmax0, Tmean0) [N] of a SYROPE rope
    (MoorDyn's SYROPE IC), None otherwise."""

    type: LineType
    length: float
    elements: int
    syrope: tuple | None = None

    def __post_init__(self):
        object.__setattr__(self, "length", _positive(self.length, "length"))
        if isinstance(self.elements, bool) or not isinstance(self.elements, (int, np.integer)):
            raise InputError(f"expected a whole number, got {self.elements!r}", key="elements")
        if self.elements < 1:
            raise InputError(f"must be at least 1, got {self.elements}", key="elements")
        law = self.type.axial
        needs = law is not None and law.kind == "syrope"
        if needs and self.syrope is None:
            raise InputError(f"line type '{self.type.name}' is a SYROPE rope: its segment needs its initial "
                             "condition, syrope = { Tmax = ..., Tmean = ... } [N] (MoorDyn's SYROPE IC)", key="syrope")
        if self.syrope is not None:
            if not needs:
                raise InputError(f"line type '{self.type.name}' is not a SYROPE rope: it takes no SYROPE initial "
                                 "condition", key="syrope")
            peak, mean = (float(value) for value in self.syrope)
            law.check_peak(peak, "syrope.Tmax")
            if not 0.0 <= mean <= peak:
                raise InputError(f"must lie in [0, Tmax = {peak:g}] N, got {mean:g}", key="syrope.Tmean")
            object.__setattr__(self, "syrope", (peak, mean))


@dataclass(frozen=True)
class Joint:
    """A point of a line at a vertex (a segment boundary or an end): a clump weight, a buoy, a
    connector. ``mass`` [kg] in air, ``volume`` [m^3] displaced (a sphere, for the part of it below
    the water surface), ``CdA`` [m^2] drag coefficient times area and ``Ca`` the added-mass
    coefficient of that volume, both isotropic, as MoorDyn's points (``cablefem.loads.points``);
    ``force`` (3,) [N] a steady external force on it (MoorDyn's FX FY FZ)."""

    name: str
    mass: float = 0.0
    volume: float = 0.0
    CdA: float = 0.0
    Ca: float = 0.0
    force: tuple = (0.0, 0.0, 0.0)

    def __post_init__(self):
        for key in ("mass", "volume", "CdA", "Ca"):
            object.__setattr__(self, key, _positive(getattr(self, key), key, allow_zero=True))
        object.__setattr__(self, "force", tuple(float(f) for f in _point(self.force, "force")))

    @property
    def loaded(self):
        """Whether the point adds any force (a massless, volumeless, unforced joint adds none)."""
        return bool(self.mass or self.volume or self.CdA or any(self.force))


@dataclass(frozen=True)
class Line:
    """A line from ``anchor`` (s = 0) to ``fairlead`` (s = L), segments listed anchor first.

    ``order`` is the polynomial order of the finite elements (1, 2, 3, ...); ``quadrature_points``
    the Gauss points per element of the loads at full points (mass, weight, drag, seabed contact
    and friction; 0: order + 1, which integrates the mass exactly). ``joints``: points
    at segment boundaries, ((boundary, Joint), ...) with boundary 0 the anchor end and
    len(segments) the fairlead end (a line of a network joined through points, ``cablefem.model.network``).
    ``prescribed``: whether the anchor and the fairlead end have prescribed positions (the default)
    or are unknowns (a free end, or an end the network solves for). ``ends``: the names of the
    network's points at the two ends (``cablefem.model.network``), None for a line's own anchor (fixed)
    and fairlead (following the scene's motion). ``element``: "lagrange" (``order`` as given) or
    "hermite", scikit-fem's C1 cubic Hermite with positions and tangents r'(s) at the vertices
    (``order`` is then 3), which a line type with EI > 0 needs (``cablefem.loads.bending``).
    ``tangents``: the directions (3,) that clamp the anchor's and the fairlead's tangent, None for
    a pinned end (Hermite only; the magnitude |r'| = 1 + strain stays free).
    """

    name: str
    anchor: np.ndarray
    fairlead: np.ndarray
    segments: tuple
    order: int = 1
    joints: tuple = ()
    prescribed: tuple = (True, True)
    ends: tuple = (None, None)
    quadrature_points: int = 0
    element: str = "lagrange"
    tangents: tuple = (None, None)

    def __post_init__(self):
        object.__setattr__(self, "anchor", _point(self.anchor, "anchor"))
        object.__setattr__(self, "fairlead", _point(self.fairlead, "fairlead"))
        segments = tuple(self.segments)
        if not segments:
            raise InputError("a line needs at least one segment", key="segments")
        object.__setattr__(self, "segments", segments)
        if isinstance(self.order, bool) or not isinstance(self.order, (int, np.integer)) or self.order < 1:
            raise InputError(f"must be a whole number >= 1, got {self.order!r}", key="order")
        self._check_element(segments)
        q = self.quadrature_points
        if isinstance(q, bool) or not isinstance(q, (int, np.integer)) or (q != 0 and not
                                                                         self.order + 1 <= q <= MAX_QUADRATURE_POINTS):
            raise InputError(f"must be a whole number from order + 1 = {self.order + 1} (fewer points do not "
                             f"integrate the mass matrix) to {MAX_QUADRATURE_POINTS}, got {q!r}",
                             key="quadrature_points")
        joints = tuple((int(k), joint) for k, joint in self.joints)
        if any(not 0 <= k <= len(segments) for k, _ in joints) or len({k for k, _ in joints}) != len(joints):
            raise InputError("joints must sit at distinct segment boundaries", key="joints")
        object.__setattr__(self, "joints", tuple(sorted(joints, key=lambda item: item[0])))
        object.__setattr__(self, "prescribed", tuple(bool(p) for p in self.prescribed))
        object.__setattr__(self, "ends", tuple(self.ends))

    def _check_element(self, segments):
        """The element kind, the order it implies, EI against it and the clamped ends' directions."""
        if self.element not in ELEMENTS:
            raise InputError(f"must be one of {', '.join(ELEMENTS)}, got {self.element!r}", key="element")
        if self.element == "hermite":
            object.__setattr__(self, "order", 3)
        else:
            bent = next((seg.type.name for seg in segments if seg.type.EI > 0), None)
            if bent is not None:
                raise InputError(f"line type '{bent}' has EI > 0: bending needs element = \"hermite\"",
                                 key="element")
        tangents = tuple(self.tangents)
        if len(tangents) != 2:
            raise InputError("expected the anchor's and the fairlead's tangent", key="tangents")
        clamped = []
        for key, tangent in zip(("anchor_tangent", "fairlead_tangent"), tangents):
            if tangent is None:
                clamped.append(None)
                continue
            if self.element != "hermite":
                raise InputError("a clamped end needs element = \"hermite\" (tangents are its unknowns)", key=key)
            direction = _point(tangent, key)
            size = float(np.linalg.norm(direction))
            if size == 0.0:
                raise InputError("must be a direction, got the zero vector", key=key)
            clamped.append(direction / size)
        object.__setattr__(self, "tangents", tuple(clamped))

    @property
    def hermite(self):
        """Whether the line is on Hermite elements (positions and tangents as unknowns)."""
        return self.element == "hermite"

    def joint_vertices(self):
        """Vertex index (k,) of each joint, in ``joints`` order."""
        first = np.concatenate([[0], np.cumsum([seg.elements for seg in self.segments])])
        return np.array([first[k] for k, _ in self.joints], dtype=np.int64)

    @property
    def unstretched_length(self):
        """Total unstretched length L [m]."""
        return float(sum(seg.length for seg in self.segments))

    @property
    def segment_bounds(self):
        """Arc lengths of the segment ends, shape (n_segments + 1,), from 0 to L [m]."""
        return np.concatenate([[0.0], np.cumsum([seg.length for seg in self.segments])])

    def node_arc_lengths(self):
        """Arc length of every mesh vertex, shape (n_elements + 1,), uniform within segments [m]."""
        bounds = self.segment_bounds
        pieces = [np.linspace(bounds[i], bounds[i + 1], seg.elements + 1)[:-1]
                  for i, seg in enumerate(self.segments)]
        return np.concatenate(pieces + [[bounds[-1]]])

    def element_segments(self):
        """Index of the segment each element belongs to, shape (n_elements,)."""
        return np.repeat(np.arange(len(self.segments)), [seg.elements for seg in self.segments])

    def chord_strain(self):
        """Strain a straight line from anchor to fairlead would need (negative if slack)."""
        return float(np.linalg.norm(self.fairlead - self.anchor) / self.unstretched_length - 1.0)

    def split_at(self, s):
        """The same line with a mesh vertex at arc length s [m]: the segment holding s is split
        in two of the same type, sharing its elements in proportion (at least one each)."""
        bounds = self.segment_bounds
        i = int(np.clip(np.searchsorted(bounds, s, side="right") - 1, 0, len(self.segments) - 1))
        seg = self.segments[i]
        a, b = bounds[i], bounds[i + 1]
        if not (a < s < b) or min(s - a, b - s) <= 1e-9 * self.unstretched_length:
            return self
        left = int(np.clip(round(seg.elements * (s - a) / (b - a)), 1, max(1, seg.elements - 1)))
        right = max(1, seg.elements - left)
        pieces = (Segment(seg.type, s - a, left, seg.syrope), Segment(seg.type, b - s, right, seg.syrope))
        segments = self.segments[:i] + pieces + self.segments[i + 1:]
        joints = tuple((k + 1 if k > i else k, joint) for k, joint in self.joints)
        return replace(self, segments=segments, joints=joints)

    def with_order(self, order):
        """The same line with another element order (a line on Hermite elements stays on them)."""
        return replace(self, order=order)

    def with_quadrature_points(self, points):
        """The same line with another number of Gauss points per element (0: order + 1)."""
        return replace(self, quadrature_points=points)

    def with_ends(self, anchor, fairlead):
        """The same line between other end points."""
        return replace(self, anchor=anchor, fairlead=fairlead)

    def with_types(self, change):
        """The same line with every segment's line type replaced by ``change(type)`` (a switch of one
        property, e.g. ``lambda t: replace(t, EA=2 * t.EA)``)."""
        return replace(self, segments=tuple(replace(seg, type=change(seg.type)) for seg in self.segments))

    def with_elements(self, elements):
        """The same line with ``elements`` elements spread over the segments by length."""
        total = self.unstretched_length
        counts = [max(1, round(elements * seg.length / total)) for seg in self.segments]
        segments = tuple(replace(seg, elements=n) for seg, n in zip(self.segments, counts))
        return replace(self, segments=segments)
