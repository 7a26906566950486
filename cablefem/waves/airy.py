"""Linear (Airy) wave kinematics of a ``Sea`` at points and times: the numpy face.

For a component of amplitude A, frequency omega, wave number k and heading beta in water of depth
h, with theta = k (x cos beta + y sin beta) - omega t + phi (Dean & Dalrymple 1991, Sec. 3-4):

    eta = A cos theta,
    u_h = A omega C(z') cos theta (cos beta, sin beta),   u_z = A omega S(z') sin theta,
    a_h = A omega^2 C(z') sin theta (cos beta, sin beta), a_z = -A omega^2 S(z') cos theta,

C = cosh k(z' + h) / sinh kh, S = sinh k(z' + h) / sinh kh, evaluated as
(e^{kz'} +- e^{-k(z' + 2h)}) / (1 - e^{-2kh}), which stays finite in deep water. The components
add; the ramp R(t) scales them (a = R a + dR/dt u, the time derivative of the ramped velocity).

z' is the height the profile is evaluated at (``Sea.stretching``):
- "wheeler": z' = h (z - eta) / (h + eta), the water column between the seabed and the
  instantaneous surface mapped onto [-h, 0] (Wheeler 1970; MoorDyn-C's stretching);
- "vertical": z' = min(z, 0), the kinematics of the mean level held up to the crest;
- "none": z' = z, linear theory extrapolated above the mean level.
Below the seabed depth z' is held at -h, and with "wheeler" above the surface at 0 (where the
kinematics are not used: a point above the surface is dry, ``Kinematics.wet``). The acceleration
is linear theory's at z' (the local derivative d/dt at fixed z', as MoorDyn-C and common practice
have it with Wheeler stretching), not the total derivative through the moving surface.

``gradients``: d u_i / d x_j and d a_i / d x_j (n, 3, 3), exact for the formulas above, z' and its
dependence on eta included (the Morison load's tangent: ``cablefem.loads.morison``).
"""

from dataclasses import dataclass

import numpy as np


@dataclass
class Kinematics:
    """At n points: elevation eta (n,) [m] above each, velocity and acceleration (n, 3) [m/s, m/s^2],
    wet (n,) (the point at or below the surface), the stretched heights (n,) [m]; with gradients,
    velocity_gradient and acceleration_gradient (n, 3, 3), [i, j] = d(component i)/d x_j."""

    eta: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    wet: np.ndarray
    stretched: np.ndarray
    velocity_gradient: np.ndarray | None = None
    acceleration_gradient: np.ndarray | None = None


def profiles(k, z, depth):
    """C(z) and S(z) (n, m) of wave numbers k (m,) at heights z (n,) [m] (see the module docstring);
    a zero k gives zeros (its component has no motion)."""
    kz = k * z[:, None]
    first = np.exp(kz)
    second = np.exp(-kz - 2.0 * k * depth)
    with np.errstate(divide="ignore"):
        scale = np.where(k > 0.0, 1.0 / (1.0 - np.exp(-2.0 * k * depth)), 0.0)
    return (first + second) * scale, (first - second) * scale


def stretched_height(sea, z, eta, eta_gradient):
    """z' (n,) and dz'/dx (n, 3) at heights z (n,) under a surface eta (n,) of horizontal
    gradient (n, 2)."""
    h = sea.depth
    dz = np.zeros(z.shape + (3,))
    if sea.stretching == "wheeler":
        column = np.maximum(h + eta, 1e-3 * h)
        zs = h * (z - eta) / column
        dz[:, 2] = h / column
        dz[:, :2] = (-h * (h + z) / column ** 2)[:, None] * eta_gradient
        upper = 0.0
    elif sea.stretching == "vertical":
        zs = z.copy()
        dz[:, 2] = 1.0
        upper = 0.0
    else:
        zs = z.copy()
        dz[:, 2] = 1.0
        upper = np.inf
    held = (zs < -h) | (zs > upper)
    dz[held] = 0.0
    return np.clip(zs, -h, upper), dz


def kinematics(sea, points, t, gradients=False):
    """The ``Kinematics`` of ``sea`` at points (n, 3) [m] at time t [s] (a number or (n,))."""
    points = np.atleast_2d(np.asarray(points, dtype=float))
    n = len(points)
    t = np.broadcast_to(np.asarray(t, dtype=float), (n,))
    amplitude, omega, k, cos_b, sin_b, phase = sea.arrays
    ramp, ramp_rate = sea.ramp_factor(t)
    x, y, z = points.T
    theta = k * (x[:, None] * cos_b + y[:, None] * sin_b) - omega * t[:, None] + phase
    cos, sin = np.cos(theta), np.sin(theta)
    eta = ramp * (cos @ amplitude)
    # d eta / d(x, y): -R sum A k sin theta (cos b, sin b)
    slope = -(ramp[:, None] * np.stack((sin @ (amplitude * k * cos_b), sin @ (amplitude * k * sin_b)), axis=1))
    zs, dz = stretched_height(sea, z, eta, slope)
    C, S = profiles(k, zs, sea.depth)
    speed = amplitude * omega  # A omega per component
    P, Q = speed * C, speed * S  # horizontal and vertical velocity amplitudes (n, m)
    # unramped velocity and acceleration, per component family
    Pc, Qs = P * cos, Q * sin
    u = np.stack((Pc @ cos_b, Pc @ sin_b, Qs.sum(axis=1)), axis=1)
    Ps, Qc = P * sin * omega, Q * cos * omega
    a = np.stack((Ps @ cos_b, Ps @ sin_b, -Qc.sum(axis=1)), axis=1)
    velocity = ramp[:, None] * u
    acceleration = ramp[:, None] * a + ramp_rate[:, None] * u
    result = Kinematics(eta, velocity, acceleration, z <= eta, zs)
    if not gradients:
        return result
    e = np.stack((cos_b, sin_b, np.zeros_like(cos_b)), axis=1)  # horizontal heading (m, 3)
    h_dir = np.stack((cos_b, sin_b), axis=0)  # (2, m)

    def gradient(horizontal, vertical, horizontal_z, vertical_z):
        """d/dx_j of (sum horizontal (cos b, sin b), sum vertical) whose theta-derivatives are
        ``horizontal``, ``vertical`` (n, m) (times k e_j) and z'-derivatives ``*_z`` (n, m)."""
        G = np.zeros((n, 3, 3))
        G[:, :2, :] = np.einsum("nm,im,mj->nij", horizontal * k, h_dir, e) \
            + np.einsum("nm,im->ni", horizontal_z * k, h_dir)[:, :, None] * dz[:, None, :]
        G[:, 2, :] = (vertical * k) @ e + (vertical_z * k).sum(axis=1)[:, None] * dz
        return G

    # u: theta-derivatives -P sin, Q cos; z'-derivatives (dC = k S, dS = k C) Q cos, P sin
    du = gradient(-P * sin, Q * cos, Q * cos, P * sin)
    # a: theta-derivatives omega P cos, omega Q sin; z'-derivatives omega Q sin, -omega P cos
    da = gradient(omega * P * cos, omega * Q * sin, omega * Q * sin, -omega * P * cos)
    result.velocity_gradient = ramp[:, None, None] * du
    result.acceleration_gradient = ramp[:, None, None] * da + ramp_rate[:, None, None] * du
    return result
