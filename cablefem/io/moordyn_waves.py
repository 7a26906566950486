"""MoorDyn-C's wave kinematics (``WaveKin``) and their files, read into a ``cablefem.waves.Sea`` as
MoorDyn-C 2.7 reads them (``source/Waves.cpp``, ``Waves/WaveSpectrum.cpp``, ``Waves/SpectrumKin.cpp``,
``Waves/WaveGrid.cpp``; docs/scene.md, "Waves from MoorDyn files").

The files are found where MoorDyn-C looks for them: in the folder of the input file
(``wave_frequencies.txt``, ``wave_elevation.txt``, ``water_grid.txt``; MoorDyn-C prefixes their
names with the input file's path as given, which is that folder).

- ``WaveKin 7`` (summed components): every row of wave_frequencies.txt is ``omega re im [beta]``
  (omega [rad/s], the complex amplitude c [m], beta [rad] in [-2 pi, 2 pi], default 0), the first
  omega 0; MoorDyn-C's surface is sum |c| sin(omega t - k (x cos beta + y sin beta) + arg c), the
  component of cablefem's convention with phase pi/2 - arg c.
- ``WaveKin 2`` (spectrum on a grid): the same file, its amplitudes interpolated linearly (complex,
  and beta) at evenly spaced frequencies i d omega, d omega the smallest spacing of the file
  (``interpEvenlySpaced``), then inverted by an FFT: surface sum |c_i| cos(omega_i t - k l + arg c_i)
  over the inner frequencies, half of Re(c_0) as a mean level and half of the last frequency's.
- ``WaveKin 3`` (elevation record on a grid): wave_elevation.txt's rows ``t eta`` (further columns
  ignored) resampled linearly every ``dtWave`` s (default 0.25) from t = 0 to the last time, the last
  sample dropped for an even count, Fourier transformed; frequencies above 0.5 Hz are cut, the mean
  is kept as a mean level.
Both grid kinds need water_grid.txt (three header rows, then per axis x, y, z a row with its kind,
0 one point at 0, 1 a list, 2 first last count, and a row of values); cablefem reads and checks it
and sums the components at each point instead of interpolating MoorDyn-C's grid linearly in x, y,
z and t (the grid's resolution is MoorDyn-C's approximation of the same waves). With a grid and a
``Currents 1`` profile MoorDyn-C adds the current to its wave grid (``UnifyCurrentGrid``, its
default) and so stretches it with the waves; cablefem takes the current at the point's own height.
MoorDyn-C stretches the kinematics with Wheeler's rule; its wave numbers come from Newman's approximation
of the dispersion relation (7 significant digits), cablefem's from the relation solved to round-off.
"""

import math
import os

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.readers import parse_number
from cablefem.io import validate as v
from cablefem.io.moordyn_sections import refuse
from cablefem.waves import Sea
from cablefem.waves.series import components_of, uniform

FREQUENCIES, ELEVATION, GRID = "wave_frequencies.txt", "wave_elevation.txt", "water_grid.txt"
#: the WaveKin values read, with their files
FILES = {2: (FREQUENCIES, GRID), 3: (ELEVATION, GRID), 7: (FREQUENCIES,)}
#: MoorDyn-C's default dtWave [s] and its cut-off of WaveKin 3 [rad/s] (0.5 Hz)
DT_WAVE, CUTOFF = 0.25, 0.5 * 2.0 * math.pi


def data_file(name, folder, key):
    """The path of MoorDyn-C's data file ``name`` in ``folder`` (the input file's); InputError at
    ``key`` when it is missing."""
    return v.existing_file(name, f"{key} ({name} beside the file)", folder)


def read_spectrum(path, key):
    """Rows of wave_frequencies.txt: omega (k,) [rad/s], complex amplitudes (k,) [m], beta (k,) [rad]."""
    name = os.path.basename(path)
    rows = v.read_rows(path, key)
    if len(rows) < 2:
        raise InputError(f"{name}: MoorDyn-C needs at least 2 rows omega re im [beta], got {len(rows)}", key=key)
    table = []
    for number, row in enumerate(rows, start=1):
        fields = row.split()
        values = [parse_number(f) for f in fields[:4]]
        if len(fields) < 3 or None in values:
            raise InputError(f"{name} line {number}: expected omega re im [beta] (numbers; MoorDyn-C reads "
                             f"every row), got '{row.strip()}'", key=key)
        if not all(math.isfinite(x) for x in values):
            raise InputError(f"{name} line {number}: values must be finite, got '{row.strip()}'", key=key)
        beta = values[3] if len(values) == 4 else 0.0
        if abs(beta) > 2.0 * math.pi:
            raise InputError(f"{name} line {number}: a direction beyond +-2 pi ({beta:g}): MoorDyn-C takes "
                             "radians", key=key)
        if values[0] < 0.0:
            raise InputError(f"{name} line {number}: a negative frequency {values[0]:g} rad/s", key=key)
        table.append((values[0], complex(values[1], values[2]), beta))
    if table[0][0] != 0.0:
        raise InputError(f"{name}: the first frequency must be 0 rad/s (MoorDyn-C), got {table[0][0]:g}", key=key)
    omega, amplitude, beta = (np.array(column) for column in zip(*table))
    return omega, amplitude, beta


def evenly_spaced(omega, amplitude, beta, key, name=FREQUENCIES):
    """MoorDyn-C's ``interpEvenlySpaced``: amplitudes and directions at i d omega, i = 0 .. n - 1."""
    spacing = np.diff(omega)
    if np.any(spacing <= 0.0):
        raise InputError(f"{name}: WaveKin 2 needs strictly increasing frequencies (MoorDyn-C: 'Ascending "
                         "frequencies are expected')", key=key)
    step = float(spacing.min())
    count = int(math.floor(omega[-1] / step)) + 1
    grid = step * np.arange(count)
    real = np.interp(grid, omega, amplitude.real)
    imag = np.interp(grid, omega, amplitude.imag)
    return grid, real + 1j * imag, np.interp(grid, omega, beta)


def read_grid(path, key):
    """water_grid.txt's axes (x, y, z), each a sorted array of coordinates [m]."""
    name = os.path.basename(path)
    rows = v.read_rows(path, key)
    if len(rows) < 9:
        raise InputError(f"{name}: MoorDyn-C needs 9 rows (3 header rows, then kind and values of x, y, z), "
                         f"got {len(rows)}", key=key)
    axes = []
    for axis, line in zip("xyz", (3, 5, 7)):
        kind = rows[line].split()[:1]
        entries = rows[line + 1].split()
        where = f"{name} line {line + 1}"
        if kind not in (["0"], ["1"], ["2"]):
            raise InputError(f"{where}: the {axis} axis's kind must be 0 (one point), 1 (a list) or 2 (first "
                             f"last count), got '{rows[line].strip()}'", key=key)
        values = [parse_number(f) for f in entries]
        if kind == ["0"]:
            axes.append(np.zeros(1))
            continue
        if not entries or None in values or not all(math.isfinite(x) for x in values):
            raise InputError(f"{where + 1}: expected numbers for the {axis} axis, got '{rows[line + 1].strip()}'",
                             key=key)
        if kind == ["2"]:
            if len(values) < 3 or values[2] != int(values[2]) or values[2] < 2:
                raise InputError(f"{where + 1}: expected first last count (count >= 2) for the {axis} axis", key=key)
            values = np.linspace(values[0], values[1], int(values[2]))
        values = np.asarray(values, dtype=float)
        if np.any(np.diff(values) <= 0.0):
            raise InputError(f"{where + 1}: the {axis} coordinates must increase (MoorDyn-C interpolates "
                             "assuming it)", key=key)
        axes.append(values)
    return tuple(axes)


def read_elevation_record(path, key):
    """wave_elevation.txt's times (k,) [s] and elevations (k,) [m] (the first two columns of every row)."""
    name = os.path.basename(path)
    times, eta = [], []
    for number, row in enumerate(v.read_rows(path, key), start=1):
        fields = row.split()
        values = [parse_number(f) for f in fields[:2]]
        if len(fields) < 2 or None in values or not all(math.isfinite(x) for x in values):
            raise InputError(f"{name} line {number}: expected t eta (numbers; MoorDyn-C reads every row), got "
                             f"'{row.strip()}'", key=key)
        if times and values[0] <= times[-1]:
            raise InputError(f"{name} line {number}: times must increase (t = {values[0]:g} after "
                             f"t = {times[-1]:g})", key=key)
        times.append(values[0])
        eta.append(values[1])
    if len(times) < 2 or times[-1] <= 0.0:
        raise InputError(f"{name}: needs rows from t = 0 on that reach past t = 0", key=key)
    return np.array(times), np.array(eta)


def read_wave_kin(mode, folder, depth, gravity, dt_wave, key):
    """The Sea of MoorDyn-C's ``WaveKin mode`` (2, 3 or 7) with its files in ``folder``; ``depth`` [m]
    the water depth its dispersion and stretching use, ``dt_wave`` [s] MoorDyn-C's dtWave (WaveKin 3)."""
    if mode not in FILES:
        refuse("WaveKin", key, f"WaveKin {mode:g}")
    paths = [data_file(name, folder, key) for name in FILES[mode]]
    options = {"depth": depth, "gravity": gravity, "stretching": "wheeler", "kind": f"MoorDyn WaveKin {mode:g}",
               "source": paths[0], "key": key}
    if mode == 7:
        omega, c, beta = read_spectrum(paths[0], key)
        return Sea.from_components(np.abs(c), omega, beta, 0.5 * np.pi - np.angle(c), **options)
    axes = read_grid(paths[1], key)
    grid = (("grid_points", [len(a) for a in axes]),)
    if mode == 2:
        omega, c, beta = evenly_spaced(*read_spectrum(paths[0], key), key)
        amplitude, phase = np.abs(c), -np.angle(c)
        amplitude[[0, -1]] *= 0.5  # the mean level and the last frequency count once in the inverse FFT
        return Sea.from_components(amplitude, omega, beta, phase, state=grid, **options)
    times, eta = read_elevation_record(paths[0], key)
    if dt_wave * 2 > times[-1]:
        raise InputError(f"dtWave = {dt_wave:g} s leaves fewer than 2 samples of {os.path.basename(paths[0])}",
                         key=key)
    samples, values = uniform(np.concatenate(([0.0], times)) if times[0] > 0.0 else times,
                              np.concatenate(([eta[0]], eta)) if times[0] > 0.0 else eta, dt_wave)
    amplitude, omega, phase, mean = components_of(samples, values)
    amplitude[omega > CUTOFF] = 0.0
    keep = amplitude > 0.0
    return Sea.from_components(np.append(abs(mean), amplitude[keep]), np.append(0.0, omega[keep]),
                               np.zeros(1 + keep.sum()), np.append(0.0 if mean >= 0 else np.pi, phase[keep]),
                               state=grid + (("dtWave", dt_wave), ("samples", len(values))), **options)
