"""TOML scene reader: documented key by key in docs/scene.md.

Every value is type- and range-checked here, so a bad scene fails with one
line naming the key path (``lines[0].segments[1].length``) and the reason;
defaults come from the dataclasses of ``cablefem.model.scene``. A ``[moordyn]``
table takes lines, points, line types and options from a MoorDyn v2 file;
keys written in the TOML then override, one key at a time, what the MoorDyn
file gave (``read_toml_scene`` states the rule). A grid, mesh or points seabed
that is planar becomes its plane unless ``[seabed] simplify = false``
(``geometry.choose_seabed``); ``scene.notes`` says which model was chosen.
"""

import math
import os
from dataclasses import replace

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

from cablefem.errors import InputError
from cablefem.geometry import Horizontal, Plane, choose_seabed
from cablefem.geometry.readers import MAX_COORDINATE
from cablefem.model.line import ELEMENTS, Line, LineType, Segment
from cablefem.dynamics.registry import INTEGRATORS
from cablefem.model import defaults as by_physics
from cablefem.model.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver
from cablefem.io import axial_input, validate as v
from cablefem.io.currents import current_profile_setting
from cablefem.io.failures import read_toml_failures
from cablefem.io.moordyn_input import BODY_NO_MOTION_NOTE, NO_MOTION_NOTE, read_moordyn
from cablefem.io.toml_network import body_motions, end, read_bodies, read_points
from cablefem.io.waves import read_waves
from cablefem.model.network import point_position, strings as network_strings

TOP_LEVEL_KEYS = ("name", "environment", "line_types", "lines", "seabed", "friction",
                  "motion", "solver", "output", "moordyn", "points", "bodies", "waves", "failures")
SEABED_KINDS = ("horizontal", "plane", "grid", "mesh", "points")
#: the key that places each kind of seabed (named by the scene-level checks)
SEABED_KEY = {"horizontal": "depth", "plane": "point", "grid": "file", "mesh": "file", "points": "file"}
SEABED_SHAPE_KEYS = {"horizontal": ("depth",),
                     "plane": ("point", "normal", "slope_deg", "azimuth_deg"),
                     "grid": ("file",), "mesh": ("file",), "points": ("file",)}
FRICTION_MODELS = ("none", "isotropic", "anisotropic")
MOTION_KINDS = ("fixed", "harmonic", "circular", "table")
MOTION_KEYS = {"fixed": (), "harmonic": ("amplitude", "period", "offset", "ramp"),
               "circular": ("radius", "period", "plane", "offset", "ramp"),
               "table": ("file", "ramp", "interpolation")}
MOTION_REQUIRED = {"fixed": (), "harmonic": ("amplitude", "period"),
                   "circular": ("radius", "period"), "table": ("file",)}
MOTION_PLANES = ("xy", "xz", "yz", "yx", "zx", "zy")  # sin along the first axis, cos along the second
TABLE_INTERPOLATIONS = ("spline", "linear")  # cablefem.model.motion
ASSEMBLY_PATHS = ("kernel", "forms")
NEWTON_MODES = ("auto", "full", "modified")

# every number is bounded by a sane limit (validate.LIMITS, docs/scene.md "Limits")
_COEFFICIENT = v.limited(v.non_negative, "coefficient")
_POINT = v.limited(v.vector3, "coordinate")
_LENGTH = v.limited(v.positive, "length")
_ORDER = v.limited(v.whole, "order")
_ELEMENTS = v.limited(v.whole, "nodes")
ENVIRONMENT_KEYS = {"water_density": v.limited(v.non_negative, "water_density"),
                    "gravity": v.limited(v.non_negative, "gravity"), "current": v.limited(v.vector3, "speed"),
                    "current_profile": lambda value, key: value}  # a file or a table: _environment
LINE_TYPE_KEYS = {"diameter": v.limited(v.positive, "diameter"), "mass": v.limited(v.positive, "mass"),
                  "EA": axial_input.toml_stiffness, "damping": v.limited(v.non_negative, "damping_time"),
                  "BA": axial_input.toml_damping, "EA_dynamic": v.limited(v.positive, "EA"),
                  "EA_dynamic_slope": v.limited(v.non_negative, "slope"),
                  "BA_dynamic": v.limited(v.non_negative, "internal_damping"), "syrope": axial_input.toml_syrope,
                  "Cd_normal": _COEFFICIENT, "Cd_tangential": _COEFFICIENT, "Ca_normal": _COEFFICIENT,
                  "Ca_tangential": _COEFFICIENT, "damping_when_slack": v.boolean,
                  "nominal_diameter": v.limited(v.positive, "diameter"), "EI": v.limited(v.non_negative, "EI")}
LINE_KEYS = {"name": v.text, "anchor": lambda value, key: value, "fairlead": lambda value, key: value,
             "segments": v.tables, "order": _ORDER, "quadrature_points": v.whole,  # an end: coordinates or a point's name (toml_network.end)
             "element": v.choice(ELEMENTS), "anchor_tangent": v.vector3, "fairlead_tangent": v.vector3}
SEGMENT_KEYS = {"type": v.text, "length": _LENGTH, "elements": _ELEMENTS, "syrope": axial_input.toml_initial}
CONTACT_KEYS = {"stiffness": v.limited(v.positive, "stiffness"),
                "damping_ratio": v.limited(v.non_negative, "damping_ratio"),
                "damping": v.limited(v.non_negative, "contact_damping"), "damping_when_opening": v.boolean}
FRICTION_KEYS = {"model": v.choice(FRICTION_MODELS), "mu": v.limited(v.non_negative, "friction"),
                 "mu_axial": v.limited(v.non_negative, "friction"),
                 "mu_transverse": v.limited(v.non_negative, "friction"),
                 "static_scale": v.limited(v.positive, "friction"), "v_threshold": v.limited(v.positive, "speed"),
                 "saturation_damping": v.limited(v.positive, "friction_damping")}
SOLVER_KEYS = {"integrator": v.choice(INTEGRATORS), "dt": v.positive, "duration": v.positive,
               "tolerance": v.positive, "max_iterations": v.limited(v.whole, "iterations"),
               "assembly": v.choice(ASSEMBLY_PATHS), "rho_inf": v.fraction, "fit_touchdown": v.boolean,
               "newton": v.choice(NEWTON_MODES), "adaptive": v.boolean, "error_tolerance": v.positive}
OUTPUT_KEYS = {"dir": v.folder, "every": v.positive}
MOORDYN_KEYS = {"file": v.text, "order": _ORDER, "elements": _ELEMENTS, "quadrature_points": v.whole}


def parse_toml(path):
    """The TOML document at ``path`` as a dict; InputError (key None) if it is not valid TOML."""
    try:
        with open(path, "rb") as handle:
            return tomllib.load(handle)
    except tomllib.TOMLDecodeError as error:
        raise InputError(f"not valid TOML: {v.one_line(error)}") from None
    except UnicodeDecodeError:
        raise InputError("not valid TOML: not UTF-8 text") from None
    except RecursionError:
        raise InputError("not valid TOML: arrays or tables nested too deeply") from None


def read_toml_scene(path, data=None):
    """The Scene of a TOML file (``data``: its parsed content, if already read).

    Precedence with ``[moordyn] file``: a key written in the TOML wins; a key
    the TOML leaves out takes the MoorDyn file's value; a key neither gives
    takes the default of ``cablefem.model.scene``. ``[line_types]`` and ``[[lines]]``
    may not be combined with ``[moordyn]`` (the lines come from the file).
    """
    from cablefem.loads import catalog  # here: a load module may read its keys' converters from cablefem.io

    path = os.path.abspath(path)
    folder = os.path.dirname(path)
    data = parse_toml(path) if data is None else data
    v.check_keys(data, TOP_LEVEL_KEYS + tuple(catalog.sections()), "")
    name = v.text(data["name"], "name") if "name" in data else os.path.splitext(os.path.basename(path))[0]
    notes = []
    keys = {} if "name" in data else {"name": (path, "name (from the file name)")}
    if "moordyn" in data:
        base = _moordyn_base(data, path)
        lines = base.lines
        keys.update({key: where for key, where in base.keys.items() if key != "name"})
        kept = [n for n in base.notes if not n.startswith("seabed:") and
                not (n == NO_MOTION_NOTE and "motion" in data) and not (n == BODY_NO_MOTION_NOTE and "bodies" in data)]
        notes += kept + [f"lines, line types and options from {base.source}; TOML keys override"]
    else:
        base = None
        v.check_keys(data, TOP_LEVEL_KEYS + tuple(catalog.sections()), "", required=("line_types", "lines", "seabed"))
    if base is not None:
        if "points" in data:
            raise InputError("[points] may not be combined with [moordyn] (the file gives them)", key="points")
        points, bodies = dict(base.points), body_motions(data.get("bodies", {}), base.bodies, folder)
    else:
        bodies = read_bodies(data["bodies"], folder) if "bodies" in data else {}
        points = read_points(data["points"], bodies) if "points" in data else {}
        written = _lines(data["lines"], _line_types(data["line_types"]), points, bodies)
        lines = network_strings(written, points, bodies) if points or bodies else written
    # a failure names a line as [[lines]] wrote it, or as cablefem names a MoorDyn file's lines
    failures = read_toml_failures(data["failures"], lines, None if base else written) if "failures" in data \
        else (base.failures if base else ())
    environment = _environment(data, base, folder)
    seabed, contact, simplify = _seabed(data.get("seabed", {}), folder, base)
    kind = data.get("seabed", {}).get("kind")
    if kind is not None:  # the TOML's seabed replaces the MoorDyn file's
        keys["seabed"] = (path, f"seabed.{SEABED_KEY.get(kind, 'kind')}")
    seabed, seabed_note = choose_seabed(seabed, lines, simplify)
    if "waves" in data:  # the TOML's waves replace a MoorDyn file's
        environment = replace(environment, waves=read_waves(data["waves"], folder, seabed, environment.gravity))
    friction = replace(base.friction if base else Friction(),
                       **_section(data, "friction", FRICTION_KEYS))
    motion = _motion(data["motion"], folder) if "motion" in data else Motion()
    solver_keys = _section(data, "solver", SOLVER_KEYS)
    solver, step_note = by_physics.step(replace(base.solver if base else Solver(), **solver_keys), solver_keys,
                                        motion, environment.waves, bodies.values())
    output_keys = _section(data, "output", OUTPUT_KEYS)
    given = set(output_keys) | ({"every"} if base is not None and "output.every" in base.keys else set())
    output, frame_note = by_physics.frames(replace(base.output if base else Output(), **output_keys), given, solver,
                                           motion, environment.waves, bodies.values())
    notes += [note for note in (step_note, frame_note) if note]
    if seabed_note is not None:  # a plane is used as given
        notes.append(seabed_note)
    load_settings = {spec.section: v.pick(v.table(data[spec.section], spec.section), spec.section, spec.keys,
                                          required=spec.required)
                     for spec in catalog.CATALOG if spec.section and spec.section in data}
    return Scene(name=name, lines=lines, seabed=seabed, contact=contact, environment=environment,
                 friction=friction, motion=motion, solver=solver, output=output, source=path,
                 notes=notes, moordyn_options=dict(base.moordyn_options) if base else {}, keys=keys,
                 load_settings=load_settings, points=points, bodies=bodies, failures=failures)


def _environment(data, base, folder):
    """[environment] over the MoorDyn base's (or the defaults): a uniform ``current`` and a
    ``current_profile`` (a file in MoorDyn-C's current_profile.txt layout, or a table of heights
    and velocities, ``io.currents``) exclude each other, and either replaces the base's."""
    values = _section(data, "environment", ENVIRONMENT_KEYS)
    if "current" in values and "current_profile" in values:
        raise InputError("give either current (uniform) or current_profile (varying with depth), not both",
                         key="environment.current_profile")
    if "current_profile" in values:
        key = "environment.current_profile"
        values["current_profile"] = current_profile_setting(values["current_profile"], key, folder)
        values["current"] = (0.0, 0.0, 0.0)
    elif "current" in values:
        values["current_profile"] = None
    return replace(base.environment if base else Environment(), **values)


def _section(data, name, converters):
    """Checked values of the optional table ``name``: dict key -> value ({} if absent)."""
    if name not in data:
        return {}
    return v.pick(v.table(data[name], name), name, converters)


def _moordyn_base(data, path):
    """The Scene of the MoorDyn file named in [moordyn] of the TOML at ``path``, with its element
    order/count applied."""
    folder = os.path.dirname(path)
    for key in ("lines", "line_types"):
        if key in data:
            raise InputError("cannot be combined with [moordyn]: the lines come from the MoorDyn file",
                             key=key)
    values = v.pick(v.table(data["moordyn"], "moordyn"), "moordyn", MOORDYN_KEYS, required=("file",))
    file = v.existing_file(values["file"], "moordyn.file", folder)
    # the TOML's [seabed] simplify decides; its [waves] replace the file's WaveKin and its files
    base = read_moordyn(file, simplify=False, waves="waves" not in data, defaults=False)
    lines = base.lines
    if "elements" in values:
        lines = [line.with_elements(values["elements"]) for line in lines]
        base.keys.update({f"lines[{i}].segments[{j}].elements": (path, "moordyn.elements")
                          for i, line in enumerate(lines) for j in range(len(line.segments))})
    if "order" in values:
        lines = [line.with_order(values["order"]) for line in lines]
    elif "elements" not in values:  # neither: NumSegs read as an accuracy
        lines, note = by_physics.moordyn_mesh(lines, base.environment.water_density)
        base.notes.append(note)
    if "quadrature_points" in values:
        try:
            lines = [line.with_quadrature_points(values["quadrature_points"]) for line in lines]
        except InputError as error:
            raise error.within(prefix="moordyn") from None
    return replace(base, lines=lines)


def _line_types(raw):
    """Line types by name from the [line_types] table of tables."""
    types = {}
    for name, entry in v.table(raw, "line_types").items():
        prefix = f"line_types.{name}"
        values = v.pick(v.table(entry, prefix), prefix, LINE_TYPE_KEYS, required=("diameter", "mass", "EA"))
        try:
            EA, law, beta = axial_input.law_of(values)
            if beta is not None:
                values["damping"] = beta
            types[name] = LineType(name, EA=EA, axial=law, **values)
        except InputError as error:
            raise error.within(prefix=prefix) from None
    if not types:
        raise InputError("must define at least one line type", key="line_types")
    return types


def _lines(raw, types, points=None, bodies=None):
    """The [[lines]] array as Line objects, anchor first, with the chord-strain check (a line
    between two points of a network: checked as a string, ``network_strings``)."""
    points, bodies = points or {}, bodies or {}
    lines, names = [], set()
    for i, entry in enumerate(v.tables(raw, "lines")):
        prefix = f"lines[{i}]"
        values = v.pick(entry, prefix, LINE_KEYS, required=("anchor", "fairlead", "segments"))
        name = values.get("name", f"line{i + 1}")
        if name in names:
            raise InputError(f"duplicate line name '{name}'", key=f"{prefix}.name")
        names.add(name)
        segments = []
        for j, seg in enumerate(values["segments"]):
            seg_prefix = f"{prefix}.segments[{j}]"
            seg_values = v.pick(seg, seg_prefix, SEGMENT_KEYS, required=("type", "length", "elements"))
            kind = seg_values["type"]
            if kind not in types:
                raise InputError(f"unknown line type '{kind}'{v.suggest(kind, types)}; "
                                 f"defined in [line_types]: {', '.join(types)}", key=f"{seg_prefix}.type")
            try:
                segments.append(Segment(types[kind], seg_values["length"], seg_values["elements"],
                                        seg_values.get("syrope")))
            except InputError as error:
                raise error.within(prefix=seg_prefix) from None
        (anchor, a), (fairlead, b) = (end(values[key], f"{prefix}.{key}", points) for key in ("anchor", "fairlead"))
        anchor = anchor if a is None else point_position(points[a], bodies)
        fairlead = fairlead if b is None else point_position(points[b], bodies)
        element = values.get("element", "lagrange")
        if element == "hermite" and values.get("order", 3) != 3:
            raise InputError(f"Hermite elements are cubic (order 3); leave order out, got {values['order']}",
                             key=f"{prefix}.order")
        try:
            line = Line(name, anchor, fairlead, segments, values.get("order", 1), ends=(a, b),
                        quadrature_points=values.get("quadrature_points", 0), element=element,
                        tangents=(values.get("anchor_tangent"), values.get("fairlead_tangent")))
        except InputError as error:
            raise error.within(prefix=prefix) from None
        lines.append(v.check_chord(line, prefix) if (a, b) == (None, None) else line)
    return lines


def _seabed(raw, folder, base):
    """(seabed as read, Contact, simplify) from [seabed]; without ``kind`` the MoorDyn base's
    seabed is kept."""
    raw = v.table(raw, "seabed")
    if "kind" not in raw and base is None:
        raise InputError("missing required key", key="seabed.kind")
    kind = v.choice(SEABED_KINDS)(raw["kind"], "seabed.kind") if "kind" in raw else None
    shape_keys = SEABED_SHAPE_KEYS.get(kind, ())
    elsewhere = {}
    for keys in SEABED_SHAPE_KEYS.values():
        for key in keys:
            elsewhere.setdefault(key, f"does not apply to seabed kind '{kind}'" if kind else
                                 "needs seabed.kind (without it the MoorDyn file's seabed is used)")
    converters = dict(CONTACT_KEYS, kind=v.text, simplify=v.boolean)
    converters.update({key: _SHAPE_CONVERTERS[key] for key in shape_keys})
    values = v.pick(raw, "seabed", converters, elsewhere=elsewhere)
    contact = replace(base.contact if base else Contact(),
                      **{key: values[key] for key in CONTACT_KEYS if key in values})
    if "damping_ratio" in values and "damping" not in values:
        contact = replace(contact, damping=None)  # the ratio the user wrote wins over MoorDyn's cBot
    simplify = values.get("simplify", True)
    if kind is None:
        return base.seabed, contact, simplify
    try:
        if kind == "horizontal":
            v.check_keys(values, converters, "seabed", required=("depth",))
            seabed = Horizontal(values["depth"])
        elif kind == "plane":
            seabed = _plane(values)
        else:
            v.check_keys(values, converters, "seabed", required=("file",))
            file = v.existing_file(values["file"], "seabed.file", folder)
            seabed = v.read_seabed_file(file, kind, "seabed.file", kind_key="seabed.kind")
    except InputError as error:
        raise (error if error.file or (error.key or "").startswith("seabed") else
               error.within(prefix="seabed")) from None
    return seabed, contact, simplify


def _plane(values):
    """A Plane from point + normal, or point + slope_deg (+ azimuth_deg)."""
    v.check_keys(values, values, "seabed", required=("point",))
    if ("normal" in values) == ("slope_deg" in values):
        raise InputError("give either normal or slope_deg (with optional azimuth_deg)", key="seabed.normal")
    if "normal" in values:
        if "azimuth_deg" in values:
            raise InputError("only applies with slope_deg, not with normal", key="seabed.azimuth_deg")
        return Plane(values["point"], values["normal"])
    slope = values["slope_deg"]
    if not 0.0 <= slope < 90.0:
        raise InputError(f"must be in [0, 90) degrees, got {slope:g}", key="seabed.slope_deg")
    return Plane.from_slope(values["point"], math.radians(slope), math.radians(values.get("azimuth_deg", 0.0)))


_SHAPE_CONVERTERS = {"depth": _LENGTH, "point": _POINT, "normal": _POINT,
                     "slope_deg": v.number, "azimuth_deg": v.number, "file": v.text}


def _motion(raw, folder):
    """The Motion of the [motion] table (kind-specific keys; tables read and checked)."""
    raw = v.table(raw, "motion")
    v.check_keys(raw, raw, "motion", required=("kind",))
    kind = v.choice(MOTION_KINDS)(raw["kind"], "motion.kind")
    elsewhere = {key: f"does not apply to motion kind '{kind}'"
                 for keys in MOTION_KEYS.values() for key in keys}
    converters = {"kind": v.text, "amplitude": v.limited(v.vector3, "length"), "period": v.positive,
                  "offset": v.limited(v.vector3, "length"), "ramp": v.non_negative,
                  "radius": _LENGTH, "plane": v.choice(MOTION_PLANES), "file": v.text,
                  "interpolation": v.choice(TABLE_INTERPOLATIONS)}
    converters = {key: converters[key] for key in ("kind",) + MOTION_KEYS[kind]}
    values = v.pick(raw, "motion", converters, required=MOTION_REQUIRED[kind], elsewhere=elsewhere)
    if kind == "table":
        file = v.existing_file(values.pop("file"), "motion.file", folder)
        values["times"], values["positions"] = read_motion_table(file, "motion.file")
    return Motion(**values)


def read_motion_table(path, key):
    """Times (k,) [s] and fairlead displacements (k, 3) [m] from a CSV with columns t, x, y, z.

    A header row ``t,x,y,z`` is optional; separators may be commas, semicolons
    or blanks; ``#`` starts a comment line. Times must strictly increase.
    """
    def limit(name, number, row, values):
        if max(abs(x) for x in values[1:]) > MAX_COORDINATE:
            raise InputError(f"{name} line {number}: a displacement beyond the sane limit of "
                             f"{MAX_COORDINATE:g} m, got '{row.strip()}'", key=key)

    data = v.read_time_table(path, key, ("t", "x", "y", "z"), 2, check=limit)
    return data[:, 0], data[:, 1:]
