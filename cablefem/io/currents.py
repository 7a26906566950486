"""Current profiles read from scenes: MoorDyn-C's ``current_profile.txt`` (``Currents 1``) and
``[environment] current_profile`` of a TOML (a file in that layout, or an inline table), as a
``cablefem.loads.current.CurrentProfile``.

MoorDyn-C's layout (``Waves/WaveGrid.cpp``, ``constructSteadyCurrentGrid``): the first three lines
are a header and skipped, whatever they hold; every line after them is ``z ux [uy [uz]]``, z the
height [m] (negative below the surface), the missing components zero. cablefem also wants the
heights strictly increasing (MoorDyn's interpolation assumes it without checking) and refuses a
header line that holds only numbers (MoorDyn would drop that row silently).
"""

import os

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.readers import parse_number
from cablefem.loads.current import CurrentProfile
from cablefem.io import validate as v

#: the file MoorDyn-C reads, in the input file's folder, with ``Currents 1``
MOORDYN_FILE = "current_profile.txt"
HEADER_LINES = 3
_SPEED = v.limited(v.vector3, "speed")
_HEIGHT = v.limited(v.number, "coordinate")


def read_current_profile(path, key):
    """The CurrentProfile in a current_profile.txt at ``path``; errors name ``key`` and the file's line."""
    name = os.path.basename(path)
    rows = v.read_rows(path, key)
    for number, row in enumerate(rows[:HEADER_LINES], start=1):
        if row.split() and all(parse_number(f) is not None for f in row.split()):
            raise InputError(f"{name} line {number}: holds numbers, but the first {HEADER_LINES} lines are a "
                             "header (MoorDyn-C skips them): write the header, then rows z ux uy uz", key=key)
    heights, velocities = [], []
    for number, row in enumerate(rows[HEADER_LINES:], start=HEADER_LINES + 1):
        fields = row.split()
        if not fields:
            continue
        values = [parse_number(f) for f in fields]
        if len(fields) < 2 or None in values:
            raise InputError(f"{name} line {number}: expected z ux [uy [uz]] (numbers), got '{row.strip()}'",
                             key=key)
        heights.append(_HEIGHT(values[0], f"{key} ({name} line {number})"))
        velocities.append(_SPEED((values[1:4] + [0.0, 0.0])[:3], f"{key} ({name} line {number})"))
    if not heights:
        raise InputError(f"{name}: no rows z ux [uy [uz]] after the {HEADER_LINES} header lines", key=key)
    return CurrentProfile.from_arrays(heights, velocities, f"{key} ({name})", source=path)


def current_profile_setting(value, key, folder):
    """``[environment] current_profile``: a file name (resolved against ``folder``) in MoorDyn-C's
    layout, or a table ``{ z = [...], velocity = [[ux, uy, uz], ...] }``."""
    if isinstance(value, str):
        return read_current_profile(v.existing_file(value, key, folder), key)
    table = v.table(value, key)
    v.check_keys(table, {"z": None, "velocity": None}, key, required=("z", "velocity"))
    heights, velocity = table["z"], table["velocity"]
    if not isinstance(heights, list) or not heights:
        raise InputError("expected an array of heights [m], bottom first", key=f"{key}.z")
    if not isinstance(velocity, list) or len(velocity) != len(heights):
        raise InputError(f"expected {len(heights)} velocities [ux, uy, uz], one per height", key=f"{key}.velocity")
    z = [_HEIGHT(h, f"{key}.z[{i}]") for i, h in enumerate(heights)]
    u = [_SPEED(row, f"{key}.velocity[{i}]") for i, row in enumerate(velocity)]
    return CurrentProfile.from_arrays(z, np.array(u, dtype=float), key, source="inline")
