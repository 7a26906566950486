"""Finite-depth dispersion of linear (Airy) waves: omega^2 = g k tanh(k h).

``wave_number`` solves it for k by Newton's method from Eckart's explicit guess, to round-off
(the residual relative to omega^2 below 1e-14); ``omega = 0`` gives k = 0.
"""

import numpy as np


def wave_number(omega, depth, gravity):
    """Wave number k [1/m] (same shape as omega) of angular frequencies omega [rad/s] in water of
    ``depth`` [m] under ``gravity`` [m/s^2]: the root of omega^2 = g k tanh(k h)."""
    omega = np.abs(np.asarray(omega, dtype=float))
    deep = omega ** 2 / gravity
    # Eckart (1952): k0 = deep / sqrt(tanh(deep h)), within ~5 % everywhere; Newton from there
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where(omega > 0.0, deep / np.sqrt(np.tanh(np.maximum(deep * depth, 1e-300))), 0.0)
        for _ in range(50):
            tanh = np.tanh(k * depth)
            residual = gravity * k * tanh - omega ** 2
            slope = gravity * (tanh + k * depth * (1.0 - tanh ** 2))
            step = np.where(omega > 0.0, residual / np.where(slope > 0.0, slope, 1.0), 0.0)
            k = k - step
            if np.all(np.abs(step) <= 1e-15 * np.maximum(k, 1e-300)):
                break
    return k


def period_of(k, depth, gravity):
    """Period [s] of waves of wave number k [1/m] in water of ``depth`` [m] (the inverse)."""
    return 2.0 * np.pi / np.sqrt(gravity * k * np.tanh(k * depth))
