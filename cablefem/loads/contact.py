"""Seabed contact per unit unstretched length: the normal force (desire2023 Eq. 11; housner2022
Eq. 4), both faces.

f_n = -d G_K min(d_G, 0) d_P - c s(d_G) min(v_n, 0) d_P   while d_G < 0,

with d_G the penetration depth and d_P the projection direction of the
seabed (geometry package), d the contact diameter, G_K the ground stiffness
per unit area [N/m^3] and v_n = v . d_P. The damping per unit length c is
2 G_c sqrt(G_K d m) (Eq. 11, G_c the fraction of critical) or, given as
MoorDyn's cBot [N s/m^3], cBot d. On a plane d_G is the distance to the
plane, which equals MoorDyn's (z_b - r_3) n_z of housner2022 Eq. 4.

The damper engages over a depth: s(d_G) = min(-d_G / delta, 1), with delta half the depth at
which the spring carries the element's submerged weight w, delta = |w| / (2 d G_K)
(``ramp_depth``; 2 mm for OC4's chain on kBot 3e6). Eq. 11 and MoorDyn switch it on in full at
d_G = 0: a force that jumps by c v_n as a point moving at v_n touches down or lifts off, where
an implicit step's residual may have no root at all. Adaptive BDF2 on OC4's chains (cBot 3e5)
stopped on one, its residual stuck at 1e-4 at every step size down to 4e-4 s; without cBot it
ran (tests/test_defaults.py). A resting point, at twice delta, is damped in full as before.

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

Friction (``cablefem.loads.friction``, the next load of the catalog) acts on
what the contact hands it at each point: the normal force magnitude N = |f_n|,
its derivatives, v_n and the projection (the numpy face's ``NormalForce`` in
``State.handed``; the compiled face's scratch ``ctx.contact``, beside the
projection in the point context).
"""

from dataclasses import dataclass


import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms, outer
from cablefem.loads._small import add_outer, dot


@dataclass
class NormalForce:
    """What the contact hands to friction at its points (``State.handed["contact"]``): the normal
    force p [N/m] (nel, nq) along d_P (3, nel, nq), negative only where an opening damper pulls a
    point down; v_n = v . d_P [m/s] (nel, nq), None in statics; with a tangent, dd_P/dr
    (3, 3, nel, nq) and dp/dr [N/m^2], dp/dv [N s/m^2] (3, nel, nq) (dp/dv None without damping)."""

    pressure: np.ndarray
    direction: np.ndarray
    normal_velocity: np.ndarray | None
    direction_r: np.ndarray | None = None
    pressure_r: np.ndarray | None = None
    pressure_v: np.ndarray | None = None


class SeabedContact:
    """Contact of a line with ``seabed``: stiffness and damping per unit length per element (nel,)."""

    name = "contact"

    def __init__(self, seabed, stiffness, damping, opening=False, ramp=0.0):
        self.seabed = seabed
        self.stiffness = np.asarray(stiffness, dtype=float)[:, None]  # G_K d [N/m^2]
        self.damping = np.asarray(damping, dtype=float)[:, None]  # [N s/m^2]
        self.opening = bool(opening)  # the damper acts on points moving out too (MoorDyn-C)
        # the depth over which the damper engages, delta [m] per element (0: at once, Eq. 11)
        self.ramp = np.broadcast_to(np.asarray(ramp, dtype=float), self.damping.shape[:1])[:, None].copy()

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
        vn = None if state.v is None else np.einsum("ceq,ceq->eq", state.v, n)
        if damped:
            closing = touching & ((vn < 0.0) | self.opening)
            engaged = np.where(closing, _engaged(gap, self.ramp), 0.0)  # s(d_G)
            pressure = pressure - self.damping * engaged * vn
        terms = Terms(force=pressure * n)
        handed = state.handed["contact"] = NormalForce(pressure, n, vn)
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
            c = self.damping * engaged
            # v_n = v . n(r): d v_n/dr = v . dn/dr; s = -d_G / delta inside the ramp
            inside = closing & (-gap < self.ramp)  # closing: in the seabed
            slope = np.where(inside, self.damping * vn / np.where(inside, self.ramp, 1.0), 0.0)
            dpressure_dr = dpressure_dr - c * np.einsum("aeq,abeq->beq", state.v, dn) + slope * grad_gap
            dpressure_dv = -c * n
            terms.force_v = outer(n, dpressure_dv)
        terms.force_r = outer(n, dpressure_dr) + pressure * dn
        handed.direction_r, handed.pressure_r, handed.pressure_v = dn, dpressure_dr, dpressure_dv
        return terms

    def energy(self, state):
        """The seabed spring's energy density k min(d_G, 0)^2 / 2 [J/m] (nel, nq), whose gradient
        is the static contact force (exactly on planes and grids, to the projection's own accuracy
        on vertex-normal meshes)."""
        gap = self.seabed.gap_only(state.r.reshape(3, -1).T).reshape(state.r.shape[1:])
        return 0.5 * self.stiffness * np.minimum(gap, 0.0) ** 2

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,)."""
        return {"k": self.stiffness[:, 0], "c": self.damping[:, 0], "opening": self.opening,
                "ramp": self.ramp[:, 0]}


def _engaged(gap, ramp):
    """The damper's share s(d_G) = min(-d_G / delta, 1) at penetration -d_G (1 where delta is 0)."""
    safe = np.where(ramp > 0.0, ramp, 1.0)
    return np.where(ramp > 0.0, np.clip(-gap / safe, 0.0, 1.0), 1.0)


def ramp_depth(contact, props, environment):
    """delta per element [m]: half the depth at which the seabed spring carries the element's submerged
    weight, |m - rho A| g / (2 d G_K); 0 where the seabed has no stiffness."""
    weight = np.abs(props["mass"] - environment.water_density * props["area"]) * environment.gravity
    stiffness = contact.stiffness * props["diameter"]
    return np.where(stiffness > 0.0, weight / (2.0 * np.where(stiffness > 0.0, stiffness, 1.0)), 0.0)


def _project(seabed, points, derivatives):
    """The seabed's projection of points (n, 3) [m]; a residual alone needs no derivatives,
    which the triangulated surface can skip (a third of its cost)."""
    if not derivatives and getattr(seabed, "kind", None) == "mesh":  # a TriangulatedSurface
        return seabed.project(points, derivatives=False)
    return seabed.project(points)


# ---------------------------------------------------------------------------- the compiled face
#: branches a point's contact may be held on (``hold.contact.bits``, Newton's corrections,
#: ``cablefem.dynamics.policy``): the seabed spring acting or not (on: -k d_G also above the
#: seabed), its damper acting or not
DAMPER_ON, DAMPER_OFF, TOUCH_ON, TOUCH_OFF = 2, 4, 8, 16
DAMPERS, TOUCHES = DAMPER_ON | DAMPER_OFF, TOUCH_ON | TOUCH_OFF
#: a point's contact state (``state.contact.bits``): in the seabed, its damper acting
TOUCHING, CLOSING = 1, 2


@njit(cache=True, _nrt=False)
def contact_point(ctx, p, old, new, state, hold, out):
    """The compiled face: the seabed's spring and damper (desire2023 Eq. 11) at one full point, on
    the branches ``hold.contact.bits`` holds when ``ctx.held``; ``state.contact.bits``: the point
    in the seabed, its damper acting. A curved seabed's normal gradient ``ctx.dn`` enters only
    where ``ctx.curved`` (a plane's is zero). Hands friction its normal force in ``ctx.contact``
    (``SPEC.scratch``). See ``cablefem.compiled.kernels`` for the arguments."""
    c_ = p.contact
    if not c_.active:
        return
    k, c = c_.k, c_.c
    gap, n, grad_gap, dn, curved, v, v_x, jac = ctx.gap, ctx.n, ctx.grad_gap, ctx.dn, ctx.curved, ctx.v, ctx.v_x, ctx.jac
    f, Ab = out.f, out.A
    handed = ctx.contact
    dp_dr, dp_dv = handed.normal_force_r, handed.normal_force_v
    bits = hold.contact.bits if ctx.held else 0
    touching = gap < 0.0 if (bits & TOUCHES) == 0 else (bits & TOUCH_ON) != 0
    pressure = -k * gap if touching else 0.0
    vn = dot(v, n)
    closing = touching and c > 0.0 and ((bits & DAMPER_ON) != 0 if (bits & DAMPERS) != 0 else
                                        (vn < 0.0 or c_.opening))
    engaged, slope = 1.0, 0.0  # the damper's share s(d_G) and c v_n ds/d(-d_G) inside its ramp
    if closing and c_.ramp > 0.0:
        if gap >= 0.0:
            engaged = 0.0
        elif -gap < c_.ramp:
            engaged = -gap / c_.ramp
            slope = c * vn / c_.ramp
    if closing:
        pressure -= c * engaged * vn
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
                    dp_dr[j] -= c * engaged * (v[0] * dn[0, j] + v[1] * dn[1, j] + v[2] * dn[2, j])
                dp_dr[j] += slope * grad_gap[j]
                dp_dv[j] = -c * engaged * n[j]
            add_outer(Ab, n, dp_dv, -v_x)
        add_outer(Ab, n, dp_dr, -1.0)
        if curved:
            for i in range(3):
                for j in range(3):
                    Ab[i, j] -= pressure * dn[i, j]
    state.contact.bits = (TOUCHING if touching else 0) | (CLOSING if closing else 0)
    handed.rubbing = touching and gap < 0.0  # a point held on the seabed's spring above it has no friction
    handed.normal_velocity = vn
    handed.normal_force = pressure
    if pressure < 0.0:  # an opening damper pulls the point down: friction reads N = |f_n|
        handed.normal_force = -pressure
        if jac:
            for j in range(3):
                dp_dr[j] = -dp_dr[j]
                dp_dv[j] = -dp_dv[j]


@njit(cache=True, _nrt=False)
def contact_hold(base, state, hold, p, again):
    """Hold the branches a rejected Newton step's trial reached at this point (``cablefem.dynamics.policy``):
    the spring and damper as the trial has them where it put the point on the seabed or lifted it
    off (a resting point's damper alone switches back and forth); ``again``: keep what is held
    already unless the trial set new holds."""
    now = state.contact.bits
    flag = 0
    if ((now ^ base.contact.bits) & TOUCHING) != 0:  # not the damper alone: resting points chatter
        flag = (TOUCH_ON if (now & TOUCHING) != 0 else TOUCH_OFF) | (DAMPER_ON if (now & CLOSING) != 0 else DAMPER_OFF)
    held = hold.contact.bits
    if again and flag == 0:
        flag = held
    changed = flag != held
    hold.contact.bits = flag
    return flag != 0, changed


def build(setting):
    """Every line rests on the seabed: the scene's contact; a line of a scene with ``[soil]`` has
    none (below the surface the soil holds it, ``cablefem.loads.soil``)."""
    if "soil" in setting.sections:
        return None
    props, contact = setting.props, setting.contact
    return SeabedContact(setting.seabed, contact.stiffness * props["diameter"], contact_damping(contact, props),
                         opening=contact.damping_when_opening,
                         ramp=ramp_depth(contact, props, setting.environment))


def contact_damping(contact, props):
    """Seabed damping per unit length [N s/m^2] per element: cBot d, or 2 G_c sqrt(G_K d m)."""
    if contact.damping is not None:
        return contact.damping * props["diameter"]
    return 2.0 * contact.damping_ratio * np.sqrt(contact.stiffness * props["diameter"] * props["mass"])


SPEC = LoadSpec("contact", "full", (("k", "f8"), ("c", "f8"), ("opening", "?"), ("ramp", "f8")), contact_point, SeabedContact,
                state=(("bits", "i1"),), hold=(("bits", "i1"),), hold_rule=contact_hold, build=build,
                # handed to friction (``cablefem.loads.friction``, whose spec reads "contact"), written at
                # every point of a line with contact: whether the point rubs on the seabed (in it, on the
                # spring's branch), v_n [m/s], the normal force N = |f_n| [N/m] and, with a tangent,
                # dN/dr [N/m^2] and dN/dv [N s/m^2] (the signed force's while the contact adds its block)
                scratch=(("rubbing", "?"), ("normal_velocity", "f8"), ("normal_force", "f8"),
                         ("normal_force_r", "f8", (3,)), ("normal_force_v", "f8", (3,))))
