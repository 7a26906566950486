"""Variable-step BDF2 (desire2023 Sec. 2.1.2), started by one backward-Euler step: the scheme's
arithmetic (``cablefem.dynamics.scheme``) and its integrator.

y' ~ c0 y_{n+1} + c1 y_n + c2 y_{n-1} on X and on V, with w = h / h_before,
c0 = (1 + 2 w) / ((1 + w) h), c1 = -(1 + w) / h, c2 = w^2 / ((1 + w) h) (backward Euler: 1/h, -1/h, 0).
"""

import numpy as np
from numba import njit

from cablefem.dynamics.integrator import Integrator
from cablefem.dynamics.scheme import Scheme

#: no parameters (a record needs a field)
PARAMETERS = np.dtype([("unused", "f8")])
#: memory rows: the step before's X and V, and the step's histories x_hist = c1 X + c2 Xp, v_hist = c1 V + c2 Vp
MEMORY = 4
XP, VP, X_HIST, V_HIST = 0, 1, 2, 3


@njit(cache=True, inline="always", _nrt=False)
def begin(scheme, clock, X, V, A, memory, guess, h):
    """The coefficients of a step of h (backward Euler to start), its histories and the Taylor
    predictor X + h V + h^2/2 A."""
    c = clock[0]
    h_before = c.h_before
    start = h_before == 0.0
    if start:
        c0, c1, c2 = 1.0 / h, -1.0 / h, 0.0
    else:
        w = h / h_before
        c0, c1, c2 = (1 + 2 * w) / ((1 + w) * h), -(1 + w) / h, w * w / ((1 + w) * h)
    c.v_x, c.a_x, c.g_x, c.h, c.t_eval = c0, c0 * c0, 1.0, h, c.t + h
    Xp, Vp, x_hist, v_hist = memory[XP], memory[VP], memory[X_HIST], memory[V_HIST]
    for i in range(X.shape[0]):
        for a in range(3):
            x_hist[i, a] = c1 * X[i, a] + c2 * (X[i, a] if start else Xp[i, a])
            v_hist[i, a] = c1 * V[i, a] + c2 * (V[i, a] if start else Vp[i, a])
            guess[i, a] = X[i, a] + h * V[i, a] + 0.5 * h * h * A[i, a]


@njit(cache=True, inline="always", _nrt=False)
def point(scheme, clock, X, V, A, memory, X1, Xe, Ve, Ae):
    """The loads at X1 itself: V = c0 X1 + x_hist, A = c0 V + v_hist."""
    c0, x_hist, v_hist = clock[0].v_x, memory[X_HIST], memory[V_HIST]
    for i in range(X1.shape[0]):
        for a in range(3):
            Xe[i, a] = X1[i, a]
            Ve[i, a] = c0 * X1[i, a] + x_hist[i, a]
            Ae[i, a] = c0 * Ve[i, a] + v_hist[i, a]


@njit(cache=True, inline="always", _nrt=False)
def accept(scheme, clock, X, V, A, memory, X1):
    """The state at t + h; the state at t becomes the step before."""
    c0, Xp, Vp, x_hist, v_hist = clock[0].v_x, memory[XP], memory[VP], memory[X_HIST], memory[V_HIST]
    for i in range(X1.shape[0]):
        for a in range(3):
            velocity = c0 * X1[i, a] + x_hist[i, a]
            Xp[i, a], Vp[i, a] = X[i, a], V[i, a]
            X[i, a], V[i, a], A[i, a] = X1[i, a], velocity, c0 * velocity + v_hist[i, a]


@njit(cache=True, inline="always", _nrt=False)
def error(scheme, clock, X, V, A, memory, X1, guess, out):
    """Milne's device: the Taylor predictor P and BDF2 have local errors h^3 X^(3) / 6 and
    -2 h^3 X^(3) / 9, so the step's error is 4/7 (X1 - P): the solution of lower order
    X1 - 4/7 (X1 - P). None for the starting backward-Euler step."""
    if clock[0].h_before == 0.0:
        return False
    for i in range(X1.shape[0]):
        for a in range(3):
            out[i, a] = X1[i, a] - 4.0 / 7.0 * (X1[i, a] - guess[i, a])
    return True


SCHEME = Scheme("bdf2", PARAMETERS, MEMORY, True, begin, point, accept, error)


class BDF2(Integrator):
    """Variable-step BDF2 (desire2023 Sec. 2.1.2), started by one backward-Euler step."""

    name = "bdf2"
    scheme = SCHEME
