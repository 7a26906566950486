"""scikit-fem forms of the line's weak form: the reference assembly.

The loads (``cablefem.loads``) give, at quadrature points, a force f and a
flux N per unit unstretched length and the blocks of their derivatives; the
weak form of desire2023 Eq. 1 is then

    G(r; v) = int N . v' - f . v ds,
    dG[u; v] = int v . (A u + B u') + v' . (C u + D u') ds,

and the inertia int m a . v ds. These decorated forms assemble it with
scikit-fem's own machinery on the ``ElementVector`` basis; ``LineFEM`` does
the same sums with precomputed basis data for speed, and the tests check
that both agree.
"""

import numpy as np
from skfem import BilinearForm, LinearForm
from skfem.helpers import dot


def _block(M, u):
    """Pointwise matrix-vector product of a (3, 3, ...) block with a (3, ...) field."""
    return np.einsum("ab...,b...->a...", M, u)


@LinearForm
def load_vector(v, w):
    """int N . v' - f . v ds with w.flux, w.force of shape (3, nel, nq)."""
    return dot(w.flux, v.grad[:, 0]) - dot(w.force, v)


@BilinearForm
def tangent(u, v, w):
    """int v . (A u + B u') + v' . (C u + D u') ds with blocks w.A ... w.D (3, 3, nel, nq)."""
    du, dv = u.grad[:, 0], v.grad[:, 0]
    return (dot(v, _block(w.A, u) + _block(w.B, du))
            + dot(dv, _block(w.C, u) + _block(w.D, du)))


@BilinearForm
def mass(u, v, w):
    """Consistent mass int m u . v ds with w.m [kg/m] of shape (nel, nq)."""
    return w.m * dot(u, v)
