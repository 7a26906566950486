"""Typed getters for scene input: every check raises ``InputError`` naming the full key path.

A converter takes ``(value, key)`` and returns the checked value; ``pick``
applies converters to the keys a table holds, after ``check_keys`` has refused
unknown keys (suggesting the closest valid one) and reported missing ones.
"""

import difflib
import math
import os
import re
import unicodedata

import numpy as np

from cablefem.errors import InputError

#: a line may not need more than this strain to reach its fairlead from its anchor
MAX_CHORD_STRAIN = 0.20

#: sane limits, checked before any work starts (docs/scene.md, "Limits"): quantity ->
#: (largest magnitude, unit, why). Far beyond anything real, and far below where products
#: of two or three such values overflow a float (1e308) or exhaust a machine.
LIMITS = {
    "coordinate": (1e8, "m", "UTM northings reach 1e7 m"),
    "length": (1e8, "m", "no line, depth or motion comes near 100 000 km"),
    "diameter": (10.0, "m", "the largest lines, buoyancy modules included, are ~2 m"),
    "mass": (1e5, "kg/m", "the heaviest chains are ~1e3 kg/m"),
    "EA": (1e13, "N", "the stiffest real lines are ~1e10-1e11 N"),
    "EI": (1e13, "N m^2", "steel risers and umbilicals are ~1e4-1e8 N m^2"),
    "damping_time": (1e6, "s", "beta is ~1e-3 to 1 s"),
    "internal_damping": (1e13, "N s", "MoorDyn's BA of synthetic ropes' slow parts is ~1e9-1e11 N s"),
    "slope": (1e4, "", "a rope's EA_D_Lm (dynamic stiffness per mean tension) is ~0.1-100"),
    "coefficient": (1e3, "", "drag and added-mass coefficients are ~0.1 to 10"),
    "water_density": (1e5, "kg/m^3", "sea water is 1025 kg/m^3"),
    "gravity": (1e3, "m/s^2", "g is 9.81 m/s^2"),
    "speed": (1500.0, "m/s", "the speed of sound in water"),
    "acceleration": (1e4, "m/s^2", "1000 g; vessels and actuators stay under a few g"),
    "stiffness": (1e16, "N/m^3", "seabeds are ~1e5-1e7 N/m^3; verification/stability uses 3e14"),
    "damping_ratio": (1e3, "", "critical damping is 1"),
    "contact_damping": (1e12, "N s/m^3", "MoorDyn's cBot is ~3e5 N s/m^3"),
    "friction": (100.0, "", "friction coefficients are ~0.1 to 1.5"),
    "friction_damping": (1e12, "N s/m", "MoorDyn's FricDamp is ~200 N s/m"),
    "iterations": (10000, "", "Newton converges in tens of iterations or not at all"),
    "shear_strength": (1e8, "Pa", "soft clays are ~1e3-1e5 Pa, the stiffest ~1e6 Pa"),
    "strength_gradient": (1e7, "Pa/m", "clays gain ~1e3-1e4 Pa per metre of depth"),
    "soil_stiffness": (1e6, "1/m", "k_n and k_t are ~1/d_b, 1-100 1/m"),
    "load_steps": (100000, "", "a pretension path needs tens to hundreds of steps"),
    "order": (20, "", "P1-P3 are the useful orders; scikit-fem's ElementLinePp is well conditioned "
              "far beyond 20"),
    "point_mass": (1e9, "kg", "the heaviest clump weights and floating platforms are ~1e7-1e8 kg"),
    "volume": (1e7, "m^3", "the largest floating platforms displace ~1e5-1e6 m^3"),
    "area": (1e6, "m^2", "a point's or body's drag area is ~1-1e4 m^2"),
    "angle": (1e4, "deg", "a few turns"),
    "inertia": (1e15, "kg m^2", "floating platforms are ~1e10-1e12 kg m^2"),
    "force": (1e10, "N", "mooring and environmental loads are ~1e6-1e8 N"),
    "moment": (1e13, "N m", "mooring and environmental moments are ~1e8-1e11 N m"),
    "nodes": (1_000_000, "", "~6 KB of memory per node (0.9 GB measured at 1e5 elements) and ~5 us "
              "per node and step: 1e6 nodes take ~6 GB and ~5 s per step"),
}


def join(prefix, key):
    """The key path ``prefix.key`` (``key`` alone without a prefix)."""
    return f"{prefix}.{key}" if prefix else str(key)


def describe_type(value):
    """A short English name of a TOML value's type ("a string", "an array", ...)."""
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, (list, tuple)):
        return "an array"
    if isinstance(value, int):
        return "an integer"
    if isinstance(value, float):
        return "a number"
    return type(value).__name__


def suggest(word, choices):
    """' (did you mean 'x'?)' for the closest of ``choices``, or ''."""
    close = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else ""


def check_keys(table, allowed, prefix, required=(), elsewhere=None):
    """Refuse keys of ``table`` not in ``allowed`` and report ``required`` keys it lacks.

    ``elsewhere`` maps keys that are valid in another variant of the table
    (another seabed kind, ...) to the reason they do not apply here.
    """
    for key in table:
        if key not in allowed:
            if elsewhere and key in elsewhere:
                raise InputError(elsewhere[key], key=join(prefix, key))
            raise InputError(f"unknown key{suggest(key, allowed)}", key=join(prefix, key))
    for key in required:
        if key not in table:
            raise InputError("missing required key", key=join(prefix, key))


def pick(table, prefix, converters, required=(), elsewhere=None):
    """Check the keys of ``table`` against ``converters`` and convert those present: dict key -> value."""
    check_keys(table, converters, prefix, required, elsewhere)
    return {key: converters[key](table[key], join(prefix, key)) for key in converters if key in table}


def number(value, key):
    """A finite float; bools, strings and arrays are refused."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise InputError(f"expected a number, got {describe_type(value)} {value!r}", key=key)
    value = float(value)
    if not math.isfinite(value):
        raise InputError(f"must be finite, got {value}", key=key)
    return value


def positive(value, key):
    """A finite float > 0."""
    value = number(value, key)
    if value <= 0:
        raise InputError(f"must be > 0, got {value:g}", key=key)
    return value


def non_negative(value, key):
    """A finite float >= 0."""
    value = number(value, key)
    if value < 0:
        raise InputError(f"must be >= 0, got {value:g}", key=key)
    return value


def fraction(value, key):
    """A finite float in [0, 1]."""
    value = number(value, key)
    if not 0.0 <= value <= 1.0:
        raise InputError(f"must be between 0 and 1, got {value:g}", key=key)
    return value


def boolean(value, key):
    """A TOML boolean (true / false); anything else is refused."""
    if not isinstance(value, bool):
        raise InputError(f"expected true or false, got {describe_type(value)}", key=key)
    return value


def whole(value, key):
    """An integer >= 1 (element counts, element order, iteration caps)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if isinstance(value, float) and not math.isfinite(value):
            raise InputError(f"must be finite, got {value}", key=key)
        raise InputError(f"expected a whole number, got {describe_type(value)} {value!r}", key=key)
    if value < 1:
        raise InputError(f"must be at least 1, got {value}", key=key)
    return int(value)


def limited(converter, quantity):
    """``converter`` followed by the sane limit ``LIMITS[quantity]`` on the magnitude of its
    result (a number, or each number of a tuple)."""
    bound, unit, why = LIMITS[quantity]

    def convert(value, key):
        value = converter(value, key)
        for k, item in enumerate(value if isinstance(value, tuple) else (value,)):
            if abs(item) > bound:
                where = f"{key}[{k}]" if isinstance(value, tuple) else key
                shown = [f"{x}" if isinstance(x, int) else f"{x:g}" for x in (item, bound)]
                raise InputError(f"{shown[0]} {unit} is beyond the sane limit of {shown[1]} {unit}"
                                 f" ({why})".replace("  ", " "), key=where)
        return value
    return convert


def text(value, key):
    """A non-empty string."""
    if not isinstance(value, str):
        raise InputError(f"expected a string, got {describe_type(value)} {value!r}", key=key)
    if not value.strip():
        raise InputError("must not be empty", key=key)
    return value


def choice(valid):
    """A converter accepting one of the strings ``valid`` (and listing them otherwise)."""
    def convert(value, key):
        value = text(value, key)
        if value not in valid:
            listed = " | ".join(valid)
            raise InputError(f"unknown value '{value}'{suggest(value, valid)}; valid: {listed}", key=key)
        return value
    return convert


def vector3(value, key):
    """Three finite numbers as a tuple of floats."""
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise InputError(f"expected 3 numbers [x, y, z], got {value!r}", key=key)
    return tuple(number(item, f"{key}[{i}]") for i, item in enumerate(value))


def table(value, key):
    """A TOML table (dict)."""
    if not isinstance(value, dict):
        raise InputError(f"expected a table, got {describe_type(value)} {value!r}", key=key)
    return value


def tables(value, key):
    """A non-empty array of TOML tables."""
    if not isinstance(value, list) or not all(isinstance(item, dict) for item in value):
        raise InputError(f"expected an array of tables, got {describe_type(value)}", key=key)
    if not value:
        raise InputError("must hold at least one entry", key=key)
    return value


def existing_file(value, key, folder):
    """The absolute path of a readable file; relative paths resolve against ``folder``."""
    value = text(value, key)
    path = os.path.normpath(os.path.join(folder, os.path.expanduser(value)))
    if not os.path.exists(path):
        raise InputError(f"file not found: {path}", key=key)
    if not os.path.isfile(path):
        raise InputError(f"not a file: {path}", key=key)
    if not os.access(path, os.R_OK):
        raise InputError(f"file not readable: {path}", key=key)
    return path


def check_chord(line, key):
    """Refuse a line that would need more than MAX_CHORD_STRAIN to span anchor to fairlead."""
    strain = line.chord_strain()
    if strain > MAX_CHORD_STRAIN:
        chord = float(np.linalg.norm(line.fairlead - line.anchor))
        raise InputError(
            f"would need an absurd strain of {100 * strain:.1f} % to reach its fairlead "
            f"(anchor-fairlead distance {chord:.6g} m, unstretched length {line.unstretched_length:.6g} m)",
            key=key)
    return line


def read_seabed_file(path, kind, key, kind_key=None):
    """A seabed from ``cablefem.geometry.read_seabed`` (imported lazily), errors located at ``key``
    (``kind_key`` when no reader is installed yet)."""
    try:
        from cablefem.geometry import read_seabed
    except ImportError:
        try:  # the readers package, before cablefem.geometry re-exports it
            from cablefem.geometry.readers import read_seabed
        except ImportError:
            raise InputError(f"seabed kind '{kind}' is not available yet", key=kind_key or key) from None
    try:
        return read_seabed(path, kind=kind)
    except InputError as error:  # keep the seabed file's own location, under the scene's key
        located = error if error.file else error.within(file=path)
        raise InputError(one_line(located.message()), key=key) from None
    except Exception as error:  # noqa: BLE001 - third-party readers (meshio, ...) raise their own types
        raise InputError(f"cannot read {kind} seabed {path}: {type(error).__name__}: {one_line(error)}",
                         key=key) from None


#: longest scene name [bytes of UTF-8]: ``<name>_<frame>.vtu`` and its temporary ``.<file>.partial``
#: stay far below the 255 bytes a file name may hold
MAX_NAME_BYTES = 200
#: Unicode categories refused in names: control, format (bidi overrides, zero width),
#: surrogate (undecodable bytes of a file name), line and paragraph separators
_HOSTILE = ("Cc", "Cf", "Cs", "Zl", "Zp")


def printable_name(value, key):
    """A name without control or invisible characters and at most MAX_NAME_BYTES of UTF-8."""
    bad = next((c for c in value if unicodedata.category(c) in _HOSTILE), None)
    if bad is not None:
        raise InputError(f"must not hold control or invisible characters, got {bad!r} in {value!r}",
                         key=key)
    size = len(value.encode("utf-8", "surrogatepass"))
    if size > MAX_NAME_BYTES:
        raise InputError(f"is {size} bytes long, at most {MAX_NAME_BYTES} (it names output files)",
                         key=key)
    return value


def file_name_part(value, key):
    """A scene name that is safe as the start of a file name: not empty, no path separator
    ('/' or '\\'), not starting with '.' (hidden files, '.' and '..'), printable, bounded."""
    if not isinstance(value, str) or not value.strip():
        raise InputError("must not be empty", key=key)
    for separator in ("/", "\\"):
        if separator in value:
            raise InputError(f"must not hold a path separator {separator!r}: it names files inside "
                             f"the output folder, got {value!r}", key=key)
    if value.startswith("."):
        raise InputError(f"must not start with '.' (hidden or parent-folder file names), got {value!r}",
                         key=key)
    return printable_name(value, key)


#: longest path [bytes] Linux takes (PATH_MAX)
MAX_PATH_BYTES = 4096


def folder(value, key):
    """A folder path: a non-empty string without control characters (NUL included), at most
    MAX_PATH_BYTES long; whether it can be written is checked when it is (cablefem.io.output)."""
    value = text(value, key)
    bad = next((c for c in value if unicodedata.category(c) in ("Cc", "Cs")), None)
    if bad is not None:
        raise InputError(f"must not hold control characters, got {bad!r} in {value!r}", key=key)
    if len(value.encode("utf-8")) > MAX_PATH_BYTES:
        raise InputError(f"is longer than the {MAX_PATH_BYTES} bytes a path may hold", key=key)
    return value


def read_time_table(path, key, columns, least, check=None):
    """Rows of numbers (k, len(columns)) of a text table whose first column is a strictly increasing
    time: separators commas, semicolons or blanks, ``#`` starts a comment line, an optional header row
    naming the ``columns``; at least ``least`` rows. ``check(name, number, row, values)`` may refuse a
    row. Errors name the file's line."""
    from cablefem.geometry.readers import parse_number

    name, listed = os.path.basename(path), ", ".join(columns)
    table = []
    for number, row in enumerate(read_rows(path, key), start=1):
        fields = [f for f in re.split(r"[,;\s]+", row.strip()) if f]
        if not fields or fields[0].startswith("#"):
            continue
        if not table and [f.lower() for f in fields] == [c.lower() for c in columns]:
            continue
        if len(fields) != len(columns):
            raise InputError(f"{name} line {number}: expected {len(columns)} columns {listed}, got {len(fields)}",
                             key=key)
        values = [parse_number(f) for f in fields]
        if None in values:
            raise InputError(f"{name} line {number}: expected numbers {listed}, got '{row.strip()}'", key=key)
        if not all(math.isfinite(x) for x in values):
            raise InputError(f"{name} line {number}: values must be finite, got '{row.strip()}'", key=key)
        if check is not None:
            check(name, number, row, values)
        if table and values[0] <= table[-1][0]:
            raise InputError(f"{name} line {number}: times must strictly increase "
                             f"(t = {values[0]:g} after t = {table[-1][0]:g})", key=key)
        table.append(values)
    if len(table) < least:
        raise InputError(f"{name}: needs at least {least} rows {listed}, got {len(table)}", key=key)
    return np.array(table)


def read_rows(path, key):
    """The lines of the UTF-8 text file at ``path``; an unreadable file is an InputError at ``key``."""
    try:
        with open(path, encoding="utf-8") as handle:
            return handle.read().splitlines()
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read {path}: {one_line(error)}", key=key) from None


def one_line(error):
    """The text of an exception on one line."""
    return " ".join(str(error).split())
