"""Morison drag per unit unstretched length, relative to a uniform current
(desire2023 Eq. 3, f_dn + f_dt, times the stretch |r'| = 1 + e of Eq. 1).

With the relative velocity u = U - v, its tangential part u_t = (u . t) t
and normal part u_n = u - u_t, t = r'/|r'|:

    f = |r'| 1/2 rho d (Cd_n |u_n| u_n + Cd_t |u_t| u_t).

Drag per unit stretched length is multiplied by the stretch because the
weak form integrates over unstretched arc length (desire2023 Eq. 1).

Tangential reference area. Cd_t here is referred to the projected area d
per unit length, as in desire2023 Eq. 3 (Palm et al. 2013). MoorDyn v2
refers its axial drag coefficient (CdAx, "Cdt") to the surface area pi d per
unit length (moordyn 2.7.2, ``moordyn.Generator.Line``: "tangential drag
coefficient (with respect to surface area, pi*d*l)"; MoorDyn-C ``Line.cpp``
uses 1/2 rho Cdt pi d). The same force therefore needs

    Cd_t (cablefem) = pi Cd_t (MoorDyn),

which ``tangential_drag_from_moordyn`` applies; a MoorDyn input's CdAx
must be converted, not copied. (The normal coefficient has the same
reference area d in both.) A second, smaller difference: the MoorDyn-C
source we read weights drag by the unstretched segment length, where Eq. 1
uses the stretched one; the two differ by the strain e.

The derivative of |w| w is |w| I + w w^T / |w|, which is continuous and
zero at w = 0, so the load is C1 in v and r' everywhere, also at zero
relative velocity. Drag is applied over the whole line, also above the
still water surface (a fairlead at z = 0 has a vanishing length in air).
"""

import numpy as np

from ..errors import InputError
from . import Terms, compose, identity_like, outer, unit_tangent


def tangential_drag_from_moordyn(cd_axial):
    """cablefem's Cd_t [-] (reference area d) from MoorDyn's CdAx [-] (reference area pi d)."""
    return np.pi * np.asarray(cd_axial, dtype=float)


def quadratic(w):
    """|w| w (3, ...) of vectors w (3, ...) and its derivative |w| I + w w^T/|w| (3, 3, ...)."""
    speed = np.sqrt(np.einsum("c...,c...->...", w, w))
    safe = np.where(speed > 0.0, speed, 1.0)
    derivative = speed * identity_like(w) + outer(w, w) / safe  # w w^T/|w| -> 0 as w -> 0
    return speed * w, derivative


class Drag:
    """Morison drag: diameter d [m], Cd_normal, Cd_tangential [-] per element (nel,),
    water density rho [kg/m^3] and uniform current U [m/s] (3,)."""

    def __init__(self, diameter, Cd_normal, Cd_tangential, water_density, current=(0.0, 0.0, 0.0)):
        current = np.asarray(current, dtype=float)
        if current.shape != (3,) or not np.all(np.isfinite(current)):
            raise InputError(f"expected 3 finite numbers, got {current.tolist()}", key="current")
        half_rho_d = 0.5 * water_density * np.asarray(diameter, dtype=float)
        self.normal = (half_rho_d * np.asarray(Cd_normal, dtype=float))[:, None]  # [kg/m^2]
        self.tangential = (half_rho_d * np.asarray(Cd_tangential, dtype=float))[:, None]
        self.current = current.reshape(3, 1, 1)

    def evaluate(self, state, jacobian=True):
        if state.v is None:
            return Terms()
        dr = state.dr
        t, stretch, _ = unit_tangent(dr)
        u = self.current - state.v
        along = np.einsum("ceq,ceq->eq", u, t)
        u_normal = u - along * t
        g_normal, dg_normal = quadratic(u_normal)
        per_stretched = self.normal * g_normal + self.tangential * np.abs(along) * along * t
        terms = Terms(force=stretch * per_stretched)
        if not jacobian:
            return terms
        eye = identity_like(t)
        tangential_projector = outer(t, t)
        normal_projector = eye - tangential_projector
        dnormal = self.normal * dg_normal
        # h(u, t) = per_stretched; dh/du with du/dv = -I
        dh_du = compose(dnormal, normal_projector) \
            + 2.0 * self.tangential * np.abs(along) * tangential_projector
        terms.force_v = -stretch * dh_du
        # d u_n/dt = -(t u^T + (u . t) I); d(|u.t| (u.t) t)/dt = |u.t| (2 t u^T + (u.t) I)
        t_u = outer(t, u)
        dh_dt = -compose(dnormal, t_u + along * eye) \
            + self.tangential * np.abs(along) * (2.0 * t_u + along * eye)
        # f = |r'| h(u, t(r')): d|r'|/dr' = t^T, dt/dr' = (I - t t^T)/|r'|
        terms.force_dr = outer(per_stretched, t) + compose(dh_dt, normal_projector)
        return terms

