"""Clamped ends of a line on Hermite elements: the tangent r' held along a direction d.

A clamp (``anchor_tangent``, ``fairlead_tangent``: a bend stiffener's root, a hang-off, a
cantilever) fixes the direction of the end's tangent row X_t, not its magnitude |r'| = 1 + e,
which the axial strain sets. The row's three equations become

    d (d . R_t) + k (I - d d^T) X_t = 0,

the residual's component along d (the force conjugate to the free magnitude) and the constraint
(I - d d^T) X_t = 0 scaled by k = EA h of the end element, the order of the row's own stiffness
(the scale sets no answer, only the conditioning). The tangent's rows there are d d^T K_t + k
(I - d d^T) on the diagonal block: the band is unchanged, and a state satisfying the constraint
keeps it under any Newton increment. R_t is the whole row, inertia included: an integrator's mass
rows at X_t are projected the same way (``project``). The compiled face is
``cablefem.compiled.kernels``' ``_clamp`` (the end element's rows, where its inertia is too).
"""

from collections import namedtuple

import numpy as np
import scipy.sparse as sp

#: a clamped end: its tangent row, its unit direction d (3,) and the constraint's scale k [N m]
Clamp = namedtuple("Clamp", "row direction scale")


def clamps(fem, EA):
    """The clamped ends of ``fem`` (a ``LineFEM``) with EA (nel,) [N] per element, as a list of
    ``Clamp`` (empty for a line without clamps)."""
    out = []
    h = np.diff(fem.mesh.p[0])
    for end, direction in enumerate(fem.clamped):
        if direction is None:
            continue
        element = 0 if end == 0 else fem.n_elements - 1
        out.append(Clamp(fem.tangent_dofs[end], np.asarray(direction, dtype=float),
                         float(EA[element] * h[element])))
    return out


def constrain_rows(clamps, X, rows):
    """The clamped rows of ``rows`` (N, 3), in place: d (d . R_t) + k (I - d d^T) X_t."""
    for c in clamps:
        d = c.direction
        x = X[c.row]
        rows[c.row] = d * (d @ rows[c.row]) + c.scale * (x - d * (d @ x))
    return rows


def reaction_moments(system, X, rows=None):
    """The moments (2, 3) [N m] the anchor's and the fairlead's clamp exert on the line at X (N, 3),
    zero at an end that is not clamped, from the rows R_t (2, 3) of the clamped tangents before the
    constraint replaced them (M A + G; default: the static loads' at X). R_t is the force conjugate to
    r'(end): a turn dtheta of the tangent, dr' = dtheta x r', does the work dtheta . (r' x R_t), which
    the clamp balances (the reaction, as the end forces are the rows of the end positions: order 4 in
    the elastica where EI kappa read from r'' at the clamp converges at order 1.4, verification/bending)."""
    if rows is None:
        loads = system.evaluate(system.state(X), jacobian=False, constrained=False)[0]
        rows = np.array([loads[row] for row in system.fem.tangent_dofs]) if system.clamps else np.zeros((2, 3))
    moments = np.zeros((2, 3))
    for c in system.clamps:
        end = system.fem.tangent_dofs.index(c.row)
        moments[end] = -np.cross(X[c.row], rows[end])
    return moments


def satisfy(clamps, X):
    """X (N, 3) with each clamped tangent row turned onto its direction, its magnitude kept (in place):
    a start that meets the constraints."""
    for c in clamps:
        X[c.row] = c.direction * float(np.linalg.norm(X[c.row]))
    return X


def _blocks(clamps, fem, free_only, scaled):
    """A sparse (3 n, 3 n) matrix holding (I - d d^T) (times k if ``scaled``) at each clamped row's
    diagonal block, n the free rows (``free_only``) or all."""
    n = len(fem.free_dofs) if free_only else fem.n_dofs
    rows, cols, values = [], [], []
    for c in clamps:
        j = int(np.searchsorted(fem.free_dofs, c.row)) if free_only else c.row
        block = np.eye(3) - np.outer(c.direction, c.direction)
        block = c.scale * block if scaled else block
        index = 3 * j + np.arange(3)
        rows.append(np.repeat(index, 3))
        cols.append(np.tile(index, 3))
        values.append(block.ravel())
    return sp.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(3 * n, 3 * n))


def project(clamps, K, fem, free_only=True):
    """K (CSR) with each clamped row's block rows projected on d: K - (I - d d^T) K there."""
    return (K - _blocks(clamps, fem, free_only, False) @ K).tocsr()


def constrain_matrix(clamps, K, fem, free_only=True):
    """The tangent K (CSR) of the loads with the clamped rows made constraints: d d^T K_t + k
    (I - d d^T) on the row's diagonal block."""
    return (project(clamps, K, fem, free_only) + _blocks(clamps, fem, free_only, True)).tocsr()


def constraint_matrix(clamps, fem, free_only=True):
    """The constraint's own part k (I - d d^T) on the clamped rows' diagonal blocks (CSR)."""
    return _blocks(clamps, fem, free_only, True)
