"""An integrator that is not cablefem's, added as docs/architecture.md tells a newcomer to: one file
with its scheme's arithmetic (numba, ``cablefem.dynamics.scheme``) and its ``Integrator`` subclass,
and one registry entry (``INTEGRATORS["backward-euler"] = BackwardEuler``).
``tests/test_integrator_extension.py`` runs it on a line and on a junction network, compiled and on
the Python ops.

Backward Euler on X and V: V_{n+1} = (X_{n+1} - X_n) / h, A_{n+1} = (V_{n+1} - V_n) / h, the loads
at t_{n+1}; first order, L-stable.
"""

import numpy as np
from numba import njit

from cablefem.dynamics.integrator import Integrator
from cablefem.dynamics.scheme import Scheme

PARAMETERS = np.dtype([("unused", "f8")])


@njit(cache=True, inline="always", _nrt=False)
def begin(scheme, clock, X, V, A, memory, guess, h):
    c = clock[0]
    c.v_x, c.a_x, c.g_x, c.h, c.t_eval = 1.0 / h, 1.0 / (h * h), 1.0, h, c.t + h
    for i in range(X.shape[0]):
        for a in range(3):
            guess[i, a] = X[i, a] + h * V[i, a] + 0.5 * h * h * A[i, a]


@njit(cache=True, inline="always", _nrt=False)
def point(scheme, clock, X, V, A, memory, X1, Xe, Ve, Ae):
    h = clock[0].h
    for i in range(X1.shape[0]):
        for a in range(3):
            Xe[i, a] = X1[i, a]
            Ve[i, a] = (X1[i, a] - X[i, a]) / h
            Ae[i, a] = (Ve[i, a] - V[i, a]) / h


@njit(cache=True, inline="always", _nrt=False)
def accept(scheme, clock, X, V, A, memory, X1):
    h = clock[0].h
    for i in range(X1.shape[0]):
        for a in range(3):
            velocity = (X1[i, a] - X[i, a]) / h
            A[i, a] = (velocity - V[i, a]) / h
            V[i, a], X[i, a] = velocity, X1[i, a]


@njit(cache=True, inline="always", _nrt=False)
def error(scheme, clock, X, V, A, memory, X1, guess, out):
    return False


class BackwardEuler(Integrator):
    """Backward Euler on X and V (see the module docstring)."""

    name = "backward-euler"
    scheme = Scheme("backward-euler", PARAMETERS, 0, True, begin, point, accept, error)
