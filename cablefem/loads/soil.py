"""Clay below the seabed surface: the chain-soil macro-element of rui2025 Sec. 2.2 (Eqs. 1-3).

At every quadrature point below the local surface the soil holds the line with three
elastic-perfectly-plastic springs, one along the line and two across it (rui2025 Eq. 1a-c), per
unit unstretched length:

    yield     t_f = E_t d_b s_u,   n_f = E_n d_b N_c s_u          (Eq. 3a, 3b over dL/2)
    stiffness K_t = k_t t_f,       K_n = k_n n_f                   (Eq. 2a, 2b)

with d_b the chain's nominal (bar) diameter and s_u the undrained shear strength at the point's own
depth below the local surface, measured along the surface normal (depth = -d_G of the seabed's
projection, so any seabed kind has it):

    s_u(depth) = zeta(depth) (su_mudline + su_gradient depth),   zeta = min(depth / d_b, 1),

and zero above the surface. The engagement zeta is this module's choice, not rui2025's: the
effective widths E_n d_b and E_t d_b belong to a fully embedded chain (Degenkamp & Dutta 1989, as
rui2025 Sec. 2.3 cites them), so the reaction grows from nothing at the surface to its full value
one bar diameter below it. With it the soil's reaction is continuous in position at the surface for
any su_mudline (with su_mudline = 0 it would be anyway); below d_b it is rui2025's exactly.

The history of a point is where the soil holds it, its anchor q (with, for output, the plastic slip
and the plastic work per unit length so far, and the reaction): the elastic offset is e = r - q,
split along the line's unit tangent t into e_t = t . e and the normal part e_n = e - e_t t. The
tangential spring returns on its own (|k_t e_t| <= 1), the two normal ones together in the normal
plane (radial return on |e_n| <= 1 / k_n, the same K_n in both directions, rui2025 Eq. 1b-c; a
circle rather than a square, so the reaction does not depend on how n1 and n2 are chosen):

    f = -s_u (E_t d_b clip(k_t e_t, -1, 1) t + E_n d_b N_c min(k_n, 1 / |e_n|) e_n),

and the trial anchor is q' = r - e', e' the returned offset. Above the surface the anchor follows
the point (q' = r: no reaction, no offset to remember), so a point entering the soil is held where
it entered. The tangent is the consistent one of the return (elastic: the springs; plastic: the
yield surface's), with the derivatives of s_u through the depth and of t through r'. The plastic
dissipation of an accepted step, (-f) . (q' - q) >= 0 per unit length, is what
``plastic_dissipation`` sums. The soil is rate independent: no velocity terms.

Where the soil acts it replaces the seabed contact (``cablefem.loads.contact``): a line of a scene
with ``[soil]`` has no contact spring, damper or friction, so the two never act at one point;
above the surface neither acts (the contact's spring only pushes once the centreline is below it).
"""

import numpy as np
from numba import njit

from cablefem.errors import InputError
from cablefem.io import validate as v
from cablefem.loads import LoadSpec, Terms, identity_like, outer, unit_tangent

#: a spring whose offset is within this fraction beyond its yield offset counts as on the yield surface,
#: where the force is the yield force and the tangent the elastic one: a point that stays on the
#: surface (the lying chain, at its bearing capacity under its own weight; a point sliding on at its
#: friction) is there to round-off, and round-off would otherwise pick its tangent, elastic or
#: plastic, at random from one Newton iteration to the next
ON_YIELD = 1e-9
#: the installation starts of the pretension path (``cablefem.statics.pretension``)
INSTALLATIONS = ("laid", "catenary")
#: defaults of the [soil] keys (rui2025 Sec. 2.3, Table 1; N_c: docs/scene.md, "[soil]")
DEFAULTS = {"su_mudline": 0.0, "bearing_factor": 7.6, "width_normal": 2.5, "width_tangential": 8.0,
            "installation": "laid", "installation_steps": 200}


class Soil:
    """The soil's macro-elements on a line over ``seabed``, per element (nel,): widths E_t d_b and
    E_n N_c d_b [m], spring constants k_t, k_n [1/m], the strength at the surface su0 [Pa] and its
    gradient su1 [Pa/m], and the engagement depth d_b [m]."""

    name = "soil"

    def __init__(self, seabed, tangential_width, normal_width, k_t, k_n, su_mudline, su_gradient, engagement):
        self.seabed = seabed
        column = (lambda x: np.broadcast_to(np.asarray(x, dtype=float), np.shape(engagement))[:, None])
        self.a_t, self.a_n = column(tangential_width), column(normal_width)
        self.k_t, self.k_n = column(k_t), column(k_n)
        self.su0, self.su1, self.ramp = column(su_mudline), column(su_gradient), column(engagement)

    def strength(self, depth):
        """s_u [Pa] and ds_u/d(depth) [Pa/m] at depths [m] (nel, nq) below the local surface."""
        inside = np.clip(depth / self.ramp, 0.0, 1.0)
        linear = self.su0 + self.su1 * np.maximum(depth, 0.0)
        slope = np.where(depth >= self.ramp, self.su1, (self.su0 + 2.0 * self.su1 * depth) / self.ramp)
        return inside * linear, np.where(depth > 0.0, slope, 0.0)

    def depth(self, r):
        """Depth below the local surface [m] (nel, nq) and its gradient d(depth)/dr (3, nel, nq)."""
        proj = self.seabed.project(r.reshape(3, -1).T)
        shape = r.shape[1:]
        return -proj.gap.reshape(shape), -proj.gap_gradient.T.reshape(3, *shape)

    def offsets(self, state):
        """The return at the points: (e_t, e_n, c, c', h, plastic normal, |e_n|, t, |r'| divisor)
        from the committed anchors (``state.old["soil"]["anchor"]``)."""
        anchor = np.moveaxis(state.old["soil"]["anchor"], -1, 0)
        t, _, divisor = unit_tangent(state.dr)
        e = state.r - anchor
        e_t = np.einsum("ceq,ceq->eq", t, e)
        e_n = e - e_t * t
        size = np.sqrt(np.einsum("ceq,ceq->eq", e_n, e_n))
        c = np.clip(self.k_t * e_t, -1.0, 1.0)
        slope = np.where(np.abs(self.k_t * e_t) <= 1.0 + ON_YIELD, self.k_t, 0.0)
        plastic = self.k_n * size > 1.0 + ON_YIELD
        h = np.where(plastic, 1.0 / np.where(plastic, size, 1.0), self.k_n)
        return e_t, e_n, c, slope, h, plastic, size, t, divisor

    def evaluate(self, state, jacobian=True):
        depth, grad_depth = self.depth(state.r)
        s, ds = self.strength(depth)
        e_t, e_n, c, slope, h, plastic, size, t, divisor = self.offsets(state)
        shape = self.a_t * c * t + self.a_n * h * e_n  # [m]: the reaction per unit strength
        force = -s * shape
        returned = c / self.k_t * t + h / self.k_n * e_n
        anchor = state.r - np.where(s > 0.0, returned, 0.0)
        self._record(state, anchor, force)
        terms = Terms(force=force)
        if not jacobian:
            return terms
        eye = identity_like(t)
        P = eye - outer(t, t)
        unit = e_n / np.where(plastic, size, 1.0)
        radial = np.where(plastic, 1.0 / np.where(plastic, size, 1.0), 0.0) * outer(unit, unit)
        d_normal = h * eye - radial  # d(h e_n)/d(e_n)
        terms.force_r = -outer(shape, ds * grad_depth) - s * (self.a_t * slope * outer(t, t)
                                                                + self.a_n * (h * P - radial))
        turn = outer(t, e_n) + e_t * P  # -d(e_n)/dr' |r'|
        terms.force_dr = -s / divisor * (self.a_t * (slope * outer(t, e_n) + c * P)
                                          - self.a_n * np.einsum("abeq,bceq->aceq", d_normal, turn))
        return terms

    def _record(self, state, anchor, force):
        """The trial history: anchors, the plastic slip [m] and plastic work [J/m] so far, and the
        reaction [N/m]."""
        old, new = state.old["soil"], state.new["soil"]
        moved = np.moveaxis(anchor, 0, -1)
        step = moved - old["anchor"]
        reaction = np.moveaxis(force, 0, -1)
        new["anchor"] = moved
        new["slip"] = old["slip"] + np.linalg.norm(step, axis=-1)
        new["work"] = old["work"] - np.einsum("eqc,eqc->eq", reaction, step)
        new["reaction"] = reaction

    def initial_history(self, state):
        """An unloaded soil at the start shape: every anchor where its point is."""
        return {"anchor": np.moveaxis(state.r, 0, -1), "slip": np.zeros(state.r.shape[1:]),
                "work": np.zeros(state.r.shape[1:]), "reaction": np.zeros(state.r.shape[1:] + (3,))}

    def energy(self, state):
        """A merit function for statics' line search [J/m] (nel, nq): the springs' energy at the
        committed anchors, s_u (E_t d_b phi_t(e_t) + E_n N_c d_b phi_n(|e_n|)), phi(x) = k x^2 / 2
        up to the yield and |x| - 1 / (2 k) beyond; its gradient is -f where s_u and t are held."""
        depth, _ = self.depth(state.r)
        s, _ = self.strength(depth)
        e_t, _, _, _, _, _, size, _, _ = self.offsets(state)
        return s * (self.a_t * _spring(np.abs(e_t), self.k_t) + self.a_n * _spring(size, self.k_n))

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,)."""
        return {"a_t": self.a_t[:, 0], "a_n": self.a_n[:, 0], "k_t": self.k_t[:, 0], "k_n": self.k_n[:, 0],
                "su0": self.su0[:, 0], "su1": self.su1[:, 0], "ramp": self.ramp[:, 0]}


def _spring(x, k):
    """Energy per unit yield force of an elastic-perfectly-plastic spring at offset x >= 0 [m]."""
    return np.where(k * x <= 1.0, 0.5 * k * x * x, x - 0.5 / k)


def plastic_dissipation(old, new, weights):
    """Plastic work [J] between two histories, ``old`` and ``new`` (record arrays (nel, nq) of the
    full points, e.g. the committed history before and after accepted steps): the soil's ``work``,
    the sum over the steps of (-f) . (q' - q) per unit length, integrated with the quadrature
    weights ``weights`` (nel, nq) [m]; >= 0 step by step by the return's construction."""
    return float(np.sum((new["soil"]["work"] - old["soil"]["work"]) * weights))


# ---------------------------------------------------------------------------- the compiled face
@njit(cache=True, _nrt=False)
def _strength(depth, su0, su1, ramp):
    """s_u and ds_u/d(depth) at one depth (``Soil.strength``)."""
    if depth <= 0.0:
        return 0.0, 0.0
    if depth >= ramp:
        return su0 + su1 * depth, su1
    return depth / ramp * (su0 + su1 * depth), (su0 + 2.0 * su1 * depth) / ramp


@njit(cache=True, _nrt=False)
def soil_point(ctx, p, old, new, state, hold, out):
    """The compiled face: the macro-element's reaction at one full point and its consistent tangent
    (A = -f_r, B = -f_dr), the trial history to ``new.soil``. See ``cablefem.compiled.kernels``."""
    q = p.soil
    if not q.active:
        return
    r, t, held, anchor = ctx.r, ctx.t, old.soil.anchor, new.soil.anchor
    e, e_n, shape, turn = ctx.soil.e, ctx.soil.e_n, ctx.soil.shape, ctx.soil.turn
    s, ds = _strength(-ctx.gap, q.su0, q.su1, q.ramp)
    for i in range(3):
        e[i] = r[i] - held[i]
    e_t = t[0] * e[0] + t[1] * e[1] + t[2] * e[2]
    for i in range(3):
        e_n[i] = e[i] - e_t * t[i]
    size = np.sqrt(e_n[0] * e_n[0] + e_n[1] * e_n[1] + e_n[2] * e_n[2])
    x = q.k_t * e_t
    c = min(max(x, -1.0), 1.0)
    slope = q.k_t if abs(x) <= 1.0 + ON_YIELD else 0.0
    plastic = q.k_n * size > 1.0 + ON_YIELD
    h = 1.0 / size if plastic else q.k_n
    moved, work = 0.0, 0.0
    for i in range(3):
        shape[i] = q.a_t * c * t[i] + q.a_n * h * e_n[i]
        out.f[i] -= s * shape[i]
        anchor[i] = r[i] - ((c / q.k_t * t[i] + h / q.k_n * e_n[i]) if s > 0.0 else 0.0)
        new.soil.reaction[i] = -s * shape[i]
        moved += (anchor[i] - held[i]) ** 2
        work += s * shape[i] * (anchor[i] - held[i])
    new.soil.slip = old.soil.slip + np.sqrt(moved)
    new.soil.work = old.soil.work + work
    if not ctx.jac or s <= 0.0:
        return
    radial = 1.0 / (size * size * size) if plastic else 0.0  # (e_n e_n^T / |e_n|^2) / |e_n|
    divisor = ctx.stretch if ctx.stretch > 0.0 else np.inf
    P, A, B, grad = ctx.P, out.A, out.B, ctx.grad_gap
    for i in range(3):
        for j in range(3):
            # -f_r: the strength's depth (depth = -gap) and the return's springs
            A[i, j] += -shape[i] * ds * grad[j] + s * (q.a_t * slope * t[i] * t[j]
                                                       + q.a_n * (h * P[i, j] - radial * e_n[i] * e_n[j]))
    for i in range(3):
        for j in range(3):
            turn_ij = t[i] * e_n[j] + e_t * P[i, j]
            turn[i, j] = turn_ij
    for i in range(3):
        for j in range(3):
            # d(h e_n)/d(e_n) = h I - radial e_n e_n^T, times turn = -|r'| d(e_n)/dr'
            normal = h * turn[i, j] - radial * e_n[i] * (e_n[0] * turn[0, j] + e_n[1] * turn[1, j]
                                                         + e_n[2] * turn[2, j])
            B[i, j] += s / divisor * (q.a_t * (slope * t[i] * e_n[j] + c * P[i, j]) - q.a_n * normal)


def build(setting):
    """A line of a scene with ``[soil]`` gets the soil (its parameters per element from the line
    types' ``nominal_diameter``); none without."""
    keys = setting.keys
    if keys is None:
        return None
    d_b = setting.props["nominal_diameter"]
    if np.any(~np.isfinite(d_b)):  # checked when a scene is read (io.checks), not in a sweep's cases
        name = next((s.type.name for s in setting.line.segments if s.type.nominal_diameter is None), "NAME")
        raise InputError("missing: [soil] needs the chain's bar diameter d_b (rui2025 Eq. 3)",
                         key=f"line_types.{name}.nominal_diameter")
    values = dict(DEFAULTS, **keys)
    k_n = values.get("stiffness_normal", 2.0 / d_b)
    k_t = values.get("stiffness_tangential", 1.0 / d_b)
    return Soil(setting.seabed, values["width_tangential"] * d_b,
                values["width_normal"] * values["bearing_factor"] * d_b, k_t, k_n,
                values["su_mudline"], values["su_gradient"], d_b)


_STRENGTH = v.limited(v.non_negative, "shear_strength")
SPEC = LoadSpec("soil", "full",
                (("a_t", "f8"), ("a_n", "f8"), ("k_t", "f8"), ("k_n", "f8"), ("su0", "f8"), ("su1", "f8"),
                 ("ramp", "f8")),
                soil_point, Soil,
                history=(("anchor", "f8", (3,)), ("slip", "f8"), ("work", "f8"), ("reaction", "f8", (3,))),
                # r - q, its part normal to the line, the reaction's shape, -|r'| d(e_n)/dr'
                scratch=(("e", "f8", (3,)), ("e_n", "f8", (3,)), ("shape", "f8", (3,)), ("turn", "f8", (3, 3))),
                frames=("reaction", "slip"), build=build, section="soil",
                keys={"su_mudline": _STRENGTH, "su_gradient": v.limited(v.non_negative, "strength_gradient"),
                      "bearing_factor": v.limited(v.positive, "coefficient"),
                      "width_normal": v.limited(v.positive, "coefficient"),
                      "width_tangential": v.limited(v.positive, "coefficient"),
                      "stiffness_normal": v.limited(v.positive, "soil_stiffness"),
                      "stiffness_tangential": v.limited(v.positive, "soil_stiffness"),
                      "installation": v.choice(INSTALLATIONS),
                      "installation_steps": v.limited(v.whole, "load_steps")},
                required=("su_gradient",))
