"""BODIES, POINTS and line ends of a MoorDyn v2 file as ``cablefem.model.network`` Bodies and Points, read
as MoorDyn-C reads them (``MoorDyn2.cpp``: ``readBody``, the POINTS rows, the LINES ends).

- BODIES (ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG I Volume CdA Ca): Fixed/Anchor/Fix -> fixed,
  Coupled/Vessel/Ves/Cpld -> coupled (at rest where the file puts it; it moves with a motion only a
  TOML that wraps the file gives), Free -> free; angles in degrees; CG one number (its z) or x|y|z, I
  one number (all three) or three, the buoyancy at the centre of gravity (MoorDyn-C's
  ``Body::doRHS``); a free body's CdA (1, 2, 3 or 6 entries) and Ca (1 or 3, translational) as
  MoorDyn-C reads them, for its drag and added mass in a run.
- POINTS (ID Attachment X Y Z M V CdA CA, or with FX FY FZ before CdA as MoorDyn-C reads rows of 12):
  Fixed/Anchor/Fix, Coupled/Vessel/Ves/Cpld/Fairlead, Free/Point/Connect/Con, BodyN (fixed to body
  N, X Y Z in its frame, relative to its reference point). FX FY FZ: a steady external force [N] on a
  free point or a point of a free body (MoorDyn-C's ``pointF``); on a point whose motion is given it
  changes nothing and is noted.
- Line ends: a point number, optionally after P/Point/C/Con (``P3``); rod ends (R1A): ``moordyn_rods``.

Names: point ID 3 is ``point3``, body 1 ``body1`` in ``Scene.points`` and ``Scene.bodies``.
"""

import re

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.readers import is_integer
from cablefem.model.network import Body, Point
from cablefem.io import validate as v
from cablefem.io.moordyn_sections import at, refuse, value

FIXED = ("ANCHOR", "FIXED", "FIX")
COUPLED = ("VESSEL", "VES", "COUPLED", "CPLD")
POINT_COUPLED = COUPLED + ("FAIRLEAD",)
FREE = ("FREE", "POINT", "CONNECT", "CON")
POINT_PREFIXES = ("", "P", "POINT", "C", "CON")
_COORDINATE = v.limited(v.number, "coordinate")
_ANGLE = v.limited(v.number, "angle")
_NON_NEGATIVE = v.limited(v.non_negative, "point_mass")
_COEFFICIENT = v.limited(v.non_negative, "coefficient")
_AREA = v.limited(v.non_negative, "area")
_FORCE = v.limited(v.number, "force")
_WORD_NUMBER = re.compile(r"([A-Za-z]*)([0-9]*)([A-Za-z]*)")  # MoorDyn's decomposeString, ASCII only


def point_name(pid):
    """The Scene name of MoorDyn point ``pid``."""
    return f"point{pid}"


def body_name(bid):
    """The Scene name of MoorDyn body ``bid``."""
    return f"body{bid}"


def _kind(token, words, key, what):
    """'fixed', 'coupled' or 'free' of an attachment word (upper case in ``words``: three tuples)."""
    for kind, names in zip(("fixed", "coupled", "free"), words):
        if token.upper() in names:
            return kind
    valid = "; ".join("/".join(n.capitalize() for n in names) for names in words)
    raise InputError(f"unknown attachment '{token}' of a {what}; valid: {valid}", key=key)


def _split(token, count, number, key, check):
    """MoorDyn's 'a|b|c' entries: a list of checked numbers, as many as one of ``count``."""
    parts = token.split("|")
    if len(parts) not in count:
        raise InputError(f"expected {' or '.join(map(str, count))} numbers separated by '|', got '{token}'",
                         key=at(number, key))
    return [value(part, number, key, check) for part in parts]


def _row_id(section, what, number, fields, seen):
    """The key (``BODIES.1``) and the ID of a table row; a number that is not a new whole number is
    an InputError."""
    key = f"{section}.{fields[0]}"
    if not is_integer(fields[0]):
        raise InputError(f"expected a {what} number, got '{fields[0]}'", key=at(number, key))
    if int(fields[0]) in seen:
        raise InputError(f"duplicate {what} ID", key=at(number, key))
    return key, int(fields[0])


def _six_drag(drag):
    """A body's CdA entries (1, 2, 3 or 6) as six: one for all, (translation, rotation), (x, y, z) for
    both, or all six (MoorDyn-C's reading; with 3 or 6 entries MoorDyn-C v2.7 leaves the surge entry
    zero, an indexing slip in MoorDyn2.cpp that is not copied here)."""
    if len(drag) == 1:
        return drag * 6
    if len(drag) == 2:
        return [drag[0]] * 3 + [drag[1]] * 3
    return drag * 2 if len(drag) == 3 else drag


def read_bodies(rows, notes):
    """BODIES rows as Bodies: dict body ID -> (row number, Body)."""
    bodies = {}
    for number, fields in rows:
        key, bid = _row_id("BODIES", "body", number, fields, bodies)
        kind = _kind(fields[1], (FIXED, COUPLED, FREE), at(number, f"{key}.Attachment"), "body")
        pose = [value(tok, number, f"{key}.{col}", _COORDINATE if i < 3 else _ANGLE)
                for i, (col, tok) in enumerate(zip(("X0", "Y0", "Z0", "r0", "p0", "y0"), fields[2:8]))]
        mass = value(fields[8], number, f"{key}.Mass", _NON_NEGATIVE)
        cg = _split(fields[9], (1, 3), number, f"{key}.CG", _COORDINATE)
        inertia = _split(fields[10], (1, 3), number, f"{key}.I", v.limited(v.non_negative, "inertia"))
        volume = value(fields[11], number, f"{key}.Volume", v.limited(v.non_negative, "volume"))
        drag = _split(fields[12], (1, 2, 3, 6), number, f"{key}.CdA", _AREA)
        added = _split(fields[13], (1, 3), number, f"{key}.Ca", _COEFFICIENT)
        if kind != "free" and (any(drag) or any(added)):
            notes.append(f"BODIES.{bid}: CdA and Ca of a {kind} body ignored (its motion is given)")
        cg = [0.0, 0.0, cg[0]] if len(cg) == 1 else cg
        extra = {"CdA": _six_drag(drag), "Ca": list(added) * 3 + [0.0] * 3 if len(added) == 1 else list(added) + [0.0] * 3
                 } if kind == "free" else {}
        try:  # buoyancy acts at the centre of gravity, as MoorDyn-C's Body::doRHS has it
            body = Body(body_name(bid), kind, pose[:3], np.radians(pose[3:]), mass=mass,
                        inertia=inertia * 3 if len(inertia) == 1 else inertia, cg=cg, cb=cg, volume=volume, **extra)
        except InputError as error:
            raise InputError(error.reason, key=at(number, key)) from None
        bodies[bid] = (number, body)
    return bodies


def read_points(rows, bodies, notes):
    """POINTS rows as Points: dict point ID -> (row number, Point); ``bodies`` by ID (read_bodies)."""
    points = {}
    for number, fields in rows:
        key, pid = _row_id("POINTS", "point", number, fields, points)
        word, digits, rest = _WORD_NUMBER.fullmatch(fields[1]).groups() if _WORD_NUMBER.fullmatch(fields[1]) \
            else (fields[1], "", "")
        body = None
        if word.upper() == "TURBINE":
            refuse("turbine", at(number, f"{key}.Attachment"), f"'{fields[1]}'")
        if word.upper() == "BODY" and not rest:
            if not digits or int(digits) not in bodies:
                raise InputError(f"attached to '{fields[1]}': no body {digits or '(number missing)'} in BODIES "
                                 f"({', '.join(f'Body{b}' for b in bodies) or 'none defined'})",
                                 key=at(number, f"{key}.Attachment"))
            body, kind = body_name(int(digits)), "fixed"
        else:
            kind = _kind(fields[1], (FIXED, POINT_COUPLED, FREE), at(number, f"{key}.Attachment"),
                         "point (or BodyN)")
        columns = ("X", "Y", "Z", "M", "V", "FX", "FY", "FZ", "CdA", "CA") if len(fields) >= 12 \
            else ("X", "Y", "Z", "M", "V", "CdA", "CA")
        values = dict(zip(columns, (value(tok, number, f"{key}.{col}", _COORDINATE if col in "XYZ" else v.number)
                                    for col, tok in zip(columns, fields[2:]))))
        force = [values.get(f, 0.0) for f in ("FX", "FY", "FZ")]
        for col, check in (("M", _NON_NEGATIVE), ("V", v.limited(v.non_negative, "volume")),
                           ("CdA", _AREA), ("CA", _COEFFICIENT), ("FX", _FORCE), ("FY", _FORCE), ("FZ", _FORCE)):
            if col in values:
                check(values[col], at(number, f"{key}.{col}"))
        moved = kind != "free" and (body is None or bodies[int(digits)][1].kind != "free")
        if any(force) and moved:
            notes.append(f"POINTS.{pid}: FX FY FZ of a point whose motion is given ignored (it moves as given)")
            force = [0.0, 0.0, 0.0]
        if kind != "free" and body is None and (values["M"] or values["V"] or values["CdA"]):
            notes.append(f"POINTS.{pid}: M, V and CdA of a {kind} point ignored (its motion is given)")
        point = Point(point_name(pid), kind, [values["X"], values["Y"], values["Z"]], values["M"], values["V"],
                      values["CdA"], values["CA"], body, force)
        points[pid] = (number, point)
    return points


def line_end(token, points, key):
    """The point name a LINES AttachA/AttachB token names (``3``, ``P3``, ``Point3``, ``C3``)."""
    match = _WORD_NUMBER.fullmatch(token)
    word, digits, rest = match.groups() if match else ("", "", "")
    if not match or rest or not digits or word.upper() not in POINT_PREFIXES or int(digits) not in points:
        raise InputError(f"no point '{token}' in POINTS", key=key)
    return point_name(int(digits))
