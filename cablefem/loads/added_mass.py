"""Added mass per unit unstretched length (desire2023 Eq. 3, f_mn, with a tangential
coefficient as MoorDyn's CaAx; times the stretch |r'| = 1 + e of Eq. 1).

    f = -|r'| rho A (Ca_n (I - t t^T) + Ca_t t t^T) a,   A = pi d^2 / 4,

with t = r'/|r'| and a the line's acceleration. Still water and a uniform
current have no fluid acceleration, so there is no Froude-Krylov term. The
load enters the residual like a mass matrix that depends on r'; its exact
derivatives are force_a (that matrix) and force_dr (through t and |r'|).
Without an acceleration in the state (statics, or an integrator that keeps
added mass elsewhere) the load contributes nothing.
"""

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms, identity_like, outer, unit_tangent
from cablefem.loads._small import dot


class AddedMass:
    """Added mass: diameter d [m], Ca_normal, Ca_tangential [-] per element (nel,),
    water density rho [kg/m^3]."""

    name = "added_mass"

    def __init__(self, diameter, Ca_normal, Ca_tangential, water_density):
        rho_area = water_density * np.pi * np.asarray(diameter, dtype=float) ** 2 / 4.0
        self.normal = (rho_area * np.asarray(Ca_normal, dtype=float))[:, None]  # [kg/m]
        self.tangential = (rho_area * np.asarray(Ca_tangential, dtype=float))[:, None]

    def matrix(self, dr):
        """Added mass per unit unstretched length |r'| rho A (Ca_n P + Ca_t T) [kg/m] (3, 3, nel, nq)."""
        t, stretch, _ = unit_tangent(dr)
        return stretch * (self.normal * identity_like(t) + (self.tangential - self.normal) * outer(t, t))

    def evaluate(self, state, jacobian=True):
        if state.a is None:
            return Terms()
        dr, a = state.dr, state.a
        t, stretch, _ = unit_tangent(dr)
        along = np.einsum("ceq,ceq->eq", a, t)
        difference = self.tangential - self.normal
        per_stretched = self.normal * a + difference * along * t  # (Ca_n P + Ca_t T) rho A a
        terms = Terms(force=-stretch * per_stretched)
        if not jacobian:
            return terms
        eye = identity_like(t)
        tangential_projector = outer(t, t)
        terms.force_a = -stretch * (self.normal * eye + difference * tangential_projector)
        # d((a . t) t)/dt = (a . t) I + t a^T; dt/dr' = (I - t t^T)/|r'|; d|r'|/dr' = t^T
        dk_dt = difference * (along * eye + outer(t, a))
        terms.force_dr = -(outer(per_stretched, t)
                           + np.einsum("ab...,bc...->ac...", dk_dt, eye - tangential_projector))
        return terms

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,)."""
        return {"normal": self.normal[:, 0], "tangential": self.tangential[:, 0]}


@njit(cache=True, _nrt=False)
def added_mass_point(ctx, p, old, new, state, hold, out):
    """The compiled face: added mass, normal and tangential, at one full point (see
    ``cablefem.compiled.kernels``; ``ctx.P``, the normal projector, is set when a tangent is)."""
    m = p.added_mass
    normal, tangential = m.normal, m.tangential
    if not m.active or not (normal > 0.0 or tangential > 0.0):
        return
    acc, t, P, stretch, a_x = ctx.a, ctx.t, ctx.P, ctx.stretch, ctx.a_x
    f, Ab, Bb = out.f, out.A, out.B
    per = ctx.added_mass.per
    along = dot(acc, t)
    diff = tangential - normal
    for i in range(3):
        per[i] = normal * acc[i] + diff * along * t[i]
        f[i] -= stretch * per[i]
    if not ctx.jac:
        return
    # Bb += per t^T + diff ((a.t) I + t a^T) P = per t^T + diff ((a.t) P + t a_perp^T)
    for i in range(3):
        for j in range(3):
            Ab[i, j] += a_x * stretch * ((normal if i == j else 0.0) + diff * t[i] * t[j])
            Bb[i, j] += per[i] * t[j] + diff * (along * P[i, j] + t[i] * (acc[j] - along * t[j]))


def build(setting):
    """Added mass in dynamics, when an added-mass coefficient is not zero (in waves
    ``cablefem.loads.morison`` has it)."""
    props = setting.props
    if not setting.dynamic or not (np.any(props["Ca_normal"] > 0) or np.any(props["Ca_tangential"] > 0)):
        return None
    if setting.environment.waves is not None:
        return None
    return AddedMass(props["diameter"], props["Ca_normal"], props["Ca_tangential"], setting.environment.water_density)


SPEC = LoadSpec("added_mass", "full", (("normal", "f8"), ("tangential", "f8")), added_mass_point, AddedMass,
                scratch=(("per", "f8", (3,)),), build=build)
