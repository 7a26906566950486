"""Current profiles read from scenes: MoorDyn-C's ``current_profile.txt`` (``Currents 1``) and
``[environment] current_profile`` of a TOML (a file in that layout, or an inline table), as a
``cablefem.loads.current.CurrentProfile``; and MoorDyn-C's currents that vary in time,
``current_profile_dynamic.txt`` (``Currents 2``) and ``current_profile_4d.txt`` (``Currents 5``), as a
``cablefem.waves.grid.CurrentGrid`` (``read_current_grid``).

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
from cablefem.waves.grid import CurrentGrid

#: the file MoorDyn-C reads, in the input file's folder, with ``Currents 1``
MOORDYN_FILE = "current_profile.txt"
#: the files of the currents that vary in time, per ``Currents`` value
GRID_FILES = {2: "current_profile_dynamic.txt", 5: "current_profile_4d.txt"}
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


def read_current_grid(mode, path, key):
    """The CurrentGrid of MoorDyn-C's ``Currents mode`` (2 or 5) in the file at ``path``, read as
    MoorDyn-C 2.7 reads it (``Waves/WaveGrid.cpp``, ``constructDynamicCurrentGrid`` and
    ``construct4DCurrentGrid``) and resampled onto its clock (``resample``).

    - ``current_profile_dynamic.txt``: five header lines (the fifth the heights z [m], read in single
      precision as MoorDyn-C's ``stof`` reads them), one more skipped, then rows ``t ux(z_1..z_nz)
      [uy(...) [uz(...)]]``; the profile is uniform in x and y.
    - ``current_profile_4d.txt``: ``nx ny nz nt``, then rows of the x, y, z and t values, then a row
      ``x y z t ux uy uz`` per grid point. MoorDyn-C starts reading those rows at the file's seventh
      line and so skips the first (its grid point keeps a zero velocity); cablefem reads them all and
      wants each grid point once.
    """
    name = os.path.basename(path)
    rows = [row.split() for row in v.read_rows(path, key)]
    while rows and not rows[-1]:
        rows.pop()
    where = lambda number: f"{name} line {number}"  # noqa: E731
    numbers = lambda fields, number: _numbers(fields, where(number), key)  # noqa: E731
    if mode == 2:
        if len(rows) < 7:
            raise InputError(f"{name}: MoorDyn-C needs at least 7 lines (5 header lines, the fifth the heights, "
                             "one more, then rows t ux ...)", key=key)
        z = np.array(numbers(rows[4], 5), dtype=np.float32).astype(float)
        nz, times, velocity = len(z), [], []
        for number, fields in enumerate(rows[6:], start=7):
            values = numbers(fields, number)
            if len(values) <= nz:
                raise InputError(f"{where(number)}: expected t and {nz} velocities ux (one per height), got "
                                 f"{len(values)} numbers", key=key)
            parts = [values[1 + c * nz:1 + (c + 1) * nz] if len(values) >= 1 + (c + 1) * nz else [0.0] * nz
                     for c in range(3)]
            times.append(values[0])
            velocity.append(np.array(parts).T)  # (nz, 3)
        axes = (np.zeros(1), np.zeros(1), z)
        values = np.array(velocity).transpose(1, 0, 2)[None, None]  # (1, 1, nz, nt, 3)
    else:
        if len(rows) < 6:
            raise InputError(f"{name}: expected nx ny nz nt, the x, y, z and t values, then rows x y z t ux uy uz",
                             key=key)
        counts = numbers(rows[0], 1)
        if len(counts) < 4 or any(c < 1 or c != int(c) for c in counts[:4]):
            raise InputError(f"{where(1)}: expected the counts nx ny nz nt (whole numbers >= 1)", key=key)
        counts = [int(c) for c in counts[:4]]
        grid = []
        for axis, (label, count) in enumerate(zip("xyzt", counts)):
            values = numbers(rows[1 + axis], 2 + axis)
            if len(values) < count:
                raise InputError(f"{where(2 + axis)}: expected {count} {label} values, got {len(values)}", key=key)
            grid.append(np.array(values[:count]))
        *axes, times = grid
        values = np.full(tuple(counts) + (3,), np.nan)
        for number, fields in enumerate(rows[5:], start=6):
            row = numbers(fields, number)
            if len(row) < 7:
                raise InputError(f"{where(number)}: expected x y z t ux uy uz", key=key)
            index = []
            for axis, (label, coordinate) in enumerate(zip("xyzt", row[:4])):
                hit = np.flatnonzero(grid[axis] == coordinate)
                if not len(hit):
                    raise InputError(f"{where(number)}: {label} = {coordinate:g} is not one of the grid's {label} "
                                     f"values (line {2 + axis})", key=key)
                index.append(hit[0])
            values[tuple(index)] = row[4:7]
        missing = int(np.isnan(values[..., 0]).sum())
        if missing:
            raise InputError(f"{name}: {missing} of the {values[..., 0].size} grid points have no row "
                             "x y z t ux uy uz", key=key)
    for label, axis in zip("xyz", axes):
        if np.any(np.diff(axis) <= 0.0):
            raise InputError(f"{name}: the {label} values must increase", key=key)
    times = np.asarray(times, dtype=float)
    if len(times) > 1 and np.any(np.diff(times) <= 0.0):
        raise InputError(f"{name}: the times must increase", key=key)
    dt, velocity = resample(times, values)
    return CurrentGrid(*axes, dt, velocity, kind=f"MoorDyn Currents {mode}", source=path)


def resample(times, values):
    """MoorDyn-C's clock of a current read at ``times`` (k,) [s] with ``values`` (..., k, 3): its step dt,
    the smallest interval of the times, and the values linearly interpolated (held beyond the ends) at
    i dt, i = 0 .. floor(t_last / dt): (dt, (..., nt, 3))."""
    if len(times) == 1:
        return 1.0, values
    dt = float(np.min(np.diff(times)))
    clock = np.arange(int(np.floor(times[-1] / dt)) + 1) * dt
    upper = np.clip(np.searchsorted(times, clock, side="left"), 1, len(times) - 1)
    fraction = np.clip((clock - times[upper - 1]) / (times[upper] - times[upper - 1]), 0.0, 1.0)[:, None]
    return dt, values[..., upper - 1, :] * (1.0 - fraction) + values[..., upper, :] * fraction


def _numbers(fields, where, key):
    """The numbers of a row's fields; InputError naming the row when one is not a number."""
    values = [parse_number(f) for f in fields]
    if None in values:
        raise InputError(f"{where}: '{fields[values.index(None)]}' is not a number", key=key)
    return values
