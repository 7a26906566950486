"""The two networks of the study, each described once (``Network``) and written from that one
description as a MoorDyn v2 input file (``moordyn_text``), a cablefem TOML scene (``toml_text``)
and a MoorPy ``System`` (``moorpy_system``), so that the three codes see the same physics.

- ``semitaut()``: three chain-polyester-chain lines (housner2022's VolturnUS-S semi-taut lines,
  validation/moordyn, with a short top chain), a clump weight at the chain-polyester joint and a
  buoy at the polyester-chain joint of each line, the fairleads on one platform (a rigid body).
- ``shared()``: two platforms, each moored by two chains, joined by a shared polyester line with
  a clump weight at its middle.

Angles are degrees in the files (MoorDyn's BODIES row, the TOML's rotation and motion) and radians
in MoorDyn's coupling calls; rotations are R = Rx(roll) Ry(pitch) Rz(yaw) in all three codes.
"""

from dataclasses import dataclass, field, replace

import numpy as np

from validation.moordyn.run import (GRAVITY, HOUSNER_BETA, IC_DYNAMIC, IC_OPTIONS, LINE_HEADER,
                                    OPTIONS_HEADER, OUTPUTS, TYPE_HEADER, WATER_DENSITY, _number, _type_row,
                                    line_type_120mm_chain, line_type_186mm_polyester)

#: MoorDyn-C's seabed defaults, written into both codes' inputs (no friction: MoorPy has none)
KBOT, CBOT = 3.0e6, 3.0e5


@dataclass(frozen=True)
class PointSpec:
    """A point: ``kind`` fixed / free, or on ``body`` at ``position`` in the body's frame [m]."""

    name: str
    kind: str
    position: tuple
    mass: float = 0.0
    volume: float = 0.0
    CdA: float = 0.0
    Ca: float = 0.0
    body: str | None = None


@dataclass(frozen=True)
class BodySpec:
    """A coupled body: rest reference point [m]; harmonic motion per component (x, y, z [m], roll,
    pitch, yaw [deg]) offset + amplitude sin(2 pi t / period + phase), ramped in over ``ramp`` [s]."""

    name: str
    position: tuple
    amplitude: tuple
    phase_deg: tuple
    period: float
    ramp: float
    free: dict | None = None  # a free body's TOML keys (mass, inertia, volume, ...): statics only


@dataclass(frozen=True)
class LineSpec:
    """A line of one type from point ``a`` to point ``b`` with ``segments`` MoorDyn segments / P1 elements."""

    name: str
    type: str
    a: str
    b: str
    length: float
    segments: int


@dataclass(frozen=True)
class Network:
    name: str
    title: str
    depth: float
    types: dict
    points: tuple
    bodies: tuple
    lines: tuple
    beta: float = HOUSNER_BETA
    options: dict = field(default_factory=dict)

    def point(self, name):
        return next(p for p in self.points if p.name == name)

    def refined(self, factor):
        """The network with every line's segment count times ``factor``."""
        return replace(self, lines=tuple(replace(line, segments=int(round(line.segments * factor)))
                                         for line in self.lines))


# ----------------------------------------------------------------------------- the systems
DEPTH = 850.0
FAIRLEAD_RADIUS, FAIRLEAD_DEPTH = 58.0, 14.0
ANCHOR_RADIUS = 1130.0
HEADINGS = (180.0, 60.0, 300.0)
BOTTOM_CHAIN, ROPE, TOP_CHAIN = 400.0, 975.0, 80.0
#: clump: 10 t of steel (7850 kg/m^3); buoy: 8 m^3 syntactic foam sphere of 2.5 t (net lift 5.7 t)
CLUMP = {"mass": 10.0e3, "volume": 10.0e3 / 7850.0, "CdA": 1.0, "Ca": 1.0}
BUOY = {"mass": 2.5e3, "volume": 8.0, "CdA": 0.6 * np.pi * (3 * 8.0 / (4 * np.pi)) ** (2 / 3), "Ca": 0.5}
#: platform motion: surge 4 m, heave 1.5 m, pitch 2 deg, yaw 3 deg, out of phase, one period
PERIOD = 14.9
PLATFORM_AMPLITUDE = (4.0, 0.0, 1.5, 0.0, 2.0, 3.0)
PLATFORM_PHASE = (0.0, 0.0, 60.0, 0.0, 120.0, 200.0)


def _types():
    return {"chain": line_type_120mm_chain(), "polyester": line_type_186mm_polyester()}


def semitaut(segments_factor=1.0, period=PERIOD):
    """The three-line semi-taut system with clumps and buoys on one coupled platform (file
    segmentation: 25 m chain, 25 m polyester, 20 m top chain, times ``segments_factor``)."""
    points, lines = [], []
    for k, heading in enumerate(HEADINGS, start=1):
        u = np.array([np.cos(np.radians(heading)), np.sin(np.radians(heading)), 0.0])
        anchor = ANCHOR_RADIUS * u - [0.0, 0.0, DEPTH]
        fairlead = FAIRLEAD_RADIUS * u - [0.0, 0.0, FAIRLEAD_DEPTH]
        chord = fairlead - anchor
        clump_at = anchor + BOTTOM_CHAIN / np.linalg.norm(chord) * chord + [0.0, 0.0, 50.0]
        buoy_at = fairlead - TOP_CHAIN / np.linalg.norm(chord) * chord - [0.0, 0.0, 30.0]
        points += [PointSpec(f"anchor{k}", "fixed", tuple(np.round(anchor, 9))),
                   PointSpec(f"clump{k}", "free", tuple(np.round(clump_at, 6)), **CLUMP),
                   PointSpec(f"buoy{k}", "free", tuple(np.round(buoy_at, 6)), **BUOY),
                   PointSpec(f"fairlead{k}", "body", tuple(np.round(fairlead, 9)), body="platform")]
        lines += [LineSpec(f"bottom{k}", "chain", f"anchor{k}", f"clump{k}", BOTTOM_CHAIN, 16),
                  LineSpec(f"rope{k}", "polyester", f"clump{k}", f"buoy{k}", ROPE, 39),
                  LineSpec(f"top{k}", "chain", f"buoy{k}", f"fairlead{k}", TOP_CHAIN, 4)]
    body = BodySpec("platform", (0.0, 0.0, 0.0), PLATFORM_AMPLITUDE, PLATFORM_PHASE, period, period)
    net = Network("semitaut", "three chain-polyester-chain lines with a clump and a buoy each, on a coupled "
                  "platform in surge, heave, pitch and yaw", DEPTH, _types(), tuple(points), (body,),
                  tuple(sorted(lines, key=lambda l: ("bottom", "rope", "top").index(l.name[:-1]) * 10 + int(l.name[-1]))))
    return net.refined(segments_factor) if segments_factor != 1.0 else net


#: the free platform of the statics (VolturnUS-S-like): mass, displaced volume balancing the weight
#: and the lines' pull at rest, waterplane area, centre of gravity below and metacentre above the
#: reference point, and a steady offset load: 0.2 MN along +x, 0.06 MN along +y, a 2 MN m yaw moment
PLATFORM = {"mass": 1.8e7, "inertia": [1.2e10, 1.2e10, 1.9e10], "volume": 1.8e4, "waterplane_area": 450.0,
            "cg": [0.0, 0.0, -2.0], "cb": [0.0, 0.0, 5.0], "force": [0.2e6, 0.06e6, 0.0], "moment": [0.0, 0.0, 2.0e6]}


def free_platform(net):
    """``net`` (the semi-taut system) with its platform free under ``PLATFORM``'s steady load."""
    (body,) = net.bodies
    return replace(net, bodies=(replace(body, free=dict(PLATFORM)),))


SHARED_DEPTH = 300.0
SHARED_SPACING = 760.0  # m between the two platforms' reference points
SHARED_LENGTH = 380.0  # each half of the shared line, a clump between
SHARED_PERIOD = 12.0


def shared(segments_factor=1.0, period=SHARED_PERIOD):
    """Two coupled platforms, each on two chains, joined by a shared polyester line with a clump
    weight at its middle (file segmentation: 25 m chain, 20 m polyester)."""
    half = SHARED_SPACING / 2
    points = [PointSpec("clump", "free", (0.0, 0.0, -120.0), mass=15.0e3, volume=15.0e3 / 7850.0, CdA=1.0, Ca=1.0),
              PointSpec("shareA", "body", (30.0, 0.0, -FAIRLEAD_DEPTH), body="A"),
              PointSpec("shareB", "body", (-30.0, 0.0, -FAIRLEAD_DEPTH), body="B")]
    lines = [LineSpec("sharedA", "polyester", "shareA", "clump", SHARED_LENGTH, 19),
             LineSpec("sharedB", "polyester", "clump", "shareB", SHARED_LENGTH, 19)]
    for body, x0, headings in (("A", -half, (135.0, 225.0)), ("B", half, (45.0, 315.0))):
        for k, heading in enumerate(headings, start=1):
            u = np.array([np.cos(np.radians(heading)), np.sin(np.radians(heading)), 0.0])
            name = f"{body}{k}"
            points += [PointSpec(f"anchor{name}", "fixed", tuple(np.round([x0, 0.0, -SHARED_DEPTH] + 600.0 * u, 9))),
                       PointSpec(f"fairlead{name}", "body", tuple(np.round(30.0 * u - [0, 0, FAIRLEAD_DEPTH], 9)),
                                 body=body)]
            lines.append(LineSpec(f"moor{name}", "chain", f"anchor{name}", f"fairlead{name}", 700.0, 28))
    bodies = (BodySpec("A", (-half, 0.0, 0.0), (3.0, 0.0, 1.0, 0.0, 2.0, 2.0), (0.0, 0.0, 90.0, 0.0, 45.0, 180.0),
                       period, period),
              BodySpec("B", (half, 0.0, 0.0), (0.0, 3.0, 1.0, 2.0, 0.0, 2.0), (0.0, 0.0, 30.0, 135.0, 0.0, 270.0),
                       period, period))
    net = Network("shared", "two coupled platforms, each on two chains, joined by a shared polyester line with a "
                  "clump weight", SHARED_DEPTH, _types(), tuple(points), bodies, tuple(lines))
    return net.refined(segments_factor) if segments_factor != 1.0 else net


# ----------------------------------------------------------------------------- writers
def moordyn_text(net, dtM=5e-4, bodies_as_points=False):
    """The network as MoorDyn v2 text: coupled BODIES, points fixed / free / on a body, lines, the
    OPTIONS of validation/moordyn's housner files (dynamic relaxation, threshIC 1e-5). With
    ``bodies_as_points`` the points on bodies are coupled points at their rest positions and the
    file has no BODIES (the caller moves each point with its body)."""
    ids = {p.name: i + 1 for i, p in enumerate(net.points)}
    body_ids = {b.name: i + 1 for i, b in enumerate(net.bodies)}
    bodies = ("---------------------- BODIES ------------------------------------------------\n"
              "ID  Attachment  X0  Y0  Z0  r0  p0  y0  Mass  CG*  I*  Volume  CdA*  Ca*\n"
              "(#) (-)         (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)\n")
    for b in net.bodies:
        x, y, z = (_number(c) for c in b.position)
        bodies += f"{body_ids[b.name]:<3} coupled     {x}  {y}  {z}  0  0  0  0  0  0  0  0  0\n"
    points = ("---------------------- POINTS ------------------------------------------------\n"
              "ID  Attachment  X  Y  Z  M  V  CdA  CA\n(-) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)\n")
    for p in net.points:
        kind = {"fixed": "Fixed", "free": "Free"}.get(p.kind) or f"Body{body_ids[p.body]}"
        position = p.position
        if p.body and bodies_as_points:
            kind, position = "Coupled", np.add(next(b for b in net.bodies if b.name == p.body).position, p.position)
        x, y, z = (_number(c) for c in position)
        points += (f"{ids[p.name]:<3} {kind:<11} {x:<21} {y:<21} {z:<21} {p.mass!r}  {p.volume!r}  "
                   f"{p.CdA!r}  {p.Ca!r}\n")
    lines = "".join(f"{i + 1:<3} {line.type:<9} {ids[line.a]:<8} {ids[line.b]:<8} {line.length!r:<9} "
                    f"{line.segments:<8} -\n" for i, line in enumerate(net.lines))
    types = "".join(_type_row(name, props, net.beta) + "\n" for name, props in net.types.items())
    return ("--------------------- MoorDyn Input File ------------------------------------\n"
            f"{net.name}: {net.title}; validation/networks\n"
            f"kBot {KBOT:g} N/m^3, cBot {CBOT:g} N s/m^3 (MoorDyn's defaults, written); no friction\n"
            + TYPE_HEADER + types + ("" if bodies_as_points else bodies) + points + LINE_HEADER + lines + OPTIONS_HEADER
            + f"{dtM!r:<21} dtM           - s\n"
            + f"{net.depth!r:<21} WtrDpth       - m\n"
            + f"{WATER_DENSITY!r:<21} WtrDnsty      - kg/m^3\n"
            + f"{GRAVITY!r:<21} g             - m/s^2\n"
            + f"{KBOT!r:<21} kBot          - N/m^3\n"
            + f"{CBOT!r:<21} cBot          - N s/m^3\n"
            + IC_OPTIONS + IC_DYNAMIC
            + OUTPUTS.format(channels="FairTen1"))


def _vec(values):
    return "[" + ", ".join(repr(float(x)) for x in values) + "]"


def toml_text(net, dt=0.005):
    """The network as a cablefem TOML scene with MoorDyn-C's physics: damping_when_slack = true (its
    damping law), Cd_tangential = pi CdAx, the seabed's kBot and cBot, no friction."""
    out = [f"# {net.name}: {net.title}\n# written by validation/networks/systems.py; the MoorDyn file of the same "
           f"network is {net.name}.dat\nname = \"{net.name}\"\n",
           f"[environment]\nwater_density = {WATER_DENSITY!r}\ngravity = {GRAVITY!r}\n"]
    for name, p in net.types.items():
        out.append(f"[line_types.{name}]\ndiameter = {p['Diam']!r}\nmass = {p['MassDen']!r}\nEA = {p['EA']!r}\n"
                   f"damping = {net.beta!r}\nCd_normal = {p['Cd']!r}\nCd_tangential = {np.pi * p['CdAx']!r}\n"
                   f"Ca_normal = {p['Ca']!r}\nCa_tangential = {p['CaAx']!r}\ndamping_when_slack = true\n")
    for b in net.bodies:
        if b.free is not None:
            out.append(f"[bodies.{b.name}]\nkind = \"free\"\nposition = {_vec(b.position)}\n" + "".join(
                f"{key} = {_vec(value) if np.ndim(value) else repr(float(value))}\n" for key, value in b.free.items()))
            continue
        out.append(f"[bodies.{b.name}]\nkind = \"coupled\"\nposition = {_vec(b.position)}\n"
                   f"[bodies.{b.name}.motion]\nkind = \"harmonic\"\namplitude = {_vec(b.amplitude)}\n"
                   f"phase_deg = {_vec(b.phase_deg)}\nperiod = {b.period!r}\nramp = {b.ramp!r}\n")
    for p in net.points:
        where = f"body = \"{p.body}\"" if p.body else f"kind = \"{p.kind}\""
        extra = "".join(f"{key} = {getattr(p, key)!r}\n" for key in ("mass", "volume", "CdA", "Ca")
                        if getattr(p, key))
        out.append(f"[points.{p.name}]\n{where}\nposition = {_vec(p.position)}\n{extra}")
    for line in net.lines:
        out.append(f"[[lines]]\nname = \"{line.name}\"\nanchor = \"{line.a}\"\nfairlead = \"{line.b}\"\n"
                   f"segments = [{{ type = \"{line.type}\", length = {line.length!r}, elements = {line.segments} }}]\n")
    out.append(f"[seabed]\nkind = \"horizontal\"\ndepth = {net.depth!r}\nstiffness = {KBOT!r}\ndamping = {CBOT!r}\n")
    out.append(f"[solver]\ndt = {dt!r}\n")
    return "\n".join(out)
