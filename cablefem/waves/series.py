"""A unidirectional sea from a record of the elevation at the origin: its discrete Fourier series.

A record eta_n at times t_0 + n dt (n = 0 .. N-1, N even) is the sum of N/2 cosines of the
frequencies omega_j = 2 pi j / (N dt): eta(0, 0, t) = sum_j A_j cos(omega_j (t - t_0) + arg X_j)
with A_j = 2 |X_j| / N (the Nyquist term j = N/2: |X_j| / N), X = the record's FFT; the sea
that has these as its components reproduces the record at its samples and repeats it with period
N dt. The record's mean (j = 0) is taken out: the still water level stays at z = 0.
"""

import numpy as np

from cablefem.errors import InputError
from cablefem.waves.sea import Sea


def uniform(times, eta, step):
    """The record (times, eta) (k,) resampled linearly at ``step`` [s] from its first time, its
    last sample dropped if that leaves an odd count: (times, values) of the even record."""
    count = int(np.floor((times[-1] - times[0]) / step + 1e-9)) + 1
    grid = times[0] + step * np.arange(count)
    values = np.interp(grid, times, eta)
    if count % 2:
        grid, values = grid[:-1], values[:-1]
    return grid, values


def components_of(times, eta):
    """Amplitudes [m], frequencies [rad/s] and phases [rad] (cablefem's convention, eta = A cos(-omega t
    + phi) at the origin) of the Fourier series of a uniform record of even length; and its mean."""
    n = len(eta)
    step = times[1] - times[0]
    X = np.fft.rfft(eta)
    j = np.arange(1, n // 2 + 1)
    amplitude = 2.0 * np.abs(X[j]) / n
    amplitude[-1] *= 0.5  # the Nyquist term counts once
    omega = 2.0 * np.pi * j / (n * step)
    # A cos(omega (t - t0) + arg X) = A cos(-omega t + (omega t0 - arg X))
    phase = omega * times[0] - np.angle(X[j])
    return amplitude, omega, phase, float(X[0].real / n)


def from_record(times, eta, depth, gravity=9.81, direction=0.0, step=None, key="waves", **options):
    """The Sea of an elevation record at the origin: times (k,) [s] strictly increasing, eta (k,) [m],
    resampled at ``step`` [s] (default: the record's smallest time step) when not uniform;
    ``direction`` [rad]; ``options`` go to ``Sea.from_components``."""
    times, eta = np.asarray(times, dtype=float), np.asarray(eta, dtype=float)
    if len(times) < 4:
        raise InputError(f"an elevation record needs at least 4 samples, got {len(times)}", key=key)
    spacing = np.diff(times)
    step = float(spacing.min()) if step is None else step
    if np.allclose(spacing, step, rtol=1e-9, atol=0.0) and len(times) % 2 == 0:
        grid, values = times, eta
    else:
        grid, values = uniform(times, eta, step)
    amplitude, omega, phase, mean = components_of(grid, values)
    state = (("samples", len(values)), ("time_step", float(grid[1] - grid[0])),
             ("record_period", float(len(values) * (grid[1] - grid[0]))), ("mean_removed", mean))
    return Sea.from_components(amplitude, omega, np.full(len(omega), direction), phase, depth, gravity,
                               kind=options.pop("kind", "elevation"), state=state, key=key, **options)
