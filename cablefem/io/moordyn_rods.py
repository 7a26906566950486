"""ROD TYPES and RODS of a MoorDyn v2 file, and lines on rod ends, read as MoorDyn-C reads them
(``MoorDyn2.cpp``: ``readRodProps``, ``readRod``, the LINES ends ``R1A``/``Rod1B``) into
``cablefem.model.rod`` Rods and the network's points and bodies (``cablefem.model.rod`` says how a
rod enters a network).

- ROD TYPES (Name Diam Mass/m Cd Ca CdEnd CaEnd);
- RODS (ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs Outputs), IDs 1, 2, ... in order:
  Fixed/Anchor/Fix -> two fixed points; Pinned/Pin -> end A held, the rod free to turn;
  Coupled/Vessel/Ves/Cpld -> a coupled body (at rest where the file puts it);
  CoupledPinned/VesselPinned/VesPin/CpldPin -> end A held where the file puts it, free to turn;
  Free/Point/Con -> a free rigid body; BodyN -> fixed on body N (ends in its frame), BodyNPinned/
  BodyNPin -> end A on body N, free to turn. NumSegs 0 is MoorDyn's zero-length rod: a point.
- Line ends ``R1A``, ``Rod1B``: end A or B of rod 1, the network point ``rod1A`` or ``rod1B``
  (``rod1`` for a zero-length rod). A line that bends (EI > 0) on a fixed rod's end is clamped to
  the rod's axis, as MoorDyn-C clamps it (``Line::setEndOrientation``); on other rods pinned, noted.
"""

from cablefem.errors import InputError
from cablefem.io import validate as v
from cablefem.io.moordyn_network import (COUPLED, FIXED, FREE, _WORD_NUMBER, _row_id, body_name)
from cablefem.io.moordyn_sections import at, value
from cablefem.model.network import Body, Point
from cablefem.model.rod import Rod, RodType, axis_angles, rod_body, rod_end_local

PINNED = ("PINNED", "PIN")
COUPLED_PINNED = ("VESSELPINNED", "VESPIN", "CPLDPIN", "COUPLEDPINNED")
ROD_FREE = tuple(word for word in FREE if word != "CONNECT")  # MoorDyn-C: Point, Con, Free
_COEFFICIENT = v.limited(v.non_negative, "coefficient")
_COORDINATE = v.limited(v.number, "coordinate")


def rod_name(rid):
    """The scene name of MoorDyn rod ``rid``."""
    return f"rod{rid}"


def read_rod_types(rows):
    """ROD TYPES rows: dict name -> RodType."""
    types = {}
    for number, fields in rows:
        key = f"ROD TYPES.{fields[0]}"
        if fields[0] in types:
            raise InputError("duplicate rod type name", key=at(number, key))
        d, w, cd, ca, cd_end, ca_end = (
            value(tok, number, f"{key}.{col}", check) for col, tok, check in zip(
                ("Diam", "Mass/m", "Cd", "Ca", "CdEnd", "CaEnd"), fields[1:7],
                (v.limited(v.positive, "diameter"), v.limited(v.non_negative, "mass"), _COEFFICIENT, _COEFFICIENT,
                 _COEFFICIENT, _COEFFICIENT)))
        types[fields[0]] = RodType(fields[0], d, w, cd, ca, cd_end, ca_end)
    return types


def _attachment(token, bodies, key):
    """(kind, body ID or None) of a RODS Attachment word: kind one of fixed, pinned, coupled, free,
    body, body-pinned."""
    match = _WORD_NUMBER.fullmatch(token)
    word, digits, rest = match.groups() if match else (token, "", "")
    word = word.upper()
    if word == "BODY":
        if not digits or int(digits) not in bodies:
            raise InputError(f"attached to '{token}': no body {digits or '(number missing)'} in BODIES "
                             f"({', '.join(f'Body{b}' for b in bodies) or 'none defined'})", key=key)
        return ("body-pinned" if rest.upper() in PINNED else "body"), int(digits)
    for kind, words in (("fixed", FIXED), ("pinned", PINNED), ("coupled", COUPLED), ("coupled-pinned", COUPLED_PINNED),
                        ("free", ROD_FREE)):
        if word in words and not digits and not rest:
            return kind, None
    raise InputError(f"unknown attachment '{token}' of a rod; valid: Fixed/Anchor/Fix, Pinned/Pin, "
                     "Coupled/Vessel/Ves/Cpld, CoupledPinned/VesselPinned/VesPin/CpldPin, Free/Point/Con, "
                     "BodyN, BodyNPinned", key=key)


def read_rods(type_rows, rod_rows, bodies, notes):
    """RODS rows: dict rod ID -> (row number, kind, body ID or None, Rod, zero length); ``bodies`` by
    ID (``read_bodies``)."""
    types = read_rod_types(type_rows)
    rods = {}
    for number, fields in rod_rows:
        key, rid = _row_id("RODS", "rod", number, fields, rods)
        if rid != len(rods) + 1:  # MoorDyn-C: "Rod ID must be sequential starting from 1"
            raise InputError(f"rod IDs must be 1, 2, ... in order (MoorDyn-C's rule), got {rid} after "
                             f"{len(rods)}", key=at(number, key))
        if fields[1] not in types:
            raise InputError(f"unknown rod type '{fields[1]}'{v.suggest(fields[1], types)}; defined in ROD TYPES: "
                             f"{', '.join(types) or 'none'}", key=at(number, f"{key}.RodType"))
        kind, body = _attachment(fields[2], bodies, at(number, f"{key}.Attachment"))
        ends = [value(tok, number, f"{key}.{col}", _COORDINATE)
                for col, tok in zip(("Xa", "Ya", "Za", "Xb", "Yb", "Zb"), fields[3:9])]
        segments = value(fields[9], number, f"{key}.NumSegs", v.non_negative)
        rod = Rod(rod_name(rid), types[fields[1]], ends[:3], ends[3:], pinned="pinned" in kind)
        zero = segments == 0 or rod.length == 0.0
        if zero and rod.length > 0.0:
            notes.append(f"RODS.{rid}: NumSegs 0 makes a zero-length rod in MoorDyn-C (end B at end A); read so")
        if not zero and kind == "body-pinned" and bodies[body][1].kind == "free":
            notes.append(f"RODS.{rid}: a rod pinned to a free body hands the body its weight and buoyancy at its "
                         "pin, at the angle the file gives it (exact unless it pierces the water surface)")
        if kind == "coupled-pinned":
            notes.append(f"RODS.{rid}: a coupled pinned rod is held at end A where the file puts it (MoorDyn files "
                         "have no motion), free to turn")
        rods[rid] = (number, kind, body, rod, zero)
    if rods:
        notes.append("RODS: a rod's weight and buoyancy (with partial submergence) are in statics; a run steps "
                     "free and pinned rods and rods on free bodies with their drag and added mass too "
                     "(cablefem.loads.rod_body; a pinned rod's pin a stiff spring)")
    return rods


def rod_end(token, rods, key):
    """The point name of a LINES AttachA/AttachB rod-end token (``R1A``, ``Rod2B``), or None if the
    token does not name a rod."""
    match = _WORD_NUMBER.fullmatch(token)
    if not match or match.group(1).upper() not in ("R", "ROD"):
        return None
    _, digits, end = match.groups()
    if not digits or int(digits) not in rods:
        raise InputError(f"no rod {digits or '(number missing)'} in RODS for '{token}' "
                         f"({', '.join(f'R{r}' for r in rods) or 'none defined'})", key=key)
    if end.upper() not in ("A", "B"):
        raise InputError(f"a rod end is A or B, got '{token}' (R{digits}A or R{digits}B)", key=key)
    rid = int(digits)
    return rod_name(rid) if rods[rid][4] else f"{rod_name(rid)}{end.upper()}"


def rod_network(rods, bodies, used, notes):
    """The points (name -> (row number, Point)) and bodies (name -> Body) that ``rods`` add to the
    network, given the rod-end point names the lines use (``used``), and the bodies of BODIES with
    the rods fixed on free ones (name -> Body)."""
    points, rod_bodies = {}, {}
    carried = {bid: [] for bid in bodies}
    for rid, (number, kind, bid, rod, zero) in rods.items():
        key = at(number, f"RODS.{rid}")
        names = [n for n in ((rod.name,) if zero else (rod.name + "A", rod.name + "B")) if n in used]
        if kind == "body-pinned" and rod.name + "B" in names and not zero:
            raise InputError("a line on end B of a rod pinned to a body (R{0}B) is not supported: attach it to the "
                             "body (a BodyN point) or make the rod fixed on the body".format(rid), key=key)
        on_body = kind in ("body", "body-pinned")
        for name in names:
            local = rod.end_a if zero or name.endswith("A") else rod.end_b
            if zero or on_body or kind == "fixed":
                point_kind = {"fixed": "fixed", "coupled": "coupled"}.get(kind, "fixed" if on_body else "free")
                points[name] = (number, Point(name, point_kind, local, body=body_name(bid) if on_body else None))
            else:  # a coupled, pinned or free rod is a body; its ends are points of it
                end = "A" if name.endswith("A") else "B"
                at_local = rod_end_local(rod, end)
                points[name] = (number, Point(name, "fixed", at_local, body=rod.name))
        if zero or kind == "fixed":
            continue
        if on_body:
            if bodies[bid][1].kind == "free":
                carried[bid].append(rod)
        elif kind == "coupled":
            rod_bodies[rod.name] = Body(rod.name, "coupled", rod.end_a, axis_angles(rod.end_b - rod.end_a))
        else:
            if not names:
                raise InputError(f"a {'pinned' if rod.pinned else 'free'} rod with no line on its ends: nothing "
                                 "holds it in cablefem's statics; attach a line to it (R{0}A or R{0}B) or make it "
                                 "fixed".format(rid), key=key)
            if rod.mass <= 0.0:
                raise InputError("a free or pinned rod needs Mass/m > 0 (a massless rigid body has no dynamics)",
                                 key=at(number, f"ROD TYPES.{rod.type.name}.Mass/m"))
            rod_bodies[rod.name] = rod_body(rod, Body)
    for bid, carry in carried.items():
        if carry:
            number, body = bodies[bid]
            bodies[bid] = (number, Body(**{**body.__dict__, "rods": tuple(carry)}))
    return points, rod_bodies


def clamp_directions(rods, name):
    """The direction a line that bends is clamped to at rod-end point ``name`` as it leaves it (its
    tangent there, pointing away from the rod end along the rod's axis as MoorDyn-C's
    ``Line::setEndOrientation`` sets it, for a line starting there), or None where it is pinned:
    only a fixed finite rod holds a direction in a run."""
    for rid, (_, kind, _, rod, zero) in rods.items():
        if not zero and kind == "fixed" and name in (rod.name + "A", rod.name + "B"):
            axis = (rod.end_b - rod.end_a) / rod.length
            return axis if name.endswith("B") else -axis
    return None
