"""The closed forms the bending study checks cablefem against.

- the cantilever under a uniform load w, small deflection (Euler-Bernoulli): w(x) = w x^2 (6 L^2 -
  4 L x + x^2) / (24 EI), tip w L^4 / (8 EI) (Timoshenko & Gere 1961, Sec. 5.5, case 1);
- the elastica of a cantilever under a dead vertical tip load P (Bisshopp & Drucker 1945, Eqs.
  6-9, with alpha = P L^2 / EI): the tip angle theta_0 from sqrt(alpha) = K(k) - F(phi_1, k),
  k^2 = (1 + sin theta_0) / 2, sin phi_1 = 1 / (k sqrt 2); the tip's horizontal position
  x / L = sqrt(2 sin theta_0 / alpha) and its drop y / L = 1 - 2 (E(k) - E(phi_1, k)) / sqrt(alpha);
  the clamp's moment P x (K, E, F, E(phi, k): the complete and incomplete elliptic integrals,
  scipy.special's parameter m = k^2);
- the cantilever under a pure end moment: the circular arc that a free end whose tangent is clamped
  at the angle theta reaches (the clamp's reaction is the moment). The curvature is the line's as
  it is, per stretched length (``cablefem.loads.bending``): kappa = theta / (L (1 + e)), so that the
  bending energy EI kappa^2 L / 2 pulls the line longer, and the strain e solves
  EA e (1 + e)^3 = EI theta^2 / L^2 (the energy's stationary point in e; e ~ EI kappa^2 / EA,
  2.5e-6 at EA = 1e6 N, theta = pi / 2, L = 1 m, EI = 1 N m^2);
- the pinned beam's natural frequencies omega_n = (n pi / L)^2 sqrt(EI / m), and a taut one's
  with tension T, omega_n = (n pi / l) sqrt(T / mu) sqrt(1 + (n pi / l)^2 EI' / T) (the beam-string,
  Blevins 1979, Table 8-1), on the stretched length l = L (1 + e), mass mu = m / (1 + e) and EI' =
  EI / (1 + e) per stretched length (the energy 1/2 EI kappa^2 per unstretched length of
  ``cablefem.loads.bending``); the cantilever's first, (1.8751 / L)^2 sqrt(EI / m).
"""

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

#: beta_1 L of a cantilever's first mode: the first root of cos(b) cosh(b) = -1
CANTILEVER_ROOT = 1.8751040687119611


def cantilever_deflection(x, w, L, EI):
    """Deflection [m] of a cantilever under a uniform load w [N/m] at x (n,) [m] from the clamp."""
    return w * x**2 * (6 * L**2 - 4 * L * x + x**2) / (24.0 * EI)


def _elastica_angle(alpha):
    """The tip angle theta_0 [rad] of the elastica at alpha = P L^2 / EI."""

    def mismatch(theta):
        m = 0.5 * (1.0 + math.sin(theta))
        return ellipk(m) - ellipkinc(math.asin(1.0 / math.sqrt(2.0 * m)), m) - math.sqrt(alpha)

    return brentq(mismatch, 1e-12, 0.5 * math.pi - 1e-14, xtol=1e-16, rtol=4 * np.finfo(float).eps)


def elastica_tip(alpha):
    """The elastica's tip (x / L, drop / L) and its angle theta_0 [rad] at alpha = P L^2 / EI."""
    theta = _elastica_angle(alpha)
    m = 0.5 * (1.0 + math.sin(theta))
    phi = math.asin(1.0 / math.sqrt(2.0 * m))
    drop = 1.0 - 2.0 * (ellipe(m) - ellipeinc(phi, m)) / math.sqrt(alpha)
    return math.sqrt(2.0 * math.sin(theta) / alpha), drop, theta


def arc_strain(theta, L, EI, EA):
    """The strain of the arc whose free end is turned by theta [rad] (module docstring)."""
    load = EI * theta**2 / (EA * L**2)
    return brentq(lambda e: e * (1.0 + e) ** 3 - load, 0.0, load, xtol=1e-18, rtol=4 * np.finfo(float).eps)


def arc(s, theta, L, strain=0.0):
    """Positions (n, 2) (along the clamp, across it) at unstretched arc lengths s (n,) of the arc of a
    cantilever of length L whose free end is turned by theta [rad], stretched by ``strain``
    (curvature theta / (L (1 + strain)))."""
    radius = L * (1.0 + strain) / theta
    return np.column_stack([radius * np.sin(s * (1.0 + strain) / radius),
                            radius * (1.0 - np.cos(s * (1.0 + strain) / radius))])


def pinned_beam(n, EI, m, L):
    """The pinned beam's n-th natural frequency [rad/s]."""
    return (n * math.pi / L) ** 2 * math.sqrt(EI / m)


def taut_beam(n, EI, m, L, T, strain):
    """The n-th natural frequency [rad/s] of a pinned beam of unstretched length L under tension T
    [N] at that strain (its stretched length, mass and bending stiffness per stretched length)."""
    length, mu, bending = L * (1 + strain), m / (1 + strain), EI / (1 + strain)
    k = n * math.pi / length
    return k * math.sqrt(T / mu) * math.sqrt(1.0 + k * k * bending / T)


def cantilever_frequency(EI, m, L):
    """The cantilever's first natural frequency [rad/s]."""
    return (CANTILEVER_ROOT / L) ** 2 * math.sqrt(EI / m)
