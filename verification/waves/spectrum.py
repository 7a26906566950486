"""(c) Irregular seas: the elevation records of many seeds hold the spectrum asked for. For each seed
a JONSWAP sea (Hs, Tp, gamma) is realised (``cablefem.waves.spectra.irregular``) and its elevation at
the origin sampled for ``duration``; m0 is the record's variance, the spectrum its periodogram
(averaged over the seeds, smoothed over ``smoothing`` frequency bins); (d) spread seas: the mean of
cos(beta - beta_0) over the components against the cos-2s law's s / (s + 1)."""

import numpy as np

from cablefem.waves.spectra import irregular, jonswap

HS, TP, GAMMA, DEPTH = 6.0, 11.0, 3.3, 150.0


def realisations(seeds, duration, step=0.5, components=200):
    """m0 per seed [m^2], the seeds' mean periodogram and its frequencies [rad/s]."""
    t = np.arange(0.0, duration, step)
    m0, spectra = [], []
    for seed in seeds:
        sea = irregular(HS, TP, DEPTH, gamma=GAMMA, components=components, seed=seed)
        eta = sea.elevation(0.0, 0.0, t)
        m0.append(float(np.var(eta)))
        X = np.fft.rfft(eta - eta.mean())
        spectra.append(2.0 * np.abs(X) ** 2 * step / (len(t) * 2.0 * np.pi))  # one-sided [m^2 s/rad]
    omega = 2.0 * np.pi * np.fft.rfftfreq(len(t), step)
    return np.array(m0), np.mean(spectra, axis=0), omega


def spectrum_check(seeds, duration, smoothing=15):
    """The table's numbers: mean m0 against Hs^2/16, the spread of m0 over seeds, the peak of the smoothed
    mean periodogram against omega_p, and the periodogram against S(omega) near the peak."""
    m0, S, omega = realisations(seeds, duration)
    kernel = np.ones(smoothing) / smoothing
    smooth = np.convolve(S, kernel, mode="same")
    peak = omega[np.argmax(smooth)]
    wp = 2.0 * np.pi / TP
    target = jonswap(omega, HS, TP, GAMMA) * (HS ** 2 / 16.0) / np.trapezoid(jonswap(omega, HS, TP, GAMMA), omega)
    near = np.abs(omega - wp) < 0.3 * wp
    return {"seeds": len(seeds), "duration_s": duration, "m0_mean": float(m0.mean()), "m0_target": HS ** 2 / 16.0,
            "m0_error": float(m0.mean() / (HS ** 2 / 16.0) - 1.0), "m0_seed_spread": float(m0.std() / m0.mean()),
            "peak_omega": float(peak), "omega_p": wp, "peak_error": float(peak / wp - 1.0),
            "resolution": float(smoothing * (omega[1] - omega[0]) / wp),
            "spectrum_error_near_peak": float(np.abs(smooth[near] - target[near]).max() / target.max())}


def spreading_check(s_values=(1.0, 4.0, 10.0), components=2000):
    """Mean cos(beta - beta_0) of the components' headings against s / (s + 1)."""
    rows = []
    for s in s_values:
        sea = irregular(HS, TP, DEPTH, components=components, seed=1, spreading=s, direction=0.3)
        mean = float(np.mean(np.cos(np.array(sea.direction) - 0.3)))
        rows.append({"s": s, "mean_cos": mean, "expected": s / (s + 1.0), "error": mean - s / (s + 1.0)})
    return rows
