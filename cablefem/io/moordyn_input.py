"""MoorDyn v2 input files (MoorDyn-C 2.x layout) read into a cablefem Scene.

Sections read: LINE TYPES (v2 columns, or the v1 header read by position as MoorDyn-C reads it),
ROD TYPES, BODIES, RODS (``moordyn_rods``), POINTS, LINES, OPTIONS (value first: ``850 WtrDpth``) and OUTPUTS (channel names, up to
``END``, recorded and ignored). Rows before the first recognised ``---`` header are the title
(``moordyn_sections`` cuts the file). What cablefem does not read (WaveKin 4 to 6, Currents 3 and
4, ...) is refused with what to do instead, from the one list ``moordyn_sections.REFUSED``. Numbers
and IDs are ASCII (``str.isdigit`` and ``float`` would take other scripts' digits) and within the
sane limits of ``validate.LIMITS``.

Mapping (each conversion checked against the MoorDyn 2.7 library, docs/scene.md):
- BODIES and POINTS become ``cablefem.model.network`` Bodies and Points (``moordyn_network``), each
  MoorDyn line a ``Line`` between two of them; ``network.strings`` joins lines through free points
  that join exactly two line ends into ONE multi-segment line named ``line1+2``, its most fixed end
  first. Junctions of three or more line ends and free bodies are read as they are: the statics
  solve them (``cablefem.statics.network``), a run steps them (``cablefem.dynamics.body_group``);
- ``Currents 1``: the steady profile of ``current_profile.txt`` beside the file (``io.currents``);
  ``Currents 2`` and ``5``: a current varying in time (and with ``5`` in x and y) from
  ``current_profile_dynamic.txt`` or ``current_profile_4d.txt``, which rides on the scene's Sea
  (``Sea.current``; still water with no WaveKin);
- ``WaveKin`` 2, 3 and 7: the waves of their files beside the file (``io.moordyn_waves``); ``WaveKin 1``
  (kinematics through MoorDyn-C's API, still water until a program sets them): still water, with a note;
- BA >= 0 is the internal damping coefficient [N s]: beta = BA / EA [s];
  BA < 0 is -zeta, MoorDyn's BA = zeta (UnstrLen / NumSegs) sqrt(EA m);
- CdAx refers to the surface area pi d l, desire2023 Eq. 3 to d: Cd_tangential = pi CdAx;
- EI > 0: the line is read on Hermite elements (``cablefem.loads.bending``), NumSegs elements;
  MoorDyn lumps EI as couples between neighbouring nodes, cablefem integrates 1/2 EI kappa^2;
- kBot, cBot -> Contact.stiffness [N/m^3], Contact.damping [N s/m^3], with MoorDyn-C's damper
  acting on penetrating nodes moving out too (Contact.damping_when_opening);
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
from dataclasses import replace

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry import Horizontal, choose_seabed
from cablefem.geometry.readers import is_number
from cablefem.model.line import Line, LineType, Segment
from cablefem.model.network import point_position, strings as network_strings
from cablefem.model import defaults as by_physics
from cablefem.model.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver
from cablefem.io import validate as v
from cablefem.io.axial_input import is_law, moordyn_law
from cablefem.io.currents import GRID_FILES, MOORDYN_FILE, read_current_grid, read_current_profile
from cablefem.io.moordyn_waves import DT_WAVE, read_wave_kin
from cablefem.waves import Sea
from cablefem.io.moordyn_network import line_end, read_bodies, read_points
from cablefem.io.moordyn_rods import clamp_directions, read_rods, rod_end, rod_network
from cablefem.io.failures import read_moordyn_failures
from cablefem.io.moordyn_sections import (TABLE_COLUMNS, at as _at, parse_sections, refuse, split_sections,
    value as _value)

NO_MOTION_NOTE = "MoorDyn files have no fairlead motion: coupled points stay fixed"
BODY_NO_MOTION_NOTE = ("MoorDyn files have no body motion: coupled bodies stay where the file puts them (a TOML "
                       "that wraps the file gives [bodies.NAME.motion])")
#: MoorDyn-C 2.x defaults of the options cablefem uses (g and kBot measured with the library)
OPTION_DEFAULTS = {"wtrdnsty": 1025.0, "g": 9.80665, "kbot": 3.0e6, "cbot": 3.0e5,
                   "frictioncoefficient": 0.0, "fricdamp": 200.0, "statdynfricscale": 1.0}
_COEFFICIENT = v.limited(v.non_negative, "coefficient")
LINE_TYPE_CHECKS = {"Diam": v.limited(v.positive, "diameter"), "MassDen": v.limited(v.positive, "mass"),
                    "EA": v.limited(v.positive, "EA"), "BA/-zeta": v.number, "EI": v.non_negative,
                    "Cd": _COEFFICIENT, "Ca": _COEFFICIENT, "CdAx": _COEFFICIENT, "CaAx": _COEFFICIENT}
OPTION_ALIASES = {"rhow": "wtrdnsty", "rho": "wtrdnsty", "gravity": "g", "kb": "kbot", "cb": "cbot"}
OPTION_CHECKS = {"wtrdpth": v.limited(v.positive, "length"),
                 "wtrdnsty": v.limited(v.non_negative, "water_density"),
                 "g": v.limited(v.non_negative, "gravity"), "kbot": v.limited(v.positive, "stiffness"),
                 "cbot": v.limited(v.non_negative, "contact_damping"),
                 "frictioncoefficient": v.limited(v.non_negative, "friction"),
                 "fricdamp": v.limited(v.positive, "friction_damping"),
                 "statdynfricscale": v.limited(v.positive, "friction"), "dtm": v.positive,
                 "tmax": v.positive, "dtout": v.non_negative, "currents": v.number, "wavekin": v.number, "dtwave": v.positive}
_WHOLE = re.compile(r"-?[0-9]+")  # ASCII digits only: str.isdigit() takes '\u00b2', which int() refuses
V1_LINES_NOTE = ("LINES (line {row}): MoorDyn v1 columns (UnstrLen NumSegs NodeAnch NodeFair), read as the header "
                 "names them: AttachA = NodeAnch, AttachB = NodeFair (MoorDyn-C 2.x reads LINES by position as v2 "
                 "columns and would take UnstrLen as AttachA)")
#: v1 LINE TYPES header names and the quantity MoorDyn-C reads at their positions (7-10)
V1_NOTE = ("LINE TYPES (line {row}): MoorDyn v1 column names (Can Cat Cdn Cdt); read by position as "
           "MoorDyn-C reads them: the 7th column as Cd (normal drag), the 8th as Ca, the 9th as CdAx, the 10th "
           "as CaAx, whatever the header says")


def _line_types(rows, v1, notes):
    """Raw line types by name: dict name -> (row number, dict of floats)."""
    for row in v1:
        notes.append(V1_NOTE.format(row=row))
    types = {}
    for number, fields in rows:
        name = fields[0]
        key = f"LINE TYPES.{name}"
        if name in types:
            raise InputError("duplicate line type name", key=_at(number, key))
        law = is_law(fields[3], fields[4])
        values = {col: _value(tok, number, f"{key}.{col}", LINE_TYPE_CHECKS[col])
                  for col, tok in zip(TABLE_COLUMNS["LINE TYPES"][1:], fields[1:10])
                  if not (law and col in ("EA", "BA/-zeta"))}
        if law:  # read per line (BA = -zeta depends on the line's segments): _line_type
            values["law"] = (fields[3], fields[4])
        if values["EI"] != 0.0:
            notes.append(f"LINE TYPES.{name}: EI = {values['EI']:g} N m^2: its lines are read on Hermite elements "
                         "(positions and tangents at the nodes), NumSegs elements each, pinned at both ends")
        if any(is_number(f) and float(f) != 0.0 for f in fields[10:]):
            notes.append(f"LINE TYPES.{name}: columns after CaAx ignored ({' '.join(fields[10:])})")
        types[name] = (number, values)
    return types


def _lines(rows, types, points, v1=(), notes=None, rods=None):
    """Raw lines in file order: dicts with id, type, ends (point names), length [m], segments, row.
    ``v1``: the rows of a v1 header (Line LineType UnstrLen NumSegs NodeAnch NodeFair Flags): its
    columns are read as it names them."""
    lines, ids = [], set()
    for row in v1:
        notes.append(V1_LINES_NOTE.format(row=row))
    for number, fields in rows:
        if v1:
            fields = fields[:2] + fields[4:6] + fields[2:4] + fields[6:]
        key = f"LINES.{fields[0]}"
        if fields[0] in ids:
            raise InputError("duplicate line ID", key=_at(number, key))
        ids.add(fields[0])
        if fields[1] not in types:
            raise InputError(f"unknown line type '{fields[1]}'{v.suggest(fields[1], types)}; "
                             f"defined in LINE TYPES: {', '.join(types) or 'none'}",
                             key=_at(number, f"{key}.LineType"))
        ends = [rod_end(token, rods or {}, _at(number, f"{key}.{column}"))
                or line_end(token, points, _at(number, f"{key}.{column}"))
                for column, token in zip(("AttachA", "AttachB"), fields[2:4])]
        length = _value(fields[4], number, f"{key}.UnstrLen", v.limited(v.positive, "length"))
        segments = v.limited(v.whole, "nodes")(int(fields[5]) if _WHOLE.fullmatch(fields[5]) else fields[5],
                                               _at(number, f"{key}.NumSegs"))
        lines.append({"id": fields[0], "type": fields[1], "ends": ends, "length": length,
                      "segments": segments, "row": number})
    if not lines:
        raise InputError("the file defines no lines", key="LINES")
    return lines


def _syrope_ic(rows, raw_lines, raw_types):
    """SYROPE IC rows ('Line(s) Tmax0 Tmean0', lines as '1' or '1,2,3') as {line ID: (Tmax0, Tmean0)}
    and {line ID: row number}; a section without a SYROPE line type is refused (MoorDyn-C does)."""
    ids = {raw["id"] for raw in raw_lines}
    initial, where = {}, {}
    if rows and not any(props.get("law", ("",))[0].startswith("SYROPE:") for _, props in raw_types.values()):
        raise InputError("a SYROPE IC section, but no line type is a SYROPE rope (EA 'SYROPE:file|EA_Dc|EA_D_Lm')",
                         key=_at(rows[0][0], "SYROPE IC"))
    for number, fields in rows:
        key = _at(number, f"SYROPE IC.{fields[0]}")
        if len(fields) < 3:
            raise InputError(f"expected 3 fields 'Line(s) Tmax0 Tmean0', got {len(fields)}", key=key)
        peak = _value(fields[1], number, f"SYROPE IC.{fields[0]}.Tmax0", v.limited(v.positive, "force"))
        mean = _value(fields[2], number, f"SYROPE IC.{fields[0]}.Tmean0", v.limited(v.non_negative, "force"))
        for line_id in fields[0].split(","):
            if line_id not in ids:
                raise InputError(f"no line '{line_id}' in LINES", key=key)
            initial[line_id], where[line_id] = (peak, mean), number
    return initial, where


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


def raw_option(raw, lower):
    """The text of option ``lower`` (case-insensitive name) as written."""
    return next(text for name, text in raw.items() if name.lower() == lower)


def _currents(path, options, numbers, notes):
    """The CurrentProfile of ``Currents 1`` (current_profile.txt beside the file) and the CurrentGrid of
    ``Currents 2`` or ``5`` (their files beside it; ``io.currents.read_current_grid``), each or None."""
    mode = options.get("currents", 0.0)
    if mode == 0.0:
        return None, None
    key = _at(numbers["currents"], "OPTIONS.Currents")
    if mode not in (1.0, 2.0, 5.0):
        refuse("Currents", key, f"Currents {mode:g}")
    name = MOORDYN_FILE if mode == 1.0 else GRID_FILES[int(mode)]
    file = v.existing_file(name, f"{key} ({name})", os.path.dirname(path))
    if mode == 1.0:
        profile = read_current_profile(file, key)
        notes.append(f"Currents 1: a steady current profile of {len(profile.z)} heights from {file}")
        return profile, None
    grid = read_current_grid(int(mode), file, key)
    nx, ny, nz, nt = grid.velocity.shape[:4]
    notes.append(f"Currents {mode:g}: a current varying in time from {file} ({nx} x {ny} x {nz} points, {nt} "
                 f"times every {grid.dt:g} s), interpolated as MoorDyn-C interpolates it; its acceleration is "
                 "zero, as MoorDyn-C has it")
    return None, grid


def _waves(path, options, numbers, depth, gravity, read, notes):
    """The Sea of ``WaveKin`` 2, 3 or 7 with its files beside the file (``io.moordyn_waves``), or None:
    WaveKin 0, or ``read`` false (a TOML that wraps the file gives [waves] instead)."""
    mode = options.get("wavekin", 0.0)
    if mode == 0.0:
        return None
    key = _at(numbers["wavekin"], "OPTIONS.WaveKin")
    if mode == 1.0 and read:
        notes.append("WaveKin 1: MoorDyn-C takes the waves through its API (ExternalWaveKinSet) and has still water "
                     "until a program sets them; a file alone is run in still water, as MoorDyn-C runs it (give "
                     "[waves] in a TOML that wraps the file for waves)")
        return None
    if not read:
        notes.append(f"WaveKin {mode:g} of {os.path.basename(path)} replaced by the TOML's [waves]")
        return None
    sea = read_wave_kin(mode, os.path.dirname(path), depth, gravity, options.get("dtwave", DT_WAVE), key)
    notes.append(f"WaveKin {mode:g}: {sea.count} wave components from {sea.source}, summed at each point"
                 + (" (MoorDyn-C interpolates them on water_grid.txt)" if mode != 7.0 else ""))
    return sea


def named_file(value, key, folder):
    """The path of a data file a MoorDyn file names (``SeafloorFile``): where MoorDyn-C opens it, the
    name as given, from the working directory; otherwise beside the file (``folder``)."""
    here = os.path.abspath(os.path.expanduser(value))
    if not os.path.isabs(value) and os.path.isfile(here):
        return here
    return v.existing_file(value, key, folder)


def damping_time(ba, ea, mass, length, segments):
    """beta [s] in T = EA (e + beta de/dt) from MoorDyn's BA [N s] or -zeta (per-segment critical ratio)."""
    if ba >= 0:
        return ba / ea
    return -ba * (length / segments) * math.sqrt(ea * mass) / ea


def read_moordyn(path, simplify=True, waves=True, defaults=True):
    """The Scene of a MoorDyn v2 input file: lines anchor first, flat or gridded seabed, fixed fairleads.

    ``simplify``: replace a planar SeafloorFile grid by its plane (``choose_seabed``); ``waves``: read
    WaveKin and its files (False: a TOML that wraps the file gives its own [waves]); ``defaults``: the
    mesh and step chosen by ``cablefem.model.defaults`` (False: each line's segments carry NumSegs
    elements and the solver its plain defaults, for a TOML that wraps the file to choose).
    """
    path = os.path.abspath(path)
    try:
        with open(path, encoding="utf-8", errors="strict") as handle:
            text = handle.read()
    except UnicodeDecodeError:
        raise InputError("not a MoorDyn input file (not text)", file=path) from None
    try:
        return _build(path, text, simplify, waves, defaults)
    except InputError as error:
        raise error.within(file=path) from None


def _build(path, text, simplify=True, waves=True, defaults=True):
    """The Scene of MoorDyn file text (errors without the file name; read_moordyn adds it)."""
    notes = []
    found = parse_sections(split_sections(text))
    if not found["LINE TYPES"] and not found["LINES"]:
        raise InputError("no LINE TYPES or LINES section: not a MoorDyn v2 input file")
    raw_types = _line_types(found["LINE TYPES"], found["v1"].get("LINE TYPES", ()), notes)
    bodies = read_bodies(found["BODIES"], notes)
    rods = read_rods(found["ROD TYPES"], found["RODS"], bodies, notes)
    points = read_points(found["POINTS"], bodies, notes)
    raw_lines = _lines(found["LINES"], raw_types, points, found["v1"].get("LINES", ()), notes, rods)
    rod_points, rod_bodies = rod_network(rods, bodies, {name for raw in raw_lines for name in raw["ends"]}, notes)
    options, raw_options, seafloor, options_rows = _options(found["OPTIONS"], notes)
    if found["OUTPUTS"]:
        notes.append(f"OUTPUTS ignored: {' '.join(f for _, fields in found['OUTPUTS'] for f in fields)}")
    get = lambda name: options.get(name, OPTION_DEFAULTS.get(name))  # noqa: E731
    profile, current_grid = _currents(path, options, options_rows, notes)
    environment = Environment(water_density=get("wtrdnsty"), gravity=get("g"), current_profile=profile)
    scene_points = {point.name: point for _, point in [*points.values(), *rod_points.values()]}
    scene_bodies = {**{body.name: body for _, body in bodies.values()}, **rod_bodies}
    syrope_ic, syrope_rows = _syrope_ic(found["SYROPE IC"], raw_lines, raw_types)
    lines, keys = _network(path, raw_lines, raw_types, points, scene_points, scene_bodies, notes, syrope_ic,
                           syrope_rows, rod_points, rods)
    keys.update({f"bodies.{body.name}": (path, _at(number, f"BODIES.{bid}")) for bid, (number, body) in bodies.items()})
    keys.update({f"bodies.{rods[rid][3].name}": (path, _at(rods[rid][0], f"RODS.{rid}")) for rid in rods})
    failures = read_moordyn_failures(found["FAILURE"], raw_lines, points, lines, _at)
    if seafloor is not None:
        keys["seabed"] = (path, _at(seafloor[1], "OPTIONS.SeafloorFile"))
        file = named_file(seafloor[0], keys["seabed"][1], os.path.dirname(path))
        seabed = v.read_seabed_file(file, "grid", keys["seabed"][1])
    elif "wtrdpth" in options:
        keys["seabed"] = (path, _at(options_rows["wtrdpth"], "OPTIONS.WtrDpth"))
        seabed = Horizontal(options["wtrdpth"])
    else:
        raise InputError("missing: needed for the seabed unless SeafloorFile is given", key="OPTIONS.WtrDpth")
    # MoorDyn-C's waves see WtrDpth, or the seafloor grid's average depth
    depth = -float(np.mean(seabed.z)) if seafloor is not None else options.get("wtrdpth", 0.0)
    sea = _waves(path, options, options_rows, depth, get("g"), waves, notes)
    if current_grid is not None:  # the current adds to the waves' velocity
        sea = Sea.current_only(current_grid, depth, get("g")) if sea is None else replace(sea, current=current_grid)
    environment = replace(environment, waves=sea)
    contact = Contact(stiffness=get("kbot"), damping=get("cbot"), damping_when_opening=True)
    seabed, seabed_note = choose_seabed(seabed, lines, simplify)
    friction = _friction(get, lines[0], environment, notes)
    solver = Solver(duration=options["tmax"]) if "tmax" in options else Solver()
    if "tmax" in options:
        keys["solver.duration"] = (path, _at(options_rows["tmax"], "OPTIONS.TMax"))
    output = Output()
    if options.get("dtout", 0.0) > 0.0:  # 0, MoorDyn's default: every coupling step, which cablefem has not
        output = Output(every=options["dtout"])
        keys["output.every"] = (path, _at(options_rows["dtout"], "OPTIONS.dtOut"))
    if defaults:  # after _friction, which scales FricDamp with MoorDyn's segments
        lines, mesh_note = by_physics.moordyn_mesh(lines, environment.water_density)
        solver, step_note = by_physics.step(solver, (), Motion(), environment.waves)
        output, frame_note = by_physics.frames(output, {"every"} if "output.every" in keys else (), solver, Motion(),
                                               environment.waves)
        notes += [note for note in (mesh_note, step_note, frame_note) if note]
    if seabed_note is not None:  # a plane is used as given
        notes.append(seabed_note)
    if any(point.kind == "coupled" and point.body is None for point in scene_points.values()):
        notes.append(NO_MOTION_NOTE)
    if any(body.kind == "coupled" for body in scene_bodies.values()):
        notes.append(BODY_NO_MOTION_NOTE)
    return Scene(name=os.path.splitext(os.path.basename(path))[0], lines=lines, seabed=seabed,
                 contact=contact, environment=environment, friction=friction, solver=solver,
                 output=output, source=path, notes=notes, moordyn_options=raw_options, keys=keys, points=scene_points,
                 bodies=scene_bodies, failures=failures)


def _network(path, raw_lines, raw_types, points, scene_points, scene_bodies, notes, syrope_ic=None, syrope_rows=None,
             rod_points=None, rods=None):
    """The strings of the file's lines (``network.strings``), named ``line1+2`` after their MoorDyn
    lines, and where their scene keys stand in the file: (lines, keys). ``rod_points``: the points of
    rod ends (``moordyn_rods.rod_network``), ``rods`` the file's rods (``moordyn_rods.read_rods``)."""
    rows = {point.name: (number, f"POINTS.{pid}") for pid, (number, point) in points.items()}
    for name, (number, pid) in rows.items():
        if not any(name in raw["ends"] for raw in raw_lines):
            raise InputError("no line uses this point: remove it, or attach a line to it", key=_at(number, pid))
    rows.update({name: (number, f"RODS.{name[3:].rstrip('AB')}") for name, (number, _) in (rod_points or {}).items()})
    built, parts = {}, []
    for raw in raw_lines:
        line_type = _line_type(raw, raw_types, built, os.path.dirname(path), notes)
        initial = syrope_ic.get(raw["id"])
        if initial is not None and (line_type.axial is None or line_type.axial.kind != "syrope"):
            notes.append(f"SYROPE IC: line {raw['id']} is not a SYROPE rope; its row is ignored (as MoorDyn-C does)")
            initial = None
        try:
            segment = Segment(line_type, raw["length"], raw["segments"], initial)
        except InputError as error:
            where = syrope_rows.get(raw["id"], raw["row"])
            section = "SYROPE IC" if raw["id"] in syrope_rows else "LINES"
            raise InputError(error.reason, key=_at(where, f"{section}.{raw['id']}")) from None
        a, b = (point_position(scene_points[name], scene_bodies) for name in raw["ends"])
        element = "hermite" if segment.type.EI > 0 else "lagrange"  # bending needs C1 elements
        tangents = (None, None)
        if element == "hermite" and rods:  # MoorDyn-C clamps a line that bends to a fixed rod's axis
            leaving = [clamp_directions(rods, name) for name in raw["ends"]]
            tangents = (leaving[0], None if leaving[1] is None else -leaving[1])
        parts.append(Line(raw["id"], a, b, [segment], ends=tuple(raw["ends"]), element=element, tangents=tangents))

    def where(key):  # a key of network.strings' errors, as it stands in the file
        if key.startswith("points."):
            number, pid = rows[key[len("points."):]]
            return _at(number, pid)
        raw = raw_lines[int(re.match(r"lines\[(\d+)\]", key).group(1))]
        return _at(raw["row"], f"LINES.{raw['id']}")

    by_id = {raw["id"]: raw for raw in raw_lines}
    lines, keys = [], {"name": (path, "name (from the file name)")}
    for string in network_strings(parts, scene_points, scene_bodies, where):
        chain = [by_id[i] for i in string.name.split("+")]
        key = _at(chain[0]["row"], f"LINES.{string.name}")
        line = replace(string, name=f"line{string.name}")
        lines.append(v.check_chord(line, key) if all(line.prescribed) else line)
        index = len(lines) - 1
        keys.update({f"lines[{index}]": (path, key), f"lines[{index}].name": (path, key)})
        for end, name in zip(("anchor", "fairlead"), line.ends):
            keys[f"lines[{index}].{end}"] = (path, _at(rows[name][0], rows[name][1]))
        for j, raw in enumerate(chain):
            keys[f"lines[{index}].segments[{j}].elements"] = (path, _at(raw["row"], f"LINES.{raw['id']}.NumSegs"))
        if len(chain) > 1:
            notes.append(f"{line.name}: MoorDyn lines {', '.join(r['id'] for r in chain)} joined through free "
                         "points into one line, its most fixed end first")
    return lines, keys


def _line_type(raw, raw_types, built, folder, notes):
    """The LineType of one MoorDyn line (BA < 0 depends on the line's segment length)."""
    number, props = raw_types[raw["type"]]
    key = _at(number, f"LINE TYPES.{raw['type']}")
    law = None
    if "law" in props:
        EA, law = moordyn_law(*props["law"], folder, key, notes, raw["length"] / raw["segments"], props["MassDen"])
        beta = 0.0
        same = lambda t: t.axial == law  # noqa: E731
    else:
        EA = props["EA"]
        beta = damping_time(props["BA/-zeta"], props["EA"], props["MassDen"], raw["length"], raw["segments"])
        v.limited(v.number, "damping_time")(beta, f"{key}.BA/-zeta (beta)")
        same = lambda t: t.damping == beta  # noqa: E731
    name = raw["type"]
    if name in built and not same(built[name]):
        name = f"{raw['type']}-line{raw['id']}"
    if name not in built:  # values were checked by _line_types
        built[name] = LineType(name, props["Diam"], props["MassDen"], EA, beta,
                               Cd_normal=props["Cd"], Cd_tangential=math.pi * props["CdAx"],
                               Ca_normal=props["Ca"], Ca_tangential=props["CaAx"], EI=props["EI"],
                               damping_when_slack=True, axial=law)  # MoorDyn-C's own law (Line.cpp, Td[i])
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
