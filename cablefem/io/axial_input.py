"""A line type's axial law from scene input (``cablefem.model.axial``): the TOML keys (EA as a number
or a strain-tension table, BA, EA_dynamic, EA_dynamic_slope, BA_dynamic, syrope; docs/scene.md) and
MoorDyn's EA and BA entries (a number, a curve file, ``EA_s|EA_d``, ``EA_s|EA_Dc|EA_D_Lm``,
``SYROPE:file|EA_Dc|EA_D_Lm``, ``BA|BA_D``), read as MoorDyn-C reads them (``MoorDyn2.cpp``:
``readLineProps``, ``read_curve``, ``read_syrope_working_curves``).

MoorDyn-C's curve files skip their first three lines, whatever they hold, then take rows
``x y``; so does cablefem, with a note when the third line held two numbers (MoorDyn's own
``syrope/owc.dat`` has two header lines: its first row, (0, 0), is dropped by both codes, and the
law then runs straight from (0, 0) to the next row in cablefem, where MoorDyn-C holds the first
row's tension below it).
"""

import os

from cablefem.errors import InputError
from cablefem.geometry.readers import parse_number
from cablefem.io import validate as v
from cablefem.model.axial import WORKING_CURVES, AxialLaw, Curve, Syrope

CURVE_HEADER_LINES = 3
_EA = v.limited(v.positive, "EA")
_BA = v.limited(v.non_negative, "internal_damping")


def table_or_number(value, key, x_name, check):
    """A number (``check``), or a table ``{ x_name = [...], tension = [...] }`` as a Curve."""
    if not isinstance(value, dict):
        return check(value, key)
    v.check_keys(value, (x_name, "tension"), key, required=(x_name, "tension"))
    return Curve.from_rows(value[x_name], value["tension"], key, x_name, "tension", signed=x_name != "strain")


def toml_stiffness(value, key):
    """``EA``: a number [N] > 0, or ``{ strain = [...], tension = [...] }``."""
    curve = table_or_number(value, key, "strain", _EA)
    if isinstance(curve, Curve):
        for i, y in enumerate(curve.y):
            _EA(max(y, 1.0), f"{key}.tension[{i}]")
    return curve


def toml_damping(value, key):
    """``BA``: a number [N s] >= 0, or ``{ strain_rate = [...], tension = [...] }``."""
    return table_or_number(value, key, "strain_rate", _BA)


def toml_syrope(value, key):
    """``syrope = { working_curve = "linear" | "quadratic" | "exp", k1 = ..., k2 = ... }``."""
    table = v.table(value, key)
    values = v.pick(table, key, {"working_curve": v.choice(WORKING_CURVES), "k1": v.non_negative,
                                 "k2": v.number}, required=("working_curve", "k1", "k2"))
    try:
        return Syrope(values["working_curve"], values["k1"], values["k2"])
    except InputError as error:
        raise error.within(prefix=key) from None


def toml_initial(value, key):
    """A SYROPE segment's ``syrope = { Tmax = ..., Tmean = ... }`` [N]: (Tmax0, Tmean0)."""
    table = v.table(value, key)
    values = v.pick(table, key, {"Tmax": v.limited(v.positive, "force"), "Tmean": v.limited(v.non_negative, "force")},
                    required=("Tmax", "Tmean"))
    return values["Tmax"], values["Tmean"]


def law_of(values):
    """The reference EA [N], the axial law (or None) and the beta [s] of a line type's values (the
    TOML keys, converted): pops the law's keys from ``values``. Errors name the keys."""
    EA, BA = values.pop("EA"), values.pop("BA", None)
    dynamic, slope = values.pop("EA_dynamic", None), values.pop("EA_dynamic_slope", None)
    dynamic_damping, syrope = values.pop("BA_dynamic", None), values.pop("syrope", None)
    if BA is not None and "damping" in values:
        raise InputError("give the internal damping once: BA [N s] or damping (beta [s]), not both", key="BA")
    for name, given in (("EA_dynamic_slope", slope), ("BA_dynamic", dynamic_damping)):
        if given is not None and dynamic is None:
            raise InputError("belongs to a viscoelastic rope: give EA_dynamic (its dynamic stiffness) too", key=name)
    table = isinstance(EA, Curve)
    if syrope is None and dynamic is None and not table and not isinstance(BA, Curve):
        beta = None if BA is None else BA / EA  # the plain law: T = EA e + BA de/dt
        return EA, None, beta
    damping_curve = BA if isinstance(BA, Curve) else None
    common = dict(damping=0.0 if BA is None or damping_curve else BA, damping_curve=damping_curve)
    if damping_curve is not None and (syrope is not None or dynamic is not None):
        raise InputError("a viscoelastic or SYROPE rope takes BA as a number [N s] (its slow part's damper)", key="BA")
    if syrope is not None:
        if not table:
            raise InputError("a SYROPE rope needs EA as its original working curve { strain = [...], tension = "
                             "[...] }", key="EA")
        if dynamic is None:
            raise InputError("a SYROPE rope needs EA_dynamic (MoorDyn's EA_Dc) and EA_dynamic_slope (EA_D_Lm)",
                             key="EA_dynamic")
        law = AxialLaw("syrope", EA, dynamic_EA=dynamic, dynamic_slope=slope or 0.0,
                       dynamic_damping=dynamic_damping or 0.0, syrope=syrope, **common)
    elif dynamic is not None:
        if table:
            raise InputError("a viscoelastic rope takes EA as its static stiffness, a number [N] (a table is a "
                             "SYROPE rope's original working curve: add syrope = {...})", key="EA")
        law = AxialLaw("viscoelastic", static_EA=EA, dynamic_EA=dynamic, dynamic_slope=slope or 0.0,
                       dynamic_damping=dynamic_damping or 0.0, **common)
    else:
        curve = EA if table else Curve((0.0, 1.0), (0.0, EA))
        law = AxialLaw("table", curve, **common)
    return law.reference_EA, law, None


# ------------------------------------------------------------------ MoorDyn files
def read_curve(token, folder, key, notes):
    """A MoorDyn EA or BA entry that is not a number: the curve file ``token`` (relative to
    ``folder``), three header lines skipped, then rows 'x y'; the rows as two lists."""
    path = v.existing_file(token, key, folder)
    name = os.path.basename(path)
    rows = v.read_rows(path, key)
    if len(rows) > CURVE_HEADER_LINES - 1 and _two_numbers(rows[CURVE_HEADER_LINES - 1]):
        notes.append(f"{key}: line {CURVE_HEADER_LINES} of {name} holds numbers, but MoorDyn-C skips the first "
                     f"{CURVE_HEADER_LINES} lines of a curve file as its header, and so does cablefem")
    xs, ys = [], []
    for number, row in enumerate(rows[CURVE_HEADER_LINES:], start=CURVE_HEADER_LINES + 1):
        fields = row.split()
        if not fields:
            continue
        values = [parse_number(f) for f in fields[:2]]
        if len(fields) < 2 or None in values:
            raise InputError(f"{name} line {number}: expected two numbers 'x y', got '{row.strip()}'", key=key)
        xs.append(values[0])
        ys.append(values[1])
    if not xs:
        raise InputError(f"{name}: no rows 'x y' after the {CURVE_HEADER_LINES} header lines", key=key)
    return xs, ys


def _two_numbers(row):
    fields = row.split()
    return len(fields) >= 2 and all(parse_number(f) is not None for f in fields[:2])


def moordyn_curve(token, folder, key, notes, x_name, check):
    """A MoorDyn entry as a number (``check``) or the Curve of its file."""
    number = parse_number(token)
    if number is not None:
        return check(number, key)
    xs, ys = read_curve(token, folder, key, notes)
    return Curve.from_rows(xs, ys, f"{key} ({token})", x_name, "tension", signed=x_name != "strain")


def read_syrope_file(token, folder, key):
    """A SYROPE settings file: its OWC path (relative to ``folder``, the input file's), and
    Syrope(WCType, k1, k2); rows 'value name', names as MoorDyn-C takes them."""
    path = v.existing_file(token, key, folder)
    name = os.path.basename(path)
    found = {}
    for number, row in enumerate(v.read_rows(path, key), start=1):
        fields = row.split()
        if len(fields) >= 2 and fields[1].lower() in ("owc", "wctype", "k1", "k2"):
            found[fields[1].lower()] = (fields[0], number)
    names = {"owc": "OWC", "wctype": "WCType", "k1": "k1", "k2": "k2"}
    missing = [shown for n, shown in names.items() if n not in found]
    if missing:
        raise InputError(f"{name}: missing {', '.join(missing)} (rows 'value name': OWC, WCType, k1, k2)", key=key)
    form = found["wctype"][0].lower()
    if form not in WORKING_CURVES:
        raise InputError(f"{name} line {found['wctype'][1]}: WCType must be LINEAR, QUADRATIC or EXP, got "
                         f"'{found['wctype'][0]}'", key=key)
    k = {}
    for n in ("k1", "k2"):
        k[n] = parse_number(found[n][0])
        if k[n] is None:
            raise InputError(f"{name} line {found[n][1]}: expected a number for {n}, got '{found[n][0]}'", key=key)
    try:
        syrope = Syrope(form, k["k1"], k["k2"])
    except InputError as error:
        raise InputError(f"{name}: {error.reason}", key=key) from None
    return found["owc"][0], syrope


def moordyn_law(ea_token, ba_token, folder, key, notes, segment_length, mass):
    """MoorDyn's EA and BA entries of a line type with a law of its own (``key``: the row's key,
    e.g. 'line 5: LINE TYPES.poly'; ``segment_length`` [m] and ``mass`` [kg/m] of the line, for
    BA = -zeta, which MoorDyn-C turns into zeta (UnstrLen / NumSegs) sqrt(EA m) with EA the law's
    reference): (reference EA [N], AxialLaw), or None for a constant EA and BA (the plain law)."""
    if not is_law(ea_token, ba_token):
        return None
    ea_parts, ba_parts = ea_token.split("|"), ba_token.split("|")
    ea_key, ba_key = f"{key}.EA", f"{key}.BA/-zeta"
    if len(ea_parts) > 3:
        raise InputError(f"at most 3 values separated by '|', got '{ea_token}'", key=ea_key)
    if len(ba_parts) > len(ea_parts) or len(ba_parts) > 2:
        raise InputError(f"'{ba_token}': BA has at most as many '|' values as EA, and at most 2 (BA|BA_D)",
                         key=ba_key)
    numbers = [_part(p, ea_key, i) for i, p in enumerate(ea_parts) if i > 0]
    if ea_parts[0].startswith("SYROPE:"):
        if len(ea_parts) != 3:
            raise InputError(f"a SYROPE entry is 'SYROPE:file|EA_Dc|EA_D_Lm', got '{ea_token}'", key=ea_key)
        owc, syrope = read_syrope_file(ea_parts[0][len("SYROPE:"):], folder, ea_key)
        curve = moordyn_curve(owc, folder, f"{ea_key} (OWC {owc})", notes, "strain", _EA)
        if not isinstance(curve, Curve):
            raise InputError(f"the OWC of a SYROPE rope is a curve file, got the number {curve:g}", key=ea_key)
        values = {"EA": curve, "EA_dynamic": _EA(numbers[0], ea_key), "EA_dynamic_slope": numbers[1],
                  "syrope": syrope}
    else:
        values = {"EA": moordyn_curve(ea_parts[0], folder, ea_key, notes, "strain", _EA)}
        if len(ea_parts) >= 2:
            values["EA_dynamic"] = _EA(numbers[0], ea_key)
        if len(ea_parts) == 3:
            values["EA_dynamic_slope"] = numbers[1]
    if "EA_dynamic" in values:
        values["BA_dynamic"] = _BA(_part(ba_parts[1], ba_key, 1), ba_key) if len(ba_parts) == 2 else 0.0
    BA = parse_number(ba_parts[0])
    if BA is None:
        values["BA"] = moordyn_curve(ba_parts[0], folder, ba_key, notes, "strain_rate", _BA)
    else:
        EA = values["EA"]
        reference = EA.secant if isinstance(EA, Curve) else EA
        values["BA"] = _BA(-BA * segment_length * (reference * mass) ** 0.5 if BA < 0.0 else BA, ba_key)
    try:
        reference, law, _ = law_of(values)
    except InputError as error:
        column = ba_key if error.key in ("BA", "BA_dynamic") else ea_key
        raise InputError(error.reason, key=column) from None
    return reference, law


def is_law(ea_token, ba_token):
    """Whether MoorDyn's EA and BA entries give a law of their own (not two numbers)."""
    return "|" in ea_token or parse_number(ea_token) is None or parse_number(ba_token) is None


def _part(token, key, index):
    number = parse_number(token)
    if number is None:
        raise InputError(f"expected a number as value {index + 1}, got '{token}'", key=key)
    return v.limited(v.number, "EA")(number, key)
