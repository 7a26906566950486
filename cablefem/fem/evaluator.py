"""The evaluator of one line system: residual rows, tangent, factors and Newton steps, behind one
interface for both faces.

Statics and dynamics ask an evaluator for the rows M A + G (N, 3) at a point (X, V, A) and for the
tangent of the unknowns, g_x (K + v_x C + a_x (M + added mass)) (``cablefem.dynamics.integrator``:
v_x, a_x, g_x are the scheme's factors; statics has v_x = a_x = 0, g_x = 1), then factor the tangent
and solve for the step of the free DOFs. Two evaluators give the same numbers to round-off
(tests/test_fused.py, tests/test_statics.py, tests/test_catalog.py):

- ``NumpyEvaluator`` (here): the loads' numpy faces (``LineSystem.evaluate``, on scikit-fem's forms
  or the same sums on precomputed basis data), the consistent or lumped mass of
  ``cablefem.fem.forms.mass_matrix``, and SuperLU on the sparse free block;
- ``cablefem.compiled.evaluator.FusedEvaluator``: the compiled kernel over the load catalog, the
  banded tangent and LAPACK's banded LU.

``LineSystem.evaluator(compiled, lumped)`` gives a system's. The interface both keep:

    evaluate(X, V, A, v_x, a_x, jacobian=True, held=False, t=0.0, h=0.0) -> (rows, tangent or None)
                                      (h: the step's size [s], 0 in statics, for the loads whose
                                      history evolves in time: ``cablefem.loads.rope``)
    factorize(tangent, scale=1.0) -> factors, or None if singular
    solve(factors, rows) -> step (N_free, 3) of the free DOFs for the residual ``rows``
    solve_many(factors, rows) -> steps (m, N_free, 3) for m residuals (m, N, 3)
    mass_factors(X, V, A, tangent, t=0.0) -> factors of the free rows' mass (M + added mass) at a state,
                                             ``tangent`` the one ``evaluate`` gave with v_x = 0, a_x = 1
    inertia(A) -> rows M A (N, 3)
    keep(), hold(again) -> bool, release()   the branch holds of Newton's corrections (the numpy
                                             loads hold no branch: ``hold`` is False)
    compiled, full_newton_pays               what it is and whether full Newton pays (a compiled
                                             tangent costs about a residual, so "auto" Newton
                                             takes full steps; on the numpy path kept factors win)
"""

from functools import cached_property

import numpy as np
import scipy.sparse.linalg as spla

from cablefem.fem import clamp
from cablefem.fem.forms import mass_matrix


class Evaluator:
    """What both faces share: the system and its mass matrix, assembled on first use."""

    compiled = False
    full_newton_pays = False

    def __init__(self, system, lumped=False):
        self.system = system
        self.lumped = lumped

    @cached_property
    def M(self):
        """The mass matrix (N 3, N 3), CSR (``forms.mass_matrix``), its clamped tangent rows projected
        as the loads' are (``cablefem.fem.clamp``); the compiled kernel carries the mass itself, so
        there it is assembled only if M A is needed at a nonzero A."""
        M = mass_matrix(self.system, self.lumped)
        return clamp.project(self.system.clamps, M, self.system.fem, free_only=False) if self.system.clamps else M

    def inertia(self, A):
        """Rows (N, 3) of M A (zeros, without assembling M, at A = 0: a start at rest)."""
        if not A.any():
            return np.zeros(A.shape)
        return (self.M @ A.ravel()).reshape(A.shape)

    def keep(self):
        """Remember the branch state of the last evaluation as the base of Newton's corrections."""

    def hold(self, again):
        """Hold the branches the last evaluation reached; whether anything is held and changed."""
        return False

    def release(self):
        """Hold no branch."""


class NumpyEvaluator(Evaluator):
    """The loads' numpy faces and a sparse LU (see the module docstring); the tangent is the
    loads' blocks with the a_x of the mass that ``factorize`` adds."""

    @cached_property
    def M_free(self):
        """The mass matrix's block of the free DOFs, CSR."""
        fem = self.system.fem
        return self.M[fem.free_vector_dofs][:, fem.free_vector_dofs].tocsr()

    def evaluate(self, X, V, A, v_x, a_x, jacobian=True, held=False, t=0.0, h=0.0):
        system = self.system
        state = system.state(X, V, A, t, inv_h=1.0 / h if h > 0.0 else 0.0)
        residual, blocks = system.evaluate(state, jacobian, v_x, a_x)
        return residual + self.inertia(A), ((blocks, a_x) if jacobian else None)

    def factorize(self, tangent, scale=1.0):
        blocks, a_x = tangent
        K = self.system.matrix(blocks)
        if a_x:
            K = scale * (K + a_x * self.M_free)
        elif scale != 1.0:
            K = scale * K
        try:
            return spla.splu(K.tocsc())
        except RuntimeError:
            return None

    def solve(self, factors, rows):
        return factors.solve(-rows[self.system.fem.free_dofs].ravel()).reshape(-1, 3)

    def solve_many(self, factors, rows):
        return np.array([self.solve(factors, part) for part in rows])

    def mass_factors(self, X, V, A, tangent, t=0.0):
        system = self.system
        blocks, _ = tangent
        static = system.evaluate(system.state(X, V, A, t), jacobian=True)[1]
        K = system.matrix(blocks) - system.matrix(static) + self.M_free
        if system.clamps:  # the constraint, which the difference took out
            K = K + clamp.constraint_matrix(system.clamps, system.fem)
        try:
            return spla.splu(K.tocsc())
        except RuntimeError:
            return None
