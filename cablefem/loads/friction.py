"""Seabed friction laws: saturated damping, isotropic (desire2023 Eq. 12) and
anisotropic (housner2022 Eq. 5-13), as pure functions with exact derivatives.

The friction force per unit unstretched length acts in the seabed's own
tangent plane, on the velocity v_pi = v - (v . d_P) d_P with d_P the
projection direction (desire2023 Eq. 12), and scales with the normal force
magnitude N = |f_n| of the contact (spring + damping, desire2023 Eq. 11):

    isotropic    F = -mu N phi(v_pi)
    anisotropic  F = -N (mu_A phi(v_A) + mu_T phi(v_T)),
                 v_A = (v_pi . q) q, v_T = v_pi - v_A          (housner2022 Eq. 5-6)

with q the line's axial direction in the seabed plane and the saturation

    phi(w) = static_scale w / v_c   for |w| < v_c,
    phi(w) = w / |w|                 for |w| >= v_c.

Below the threshold v_c the force is a damping with slope mu_s c_v, c_v =
N / v_c and mu_s = static_scale mu (housner2022 Eq. 11-12); beyond it is the
kinetic force mu N. With static_scale > 1 the force reaches mu_s N at v_c and
drops to mu N there, as MoorDyn's StatDynFricScale does; with static_scale =
1 it is desire2023 Eq. 12 exactly, continuous everywhere. phi is smooth
except on |w| = v_c (a kink, or a jump when static_scale != 1).

MoorDyn-C sets the ramp by a damping FricDamp = c_v [N s/m per node] instead
of v_c; the two agree for v_c = static_scale N / c_v, which depends on N, so
``friction_law`` uses ``v_threshold`` and not ``Friction.saturation_damping``.

The contact load (``cablefem.loads.contact``) supplies N, d_P, q and the
chain rule to positions; this module knows only the laws.
"""

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from cablefem.errors import InputError
from cablefem.loads import compose, identity_like, outer


def saturation(w, v_threshold, static_scale=1.0):
    """phi(w) (3, ...) [-] of velocities w (3, ...) [m/s] and its derivative dphi/dw (3, 3, ...) [s/m]."""
    speed = np.sqrt(np.einsum("c...,c...->...", w, w))
    ramp = speed < v_threshold
    safe = np.where(ramp, 1.0, speed)  # no division by |w| inside the ramp, where w may be 0
    gain = np.where(ramp, static_scale / v_threshold, 1.0 / safe)
    unit = w / safe
    eye = identity_like(w)
    dphi = gain * eye - np.where(ramp, 0.0, 1.0 / safe) * outer(unit, unit)
    return gain * w, dphi


def isotropic_friction(v_plane, normal_force, mu, v_threshold, static_scale=1.0):
    """Force F = -mu N phi(v_pi) [N/m] (3, ...) and dF/dv_pi [N s/m^2] (3, 3, ...), dF/dN [-] (3, ...)
    for in-plane velocities v_plane (3, ...) [m/s] and normal force magnitudes N (...) [N/m]."""
    phi, dphi = saturation(v_plane, v_threshold, static_scale)
    d_normal = -mu * phi
    return normal_force * d_normal, normal_force * -mu * dphi, d_normal


def anisotropic_friction(v_plane, axis, normal_force, mu_axial, mu_transverse, v_threshold,
                         static_scale=1.0):
    """Force F = -N (mu_A phi(v_A) + mu_T phi(v_T)) [N/m] (3, ...) for in-plane velocities
    v_plane (3, ...) [m/s], in-plane unit axial directions ``axis`` q (3, ...) and normal
    force magnitudes N (...) [N/m]; with dF/dv_pi (3, 3, ...), dF/dN (3, ...), dF/dq (3, 3, ...)."""
    along = np.einsum("c...,c...->...", v_plane, axis)
    v_axial = along * axis
    v_transverse = v_plane - v_axial
    phi_a, dphi_a = saturation(v_axial, v_threshold, static_scale)
    phi_t, dphi_t = saturation(v_transverse, v_threshold, static_scale)
    d_normal = -(mu_axial * phi_a + mu_transverse * phi_t)
    axial_projector = outer(axis, axis)
    # d v_A / d v_pi = q q^T; d v_A / d q = q v_pi^T + (v_pi . q) I = -d v_T / d q
    dva_dq = outer(axis, v_plane) + along * identity_like(axis)
    ga = mu_axial * dphi_a
    gt = mu_transverse * dphi_t
    d_velocity = -normal_force * (compose(ga, axial_projector)
                                  + compose(gt, identity_like(axis) - axial_projector))
    d_axis = -normal_force * compose(ga - gt, dva_dq)
    return normal_force * d_normal, d_velocity, d_normal, d_axis



def _check(value, key, positive):
    value = float(value)
    if not np.isfinite(value) or value < 0.0 or (positive and value == 0.0):
        raise InputError(f"must be a finite number {'> 0' if positive else '>= 0'}, got {value!r}",
                         key=f"friction.{key}")
    return value


@dataclass(frozen=True)
class IsotropicFriction:
    """desire2023 Eq. 12: kinetic coefficient mu [-], static/kinetic scale [-], threshold v_c [m/s]."""

    mu: float
    static_scale: float = 1.0
    v_threshold: float = 0.01
    uses_axis: ClassVar[bool] = False

    def __post_init__(self):
        for key, positive in (("mu", False), ("static_scale", True), ("v_threshold", True)):
            object.__setattr__(self, key, _check(getattr(self, key), key, positive))

    def evaluate(self, v_plane, normal_force, axis=None):
        """(F, dF/dv_pi, dF/dN, dF/dq = None) as ``isotropic_friction``; shapes (3, ...), (3, 3, ...)."""
        return (*isotropic_friction(v_plane, normal_force, self.mu, self.v_threshold,
                                    self.static_scale), None)


@dataclass(frozen=True)
class AnisotropicFriction:
    """housner2022 Eq. 5-13: kinetic coefficients along (mu_axial) and across (mu_transverse) the
    line [-], static/kinetic scale [-] (mu_s = static_scale mu_k in both directions), v_c [m/s]."""

    mu_axial: float
    mu_transverse: float
    static_scale: float = 1.0
    v_threshold: float = 0.01
    uses_axis: ClassVar[bool] = True

    def __post_init__(self):
        for key, positive in (("mu_axial", False), ("mu_transverse", False),
                              ("static_scale", True), ("v_threshold", True)):
            object.__setattr__(self, key, _check(getattr(self, key), key, positive))

    def evaluate(self, v_plane, normal_force, axis):
        """(F, dF/dv_pi, dF/dN, dF/dq) as ``anisotropic_friction``; shapes (3, ...), (3, 3, ...)."""
        return anisotropic_friction(v_plane, axis, normal_force, self.mu_axial, self.mu_transverse,
                                    self.v_threshold, self.static_scale)


def friction_law(friction):
    """The law of a ``cablefem.model.scene.Friction``: IsotropicFriction, AnisotropicFriction or None."""
    if friction.model == "none":
        return None
    if friction.model == "isotropic":
        return IsotropicFriction(friction.mu, friction.static_scale, friction.v_threshold)
    if friction.model == "anisotropic":
        return AnisotropicFriction(friction.mu_axial, friction.mu_transverse,
                                   friction.static_scale, friction.v_threshold)
    raise InputError(f"unknown friction model {friction.model!r} "
                     f"(expected none, isotropic or anisotropic)", key="friction.model")
