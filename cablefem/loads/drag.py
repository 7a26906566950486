"""Morison drag per unit unstretched length, relative to the current
(desire2023 Eq. 3, f_dn + f_dt, times the stretch |r'| = 1 + e of Eq. 1).

The current U is uniform, or a depth profile U(z) evaluated at each quadrature point's height
(``cablefem.loads.current``, MoorDyn-C's ``Currents = 1``); then the force depends on the position
too, df/dr = |r'| dh/du dU/dz e_z^T. With the relative velocity u = U - v, its tangential part u_t = (u . t) t
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
from numba import njit

from cablefem.errors import InputError
from cablefem.loads import LoadSpec, Terms, compose, identity_like, outer, unit_tangent
from cablefem.loads._small import dot
from cablefem.loads.current import PROFILE_FIELDS, current_at, no_profile


def tangential_drag_from_moordyn(cd_axial):
    """cablefem's Cd_t [-] (reference area d) from MoorDyn's CdAx [-] (reference area pi d)."""
    return np.pi * np.asarray(cd_axial, dtype=float)


def quadratic(w):
    """|w| w (3, ...) of vectors w (3, ...) and its derivative |w| I + w w^T/|w| (3, 3, ...)."""
    speed = np.sqrt(np.einsum("c...,c...->...", w, w))
    safe = np.where(speed > 0.0, speed, 1.0)
    derivative = speed * identity_like(w) + outer(w, w) / safe  # w w^T/|w| -> 0 as w -> 0
    return speed * w, derivative


def relative_drag(u, t, normal, tangential, jacobian=True):
    """Morison drag per unit stretched length h = Dn |u_n| u_n + Dt |u.t| (u.t) t (3, nel, nq) of the
    relative velocity u (3, nel, nq) at unit tangents t, Dn, Dt = normal, tangential (nel, 1) [kg/m^2];
    with ``jacobian`` also dh/du and dh/dt (3, 3, nel, nq) (None otherwise)."""
    along = np.einsum("ceq,ceq->eq", u, t)
    u_normal = u - along * t
    g_normal, dg_normal = quadratic(u_normal)
    per_stretched = normal * g_normal + tangential * np.abs(along) * along * t
    if not jacobian:
        return per_stretched, None, None
    eye = identity_like(t)
    tangential_projector = outer(t, t)
    normal_projector = eye - tangential_projector
    dnormal = normal * dg_normal
    dh_du = compose(dnormal, normal_projector) + 2.0 * tangential * np.abs(along) * tangential_projector
    # d u_n/dt = -(t u^T + (u . t) I); d(|u.t| (u.t) t)/dt = |u.t| (2 t u^T + (u.t) I)
    t_u = outer(t, u)
    dh_dt = -compose(dnormal, t_u + along * eye) + tangential * np.abs(along) * (2.0 * t_u + along * eye)
    return per_stretched, dh_du, dh_dt


class Drag:
    """Morison drag: diameter d [m], Cd_normal, Cd_tangential [-] per element (nel,),
    water density rho [kg/m^3] and uniform current U [m/s] (3,), or a ``CurrentProfile``
    (``profile``, which then replaces ``current``)."""

    name = "drag"

    def __init__(self, diameter, Cd_normal, Cd_tangential, water_density, current=(0.0, 0.0, 0.0), profile=None):
        current = np.asarray(current, dtype=float)
        if current.shape != (3,) or not np.all(np.isfinite(current)):
            raise InputError(f"expected 3 finite numbers, got {current.tolist()}", key="current")
        half_rho_d = 0.5 * water_density * np.asarray(diameter, dtype=float)
        self.normal = (half_rho_d * np.asarray(Cd_normal, dtype=float))[:, None]  # [kg/m^2]
        self.tangential = (half_rho_d * np.asarray(Cd_tangential, dtype=float))[:, None]
        self.current = current.reshape(3, 1, 1)
        self.profile = profile

    def evaluate(self, state, jacobian=True):
        if state.v is None:
            return Terms()
        t, stretch, _ = unit_tangent(state.dr)
        if self.profile is None:
            u = self.current - state.v
        else:
            U, slope = self.profile.at(state.r[2])
            u = U - state.v
        per_stretched, dh_du, dh_dt = relative_drag(u, t, self.normal, self.tangential, jacobian)
        terms = Terms(force=stretch * per_stretched)
        if not jacobian:
            return terms
        terms.force_v = -stretch * dh_du
        # f = |r'| h(u, t(r')): d|r'|/dr' = t^T, dt/dr' = (I - t t^T)/|r'|
        terms.force_dr = outer(per_stretched, t) + compose(dh_dt, identity_like(t) - outer(t, t))
        if self.profile is not None:  # U(z): df/dr = |r'| dh/du dU/dz e_z^T
            terms.force_r = np.zeros_like(dh_du)
            terms.force_r[:, 2] = stretch * np.einsum("ab...,b...->a...", dh_du, slope)
        return terms

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,) or (nel, 3)."""
        nel = self.normal.shape[0]
        profile = no_profile(nel) if self.profile is None else self.profile.params(nel)
        return {"normal": self.normal[:, 0], "tangential": self.tangential[:, 0],
                "current": np.tile(self.current.ravel(), (nel, 1)), **profile}


@njit(cache=True, _nrt=False)
def drag_point(ctx, p, old, new, state, hold, out):
    """The compiled face: Morison drag on the velocity relative to the current at one full point
    (see ``cablefem.compiled.kernels``; ``ctx.P``, the normal projector, is set when a tangent is)."""
    d = p.drag
    normal, tangential = d.normal, d.tangential
    if not d.active or not (normal > 0.0 or tangential > 0.0):
        return
    v, t, P, stretch, v_x = ctx.v, ctx.t, ctx.P, ctx.stretch, ctx.v_x
    f, Ab, Bb = out.f, out.A, out.B
    s = ctx.drag
    w, un, per, current, slope = s.w, s.un, s.per, s.current, s.slope
    if d.profile_n == 0:
        for i in range(3):
            current[i] = d.current[i]
    else:
        current_at(ctx.r[2], d.profile_n, d.profile_z, d.profile_u, current, slope)
    w[0], w[1], w[2] = current[0] - v[0], current[1] - v[1], current[2] - v[2]  # u
    along = dot(w, t)
    for i in range(3):
        un[i] = w[i] - along * t[i]
    speed = np.sqrt(dot(un, un))
    for i in range(3):
        per[i] = normal * speed * un[i] + tangential * abs(along) * along * t[i]
        f[i] += stretch * per[i]
    if not ctx.jac:
        return
    # with dg = Dn (|un| I + un un^T / |un|), and P un = un, t^T un = 0:
    # A -= v_x f_v: Ab += v_x |r'| (dg P + 2 Dt |u.t| t t^T), dg P = Dn (|un| P + un un^T / |un|)
    # B -= f_dr: Bb -= per t^T + dF_dw P, dF_dw P = -Dn (|un| t un^T + (u.t)(|un| P + un un^T / |un|))
    #                                               + Dt |u.t| (2 t un^T + (u.t) P)
    inverse = 1.0 / speed if speed > 0.0 else 0.0
    axial = tangential * abs(along)
    for i in range(3):
        for j in range(3):
            dgP = normal * (speed * P[i, j] + un[i] * un[j] * inverse)
            Ab[i, j] += v_x * stretch * (dgP + 2.0 * axial * t[i] * t[j])
            Bb[i, j] += normal * speed * t[i] * un[j] + along * dgP \
                - axial * (2.0 * t[i] * un[j] + along * P[i, j]) - per[i] * t[j]
            if d.profile_n != 0:  # A -= f_r: f_r[:, 2] = |r'| dh/du dU/dz
                Ab[i, 2] -= stretch * (dgP + 2.0 * axial * t[i] * t[j]) * slope[j]


def build(setting):
    """Drag in dynamics, when a drag coefficient is not zero (in waves ``cablefem.loads.morison`` has it)."""
    props, env = setting.props, setting.environment
    if not setting.dynamic or not (np.any(props["Cd_normal"] > 0) or np.any(props["Cd_tangential"] > 0)):
        return None
    if env.waves is not None:
        return None
    return Drag(props["diameter"], props["Cd_normal"], props["Cd_tangential"], env.water_density, env.current,
                profile=env.current_profile)


SPEC = LoadSpec("drag", "full", (("normal", "f8"), ("tangential", "f8"), ("current", "f8", (3,))) + PROFILE_FIELDS,
                drag_point, Drag, build=build,
                # the relative velocity u - v, its part normal to the line, the force per stretched
                # length, the current at the point and its slope dU/dz
                scratch=(("w", "f8", (3,)), ("un", "f8", (3,)), ("per", "f8", (3,)), ("current", "f8", (3,)),
                         ("slope", "f8", (3,))))
