"""Bending stiffness: the elastic energy 1/2 int EI kappa^2 ds of a line on Hermite elements.

The curvature is that of the line as it is, for any rotation and stretch: of the space curve
r(s) parametrised by its unstretched arc length s,

    kappa = |r' x r''| / |r'|^3

(do Carmo, *Differential Geometry of Curves and Surfaces*, 1976, Sec. 1-5, Exercise 12: the
curvature of a regular curve in any parametrisation), the rate of turn of the tangent per unit
of stretched length, as MoorDyn's node couples measure it (its ``GetCurvature``: the turn between
two segments over their stretched lengths). The bending moment is M = EI kappa, and the energy
per unit unstretched length W = EI kappa^2 / 2 = EI |c|^2 / (2 u^3) with a = r', b = r'',
c = a x b and u = |a|^2. Its first variation is int N . v' + Q . v'' ds with

    N = dW/da = EI ((b x c) / u^3 - 3 |c|^2 a / u^4),   Q = dW/db = EI (c x a) / u^3,

(the flux against v', the moment against v'': ``cablefem.fem.forms``), and the exact tangent
(the Hessian of W in (a, b), symmetric: N_b = Q_a^T), with [x] the cross-product matrix
[x] y = x x y,

    N_a = EI (-[b]^2 / u^3 - 6 ((b x c) a^T + a (b x c)^T) / u^4 - 3 |c|^2 I / u^4
              + 24 |c|^2 a a^T / u^5),
    N_b = EI ((-[c] + [b][a]) / u^3 - 6 a (c x a)^T / u^4),
    Q_a = EI (([c] + [a][b]) / u^3 - 6 (c x a) a^T / u^4),
    Q_b = -EI [a]^2 / u^3.

This is the Kirchhoff rod's bending without twist (an isotropic section, whose torsion decouples
from its centreline for a line free to twist), exact for large rotations; no bending damping.
Where two points of the line coincide (|r'| = 0) the load gives nothing (``unit_tangent``'s rule).
"""

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms, compose, identity_like, outer
from cablefem.loads._small import unit_divisor


def _cross(x, y):
    """Pointwise cross products of (3, ...) arrays."""
    return np.stack([x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]])


def _skew(x):
    """Cross-product matrices [x] (3, 3, ...) of (3, ...) arrays: [x] y = x x y."""
    zero = np.zeros_like(x[0])
    return np.array([[zero, -x[2], x[1]], [x[2], zero, -x[0]], [-x[1], x[0], zero]])


def _inverse_square(dr):
    """1 / |r'|^2 (...), zero where r' = 0."""
    u = np.einsum("c...,c...->...", dr, dr)
    return np.where(u > 0.0, 1.0 / np.where(u > 0.0, u, 1.0), 0.0)


def curvature(dr, ddr):
    """Curvature kappa [1/m] (...) from r' and r'' (3, ...): |r' x r''| / |r'|^3 (0 where r' = 0)."""
    c = _cross(dr, ddr)
    inv = _inverse_square(dr)
    return np.sqrt(np.einsum("c...,c...->...", c, c) * inv ** 3)


class Bending:
    """Bending stiffness EI [N m^2] per element (nel,), evaluated at the full points of a line on
    Hermite elements (the state's r'')."""

    name = "bending"
    rule = "full"

    def __init__(self, EI):
        self.EI = np.asarray(EI, dtype=float)[:, None]

    def evaluate(self, state, jacobian=True):
        a, b = state.dr, state.ddr
        c = _cross(a, b)
        inv = _inverse_square(a)
        inv3, inv4 = inv ** 3, inv ** 4
        cc = np.einsum("ceq,ceq->eq", c, c)
        bc, ca = _cross(b, c), _cross(c, a)
        EI = self.EI
        terms = Terms(flux=EI * (bc * inv3 - 3.0 * cc * a * inv4), moment=EI * ca * inv3)
        if not jacobian:
            return terms
        A, B, C = _skew(a), _skew(b), _skew(c)
        eye = identity_like(a)
        terms.flux_dr = EI * (-compose(B, B) * inv3 - 6.0 * (outer(bc, a) + outer(a, bc)) * inv4
                              - 3.0 * cc * eye * inv4 + 24.0 * cc * outer(a, a) * inv4 * inv)
        terms.flux_ddr = EI * ((compose(B, A) - C) * inv3 - 6.0 * outer(a, ca) * inv4)
        terms.moment_dr = EI * ((C + compose(A, B)) * inv3 - 6.0 * outer(ca, a) * inv4)
        terms.moment_ddr = -EI * compose(A, A) * inv3
        return terms

    def energy(self, state):
        """Bending energy density EI kappa^2 / 2 [J/m] (nel, nq)."""
        return 0.5 * self.EI * curvature(state.dr, state.ddr) ** 2

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``), each (nel,)."""
        return {"EI": self.EI[:, 0]}


@njit(cache=True, _nrt=False)
def bending_point(ctx, p, old, new, state, hold, out):
    """The compiled face: at one full point of a Hermite line, the flux N and the moment Q (against
    phi', phi'') and their blocks D = N_a, E = N_b, F = Q_a, G = Q_b (module docstring)."""
    q = p.bending
    if not q.active:
        return
    a, b = ctx.dr, ctx.ddr
    EI = q.EI
    stretch = np.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    divisor = unit_divisor(stretch)
    inv = 1.0 / (divisor * divisor)
    inv3 = inv * inv * inv
    inv4 = inv3 * inv
    c0, c1, c2 = a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
    cc = c0 * c0 + c1 * c1 + c2 * c2
    bc = (b[1] * c2 - b[2] * c1, b[2] * c0 - b[0] * c2, b[0] * c1 - b[1] * c0)
    ca = (c1 * a[2] - c2 * a[1], c2 * a[0] - c0 * a[2], c0 * a[1] - c1 * a[0])
    for i in range(3):
        out.N[i] += EI * (bc[i] * inv3 - 3.0 * cc * a[i] * inv4)
        out.Q[i] += EI * ca[i] * inv3
    if not ctx.jac:
        return
    c = (c0, c1, c2)
    for i in range(3):
        for j in range(3):
            delta = 1.0 if i == j else 0.0
            # [x][y] = y x^T - (x . y) I; [x]_ij = -eps_ijk x_k
            ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
            bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2]
            aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2]
            BB = b[j] * b[i] - bb * delta
            BA = a[i] * b[j] - ab * delta
            AB = b[i] * a[j] - ab * delta
            AA = a[j] * a[i] - aa * delta
            Cij = _skew_entry(c, i, j)
            out.D[i, j] += EI * (-BB * inv3 - 6.0 * (bc[i] * a[j] + a[i] * bc[j]) * inv4
                                 - 3.0 * cc * delta * inv4 + 24.0 * cc * a[i] * a[j] * inv4 * inv)
            out.E[i, j] += EI * ((BA - Cij) * inv3 - 6.0 * a[i] * ca[j] * inv4)
            out.F[i, j] += EI * ((Cij + AB) * inv3 - 6.0 * ca[i] * a[j] * inv4)
            out.G[i, j] += -EI * AA * inv3


@njit(cache=True, inline="always", _nrt=False)
def _skew_entry(x, i, j):
    """Entry (i, j) of the cross-product matrix [x]."""
    if i == j:
        return 0.0
    k = 3 - i - j
    sign = 1.0 if (j - i) % 3 == 1 else -1.0  # [x]_01 = -x2, [x]_12 = -x0, [x]_20 = -x1
    return -sign * x[k]


def build(setting):
    """A line whose line types bend (EI > 0 somewhere) carries its bending (on Hermite elements:
    ``Line`` refuses EI > 0 on Lagrange ones)."""
    EI = setting.props["EI"]
    if not np.any(EI > 0.0):
        return None
    return Bending(EI)


SPEC = LoadSpec("bending", "full", (("EI", "f8"),), bending_point, Bending, build=build)
