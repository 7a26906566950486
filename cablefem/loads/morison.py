"""Morison's equation on a line in waves, per unit unstretched length (desire2023 Eq. 3 with the
water moving: f_dn + f_dt + f_mn, times the stretch |r'| = 1 + e of Eq. 1).

With the water's velocity u_w and acceleration a_w at the point (``cablefem.waves``: linear waves,
plus the current U, uniform or a profile U(z)), the relative velocity w = U + u_w - v, the unit
tangent t, P = I - t t^T and T = t t^T:

    f = |r'| [ 1/2 rho d (Cd_n |w_n| w_n + Cd_t |w.t| (w.t) t)                    drag
             + rho A ((1 + Ca_n) P + (1 + Ca_t) T) a_w                              Froude-Krylov + added mass
             - rho A (Ca_n P + Ca_t T) a ],                                          added mass of the line

A = pi d^2 / 4, a the line's acceleration: MoorDyn-C's line (``Line.cpp``: Dp, Dq, Ap, Aq and the
added mass of its node mass matrix), Cd_t referred to d as in ``cablefem.loads.drag``. A point of the
line above the instantaneous surface (z > eta) feels none of it, as MoorDyn-C's submerged fraction
has it (its buoyancy stays the still-water one of ``cablefem.loads.gravity``).

In waves this load replaces ``drag`` and ``added_mass`` on every line (their builders step aside):
the drag is nonlinear in the relative velocity, so the current's and the waves' cannot be summed as
two loads. Its exact tangent adds what the drag and the added mass have to the position dependence
of the water's kinematics: df/dr = |r'| (dh/dw (dU/dr + du_w/dr) + rho A ((1 + Ca_n) P + (1 + Ca_t) T)
da_w/dr) (the kinematics' gradients, ``cablefem.waves.airy``); the surface's mask is a jump, which
the tangent does not see. The compiled face reads the kinematics from the point's context, which
``cablefem.compiled.kernels`` fills from the line's sea at the evaluation time.
"""

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms, compose, identity_like, outer, unit_tangent
from cablefem.loads._small import dot
from cablefem.loads.current import PROFILE_FIELDS, no_profile, relative_water
from cablefem.loads.drag import relative_drag


def to_points(values, shape):
    """(n, ...) values at the n points of ``shape`` (nel, nq) as (..., nel, nq)."""
    return np.moveaxis(values, 0, -1).reshape(values.shape[1:] + shape)


class Morison:
    """Morison's equation in waves: diameter d [m], Cd_normal, Cd_tangential, Ca_normal, Ca_tangential
    [-] per element (nel,), water density [kg/m^3], the ``sea`` (``cablefem.waves.Sea``), the current
    U [m/s] (3,) or a ``CurrentProfile`` (``profile``)."""

    name = "morison"

    def __init__(self, diameter, Cd_normal, Cd_tangential, Ca_normal, Ca_tangential, water_density, sea,
                 current=(0.0, 0.0, 0.0), profile=None):
        diameter = np.asarray(diameter, dtype=float)
        half_rho_d = 0.5 * water_density * diameter
        rho_area = water_density * np.pi * diameter ** 2 / 4.0
        column = lambda x: np.asarray(x, dtype=float)[:, None]  # noqa: E731
        self.drag_normal, self.drag_tangential = column(half_rho_d * Cd_normal), column(half_rho_d * Cd_tangential)
        self.added_normal, self.added_tangential = column(rho_area * Ca_normal), column(rho_area * Ca_tangential)
        self.fluid_normal = column(rho_area * (1.0 + np.asarray(Ca_normal, dtype=float)))
        self.fluid_tangential = column(rho_area * (1.0 + np.asarray(Ca_tangential, dtype=float)))
        self.sea = sea
        self.current = np.asarray(current, dtype=float).reshape(3, 1, 1)
        self.profile = profile

    def water(self, state, gradients):
        """The water at the points of ``state``: (wet (nel, nq), U + u_w, a_w (3, nel, nq), and with
        ``gradients`` d(U + u_w)/dr, d a_w/dr (3, 3, nel, nq))."""
        shape = state.r.shape[1:]
        kin = self.sea.kinematics(state.r.reshape(3, -1).T, state.t, gradients)
        velocity, acceleration = to_points(kin.velocity, shape), to_points(kin.acceleration, shape)
        if self.profile is None:
            velocity = velocity + self.current
        else:
            U, slope = self.profile.at(state.r[2])
            velocity = velocity + U
        if not gradients:
            return kin.wet.reshape(shape), velocity, acceleration, None, None
        dU = to_points(kin.velocity_gradient, shape)
        if self.profile is not None:
            dU[:, 2] += slope
        return kin.wet.reshape(shape), velocity, acceleration, dU, to_points(kin.acceleration_gradient, shape)

    def evaluate(self, state, jacobian=True):
        if state.v is None:
            return Terms()
        t, stretch, _ = unit_tangent(state.dr)
        wet, U, a_w, dU, da_w = self.water(state, jacobian)
        mask = np.where(wet, stretch, 0.0)  # |r'| below the surface, nothing above it
        per_drag, dh_dw, dh_dt = relative_drag(U - state.v, t, self.drag_normal, self.drag_tangential, jacobian)
        along_w = np.einsum("ceq,ceq->eq", a_w, t)
        fluid_difference = self.fluid_tangential - self.fluid_normal
        per = per_drag + self.fluid_normal * a_w + fluid_difference * along_w * t
        a = np.zeros_like(state.v) if state.a is None else state.a
        along_a = np.einsum("ceq,ceq->eq", a, t)
        added_difference = self.added_tangential - self.added_normal
        per = per - (self.added_normal * a + added_difference * along_a * t)
        terms = Terms(force=mask * per)
        if not jacobian:
            return terms
        eye, tangential_projector = identity_like(t), outer(t, t)
        terms.force_v = -mask * dh_dw
        terms.force_a = -mask * (self.added_normal * eye + added_difference * tangential_projector)
        fluid = self.fluid_normal * eye + fluid_difference * tangential_projector
        terms.force_r = mask * (compose(dh_dw, dU) + compose(fluid, da_w))
        dh_dt = dh_dt + fluid_difference * (along_w * eye + outer(t, a_w)) \
            - added_difference * (along_a * eye + outer(t, a))
        terms.force_dr = np.where(wet, 1.0, 0.0) * (outer(per, t) + compose(dh_dt, eye - tangential_projector))
        return terms

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,) or (nel, 3)."""
        nel = self.drag_normal.shape[0]
        profile = no_profile(nel) if self.profile is None else self.profile.params(nel)
        return {"drag_normal": self.drag_normal[:, 0], "drag_tangential": self.drag_tangential[:, 0],
                "fluid_normal": self.fluid_normal[:, 0], "fluid_tangential": self.fluid_tangential[:, 0],
                "added_normal": self.added_normal[:, 0], "added_tangential": self.added_tangential[:, 0],
                "current": np.tile(self.current.ravel(), (nel, 1)), **profile}


@njit(cache=True, _nrt=False)
def morison_point(ctx, p, old, new, state, hold, out):
    """The compiled face at one full point: the water's velocity and acceleration and their gradients
    are in the context (``water_u``, ``water_a``, ``water_du``, ``water_da``, ``wet``)."""
    q = p.morison
    if not q.active or not ctx.wet:
        return
    t, P, stretch, acc = ctx.t, ctx.P, ctx.stretch, ctx.a
    f, Ab, Bb, s = out.f, out.A, out.B, ctx.morison
    w, un, per, current, slope, D = s.w, s.un, s.per, s.current, s.slope, s.D
    Dn, Dt, Fn, Mn = q.drag_normal, q.drag_tangential, q.fluid_normal, q.added_normal
    dF, dM = q.fluid_tangential - Fn, q.added_tangential - Mn
    relative_water(ctx, q.profile_n, q.current, q.profile_z, q.profile_u, current, slope, w)
    aw = ctx.water_a
    along, along_w, along_a = dot(w, t), dot(aw, t), dot(acc, t)
    for i in range(3):
        un[i] = w[i] - along * t[i]
    speed = np.sqrt(dot(un, un))
    axial = Dt * abs(along)
    for i in range(3):
        per[i] = Dn * speed * un[i] + axial * along * t[i] + Fn * aw[i] + dF * along_w * t[i] \
            - (Mn * acc[i] + dM * along_a * t[i])
        f[i] += stretch * per[i]
    if not ctx.jac:
        return
    inverse = 1.0 / speed if speed > 0.0 else 0.0
    for i in range(3):  # D = dh/dw = Dn (|w_n| P + w_n w_n^T / |w_n|) + 2 Dt |w.t| t t^T (drag.py)
        for j in range(3):
            D[i, j] = Dn * (speed * P[i, j] + un[i] * un[j] * inverse) + 2.0 * axial * t[i] * t[j]
    # A -= f_r + v_x f_v + a_x f_a: f_v = -|r'| D, f_a = -|r'| (Mn I + dM t t^T),
    # f_r = |r'| (D (du_w/dr + dU/dz e_z^T) + (Fn I + dF t t^T) da_w/dr)
    # B -= f_dr = per t^T + (dh/dt) P, as drag.py's and added_mass.py's, with the fluid's dF term
    for i in range(3):
        for j in range(3):
            position = dF * t[i] * dot(t, ctx.water_da[:, j]) + Fn * ctx.water_da[i, j]
            for k in range(3):
                position += D[i, k] * (ctx.water_du[k, j] + (slope[k] if j == 2 else 0.0))
            Ab[i, j] += stretch * (ctx.v_x * D[i, j] + ctx.a_x * ((Mn if i == j else 0.0) + dM * t[i] * t[j])
                                   - position)
            dgP = Dn * (speed * P[i, j] + un[i] * un[j] * inverse)
            Bb[i, j] += Dn * speed * t[i] * un[j] + along * dgP - axial * (2.0 * t[i] * un[j] + along * P[i, j]) \
                - per[i] * t[j] - dF * (along_w * P[i, j] + t[i] * (aw[j] - along_w * t[j])) \
                + dM * (along_a * P[i, j] + t[i] * (acc[j] - along_a * t[j]))


def build(setting):
    """In waves, in dynamics, every line gets it (the Froude-Krylov force acts whatever its coefficients)."""
    env, props = setting.environment, setting.props
    if not setting.dynamic or env.waves is None:
        return None
    return Morison(props["diameter"], props["Cd_normal"], props["Cd_tangential"], props["Ca_normal"],
                   props["Ca_tangential"], env.water_density, env.waves, env.current, profile=env.current_profile)


SPEC = LoadSpec("morison", "full", (("drag_normal", "f8"), ("drag_tangential", "f8"), ("fluid_normal", "f8"),
                                    ("fluid_tangential", "f8"), ("added_normal", "f8"), ("added_tangential", "f8"),
                                    ("current", "f8", (3,))) + PROFILE_FIELDS,
                morison_point, Morison, build=build,
                # the water's velocity relative to the point, its part normal to the line, the force
                # per stretched length, the current and its slope dU/dz, the drag's derivative dh/dw
                scratch=(("w", "f8", (3,)), ("un", "f8", (3,)), ("per", "f8", (3,)), ("current", "f8", (3,)),
                         ("slope", "f8", (3,)), ("D", "f8", (3, 3))))
