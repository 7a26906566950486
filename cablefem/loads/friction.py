"""Seabed friction, both faces: the laws (saturated damping, isotropic desire2023 Eq. 12,
anisotropic housner2022 Eq. 5-13) as pure functions with exact derivatives, and the load.

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

The load (``SeabedFriction``) acts in dynamics where the line rubs on the seabed, on what the
contact (``cablefem.loads.contact``, before it in the catalog) hands it at each point: N = |f_n|
with its derivatives, v_n and d_P (numpy: the contact's ``NormalForce`` in ``State.handed``;
compiled: its scratch ``ctx.contact``). The in-plane axial direction is q = normalise((I - d_P d_P) t),
t = r'/|r'| (housner2022 Eq. 5); where the line is normal to the seabed q is taken as 0 (all
sliding transverse).
"""

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numba import njit

from cablefem.errors import InputError
from cablefem.loads import LoadSpec, Terms, compose, identity_like, outer, unit_tangent
from cablefem.loads._small import add_matmul, add_outer, dot, unit_divisor

#: |(I - d_P d_P) t| below which the in-plane axial direction q is taken as 0
DEGENERATE_AXIS = 1e-12


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


class SeabedFriction:
    """Friction of a line on the seabed by ``law`` (``IsotropicFriction`` / ``AnisotropicFriction``,
    ``friction_law``), on the normal force the contact hands it (``State.handed["contact"]``)."""

    name = "friction"

    def __init__(self, law):
        self.law = law

    def evaluate(self, state, jacobian=True):
        if state.v is None:  # statics: no friction
            return Terms()
        normal = state.handed.get("contact")
        if normal is None:
            raise ValueError("friction reads the seabed contact's normal force: evaluate the contact first, "
                             "at the same points (LoadSpec.reads)")
        n, vn, pressure = normal.direction, normal.normal_velocity, normal.pressure
        v_plane = state.v - vn * n
        axis, axis_norm, t, divisor = _axis(state.dr, n) if self.law.uses_axis else (None,) * 4
        # N = |f_n|: the pressure is negative only where an opening damper pulls a point down
        sign = np.where(pressure < 0.0, -1.0, 1.0)
        force, df_dw, df_dN, df_dq = self.law.evaluate(v_plane, sign * pressure, axis)
        df_dN = sign * df_dN  # dF/dp
        terms = Terms(force=force)
        if not jacobian:
            return terms
        dn = normal.direction_r
        eye = identity_like(n)
        in_plane = eye - outer(n, n)
        # v_pi = v - (v . n) n: d v_pi/dn = -(n v^T + (v . n) I)
        dw_dr = compose(-(outer(n, state.v) + vn * eye), dn)
        force_r = compose(df_dw, dw_dr) + outer(df_dN, normal.pressure_r)
        force_v = compose(df_dw, in_plane)
        if normal.pressure_v is not None:
            force_v = force_v + outer(df_dN, normal.pressure_v)
        if axis is not None:
            # q = p / |p|, p = (I - n n^T) t, t = r'/|r'|; the t t^T part of dt/dr' drops
            # out, since (I - q q^T)(I - n n^T) t = (I - q q^T) |p| q = 0
            dq_dp = (eye - outer(axis, axis)) / axis_norm
            dq_ddr = compose(dq_dp, in_plane) / divisor
            terms.force_dr = compose(df_dq, dq_ddr)
            dp_dn = -(outer(n, t) + np.einsum("ceq,ceq->eq", n, t) * eye)
            force_r = force_r + compose(df_dq, compose(dq_dp, compose(dp_dn, dn)))
        terms.force_r, terms.force_v = force_r, force_v
        return terms

    def params(self):
        """The compiled face's parameters (``SPEC.params``), the same on every element."""
        law = self.law
        return {"anisotropic": law.uses_axis, "mu": getattr(law, "mu", 0.0), "mu_axial": getattr(law, "mu_axial", 0.0),
                "mu_transverse": getattr(law, "mu_transverse", 0.0), "scale": law.static_scale, "vc": law.v_threshold}


def _axis(dr, n):
    """In-plane unit axial direction q (3, nel, nq), |p| with p = (I - n n^T) t (nel, nq),
    the unit tangent t (3, nel, nq) and |r'| as a divisor (nel, nq) (``unit_tangent``), for dr/ds and
    the normal n."""
    t, _, divisor = unit_tangent(dr)
    p = t - np.einsum("ceq,ceq->eq", t, n) * n
    size = np.sqrt(np.einsum("ceq,ceq->eq", p, p))
    degenerate = size < DEGENERATE_AXIS
    # a zero q makes the law all transverse and, with an infinite |p|, zeroes dq
    safe = np.where(degenerate, np.inf, size)
    return p / safe, safe, t, divisor


# ---------------------------------------------------------------------------- the compiled face
@njit(cache=True, _nrt=False)
def _saturation(w, vc, scale, phi, dphi, stick):
    """phi(w) and dphi/dw of the saturated-damping law (``saturation``); with ``stick``, of its
    ramp (the sticking branch) at any speed."""
    speed = np.sqrt(dot(w, w))
    ramp = speed < vc or stick
    gain = scale / vc if ramp else 1.0 / speed
    for a in range(3):
        phi[a] = gain * w[a]
        for b in range(3):
            dphi[a, b] = (gain if a == b else 0.0) - (0.0 if ramp else w[a] * w[b] / speed ** 3)


@njit(cache=True, _nrt=False)
def friction_point(ctx, p, old, new, state, hold, out):
    """The compiled face at one full point the contact found rubbing (``ctx.contact``), on the ramp
    (sticking) where ``ctx.held`` and ``hold.friction.stick``; ``state.friction.slip``: the slip
    velocity w (zero off the seabed). See ``cablefem.compiled.kernels`` for the arguments."""
    q = p.friction
    if not q.active:
        return
    slip = state.friction.slip
    slip[0], slip[1], slip[2] = 0.0, 0.0, 0.0
    contact = ctx.contact
    if not contact.rubbing:
        return
    n, dn, curved, v, v_x, jac = ctx.n, ctx.dn, ctx.curved, ctx.v, ctx.v_x, ctx.jac
    f, Ab = out.f, out.A
    pressure, vn = contact.normal_force, contact.normal_velocity
    dp_dr, dp_dv = contact.normal_force_r, contact.normal_force_v
    s = ctx.friction
    w, dN, tmp, dphi, dw_dr = s.w, s.dF_dN, s.tmp, s.dphi, s.dw_dr
    stick = ctx.held and hold.friction.stick
    vc = q.vc
    for i in range(3):
        w[i] = v[i] - vn * n[i]
        slip[i] = w[i]
    if q.anisotropic:
        _anisotropic(ctx, q, pressure, vn, stick, out)
        return
    # isotropic: dphi = gain I - ramp_off w w^T / |w|^3, w on the bed
    mu = q.mu
    speed = np.sqrt(dot(w, w))
    ramp = speed < vc or stick
    gain = q.scale / vc if ramp else 1.0 / speed
    bend = 0.0 if ramp else 1.0 / (speed * speed * speed)
    for i in range(3):
        dN[i] = -mu * gain * w[i]
        f[i] += pressure * dN[i]
    if jac:
        # F = p dN(w), w = (I - n n^T) v: Ab -= v_x dF_dw In + dN (dp_dr + v_x dp_dv)^T, and
        # dF_dw In = -mu p (gain In - bend w w^T) since w is normal to n
        scale = v_x * mu * pressure
        for i in range(3):
            for j in range(3):
                Ab[i, j] += scale * ((gain if i == j else 0.0) - gain * n[i] * n[j] - bend * w[i] * w[j]) \
                    - dN[i] * (dp_dr[j] + v_x * dp_dv[j])
        if curved:  # dw/dr through the normal's gradient
            for i in range(3):
                for j in range(3):
                    dphi[i, j] = -mu * pressure * ((gain if i == j else 0.0) - bend * w[i] * w[j])
                    tmp[i, j] = -(n[i] * v[j] + (vn if i == j else 0.0))
            dw_dr[:, :] = 0.0
            add_matmul(dw_dr, tmp, dn, 1.0)
            add_matmul(Ab, dphi, dw_dr, -1.0)


@njit(cache=True, _nrt=False)
def _anisotropic(ctx, q_, pressure, vn, stick, out):
    """Anisotropic friction at a rubbing point (``friction_point``), along the line's direction on the
    seabed and across it (housner2022 Eq. 5-6), on its slip ``ctx.friction.w``."""
    n, dn, v, v_x, t, jac = ctx.n, ctx.dn, ctx.v, ctx.v_x, ctx.t, ctx.jac
    f, Ab, Bb = out.f, out.A, out.B
    vc, fscale, mu_a, mu_t = q_.vc, q_.scale, q_.mu_axial, q_.mu_transverse
    dp_dr, dp_dv = ctx.contact.normal_force_r, ctx.contact.normal_force_v
    s = ctx.friction
    w, dN, tmp, dphi, dw_dr, In = s.w, s.dF_dN, s.tmp, s.dphi, s.dw_dr, s.In
    dphia, dF_dw, dF_dq, dq_dp, dp_dn, dg = s.dphia, s.dF_dw, s.dF_dq, s.dq_dp, s.dp_dn, s.dg
    phi, phia, q, un, pv, va = s.phi, s.phia, s.q, s.un, s.pv, s.va
    tn = dot(t, n)
    for i in range(3):
        pv[i] = t[i] - tn * n[i]
    size = np.sqrt(dot(pv, pv))
    if size < DEGENERATE_AXIS:
        size = np.inf
        q[:] = 0.0
    else:
        for i in range(3):
            q[i] = pv[i] / size
    along = dot(w, q)
    for i in range(3):
        va[i] = along * q[i]
        un[i] = w[i] - va[i]  # the transverse velocity
    _saturation(va, vc, fscale, phia, dphia, stick)
    _saturation(un, vc, fscale, phi, dphi, stick)
    for i in range(3):
        dN[i] = -(mu_a * phia[i] + mu_t * phi[i])
        f[i] += pressure * dN[i]
    if not jac:
        return
    # dF/dw = -N (ga q q^T + gt (I - q q^T)); dF/dq = -N (ga - gt)(q w^T + (w.q) I)
    for i in range(3):
        for j in range(3):
            tmp[i, j] = q[i] * q[j]
    dF_dw[:, :] = 0.0
    add_matmul(dF_dw, dphia, tmp, -pressure * mu_a)
    for i in range(3):
        for j in range(3):
            tmp[i, j] = (1.0 if i == j else 0.0) - q[i] * q[j]
    add_matmul(dF_dw, dphi, tmp, -pressure * mu_t)
    for i in range(3):
        for j in range(3):
            tmp[i, j] = q[i] * w[j] + (along if i == j else 0.0)
    dF_dq[:, :] = 0.0
    add_matmul(dF_dq, dphia, tmp, -pressure * mu_a)
    add_matmul(dF_dq, dphi, tmp, pressure * mu_t)
    for i in range(3):
        for j in range(3):
            In[i, j] = (1.0 if i == j else 0.0) - n[i] * n[j]
            tmp[i, j] = -(n[i] * v[j] + (vn if i == j else 0.0))
    dw_dr[:, :] = 0.0
    add_matmul(dw_dr, tmp, dn, 1.0)
    add_matmul(Ab, dF_dw, dw_dr, -1.0)
    add_outer(Ab, dN, dp_dr, -1.0)
    add_matmul(Ab, dF_dw, In, -v_x)
    add_outer(Ab, dN, dp_dv, -v_x)
    if size < np.inf:
        for i in range(3):
            for j in range(3):
                dq_dp[i, j] = ((1.0 if i == j else 0.0) - q[i] * q[j]) / size
        tmp[:, :] = 0.0
        add_matmul(tmp, dq_dp, In, 1.0 / unit_divisor(ctx.stretch))
        add_matmul(Bb, dF_dq, tmp, -1.0)
        tn = dot(n, t)
        for i in range(3):
            for j in range(3):
                dp_dn[i, j] = -(n[i] * t[j] + (tn if i == j else 0.0))
        tmp[:, :] = 0.0
        add_matmul(tmp, dp_dn, dn, 1.0)
        dg[:, :] = 0.0
        add_matmul(dg, dq_dp, tmp, 1.0)
        add_matmul(Ab, dF_dq, dg, -1.0)


@njit(cache=True, _nrt=False)
def friction_hold(base, state, hold, p, again):
    """Hold friction on its ramp (``cablefem.dynamics.policy``) where the point slid at the base of a
    rejected Newton step (|w| >= v_c) and the trial took it, still on the seabed, into the ramp or
    against its slip; ``again``: also where it is held already."""
    if not p.friction.active:
        return False, False
    b, s = base.friction.slip, state.friction.slip
    vc = p.friction.vc
    before = np.sqrt(dot(b, b))
    after = np.sqrt(dot(s, s))
    stick = before >= vc and after > 0.0 and (after < vc or dot(b, s) <= 0.0)
    held = hold.friction.stick
    if again:
        stick = stick or held
    hold.friction.stick = stick
    return stick, stick != held


def build(setting):
    """Friction in dynamics, by the scene's ``[friction]`` model (none: no load); only on a line with
    seabed contact (``SPEC.reads``)."""
    law = None if setting.friction is None else friction_law(setting.friction)
    return None if law is None else SeabedFriction(law)


SPEC = LoadSpec("friction", "full",
                (("anisotropic", "?"), ("mu", "f8"), ("mu_axial", "f8"), ("mu_transverse", "f8"), ("scale", "f8"),
                 ("vc", "f8")),
                friction_point, SeabedFriction, state=(("slip", "f8", (3,)),), hold=(("stick", "?"),),
                hold_rule=friction_hold, build=build, reads=("contact",),
                # the slip w and dF/dN at a rubbing point, then the blocks and vectors of the chain rule
                scratch=tuple((name, "f8", (3,)) for name in ("w", "dF_dN", "phi", "phia", "q", "un", "pv", "va"))
                + tuple((name, "f8", (3, 3)) for name in ("tmp", "dphi", "dw_dr", "In", "dphia", "dF_dw", "dF_dq",
                                                          "dq_dp", "dp_dn", "dg")))
