"""Typed getters for scene input: every check raises ``InputError`` naming the full key path.

A converter takes ``(value, key)`` and returns the checked value; ``pick``
applies converters to the keys a table holds, after ``check_keys`` has refused
unknown keys (suggesting the closest valid one) and reported missing ones.
"""

import difflib
import math
import os

import numpy as np

from ..errors import InputError

#: a line may not need more than this strain to reach its fairlead from its anchor
MAX_CHORD_STRAIN = 0.20


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
        from ..geometry import read_seabed
    except ImportError:
        try:  # the readers package, before cablefem.geometry re-exports it
            from ..geometry.readers import read_seabed
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


def one_line(error):
    """The text of an exception on one line."""
    return " ".join(str(error).split())
