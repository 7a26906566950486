"""The network tables of a TOML scene: [points.NAME], [bodies.NAME] (with [bodies.NAME.motion]) and
line ends that name a point (docs/scene.md, "Networks"; ``cablefem.model.network``)."""

import math
import re
from dataclasses import replace

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.readers import parse_number
from cablefem.model.network import Body, Point
from cablefem.model.scene import Motion
from cablefem.io import validate as v

_COORDINATE = v.limited(v.vector3, "coordinate")
_MASS = v.limited(v.non_negative, "point_mass")
POINT_KEYS = {"kind": v.choice(("fixed", "coupled", "free")), "position": _COORDINATE, "mass": _MASS,
              "volume": v.limited(v.non_negative, "volume"), "CdA": v.limited(v.non_negative, "area"),
              "Ca": v.limited(v.non_negative, "coefficient"), "body": v.text, "force": v.limited(v.vector3, "force")}
BODY_KEYS = {"kind": v.choice(("fixed", "coupled", "free")), "position": _COORDINATE,
             "rotation_deg": v.limited(v.vector3, "angle"), "mass": _MASS,
             "inertia": v.limited(v.vector3, "inertia"), "cg": _COORDINATE,
             "volume": v.limited(v.non_negative, "volume"), "cb": _COORDINATE,
             "waterplane_area": v.limited(v.non_negative, "area"),
             "force": v.limited(v.vector3, "force"), "moment": v.limited(v.vector3, "moment"),
             "motion": v.table}


def _six(check):
    """One number (all six axes) or six: surge, sway, heave, roll, pitch, yaw (a free body's CdA, Ca)."""

    def convert(value, key):
        if isinstance(value, (list, tuple)):
            if len(value) != 6:
                raise InputError(f"expected one number or 6 (surge, sway, heave, roll, pitch, yaw), got {value!r}",
                                 key=key)
            return tuple(check(item, f"{key}[{i}]") for i, item in enumerate(value))
        return (check(value, key),) * 6

    return convert


BODY_KEYS["CdA"] = _six(v.limited(v.non_negative, "area"))
BODY_KEYS["Ca"] = _six(v.limited(v.non_negative, "coefficient"))
BODY_MOTION_KINDS = ("fixed", "harmonic", "table")
BODY_MOTION_KEYS = {"fixed": (), "harmonic": ("amplitude", "period", "phase_deg", "offset", "ramp"),
                    "table": ("file", "ramp", "interpolation")}
#: OpenFAST's platform motion channels, in the order of a body's six components
OPENFAST_COLUMNS = ("PtfmSurge", "PtfmSway", "PtfmHeave", "PtfmRoll", "PtfmPitch", "PtfmYaw")


def _names(raw, section):
    """The tables of [section.NAME] as (name, table) pairs, names checked printable."""
    raw = v.table(raw, section)
    return [(v.printable_name(name, f"{section}.{name}"), v.table(entry, f"{section}.{name}"))
            for name, entry in raw.items()]


def read_points(raw, bodies):
    """[points.NAME] tables as Point objects by name; a point on a body names one of ``bodies``."""
    points = {}
    for name, entry in _names(raw, "points"):
        prefix = f"points.{name}"
        values = v.pick(entry, prefix, POINT_KEYS, required=("position",))
        body = values.get("body")
        if body is not None and body not in bodies:
            raise InputError(f"no body '{body}'{v.suggest(body, bodies)} in [bodies]", key=f"{prefix}.body")
        if body is None and "kind" not in values:
            raise InputError("missing: fixed, coupled or free (or a body the point is attached to)",
                             key=f"{prefix}.kind")
        if body is not None and "kind" in values:
            raise InputError("a point on a body moves with it: leave out kind", key=f"{prefix}.kind")
        moved = values.get("kind", "fixed") != "free" if body is None else bodies[body].kind != "free"
        if moved and any(values.get("force", (0.0, 0.0, 0.0))):
            raise InputError("a force acts on a free point or a point of a free body; this point moves as given, "
                             "so a force on it would change nothing", key=f"{prefix}.force")
        try:
            points[name] = Point(name, values.get("kind", "fixed"), values["position"], values.get("mass", 0.0),
                                 values.get("volume", 0.0), values.get("CdA", 0.0), values.get("Ca", 0.0), body,
                                 values.get("force", (0.0, 0.0, 0.0)))
        except InputError as error:
            raise error.within(prefix=prefix) from None
    return points


def read_bodies(raw, folder):
    """[bodies.NAME] tables as Body objects by name (angles in degrees in the file, radians here)."""
    bodies = {}
    for name, entry in _names(raw, "bodies"):
        prefix = f"bodies.{name}"
        values = v.pick(entry, prefix, BODY_KEYS, required=("kind", "position"))
        kind = values["kind"]
        if kind == "free":
            for key in ("mass", "inertia"):
                if key not in values:
                    raise InputError("missing: a free body needs it", key=f"{prefix}.{key}")
        for key in ("CdA", "Ca"):
            if key in values and kind != "free":
                raise InputError(f"only a free body has drag and added mass (this one is {kind}: its motion is "
                                 "given)", key=f"{prefix}.{key}")
        motion = values.pop("motion", None)
        if motion is not None and kind != "coupled":
            raise InputError(f"only a coupled body has a motion (this one is {kind})", key=f"{prefix}.motion")
        if kind == "coupled" and motion is not None:
            values["motion"] = _body_motion(motion, f"{prefix}.motion", folder)
        if "rotation_deg" in values:
            values["rotation"] = np.radians(values.pop("rotation_deg"))
        try:
            bodies[name] = Body(name, **values)
        except InputError as error:
            raise error.within(prefix=prefix) from None
    return bodies


def body_motions(raw, bodies, folder):
    """The bodies of a MoorDyn file (``bodies`` by name: ``body1``, ...) with the motions a TOML that
    wraps it gives its coupled ones: [bodies.NAME] there holds ``motion`` only."""
    bodies = dict(bodies)
    for name, entry in _names(raw, "bodies"):
        prefix = f"bodies.{name}"
        if name not in bodies:
            raise InputError(f"no body '{name}'{v.suggest(name, bodies)} in the MoorDyn file "
                             f"(its bodies: {', '.join(bodies) or 'none'})", key=prefix)
        v.check_keys(entry, {"motion": None}, prefix, required=("motion",),
                     elsewhere={key: "the MoorDyn file gives it; with [moordyn], [bodies.NAME] holds motion "
                                "only" for key in BODY_KEYS})
        if bodies[name].kind != "coupled":
            raise InputError(f"only a coupled body has a motion (this one is {bodies[name].kind})",
                             key=f"{prefix}.motion")
        bodies[name] = replace(bodies[name], motion=_body_motion(v.table(entry["motion"], f"{prefix}.motion"),
                                                                f"{prefix}.motion", folder))
    return bodies


def _six(value, key, quantity="length"):
    """Six finite numbers: three lengths [m] and three angles [deg] in the file."""
    if not isinstance(value, (list, tuple)) or len(value) != 6:
        raise InputError(f"expected 6 numbers (x, y, z [m], roll, pitch, yaw [deg]), got {value!r}", key=key)
    out = np.array([v.number(x, f"{key}[{i}]") for i, x in enumerate(value)])
    v.limited(v.vector3, quantity)(list(out[:3]), key)
    v.limited(v.vector3, "angle")(list(out[3:]), key)
    return out


def _body_motion(raw, prefix, folder):
    """A coupled body's [bodies.NAME.motion]: a Motion of six components (radians inside)."""
    v.check_keys(raw, raw, prefix, required=("kind",))
    kind = v.choice(BODY_MOTION_KINDS)(raw["kind"], f"{prefix}.kind")
    elsewhere = {key: f"does not apply to motion kind '{kind}'" for keys in BODY_MOTION_KEYS.values() for key in keys}
    converters = {"kind": v.text, "amplitude": _six, "period": v.positive, "phase_deg": _six, "offset": _six,
                  "ramp": v.non_negative, "file": v.text,
                  "interpolation": v.choice(("spline", "linear"))}
    converters = {key: converters[key] for key in ("kind",) + BODY_MOTION_KEYS[kind]}
    required = {"fixed": (), "harmonic": ("amplitude", "period"), "table": ("file",)}[kind]
    values = v.pick(raw, prefix, converters, required=required, elsewhere=elsewhere)
    degrees = np.array([1.0, 1.0, 1.0, math.pi / 180, math.pi / 180, math.pi / 180])
    if kind == "fixed":
        return Motion("fixed", offset=np.zeros(6))
    if kind == "harmonic":
        return Motion("harmonic", amplitude=values["amplitude"] * degrees, period=values["period"],
                      offset=values.get("offset", np.zeros(6)) * degrees, ramp=values.get("ramp", 0.0),
                      phase=np.radians(values["phase_deg"]) if "phase_deg" in values else np.zeros(6))
    file = v.existing_file(values["file"], f"{prefix}.file", folder)
    times, motions = read_six_table(file, f"{prefix}.file")
    return Motion("table", offset=np.zeros(6), ramp=values.get("ramp", 0.0), times=times,
                  positions=motions * degrees, interpolation=values.get("interpolation", "spline"))


def read_six_table(path, key):
    """Times (k,) [s] and six-component motions (k, 6) (x, y, z [m], roll, pitch, yaw [deg]) from a
    text table: seven columns t x y z roll pitch yaw (comma, semicolon or blank separated, a header
    row of names optional, ``#`` comments), or an OpenFAST output (.out) with a ``Time`` column and
    the PtfmSurge ... PtfmYaw channels, found by name."""
    rows = v.read_rows(path, key)
    columns, table, name = None, [], path.rsplit("/", 1)[-1]
    for number, row in enumerate(rows, start=1):
        fields = [f for f in re.split(r"[,;\s]+", row.strip()) if f]
        if not fields or fields[0].startswith("#"):
            continue
        values = [parse_number(f) for f in fields]
        if None in values:
            if not table and "Time" in fields and all(c in fields for c in OPENFAST_COLUMNS):
                columns = [fields.index("Time")] + [fields.index(c) for c in OPENFAST_COLUMNS]
            elif table or columns is not None:
                if columns is not None and row.strip().startswith("("):  # OpenFAST's units row
                    continue
                raise InputError(f"{name} line {number}: expected numbers, got '{row.strip()}'", key=key)
            continue
        picked = [values[c] for c in columns] if columns is not None else values
        if len(picked) != 7 or (columns is None and len(values) != 7):
            raise InputError(f"{name} line {number}: expected 7 columns t, x, y, z, roll, pitch, yaw, got "
                             f"{len(values)}", key=key)
        if not all(math.isfinite(x) for x in picked):
            raise InputError(f"{name} line {number}: values must be finite", key=key)
        if table and picked[0] <= table[-1][0]:
            raise InputError(f"{name} line {number}: times must strictly increase", key=key)
        table.append(picked)
    if len(table) < 2:
        raise InputError(f"{name}: needs at least 2 rows t, x, y, z, roll, pitch, yaw, got {len(table)}", key=key)
    data = np.array(table)
    for k, quantity in ((1, "length"), (4, "angle")):
        v.limited(v.vector3, quantity)(list(np.abs(data[:, k:k + 3]).max(axis=0)), key)
    return data[:, 0], data[:, 1:]


def end(value, key, points):
    """A line end: coordinates (3,) [m] (returned with name None) or the name of one of ``points``."""
    if isinstance(value, str):
        if value not in points:
            raise InputError(f"no point '{value}'{v.suggest(value, points)} in [points]", key=key)
        return None, value
    return _COORDINATE(value, key), None
