"""MoorDyn v2 input files (MoorDyn-C 2.x layout) read into a cablefem Scene.

Sections read: LINE TYPES, POINTS, LINES, OPTIONS (value first: ``850 WtrDpth``)
and OUTPUTS (channel names, up to ``END``, recorded and ignored). Rows before
the first recognised ``---`` header are the title (``moordyn_sections`` cuts the
file). RODS, BODIES, ROD TYPES, FAILURE or any unrecognised section that holds
rows is refused by name. Numbers and IDs are ASCII (``str.isdigit`` and ``float``
would take other scripts' digits) and within the sane limits of ``validate.LIMITS``.

Mapping (each conversion checked against the MoorDyn 2.7 library, docs/scene.md):
- every chain of MoorDyn lines joined through massless free points that join
  exactly two lines becomes ONE multi-segment ``Line``, anchor (Fixed end) first;
- BA >= 0 is the internal damping coefficient [N s]: beta = BA / EA [s];
  BA < 0 is -zeta, MoorDyn's BA = zeta (UnstrLen / NumSegs) sqrt(EA m);
- CdAx refers to the surface area pi d l, desire2023 Eq. 3 to d: Cd_tangential = pi CdAx;
- kBot, cBot -> Contact.stiffness [N/m^3], Contact.damping [N s/m^3];
- MoorDyn-C friction is isotropic saturated damping (housner2022 Sec. 2.2 with one
  coefficient): |F| = mu FricDamp |v| per node until it exceeds StatDynFricScale mu |F_n|,
  then mu |F_n|; v_threshold is the velocity where that happens for a node of the
  first line's anchor segment resting on the seabed (FricDamp is kept as well).

Seabed (model only what a scene needs, docs/seabeds.md): a SeafloorFile grid that is
planar is replaced by its plane (``geometry.choose_seabed``, shared with the TOML reader),
and the note says which model was chosen.
"""

import math
import os
import re

import numpy as np

from ..errors import InputError
from ..geometry import Horizontal, choose_seabed
from ..geometry.readers import is_integer, is_number, parse_number
from ..line import Line, LineType, Segment
from ..scene import Contact, Environment, Friction, Scene, Solver
from . import validate as v
from .moordyn_sections import TABLE_COLUMNS, at as _at, parse_sections, split_sections

FIXED = ("ANCHOR", "FIXED", "FIX")
COUPLED = ("VESSEL", "VES", "COUPLED", "CPLD", "FAIRLEAD")
FREE = ("CONNECT", "CON", "FREE")
NO_MOTION_NOTE = "MoorDyn files have no fairlead motion: coupled points stay fixed"
#: MoorDyn-C 2.x defaults of the options cablefem uses (g and kBot measured with the library)
OPTION_DEFAULTS = {"wtrdnsty": 1025.0, "g": 9.80665, "kbot": 3.0e6, "cbot": 3.0e5,
                   "frictioncoefficient": 0.0, "fricdamp": 200.0, "statdynfricscale": 1.0}
_COEFFICIENT = v.limited(v.non_negative, "coefficient")
LINE_TYPE_CHECKS = {"Diam": v.limited(v.positive, "diameter"), "MassDen": v.limited(v.positive, "mass"),
                    "EA": v.limited(v.positive, "EA"), "BA/-zeta": v.number, "EI": v.non_negative,
                    "Cd": _COEFFICIENT, "Ca": _COEFFICIENT, "CdAx": _COEFFICIENT, "CaAx": _COEFFICIENT}
OPTION_ALIASES = {"rhow": "wtrdnsty", "gravity": "g"}
OPTION_CHECKS = {"wtrdpth": v.limited(v.positive, "length"),
                 "wtrdnsty": v.limited(v.positive, "water_density"),
                 "g": v.limited(v.positive, "gravity"), "kbot": v.limited(v.positive, "stiffness"),
                 "cbot": v.limited(v.non_negative, "contact_damping"),
                 "frictioncoefficient": v.limited(v.non_negative, "friction"),
                 "fricdamp": v.limited(v.positive, "friction_damping"),
                 "statdynfricscale": v.limited(v.positive, "friction"), "dtm": v.positive,
                 "tmax": v.positive}
_COORDINATE = v.limited(v.number, "coordinate")
_WHOLE = re.compile(r"-?[0-9]+")  # ASCII digits only: str.isdigit() takes '\u00b2', which int() refuses


def _value(token, number, key, check=v.number):
    """A checked number from a file token; the error names the file line and the column."""
    value = parse_number(token)
    if value is None:
        raise InputError(f"expected a number, got '{token}'", key=_at(number, key))
    return check(value, _at(number, key))


def _line_types(rows, notes):
    """Raw line types by name: dict name -> (row number, dict of floats)."""
    types = {}
    for number, fields in rows:
        name = fields[0]
        key = f"LINE TYPES.{name}"
        if name in types:
            raise InputError("duplicate line type name", key=_at(number, key))
        for column, token in zip(("EA", "BA/-zeta"), fields[3:5]):
            if "|" in token or not is_number(token):
                raise InputError(f"nonlinear or viscoelastic {column} ('{token}') is not supported yet",
                                 key=_at(number, f"{key}.{column}"))
        values = {col: _value(tok, number, f"{key}.{col}", LINE_TYPE_CHECKS[col])
                  for col, tok in zip(TABLE_COLUMNS["LINE TYPES"][1:], fields[1:10])}
        if values["EI"] != 0.0:
            notes.append(f"LINE TYPES.{name}: EI = {values['EI']:g} N m^2 ignored (no bending stiffness)")
        if any(is_number(f) and float(f) != 0.0 for f in fields[10:]):
            notes.append(f"LINE TYPES.{name}: columns after CaAx ignored ({' '.join(fields[10:])})")
        types[name] = (number, values)
    return types


def _points(rows, notes):
    """Points by ID: dict id -> (row number, kind 'fixed'|'coupled'|'free', position (3,), M, V)."""
    points = {}
    for number, fields in rows:
        key = f"POINTS.{fields[0]}"
        if not is_integer(fields[0]):
            raise InputError(f"expected a point number, got '{fields[0]}'", key=_at(number, key))
        pid = int(fields[0])
        if pid in points:
            raise InputError("duplicate point ID", key=_at(number, key))
        attachment = fields[1].upper()
        if attachment.startswith(("BODY", "TURBINE")):
            raise InputError(f"attachment '{fields[1]}': BODIES are not supported yet", key=_at(number, key))
        kind = ("fixed" if attachment in FIXED else "coupled" if attachment in COUPLED
                else "free" if attachment in FREE else None)
        if kind is None:
            raise InputError(f"unknown attachment '{fields[1]}'; valid: Fixed/Anchor, Coupled/Vessel, "
                             "Free/Connect", key=_at(number, f"{key}.Attachment"))
        x, y, z, mass, volume, cda, ca = (_value(tok, number, f"{key}.{col}", _COORDINATE if col in ("X", "Y", "Z")
                                                 else v.number)
                                          for col, tok in zip(TABLE_COLUMNS["POINTS"][2:], fields[2:9]))
        if kind == "free" and (cda or ca) and not (mass or volume):
            notes.append(f"POINTS.{pid}: CdA and CA of a joint between two lines ignored")
        points[pid] = (number, kind, np.array([x, y, z]), mass, volume)
    return points


def _lines(rows, types, points):
    """Raw lines in file order: dicts with id, type, ends (point IDs), length [m], segments, row."""
    lines, ids = [], set()
    for number, fields in rows:
        key = f"LINES.{fields[0]}"
        if fields[0] in ids:
            raise InputError("duplicate line ID", key=_at(number, key))
        ids.add(fields[0])
        if fields[1] not in types:
            raise InputError(f"unknown line type '{fields[1]}'{v.suggest(fields[1], types)}; "
                             f"defined in LINE TYPES: {', '.join(types) or 'none'}",
                             key=_at(number, f"{key}.LineType"))
        ends = []
        for column, token in zip(("AttachA", "AttachB"), fields[2:4]):
            if token.upper().startswith("R"):
                raise InputError(f"attached to rod end '{token}': RODS are not supported yet",
                                 key=_at(number, f"{key}.{column}"))
            if not is_integer(token) or int(token) not in points:
                raise InputError(f"no point '{token}' in POINTS", key=_at(number, f"{key}.{column}"))
            ends.append(int(token))
        length = _value(fields[4], number, f"{key}.UnstrLen", v.limited(v.positive, "length"))
        segments = v.limited(v.whole, "nodes")(int(fields[5]) if _WHOLE.fullmatch(fields[5]) else fields[5],
                                               _at(number, f"{key}.NumSegs"))
        lines.append({"id": fields[0], "type": fields[1], "ends": ends, "length": length,
                      "segments": segments, "row": number})
    if not lines:
        raise InputError("the file defines no lines", key="LINES")
    return lines


def _options(rows, notes):
    """OPTIONS as (checked values by lower-case name, raw text by name, seafloor file or None,
    file line numbers by lower-case name)."""
    values, raw, seafloor, ignored, numbers = {}, {}, None, [], {}
    for number, fields in rows:
        if len(fields) < 2:
            raise InputError("expected 'value name'", key=_at(number, "OPTIONS"))
        token, name = fields[0], fields[1]
        raw[name] = token
        lower = OPTION_ALIASES.get(name.lower(), name.lower())
        if lower == "seafloorfile":
            seafloor = (token, number)
        elif lower in OPTION_CHECKS:
            values[lower] = _value(token, number, f"OPTIONS.{name}", OPTION_CHECKS[lower])
            numbers[lower] = number
        else:
            ignored.append(name)
    if ignored:
        notes.append(f"OPTIONS ignored by cablefem: {', '.join(ignored)}")
    if "dtm" in values:
        notes.append(f"dtM = {values['dtm']:g} s is MoorDyn's explicit step; the implicit solver keeps its own dt")
    return values, raw, seafloor, numbers


def damping_time(ba, ea, mass, length, segments):
    """beta [s] in T = EA (e + beta de/dt) from MoorDyn's BA [N s] or -zeta (per-segment critical ratio)."""
    if ba >= 0:
        return ba / ea
    return -ba * (length / segments) * math.sqrt(ea * mass) / ea


def _chains(lines, points):
    """Lists of (raw line) joined through free points, each ordered anchor first."""
    at_point = {}
    for index, line in enumerate(lines):
        for end, pid in enumerate(line["ends"]):
            at_point.setdefault(pid, []).append((index, end))
    for pid, (number, kind, _, mass, volume) in points.items():
        count = len(at_point.get(pid, []))
        if kind != "free" or count == 0:
            continue
        if mass or volume:
            raise InputError(f"free point with mass {mass:g} kg / volume {volume:g} m^3 is not supported yet "
                             "(only massless joints between two lines)", key=_at(number, f"POINTS.{pid}"))
        if count != 2:
            raise InputError(f"free point joining {count} line ends is not supported yet "
                             "(only joints between exactly two lines)", key=_at(number, f"POINTS.{pid}"))
    chains, used = [], set()
    for start in range(len(lines)):
        if start in used:
            continue
        chain, used_here = [start], {start}
        for forward in (True, False):
            index, pid = start, lines[start]["ends"][1 if forward else 0]
            while points[pid][1] == "free":
                others = [e for e in at_point[pid] if e[0] != index]
                index, end = others[0] if others else (index, 0)
                if index in used_here:
                    raise InputError("lines joined through free points form a loop",
                                     key=_at(lines[index]["row"], f"LINES.{lines[index]['id']}"))
                used_here.add(index)
                chain.insert(len(chain) if forward else 0, index)
                pid = lines[index]["ends"][1 - end]
            if forward:
                last = pid
            else:
                first = pid
        used |= used_here
        kinds = (points[first][1], points[last][1])
        if kinds == ("coupled", "fixed"):
            chain.reverse()
            first, last = last, first
        elif kinds != ("fixed", "coupled"):
            ids = "+".join(lines[i]["id"] for i in chain)
            raise InputError(f"runs between a {kinds[0]} and a {kinds[1]} point; cablefem needs one Fixed "
                             "(anchor) and one Coupled (fairlead) end", key=_at(lines[chain[0]]["row"], f"LINES.{ids}"))
        chains.append(([lines[i] for i in chain], first, last))
    return chains


def read_moordyn(path, simplify=True):
    """The Scene of a MoorDyn v2 input file: lines anchor first, flat or gridded seabed, fixed fairleads.

    ``simplify``: replace a planar SeafloorFile grid by its plane (``choose_seabed``).
    """
    path = os.path.abspath(path)
    try:
        with open(path, encoding="utf-8", errors="strict") as handle:
            text = handle.read()
    except UnicodeDecodeError:
        raise InputError("not a MoorDyn input file (not text)", file=path) from None
    try:
        return _build(path, text, simplify)
    except InputError as error:
        raise error.within(file=path) from None


def _build(path, text, simplify=True):
    """The Scene of MoorDyn file text (errors without the file name; read_moordyn adds it)."""
    notes = []
    found = parse_sections(split_sections(text))
    if not found["LINE TYPES"] and not found["LINES"]:
        raise InputError("no LINE TYPES or LINES section: not a MoorDyn v2 input file")
    raw_types = _line_types(found["LINE TYPES"], notes)
    points = _points(found["POINTS"], notes)
    raw_lines = _lines(found["LINES"], raw_types, points)
    options, raw_options, seafloor, options_rows = _options(found["OPTIONS"], notes)
    if found["OUTPUTS"]:
        notes.append(f"OUTPUTS ignored: {' '.join(f for _, fields in found['OUTPUTS'] for f in fields)}")
    get = lambda name: options.get(name, OPTION_DEFAULTS.get(name))  # noqa: E731
    environment = Environment(water_density=get("wtrdnsty"), gravity=get("g"))
    built_types, lines, keys = {}, [], {"name": (path, "name (from the file name)")}
    for chain, first, last in _chains(raw_lines, points):
        segments = [Segment(_line_type(raw, raw_types, built_types), raw["length"], raw["segments"])
                    for raw in chain]
        name = "line" + "+".join(raw["id"] for raw in chain)
        line = Line(name, points[first][2], points[last][2], segments)
        key = _at(chain[0]["row"], f"LINES.{'+'.join(r['id'] for r in chain)}")
        lines.append(v.check_chord(line, key))
        keys.update(_line_keys(path, len(lines) - 1, key, chain, (first, last), points))
        if len(chain) > 1:
            notes.append(f"{name}: MoorDyn lines {', '.join(r['id'] for r in chain)} joined through free "
                         "points into one line, anchor first")
    for pid, (number, kind, _, _, _) in points.items():
        if not any(pid in raw["ends"] for raw in raw_lines):
            notes.append(f"POINTS.{pid} ({kind}) is attached to no line; ignored")
    if seafloor is not None:
        keys["seabed"] = (path, _at(seafloor[1], "OPTIONS.SeafloorFile"))
        file = v.existing_file(seafloor[0], keys["seabed"][1], os.path.dirname(path))
        seabed = v.read_seabed_file(file, "grid", keys["seabed"][1])
    elif "wtrdpth" in options:
        keys["seabed"] = (path, _at(options_rows["wtrdpth"], "OPTIONS.WtrDpth"))
        seabed = Horizontal(options["wtrdpth"])
    else:
        raise InputError("missing: needed for the seabed unless SeafloorFile is given", key="OPTIONS.WtrDpth")
    contact = Contact(stiffness=get("kbot"), damping=get("cbot"))
    seabed, seabed_note = choose_seabed(seabed, lines, simplify)
    friction = _friction(get, lines[0], environment, notes)
    solver = Solver(duration=options["tmax"]) if "tmax" in options else Solver()
    if "tmax" in options:
        keys["solver.duration"] = (path, _at(options_rows["tmax"], "OPTIONS.TMax"))
    notes += [seabed_note, NO_MOTION_NOTE]
    return Scene(name=os.path.splitext(os.path.basename(path))[0], lines=lines, seabed=seabed,
                 contact=contact, environment=environment, friction=friction, solver=solver,
                 source=path, notes=notes, moordyn_options=raw_options, keys=keys)


def _line_keys(path, index, key, chain, ends, points):
    """Where the scene keys of line ``index`` stand in the MoorDyn file: dict scene key -> (path, key)."""
    keys = {f"lines[{index}]": (path, key), f"lines[{index}].name": (path, key)}
    for end, pid in zip(("anchor", "fairlead"), ends):
        keys[f"lines[{index}].{end}"] = (path, _at(points[pid][0], f"POINTS.{pid}"))
    for j, raw in enumerate(chain):
        keys[f"lines[{index}].segments[{j}].elements"] = (path, _at(raw["row"], f"LINES.{raw['id']}.NumSegs"))
    return keys


def _line_type(raw, raw_types, built):
    """The LineType of one MoorDyn line (BA < 0 depends on the line's segment length)."""
    number, props = raw_types[raw["type"]]
    beta = damping_time(props["BA/-zeta"], props["EA"], props["MassDen"], raw["length"], raw["segments"])
    v.limited(v.number, "damping_time")(beta, _at(number, f"LINE TYPES.{raw['type']}.BA/-zeta (beta)"))
    name = raw["type"]
    if name in built and built[name].damping != beta:
        name = f"{raw['type']}-line{raw['id']}"
    if name not in built:  # values were checked by _line_types
        built[name] = LineType(name, props["Diam"], props["MassDen"], props["EA"], beta,
                               Cd_normal=props["Cd"], Cd_tangential=math.pi * props["CdAx"],
                               Ca_normal=props["Ca"], Ca_tangential=props["CaAx"],
                               damping_when_slack=True)  # MoorDyn-C's own law (Line.cpp, Td[i])
    return built[name]


def _friction(get, first_line, environment, notes):
    """Friction from FrictionCoefficient, FricDamp and StatDynFricScale (see the module docstring)."""
    mu, damping, scale = get("frictioncoefficient"), get("fricdamp"), get("statdynfricscale")
    if mu == 0:
        return Friction(model="none", static_scale=scale, saturation_damping=damping)
    segment = first_line.segments[0]
    node_force = abs(segment.type.submerged_weight(environment.water_density, environment.gravity)
                     * segment.length / segment.elements)
    v_threshold = scale * node_force / damping if node_force > 0 else Friction.v_threshold
    notes.append(f"friction: MoorDyn-C isotropic saturated damping, mu = {mu:g}, FricDamp = {damping:g} "
                 f"N s/m -> v_threshold = {v_threshold:.4g} m/s for a resting node of {first_line.name}")
    return Friction(model="isotropic", mu=mu, static_scale=scale, v_threshold=v_threshold,
                    saturation_damping=damping)
