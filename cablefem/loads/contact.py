"""Seabed contact per unit unstretched length: normal force (desire2023 Eq. 11; housner2022
Eq. 4) and, optionally, friction (desire2023 Eq. 12; housner2022 Eq. 5-14).

f_n = -d G_K min(d_G, 0) d_P - c min(v_n, 0) d_P   while d_G < 0,

with d_G the penetration depth and d_P the projection direction of the
seabed (geometry package), d the contact diameter, G_K the ground stiffness
per unit area [N/m^3] and v_n = v . d_P. The damping per unit length c is
2 G_c sqrt(G_K d m) (Eq. 11, G_c the fraction of critical) or, given as
MoorDyn's cBot [N s/m^3], cBot d. On a plane d_G is the distance to the
plane, which equals MoorDyn's (z_b - r_3) n_z of housner2022 Eq. 4.

The damper resists closing only (Eq. 11's min(v_n, 0)): it does not hold a point back as it
lifts off. With ``opening`` (``[seabed] damping_when_opening``, MoorDyn-C's law: its
``Line::getStateDeriv`` applies B_z = ((z_b - z) kBot - v_z cBot) d l to every penetrating node)
it acts on every point in the seabed, -c v_n d_P, and can pull a point lifting off down; the
normal force friction reads is then |f_n|, as MoorDyn-C's |B_z|.

Eq. 11's third term, |p . d_P| d_P (the normal part of the line's weight,
added in contact), is left out: it switches on discontinuously as a point
touches the seabed, which breaks Newton's convergence, and it only shifts
the resting penetration from w/(d G_K) to zero; with the stiffnesses in use
(3e5 N/m^3 gives 0.07 m for the Table 5 chain) the spring carries the weight.

Friction (``cablefem.loads.friction``) uses the same projection: the normal
force magnitude N = |f_n|, the in-plane velocity v_pi = v - (v . d_P) d_P
and, for the anisotropic law, the axial direction q = normalise((I - d_P d_P) t)
with t = r'/|r'| (housner2022 Eq. 5). It acts only where d_G < 0 (N = 0
elsewhere) and only when a velocity is given (statics has none). Where the
line is perpendicular to the seabed q is undefined and taken as 0, so all
sliding counts as transverse.
"""

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms, add, compose, identity_like, outer, unit_tangent
from cablefem.loads._small import add_matmul, add_outer, dot, unit_divisor

#: |(I - d_P d_P) t| below which the in-plane axial direction q is taken as 0
DEGENERATE_AXIS = 1e-12


class SeabedContact:
    """Contact of a line with ``seabed``: stiffness and damping per unit length per element (nel,),
    and optionally a friction law (``IsotropicFriction`` / ``AnisotropicFriction``, see
    ``cablefem.loads.friction.friction_law``)."""

    name = "contact"

    def __init__(self, seabed, stiffness, damping, friction=None, opening=False):
        self.seabed = seabed
        self.stiffness = np.asarray(stiffness, dtype=float)[:, None]  # G_K d [N/m^2]
        self.damping = np.asarray(damping, dtype=float)[:, None]  # [N s/m^2]
        self.friction = friction
        self.opening = bool(opening)  # the damper acts on points moving out too (MoorDyn-C)

    def evaluate(self, state, jacobian=True):
        r = state.r
        shape = r.shape[1:]
        points = r.reshape(3, -1).T
        proj = _project(self.seabed, points, jacobian)
        gap = proj.gap.reshape(shape)
        n = proj.direction.T.reshape(3, *shape)
        touching = gap < 0.0
        pressure = -self.stiffness * np.where(touching, gap, 0.0)  # >= 0
        damped = state.v is not None and np.any(self.damping > 0)
        sliding = state.v is not None and self.friction is not None
        if damped or sliding:
            vn = np.einsum("ceq,ceq->eq", state.v, n)
        if damped:
            closing = touching & ((vn < 0.0) | self.opening)
            pressure = pressure - self.damping * np.where(closing, vn, 0.0)
        terms = Terms(force=pressure * n)
        if sliding:
            v_plane = state.v - vn * n
            axis, axis_norm, t, divisor = _axis(state.dr, n) if self.friction.uses_axis else (None,) * 4
            # N = |f_n|: the pressure is negative only where an opening damper pulls a point down
            sign = np.where(pressure < 0.0, -1.0, 1.0)
            friction, df_dw, df_dN, df_dq = self.friction.evaluate(v_plane, sign * pressure, axis)
            df_dN = sign * df_dN  # dF/dp
            terms.force = terms.force + friction
        if not jacobian:
            return terms
        grad_gap = proj.gap_gradient.T.reshape(3, *shape)
        dn = np.moveaxis(proj.direction_gradient, 0, -1).reshape(3, 3, *shape)
        # a point exactly on the seabed counts as touching in the tangent (a semismooth
        # Newton choice): a guess resting at d_G = 0 then gets the seabed's support at once
        on = (gap <= 0.0).astype(float)
        dpressure_dr = -self.stiffness * on * grad_gap
        dpressure_dv = None
        if damped:
            c = self.damping * closing
            # v_n = v . n(r): d v_n/dr = v . dn/dr
            dpressure_dr = dpressure_dr - c * np.einsum("aeq,abeq->beq", state.v, dn)
            dpressure_dv = -c * n
            terms.force_v = outer(n, dpressure_dv)
        terms.force_r = outer(n, dpressure_dr) + pressure * dn
        if sliding:
            eye = identity_like(n)
            in_plane = eye - outer(n, n)
            # v_pi = v - (v . n) n: d v_pi/dn = -(n v^T + (v . n) I)
            dw_dr = compose(-(outer(n, state.v) + vn * eye), dn)
            force_r = compose(df_dw, dw_dr) + outer(df_dN, dpressure_dr)
            force_v = compose(df_dw, in_plane)
            if dpressure_dv is not None:
                force_v = force_v + outer(df_dN, dpressure_dv)
            if axis is not None:
                # q = p / |p|, p = (I - n n^T) t, t = r'/|r'|; the t t^T part of dt/dr' drops
                # out, since (I - q q^T)(I - n n^T) t = (I - q q^T) |p| q = 0
                dq_dp = (eye - outer(axis, axis)) / axis_norm
                dq_ddr = compose(dq_dp, in_plane) / divisor
                terms.force_dr = compose(df_dq, dq_ddr)
                dp_dn = -(outer(n, t) + np.einsum("ceq,ceq->eq", n, t) * eye)
                force_r = force_r + compose(df_dq, compose(dq_dp, compose(dp_dn, dn)))
            terms.force_r = terms.force_r + force_r
            terms.force_v = add(terms.force_v, force_v)
        return terms


    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,)."""
        from cablefem.loads.friction import AnisotropicFriction, IsotropicFriction

        law, nel = self.friction, self.stiffness.shape[0]
        model = ISOTROPIC if isinstance(law, IsotropicFriction) else (
            ANISOTROPIC if isinstance(law, AnisotropicFriction) else NO_FRICTION)
        values = {"k": self.stiffness[:, 0], "c": self.damping[:, 0], "model": np.full(nel, model),
                  "mu": 0.0, "mu_axial": 0.0, "mu_transverse": 0.0, "scale": 1.0, "vc": 1.0,
                  "opening": self.opening}
        if law is not None:
            values.update(scale=law.static_scale, vc=law.v_threshold)
            values.update({"mu": law.mu} if model == ISOTROPIC else
                          {"mu_axial": law.mu_axial, "mu_transverse": law.mu_transverse})
        return values


def _project(seabed, points, derivatives):
    """The seabed's projection of points (n, 3) [m]; a residual alone needs no derivatives,
    which the triangulated surface can skip (a third of its cost)."""
    if not derivatives and getattr(seabed, "kind", None) == "mesh":  # a TriangulatedSurface
        return seabed.project(points, derivatives=False)
    return seabed.project(points)


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
#: branches a point's contact may be held on (``hold.contact.bits``, Newton's corrections,
#: ``cablefem.dynamics.policy``): friction on its ramp (sticking), the seabed spring acting or not (on:
#: -k d_G also above the seabed), its damper acting or not
STICK, DAMPER_ON, DAMPER_OFF, TOUCH_ON, TOUCH_OFF = 1, 2, 4, 8, 16
DAMPERS, TOUCHES = DAMPER_ON | DAMPER_OFF, TOUCH_ON | TOUCH_OFF
#: a point's contact state (``state.contact.bits``): in the seabed, its damper acting
TOUCHING, CLOSING = 1, 2
#: the friction law in ``p.contact.model``
NO_FRICTION, ISOTROPIC, ANISOTROPIC = 0, 1, 2


@njit(cache=True, _nrt=False)
def _saturation(w, vc, scale, phi, dphi, stick):
    """phi(w) and dphi/dw of the saturated-damping law (``friction.saturation``); with ``stick``,
    of its ramp (the sticking branch) at any speed."""
    speed = np.sqrt(dot(w, w))
    ramp = speed < vc or stick
    gain = scale / vc if ramp else 1.0 / speed
    for a in range(3):
        phi[a] = gain * w[a]
        for b in range(3):
            dphi[a, b] = (gain if a == b else 0.0) - (0.0 if ramp else w[a] * w[b] / speed ** 3)


@njit(cache=True, _nrt=False)
def contact_point(ctx, p, old, new, state, hold, out, M, u):
    """The compiled face: the seabed's spring and damper (desire2023 Eq. 11) and friction
    (Eq. 12; housner2022 Eq. 5-13) at one full point, on the branches ``hold.contact.bits`` holds
    when ``ctx.held``; ``state.contact``: the contact bits and the slip velocity w (zero off the
    seabed or without friction). A curved seabed's normal gradient ``ctx.dn`` enters only where
    ``ctx.curved`` (a plane's is zero). See ``cablefem.compiled.kernels`` for the arguments."""
    c_ = p.contact
    if not c_.active:
        return
    k, c, model, vc = c_.k, c_.c, c_.model, c_.vc
    gap, n, grad_gap, dn, curved, v, v_x, jac = ctx.gap, ctx.n, ctx.grad_gap, ctx.dn, ctx.curved, ctx.v, ctx.v_x, ctx.jac
    f, Ab = out.f, out.A
    bits = hold.contact.bits if ctx.held else 0
    eye, tmp, dphi, dw_dr, In = M[0], M[1], M[2], M[3], M[4]
    w, dp_dr, dp_dv, dN = u[0], u[1], u[2], u[3]
    if jac:
        for i in range(3):
            for j in range(3):
                eye[i, j] = 1.0 if i == j else 0.0
    touching = gap < 0.0 if (bits & TOUCHES) == 0 else (bits & TOUCH_ON) != 0
    pressure = -k * gap if touching else 0.0
    vn = dot(v, n)
    closing = touching and c > 0.0 and ((bits & DAMPER_ON) != 0 if (bits & DAMPERS) != 0 else
                                        (vn < 0.0 or c_.opening))
    stick = (bits & STICK) != 0
    if closing:
        pressure -= c * vn
    for i in range(3):
        f[i] += pressure * n[i]
    if jac:
        on = (1.0 if gap <= 0.0 else 0.0) if (bits & TOUCHES) == 0 else (1.0 if touching else 0.0)
        for j in range(3):
            dp_dr[j] = -k * on * grad_gap[j]
            dp_dv[j] = 0.0
        if closing:
            for j in range(3):
                if curved:
                    dp_dr[j] -= c * (v[0] * dn[0, j] + v[1] * dn[1, j] + v[2] * dn[2, j])
                dp_dv[j] = -c * n[j]
            add_outer(Ab, n, dp_dv, -v_x)
        add_outer(Ab, n, dp_dr, -1.0)
        if curved:
            for i in range(3):
                for j in range(3):
                    Ab[i, j] -= pressure * dn[i, j]
    slip = state.contact.slip
    slip[0], slip[1], slip[2] = 0.0, 0.0, 0.0
    state.contact.bits = (TOUCHING if touching else 0) | (CLOSING if closing else 0)
    rubbing = touching and gap < 0.0  # a point held on the seabed's spring above it has no friction
    if not rubbing or model == NO_FRICTION:
        return
    if pressure < 0.0:  # an opening damper pulls the point down: friction reads N = |f_n|
        pressure = -pressure
        for j in range(3):
            dp_dr[j] = -dp_dr[j]
            dp_dv[j] = -dp_dv[j]
    for i in range(3):
        w[i] = v[i] - vn * n[i]
        slip[i] = w[i]
    if model == ISOTROPIC:  # dphi = gain I - ramp_off w w^T / |w|^3, w on the bed
        mu = c_.mu
        speed = np.sqrt(dot(w, w))
        ramp = speed < vc or stick
        gain = c_.scale / vc if ramp else 1.0 / speed
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
    else:
        _anisotropic(ctx, c_, pressure, vn, stick, eye, In, M, u, out)


@njit(cache=True, _nrt=False)
def _anisotropic(ctx, c_, pressure, vn, stick, eye, In, M, u, out):
    """Anisotropic friction at a rubbing point (``contact_point``): along the line's direction on the
    seabed and across it (housner2022 Eq. 5-6), with w = u[0], dp_dr = u[1], dp_dv = u[2], dN = u[3]."""
    n, dn, v, v_x, t, jac = ctx.n, ctx.dn, ctx.v, ctx.v_x, ctx.t, ctx.jac
    f, Ab, Bb = out.f, out.A, out.B
    vc, fscale, mu_a, mu_t = c_.vc, c_.scale, c_.mu_axial, c_.mu_transverse
    tmp, dphi, dw_dr, dphia, dF_dw, dF_dq, dq_dp, dp_dn, dg = M[1], M[2], M[3], M[5], M[6], M[7], M[8], M[9], M[10]
    w, dp_dr, dp_dv, dN, phi, phia, q, un, pv, va = u[0], u[1], u[2], u[3], u[4], u[5], u[6], u[7], u[8], u[9]
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
    for i in range(3):
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
            tmp[i, j] = eye[i, j] - q[i] * q[j]
    add_matmul(dF_dw, dphi, tmp, -pressure * mu_t)
    for i in range(3):
        for j in range(3):
            tmp[i, j] = q[i] * w[j] + (along if i == j else 0.0)
    dF_dq[:, :] = 0.0
    add_matmul(dF_dq, dphia, tmp, -pressure * mu_a)
    add_matmul(dF_dq, dphi, tmp, pressure * mu_t)
    for i in range(3):
        for j in range(3):
            In[i, j] = eye[i, j] - n[i] * n[j]
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
                dq_dp[i, j] = (eye[i, j] - q[i] * q[j]) / size
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
def contact_hold(base, state, hold, p, again):
    """Hold the branches a rejected Newton step's trial reached at this point (``cablefem.dynamics.policy``):
    friction on its ramp where the point slid at the base (|w| >= v_c) and the trial took it, still
    on the seabed, into the ramp or against its slip; the spring and damper as the trial has them
    where it put the point on the seabed or lifted it off (a resting point's damper alone switches
    back and forth); ``again``: also what is held already."""
    b, s = base.contact, state.contact
    vc = p.contact.vc
    before = np.sqrt(dot(b.slip, b.slip))
    after = np.sqrt(dot(s.slip, s.slip))
    flag = 0
    if before >= vc and after > 0.0 and (after < vc or dot(b.slip, s.slip) <= 0.0):
        flag |= STICK
    now = s.bits
    if ((now ^ b.bits) & TOUCHING) != 0:  # not the damper alone: resting points chatter
        flag |= (TOUCH_ON if (now & TOUCHING) != 0 else TOUCH_OFF) | (DAMPER_ON if (now & CLOSING) != 0 else DAMPER_OFF)
    held = hold.contact.bits
    if again:
        flag |= held if (flag & (TOUCHES | DAMPERS)) == 0 else held & STICK
    changed = flag != held
    hold.contact.bits = flag
    return flag != 0, changed


def build(setting):
    """Every line rests on the seabed: the scene's contact, with friction in dynamics; a line of a
    scene with ``[soil]`` has none (below the surface the soil holds it, ``cablefem.loads.soil``)."""
    from cablefem.loads.friction import friction_law

    if "soil" in setting.sections:
        return None
    props, contact = setting.props, setting.contact
    friction = None if setting.friction is None else friction_law(setting.friction)
    return SeabedContact(setting.seabed, contact.stiffness * props["diameter"], contact_damping(contact, props),
                         friction=friction, opening=contact.damping_when_opening)


def contact_damping(contact, props):
    """Seabed damping per unit length [N s/m^2] per element: cBot d, or 2 G_c sqrt(G_K d m)."""
    if contact.damping is not None:
        return contact.damping * props["diameter"]
    return 2.0 * contact.damping_ratio * np.sqrt(contact.stiffness * props["diameter"] * props["mass"])


SPEC = LoadSpec("contact", "full",
                (("k", "f8"), ("c", "f8"), ("model", "i8"), ("mu", "f8"), ("mu_axial", "f8"),
                 ("mu_transverse", "f8"), ("scale", "f8"), ("vc", "f8"), ("opening", "?")),
                contact_point, SeabedContact,
                state=(("bits", "i1"), ("slip", "f8", (3,))), hold=(("bits", "i1"),), hold_rule=contact_hold,
                scratch=(11, 10), build=build)
