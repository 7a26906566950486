"""Seabed readers, one small module per file format, behind one ``read_seabed`` entry.

The registry ``FORMATS`` maps a format name to (seabed kind, module); each
module exposes ``read(path) -> Seabed`` and is imported only when a file of its
format is read, so a missing optional reader costs nothing until it is needed.
Grid files are told apart by their first lines (``sniff_grid``). Shared here:
the small text helpers the grid readers use to report errors by line number.
"""

import importlib
import re
from pathlib import Path

import numpy as np

from cablefem.errors import InputError

#: format name -> (seabed kind, module holding ``read(path)``, what the file holds)
FORMATS = {
    "moordyn-c": ("grid", "cablefem.geometry.readers.moordyn_c",
                  "MoorDyn-C SeafloorFile: 'nx ny', the x values, the y values, rows 'x y z'"),
    "moordyn-f": ("grid", "cablefem.geometry.readers.moordyn_f",
                  "MoorDyn-F/MoorPy bathymetry: title, 'nGridX n', 'nGridY n', x values, "
                  "rows 'y depth ...' (depth positive down)"),
    "mesh": ("mesh", "cablefem.geometry.readers.meshio_surface",
             "any triangle surface meshio reads (.stl, .obj, .ply, .vtu, ...)"),
    "points": ("points", "cablefem.geometry.readers.xyz",
               "soundings, one 'x y z' row per point, Delaunay-triangulated"),
}

#: the seabed kinds of a scene's [seabed] section that name a file
KINDS = ("grid", "mesh", "points")

_GRID_FORMATS = ("moordyn-f", "moordyn-c")
_TEXT_SUFFIXES = {".txt", ".dat", ".bath", ".bathy", ".xyz", ".csv", ".pts", ""}


def read_seabed(path, kind=None):
    """The seabed in file path: kind "grid", "mesh", "points" or a format of FORMATS; None guesses."""
    path = Path(path)
    if kind is not None and kind not in KINDS and kind not in FORMATS:
        raise InputError(f"unknown seabed kind {kind!r}; expected one of "
                         f"{', '.join(KINDS)} (or a format: {', '.join(FORMATS)})", key="kind",
                         file=path)
    if not path.exists():
        raise InputError("no such file", file=path)
    if not path.is_file():
        raise InputError("not a regular file", file=path)
    if kind is None:
        kind = guess_kind(path)
    if kind == "grid":
        fmt = sniff_grid(path)
        if fmt is None:
            raise InputError("not a bathymetry grid: expected 'nx ny' on the first line (MoorDyn-C) "
                             "or 'nGridX n' on the second (MoorDyn-F/MoorPy)", file=path)
    else:
        fmt = kind
    module = _load(fmt, path)
    try:
        return module.read(path)
    except InputError as error:
        raise error.within(file=path) from None


def _load(fmt, path):
    """The reader module of format fmt, imported now."""
    name = FORMATS[fmt][1]
    try:
        return importlib.import_module(name)
    except ModuleNotFoundError as error:
        if error.name != name:
            raise
        raise InputError(f"no reader for {fmt!r} files in this installation ({name} is missing)",
                         key="kind", file=path) from None


def _head(path, count=6):
    """The first count lines of a text file (list of str), or [] if it is not text."""
    try:
        with open(path, encoding="utf-8") as f:
            return [line for line, _ in zip(f, range(count))]
    except (OSError, UnicodeDecodeError):
        return []


def sniff_grid(path):
    """The grid format of path ("moordyn-c" or "moordyn-f"), or None if it is neither."""
    head = _head(path)
    for fmt in _GRID_FORMATS:
        if importlib.import_module(FORMATS[fmt][1]).matches(head):
            return fmt
    return None


def guess_kind(path):
    """The seabed kind of a file from its first lines and its suffix: grid, mesh or points."""
    if sniff_grid(path) is not None:
        return "grid"
    suffix = path.suffix.lower()
    if suffix not in _TEXT_SUFFIXES:
        import meshio
        if suffix in meshio.extension_to_filetypes:
            return "mesh"
    rows = [line.split() for line in _head(path) if line.strip() and not line.lstrip().startswith("#")]
    if rows and all(len(row) == 3 and all(is_number(t) for t in row) for row in rows):
        return "points"
    raise InputError("cannot tell which kind of seabed this file holds; give kind = "
                     "grid | mesh | points", key="kind", file=path)


# -- text helpers shared by the grid readers ---------------------------------

#: largest |coordinate| [m] in a seabed file (UTM northings reach 1e7 m; cablefem.io.validate.LIMITS)
MAX_COORDINATE = 1e8
#: most grid lines along one axis: a 1e5 x 1e5 grid of doubles would already take 80 GB
MAX_GRID_NODES = 100_000
_INTEGER = re.compile(r"[0-9]+")


def parse_number(token):
    """The float a text token spells in ASCII (``12``, ``-1.5e3``, ``nan``), or None.

    Python's ``float`` also reads other scripts' digits ('\u0663' is 3) and ``1_000``; files
    written for MoorDyn or MoorPy never hold them, and their readers refuse them."""
    if not token.isascii() or "_" in token:
        return None
    try:
        return float(token)
    except ValueError:
        return None


def is_number(token):
    """Whether a text token reads as an ASCII float (shared by the seabed and MoorDyn file readers)."""
    return parse_number(token) is not None


def is_integer(token):
    """Whether a text token is a whole number >= 0 in ASCII digits (not str.isdigit: it takes '\u00b2')."""
    return _INTEGER.fullmatch(token) is not None


def read_lines(path):
    """Lines of a text file (list of str) or an InputError saying why it cannot be read."""
    try:
        return Path(path).read_text(encoding="utf-8").splitlines()
    except UnicodeDecodeError:
        raise InputError("not a text file (not UTF-8)", file=path) from None
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", file=path) from None


def numbers(tokens, line, what):
    """Tokens (list of str) of 1-based file line ``line`` as finite floats (k,) within
    +-MAX_COORDINATE."""
    parsed = [parse_number(t) for t in tokens]
    if None in parsed:
        bad = tokens[parsed.index(None)]
        raise InputError(f"{what}: {bad!r} is not a number", key=f"line {line}")
    values = np.array(parsed, dtype=float)
    if not np.all(np.isfinite(values)):
        bad = tokens[int(np.flatnonzero(~np.isfinite(values))[0])]
        raise InputError(f"{what}: {bad!r} is not a finite number", key=f"line {line}")
    check_coordinates(values, f"line {line}", what)
    return values


def check_coordinates(values, key, what="coordinates"):
    """Raise an InputError at ``key`` if any of values (any shape) [m] exceeds MAX_COORDINATE."""
    beyond = np.flatnonzero(np.abs(np.ravel(values)) > MAX_COORDINATE)
    if len(beyond):
        raise InputError(f"{what}: {np.ravel(values)[beyond[0]]:g} m is beyond the sane limit of "
                         f"{MAX_COORDINATE:g} m (UTM northings reach 1e7 m)", key=key)


def count(token, line, name):
    """Token (str) of file line ``line`` as a grid size, an integer >= 2 (at most MAX_GRID_NODES)."""
    if not is_integer(token):
        raise InputError(f"{name} must be an integer, got {token!r}", key=f"line {line}")
    value = int(token)
    if value > MAX_GRID_NODES:
        raise InputError(f"{name} = {value} is beyond the sane limit of {MAX_GRID_NODES} grid lines",
                         key=f"line {line}")
    if value < 2:
        raise InputError(f"{name} must be at least 2, got {value}", key=f"line {line}")
    return value


def strictly_increasing(values, line, name):
    """Raise an InputError for file line ``line`` unless values (k,) increase strictly."""
    step = np.flatnonzero(np.diff(values) <= 0)
    if len(step):
        k = step[0] + 1
        raise InputError(f"{name} values must increase strictly: {name}[{k}] = {values[k]:g} "
                         f"follows {name}[{k - 1}] = {values[k - 1]:g}", key=f"line {line}")


def match_axis(axis, values):
    """Index (n,) of each value (n,) in the increasing axis (m,), -1 where it is not on it.

    A value matches a tick within 1e-6 of the smallest tick spacing, so that
    '100' and '100.0000001' written by different tools agree; anything farther
    is off the grid (MoorDyn-C would silently move it to the tick below).
    """
    tolerance = 1e-6 * np.min(np.diff(axis))
    right = np.clip(np.searchsorted(axis, values), 1, len(axis) - 1)
    nearest = np.where(np.abs(axis[right] - values) < np.abs(values - axis[right - 1]),
                       right, right - 1)
    return np.where(np.abs(axis[nearest] - values) <= tolerance, nearest, -1)
