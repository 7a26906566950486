"""Axial tension with internal damping, T = EA (e + beta de/dt) (desire2023 Eq. 2).

The strain over unstretched arc length is e = |r'| - 1 and the line carries
no compression: T = 0 when e <= 0 (a slack element), and the damping part
cannot make a taut element push (T >= 0). The internal force is the flux
N = T t with t = r'/|r'| (the first term on the right of Eq. 1), whose
consistent tangent has a material part EA t (x) t and a geometric part
T (I - t (x) t) / |r'|. A slack element has no stiffness at all, which
would make the Newton matrix singular (a line in a vertical plane has no
out-of-plane stiffness without tension): its tangent gets a tiny isotropic
stiffness ``SLACK_STIFFNESS`` EA instead, which changes the Newton path, not
the equilibrium. ``compression=True`` lets the line push (T = EA e for all
e); statics starts with it, see ``cablefem.statics.newton``.

Two damping laws, per line type (``damping_when_slack``): by default the one
above, where a slack element carries nothing (a chain's links go loose: no
force, no dissipation); or MoorDyn-C's (``Line.cpp``: ``Td[i] = BA ldstr[i] /
l[i] qs[i]``, only the elastic part zeroed when slack),

    T = EA max(e, 0) + EA beta de/dt,

where the damping part acts in slack segments too and may push. MoorDyn input
files are read with it, so that both codes run the same physics.

A line type that bends (EI > 0, ``cablefem.loads.bending``) is a rod: its elements push too,
T = EA (e + beta de/dt) for every e (``rod``). Without it a straight bending line would have no
axial stiffness at zero strain, and a bent one under no axial load (an arc under an end moment)
none at all; MoorDyn's lines never push, whatever their EI (its rods do).
"""

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms, identity_like, outer, unit_tangent
from cablefem.loads._small import unit_divisor

#: tangent stiffness of a slack element, as a fraction of EA
SLACK_STIFFNESS = 1e-6


def strain(dr):
    """Engineering strain e = |dr/ds| - 1 and the stretch |dr/ds|, each (nel, nq)."""
    stretch = np.sqrt(np.einsum("ceq,ceq->eq", dr, dr))
    return stretch - 1.0, stretch


def axial_tension(dr, EA, beta=None, dv=None):
    """Tension T [N] (nel, nq) from dr/ds and, with damping, dv/ds (3, nel, nq); EA, beta (nel, 1)."""
    _, stretch, divisor = unit_tangent(dr)
    e = stretch - 1.0
    T = EA * e
    if beta is not None and dv is not None:
        T = T + EA * beta * np.einsum("ceq,ceq->eq", dr, dv) / divisor
    return np.where(e > 0.0, np.maximum(T, 0.0), 0.0)


class Tension:
    """Axial stiffness EA [N] and damping beta [s] per element, arrays of shape (nel,).

    Evaluated at the reduced quadrature (p Gauss points for order p), which removes the
    membrane locking of curved elements of a stiff line (``cablefem.fem.discretisation.LineFEM``).
    """

    name = "tension"
    rule = "reduced"

    def __init__(self, EA, beta=None, compression=False, slack_damping=None, rod=None):
        self.EA = np.asarray(EA, dtype=float)[:, None]
        self.compression = compression  # True: T = EA e also for e < 0 (a statics start-up aid)
        # per element: pushes always (a line type with EI > 0), None if no element does
        self.rod = np.asarray(rod, dtype=bool)[:, None] if rod is not None and np.any(rod) else None
        beta = None if beta is None else np.asarray(beta, dtype=float)[:, None]
        self.beta = beta if beta is not None and np.any(beta > 0) else None
        # per element: MoorDyn-C's law, the damping part acting in slack segments too
        self.slack_damping = (np.asarray(slack_damping, dtype=bool)[:, None]
                              if slack_damping is not None and np.any(slack_damping) else None)

    def evaluate(self, state, jacobian=True):
        dr, dv = state.dr, state.dv
        t, stretch, divisor = unit_tangent(dr)
        e = stretch - 1.0
        damped = self.beta is not None and dv is not None
        rate = np.einsum("ceq,ceq->eq", t, dv) if damped else 0.0  # de/dt
        T = self.EA * (e + (self.beta * rate if damped else 0.0))
        active = np.full(e.shape, True) if self.compression else (e > 0.0) & (T > 0.0)
        if self.rod is not None:
            active = active | self.rod
        T = np.where(active, T, 0.0)
        elastic = damping = active.astype(float)  # where each part of T acts
        if self.slack_damping is not None and damped and not self.compression:
            # MoorDyn-C: the elastic part is zero when slack, the damping part acts always
            moordyn = self.EA * (np.maximum(e, 0.0) + self.beta * rate)
            law = self.slack_damping if self.rod is None else self.slack_damping & ~self.rod
            T = np.where(law, moordyn, T)
            elastic = np.where(law, (e > 0.0).astype(float), elastic)
            damping = np.where(law, 1.0, damping)
        terms = Terms(flux=T * t)
        if not jacobian:
            return terms
        dT_ddr = self.EA * elastic * t
        if damped:
            dT_ddr = dT_ddr + self.EA * self.beta * damping * (dv - rate * t) / divisor
            terms.flux_dv = outer(t, self.EA * self.beta * damping * t)
        tt = outer(t, t)
        eye = identity_like(t)
        terms.flux_dr = outer(t, dT_ddr) + (T / divisor) * (eye - tt) \
            + (SLACK_STIFFNESS * self.EA * (1.0 - elastic)) * eye
        return terms

    def energy(self, state):
        """Strain energy density EA e^2 / 2 [J/m] (nel, nq) of the elastic part (statics)."""
        e, _ = strain(state.dr)
        stretched = e if self.compression else np.maximum(e, 0.0)
        if self.rod is not None and not self.compression:
            stretched = np.where(self.rod, e, stretched)
        return 0.5 * self.EA * stretched**2

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,); ``pushes``: the
        line may push (``compression``), read when a kernel is built."""
        nel = self.EA.shape[0]
        beta = np.zeros(nel) if self.beta is None else self.beta[:, 0]
        slack = np.zeros(nel, dtype=bool) if self.slack_damping is None else self.slack_damping[:, 0]
        pushes = np.full(nel, self.compression) if self.rod is None else self.compression | self.rod[:, 0]
        return {"EA": self.EA[:, 0], "beta": beta, "pushes": pushes, "slack_damping": slack}


@njit(cache=True, _nrt=False)
def tension_point(ctx, p, old, new, state, hold, out):
    """The compiled face: the flux N = T t at one reduced point and D = N_dr + v_x N_dv, with the
    line pulling and pushing where Newton's taut correction holds it (``hold.tension.pull``);
    ``state.tension.taut``: whether the point is taut (see ``cablefem.compiled.kernels``)."""
    q = p.tension
    if not q.active:
        return
    dr, dv, N, D = ctx.dr, ctx.dv, out.N, out.D
    EA, beta, v_x = q.EA, q.beta, ctx.v_x
    stretch = np.sqrt(dr[0] * dr[0] + dr[1] * dr[1] + dr[2] * dr[2])
    divisor = unit_divisor(stretch)
    t0, t1, t2 = dr[0] / divisor, dr[1] / divisor, dr[2] / divisor
    e = stretch - 1.0
    rate = t0 * dv[0] + t1 * dv[1] + t2 * dv[2]
    T = EA * (e + beta * rate)
    pulled = q.pushes or (ctx.held and hold.tension.pull)
    if q.slack_damping and not q.pushes:  # MoorDyn-C: the damping part acts in slack segments too
        elastic = 1.0 if pulled or e > 0.0 else 0.0
        damping = 1.0
        T = EA * (elastic * e + beta * rate)
        taut = e > 0.0
    else:
        active = pulled or (e > 0.0 and T > 0.0)
        if not active:
            T = 0.0
        elastic = damping = 1.0 if active else 0.0
        taut = e > 0.0 and T > 0.0
    N[0] += T * t0
    N[1] += T * t1
    N[2] += T * t2
    if ctx.jac:
        t = (t0, t1, t2)
        for i in range(3):
            for j in range(3):
                dT = EA * elastic * t[j] + EA * beta * damping * (dv[j] - rate * t[j]) / divisor
                delta = 1.0 if i == j else 0.0
                D[i, j] += t[i] * dT + (T / divisor) * (delta - t[i] * t[j]) \
                    + SLACK_STIFFNESS * EA * (1.0 - elastic) * delta + v_x * EA * beta * damping * t[i] * t[j]
    state.tension.taut = taut


@njit(cache=True, _nrt=False)
def tension_hold(base, state, hold, p, again):
    """Hold the taut branch where the trial pulled a point slack at the base taut (and, ``again``,
    where it is held already): Newton's taut correction (``cablefem.dynamics.policy``)."""
    flag = (state.tension.taut and not base.tension.taut) or (again and hold.tension.pull)
    changed = flag != hold.tension.pull
    hold.tension.pull = flag
    return flag, changed


def build(setting):
    """Every line carries its tension, with each line type's damping law (EA = 0 on the elements of
    a line type with an axial law of its own: ``cablefem.loads.rope`` carries them); a line type
    that bends pushes."""
    props = setting.props
    return Tension(props["EA"] * ~props["rope"], props["damping"], slack_damping=props["damping_when_slack"],
                   rod=props["EI"] > 0.0)


SPEC = LoadSpec("tension", "reduced", (("EA", "f8"), ("beta", "f8"), ("pushes", "?"), ("slack_damping", "?")),
                tension_point, Tension,
                state=(("taut", "?"),), hold=(("pull", "?"),), hold_rule=tension_hold, build=build)
