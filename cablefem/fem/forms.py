"""scikit-fem forms of the line's weak form: the reference assembly.

The loads (``cablefem.loads``) give, at quadrature points, a force f and a
flux N per unit unstretched length and the blocks of their derivatives; the
weak form of desire2023 Eq. 1 is then

    G(r; v) = int N . v' - f . v ds,
    dG[u; v] = int v . (A u + B u') + v' . (C u + D u') ds,

and the inertia int m a . v ds. On Hermite elements a load may also give a
moment Q against v'' (the bending load, ``cablefem.loads.bending``), which adds

    int Q . v'' ds   and   int v' . E u'' + v'' . (F u' + G u'') ds. These decorated forms assemble it with
scikit-fem's own machinery on the ``ElementVector`` basis; ``LineFEM`` does
the same sums with precomputed basis data for speed, and the tests check
that both agree.
"""

import numpy as np
import scipy.sparse as sp
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


@LinearForm
def moment_vector(v, w):
    """int Q . v'' ds with w.moment (3, nel, nq) (Hermite elements: v.hess exists)."""
    return dot(w.moment, v.hess[:, 0, 0])


@BilinearForm
def curvature_tangent(u, v, w):
    """int v' . E u'' + v'' . (F u' + G u'') ds with blocks w.E, w.F, w.G (3, 3, nel, nq)."""
    du, dv, ddu, ddv = u.grad[:, 0], v.grad[:, 0], u.hess[:, 0, 0], v.hess[:, 0, 0]
    return dot(dv, _block(w.E, ddu)) + dot(ddv, _block(w.F, du) + _block(w.G, ddu))


@BilinearForm
def mass(u, v, w):
    """Consistent mass int m u . v ds with w.m [kg/m] of shape (nel, nq)."""
    return w.m * dot(u, v)


@BilinearForm
def scalar_mass(u, v, w):
    """int m u v ds on a scalar basis, w.m [kg/m] of shape (nel, nq): ``mass`` between like
    components (its u . v is u_c v_c there, zero between different components)."""
    return w.m * (u * v)


def mass_matrix(system, lumped=False):
    """The line's mass matrix (N 3, N 3), CSR: consistent (``mass``, assembled as ``scalar_mass``
    on the scalar basis once for the three components: the same numbers without the vector
    basis and its zero blocks), or lumped (row sums; order 1 only)."""
    fem = system.fem
    m = system.props["mass"][:, None] * np.ones_like(fem.full.dx)
    S = scalar_mass.assemble(fem.scalar_basis, m=m).tocsr()
    if fem.skfem_dof is not None:  # Hermite: positions, then tangents (``LineFEM``)
        S = S[fem.skfem_dof][:, fem.skfem_dof]
        S.sort_indices()
    M = _per_component(S)
    if lumped:
        if fem.order != 1:
            raise ValueError("a lumped mass needs order 1 elements")
        M = sp.diags(np.asarray(M.sum(axis=1)).ravel()).tocsr()
    return M


def _per_component(S):
    """kron(S, I_3) in CSR for a canonical CSR S (n, n): row 3 i + c holds row i of S at the
    columns 3 j + c (scikit-fem's vector DOF order); scipy's kron took ~0.7 ms at 15 nodes."""
    n, counts = S.shape[0], np.diff(S.indptr)
    row_counts = np.repeat(counts, 3)
    indptr = np.zeros(3 * n + 1, dtype=S.indptr.dtype)
    np.cumsum(row_counts, out=indptr[1:])
    source = np.repeat(np.repeat(S.indptr[:-1], 3) - indptr[:-1], row_counts) + np.arange(indptr[-1])
    component = np.repeat(np.tile(np.arange(3), n), row_counts)
    return sp.csr_matrix((S.data[source], 3 * S.indices[source] + component, indptr), shape=(3 * n, 3 * n))
