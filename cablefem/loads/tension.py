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
e); statics starts with it, see ``cablefem.statics``.
"""

import numpy as np

from . import Terms, identity_like, outer, unit_tangent

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
    membrane locking of curved elements of a stiff line (``cablefem.fem.LineFEM``).
    """

    rule = "reduced"

    def __init__(self, EA, beta=None, compression=False):
        self.EA = np.asarray(EA, dtype=float)[:, None]
        self.compression = compression  # True: T = EA e also for e < 0 (a statics start-up aid)
        beta = None if beta is None else np.asarray(beta, dtype=float)[:, None]
        self.beta = beta if beta is not None and np.any(beta > 0) else None

    def evaluate(self, state, jacobian=True):
        dr, dv = state.dr, state.dv
        t, stretch, divisor = unit_tangent(dr)
        e = stretch - 1.0
        damped = self.beta is not None and dv is not None
        rate = np.einsum("ceq,ceq->eq", t, dv) if damped else 0.0  # de/dt
        T = self.EA * (e + (self.beta * rate if damped else 0.0))
        active = np.full(e.shape, True) if self.compression else (e > 0.0) & (T > 0.0)
        T = np.where(active, T, 0.0)
        terms = Terms(flux=T * t)
        if not jacobian:
            return terms
        on = active.astype(float)
        dT_ddr = self.EA * on * t
        if damped:
            dT_ddr = dT_ddr + self.EA * self.beta * on * (dv - rate * t) / divisor
            terms.flux_dv = outer(t, self.EA * self.beta * on * t)
        tt = outer(t, t)
        eye = identity_like(t)
        terms.flux_dr = outer(t, dT_ddr) + (T / divisor) * (eye - tt) \
            + (SLACK_STIFFNESS * self.EA * (1.0 - on)) * eye
        return terms

    def energy(self, state):
        """Strain energy density EA e^2 / 2 [J/m] (nel, nq) of the elastic part (statics)."""
        e, _ = strain(state.dr)
        stretched = e if self.compression else np.maximum(e, 0.0)
        return 0.5 * self.EA * stretched**2
