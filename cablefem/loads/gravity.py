"""Weight and buoyancy per unit unstretched length (desire2023 Eq. 3, f_hg times (1 + e)).

Mass per unit unstretched length is conserved as the line stretches, and so
is the displaced volume in this model, so the submerged weight per unit
unstretched length is (m - rho A) g, a constant, below the water. A line that
reaches the still water surface z = 0 is buoyed by the part of its cross-section
below it: a circle of the volume-equivalent diameter d whose centre is at
height z has the submerged height h = clip(d/2 - z, 0, d) and the submerged
fraction

    phi(h) = (theta - sin theta) / (2 pi),   theta = 2 arccos(1 - 2 h / d),

with dphi/dh = 8 sqrt(h (d - h)) / (pi d^2) (the waterline's width over the
area). The buoyancy rho A g phi is then continuous and differentiable in z, so a
buoyant line floating at the surface (a lazy-wave buoyancy section, a rope
with floats, a line longer than its span) has an equilibrium Newton can reach:
it floats where phi = m / (rho A). Below z = -d/2 this is the full buoyancy,
above z = d/2 none, as before.
"""

import math

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms


def submerged_fraction(z, diameter):
    """Submerged fraction phi (...) of a circular cross-section of ``diameter`` [m] whose centre is
    at height z [m] (...) and its derivative dphi/dz [1/m] (...)."""
    h = np.clip(0.5 * diameter - z, 0.0, diameter)
    cosine = np.clip(1.0 - 2.0 * h / diameter, -1.0, 1.0)
    theta = 2.0 * np.arccos(cosine)
    fraction = (theta - np.sin(theta)) / (2.0 * np.pi)
    width = 8.0 * np.sqrt(np.maximum(h * (diameter - h), 0.0)) / (np.pi * diameter**2)
    return fraction, -width


def submerged_integral(z, diameter):
    """G(z) (...) [m] with dG/dz = phi(z): z below the band |z| < d/2, 0 above it; the buoyancy's
    potential energy density is -rho A g G(z)."""
    h = np.clip(0.5 * diameter - z, 0.0, diameter)
    half = 0.5 * 2.0 * np.arccos(np.clip(1.0 - 2.0 * h / diameter, -1.0, 1.0))  # theta / 2
    inside = diameter / (8.0 * math.pi) * (-4.0 * half * np.cos(half) + 4.0 * np.sin(half)
                                          - 4.0 / 3.0 * np.sin(half) ** 3)
    return np.where(z <= -0.5 * diameter, z, -inside)


class Weight:
    """Mass [kg/m] and volume-equivalent area [m^2] per element (nel,), water density, gravity."""

    name = "weight"

    def __init__(self, mass, area, water_density, gravity):
        self.dry = np.asarray(mass, dtype=float)[:, None] * gravity
        area = np.asarray(area, dtype=float)[:, None]
        self.buoyancy = water_density * area * gravity
        self.diameter = np.sqrt(4.0 * area / np.pi)

    def evaluate(self, state, jacobian=True):
        z = state.r[2]
        fraction, slope = submerged_fraction(z, self.diameter)
        force = np.zeros_like(state.r)
        force[2] = -(self.dry - self.buoyancy * fraction)
        terms = Terms(force=force)
        if jacobian and np.any(slope != 0.0):
            terms.force_r = np.zeros((3, 3) + z.shape)
            terms.force_r[2, 2] = self.buoyancy * slope
        return terms

    def energy(self, state):
        """Potential energy density [J/m] (nel, nq): dry weight x z minus buoyancy x G(z)."""
        z = state.r[2]
        return self.dry * z - self.buoyancy * submerged_integral(z, self.diameter)

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,)."""
        return {"dry": self.dry[:, 0], "buoyancy": self.buoyancy[:, 0], "diameter": self.diameter[:, 0]}


@njit(cache=True, _nrt=False)
def submerged_point(z, diameter):
    """Submerged fraction of the cross-section centred at height z and d/dz of it
    (``submerged_fraction`` at one point)."""
    if z <= -0.5 * diameter:
        return 1.0, 0.0
    if z >= 0.5 * diameter:
        return 0.0, 0.0
    h = 0.5 * diameter - z
    theta = 2.0 * np.arccos(min(max(1.0 - 2.0 * h / diameter, -1.0), 1.0))
    width = 8.0 * np.sqrt(max(h * (diameter - h), 0.0)) / (np.pi * diameter * diameter)
    return (theta - np.sin(theta)) / (2.0 * np.pi), -width


@njit(cache=True, _nrt=False)
def weight_point(ctx, p, old, new, state, hold, out):
    """The compiled face: weight and buoyancy at one point (see ``cablefem.compiled.kernels``)."""
    w = p.weight
    if not w.active:
        return
    submerged, slope = submerged_point(ctx.r[2], w.diameter)
    out.f[2] += -(w.dry - w.buoyancy * submerged)
    if ctx.jac:
        out.A[2, 2] += -w.buoyancy * slope


def build(setting):
    """Every line has weight and buoyancy."""
    env = setting.environment
    return Weight(setting.props["mass"], setting.props["area"], env.water_density, env.gravity)


SPEC = LoadSpec("weight", "full", (("dry", "f8"), ("buoyancy", "f8"), ("diameter", "f8")), weight_point, Weight,
                build=build)
