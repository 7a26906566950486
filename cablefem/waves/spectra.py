"""Irregular seas from a wave spectrum: JONSWAP and Pierson-Moskowitz (DNV-RP-C205, 2019, Sec.
3.5.5), realised as components with random phases, optionally spread in direction.

    S_PM(omega) = 5/16 Hs^2 omega_p^4 omega^-5 exp(-5/4 (omega / omega_p)^-4),
    S_J(omega)  = S_PM(omega) gamma^exp(-(omega - omega_p)^2 / (2 sigma^2 omega_p^2)),

sigma = 0.07 below omega_p and 0.09 above, omega_p = 2 pi / Tp; Pierson-Moskowitz is JONSWAP with
gamma = 1. The components' frequencies split the band [omega_lo, omega_hi] (by default 0.5 to 4
omega_p, which holds all but ~0.1 % of the energy) into equal bins, one frequency drawn uniformly in
each bin (so that a record does not repeat itself after 2 pi / d omega); their amplitudes are
A = sqrt(2 S(omega) d omega), scaled so that the components' m0 = sum A^2 / 2 is Hs^2 / 16 exactly
(the DNV formula's own normalisation, A_gamma = 1 - 0.287 ln gamma, is within ~1 % of it); their
phases are uniform in [0, 2 pi). With ``spreading`` s each component travels at its own heading
drawn from D(beta) ~ cos^2s((beta - beta_0) / 2) (Longuet-Higgins' cos-2s spreading; one heading
per frequency, so that components do not lock in phase). ``seed`` makes the draw repeatable
(numpy's default generator, PCG64).
"""

import numpy as np

from cablefem.errors import InputError
from cablefem.waves.sea import Sea

SPECTRA = ("jonswap", "pierson-moskowitz")
#: the band of the components, as multiples of the peak frequency
BAND = (0.5, 4.0)


def jonswap(omega, Hs, Tp, gamma=3.3):
    """JONSWAP spectral density S(omega) [m^2 s/rad] at omega [rad/s] (DNV-RP-C205 Eq. 3.5.7 without
    its normalising factor; gamma = 1 is Pierson-Moskowitz)."""
    omega = np.asarray(omega, dtype=float)
    wp = 2.0 * np.pi / Tp
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        pm = np.where(omega > 0.0, 5.0 / 16.0 * Hs ** 2 * wp ** 4 * omega ** -5.0
                      * np.exp(-1.25 * (omega / wp) ** -4.0), 0.0)
    sigma = np.where(omega <= wp, 0.07, 0.09)
    return pm * gamma ** np.exp(-0.5 * ((omega - wp) / (sigma * wp)) ** 2)


def spreading_headings(rng, count, heading, s):
    """``count`` headings [rad] drawn from D(beta) ~ cos^2s((beta - heading) / 2) on heading +- pi."""
    grid = np.linspace(-np.pi, np.pi, 4001)
    density = np.cos(0.5 * grid) ** (2.0 * s)
    cumulative = np.concatenate(([0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(grid))))
    return heading + np.interp(rng.uniform(0.0, cumulative[-1], count), cumulative, grid)


def irregular(Hs, Tp, depth, gravity=9.81, spectrum="jonswap", gamma=3.3, direction=0.0, components=200,
              seed=0, spreading=None, band=None, key="waves", **options):
    """A Sea realising ``spectrum`` of significant height Hs [m] and peak period Tp [s] with
    ``components`` components, heading ``direction`` [rad], optional cos-2s ``spreading`` exponent,
    frequency ``band`` (omega_lo, omega_hi) [rad/s] (default ``BAND`` times omega_p); ``options``
    go to ``Sea.from_components`` (stretching, ramp)."""
    if spectrum not in SPECTRA:
        raise InputError(f"unknown spectrum '{spectrum}'; valid: {' | '.join(SPECTRA)}", key=f"{key}.spectrum")
    if spectrum == "pierson-moskowitz":
        gamma = 1.0
    wp = 2.0 * np.pi / Tp
    lo, hi = (BAND[0] * wp, BAND[1] * wp) if band is None else band
    if not 0.0 < lo < hi:
        raise InputError(f"the frequency band must satisfy 0 < low < high, got [{lo:g}, {hi:g}] rad/s",
                         key=f"{key}.frequency_band")
    rng = np.random.default_rng(seed)
    edges = np.linspace(lo, hi, components + 1)
    width = np.diff(edges)
    omega = edges[:-1] + width * rng.uniform(0.0, 1.0, components)
    phase = rng.uniform(0.0, 2.0 * np.pi, components)
    headings = (np.full(components, direction) if spreading is None
                else spreading_headings(rng, components, direction, spreading))
    energy = jonswap(omega, Hs, Tp, gamma) * width
    if not np.sum(energy) > 0.0:
        raise InputError(f"the spectrum holds no energy in [{lo:g}, {hi:g}] rad/s", key=f"{key}.frequency_band")
    amplitude = np.sqrt(2.0 * energy * (Hs ** 2 / 16.0) / np.sum(energy))
    state = (("spectrum", spectrum), ("Hs", Hs), ("Tp", Tp), ("gamma", gamma), ("direction_deg",
             float(np.degrees(direction))), ("seed", seed)) + ((("spreading", spreading),) if spreading else ())
    return Sea.from_components(amplitude, omega, headings, phase, depth, gravity, kind="irregular",
                               state=state, key=key, **options)
