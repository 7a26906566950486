"""Generalised-alpha (Chung & Hulbert 1993): the scheme's arithmetic (``cablefem.dynamics.scheme``) and
its integrator.

The Newmark update from the state at t_n, A1 = (X1 - X - h V) / (beta h^2) - (1 / (2 beta) - 1) A and
V1 = V + h ((1 - gamma) A + gamma A1), with the loads at t_{n+1-alpha_f} (positions and velocities
weighted by alpha_f) and the inertia at n+1-alpha_m; alpha_m = (2 rho - 1) / (rho + 1),
alpha_f = rho / (rho + 1), gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4 for
the spectral radius rho at infinite frequency.
"""

import numpy as np
from numba import njit

from cablefem.dynamics.integrator import Integrator
from cablefem.dynamics.scheme import Scheme

PARAMETERS = np.dtype([("alpha_m", "f8"), ("alpha_f", "f8"), ("gamma", "f8"), ("beta", "f8")])
MEMORY = 0


@njit(cache=True, inline="always", _nrt=False)
def _newmark(X, V, A, X1, i, a, h, g, b):
    """V and A at t + h of row i, component a, from X1."""
    acceleration = (X1[i, a] - X[i, a] - h * V[i, a]) / (b * h * h) - (0.5 / b - 1.0) * A[i, a]
    return V[i, a] + h * ((1 - g) * A[i, a] + g * acceleration), acceleration


@njit(cache=True, inline="always", _nrt=False)
def begin(scheme, clock, X, V, A, memory, guess, h):
    """The factors of a step of h: v_x = gamma / (beta h), a_x = (1 - alpha_m) / ((1 - alpha_f) beta
    h^2), g_x = 1 - alpha_f, the loads at t + h - alpha_f h; the Taylor predictor."""
    p, c = scheme[0], clock[0]
    am, af, g, b = p.alpha_m, p.alpha_f, p.gamma, p.beta
    c.v_x, c.a_x, c.g_x, c.h, c.t_eval = g / (b * h), (1 - am) / ((1 - af) * b * h * h), 1 - af, h, c.t + h - af * h
    for i in range(X.shape[0]):
        for a in range(3):
            guess[i, a] = X[i, a] + h * V[i, a] + 0.5 * h * h * A[i, a]


@njit(cache=True, inline="always", _nrt=False)
def point(scheme, clock, X, V, A, memory, X1, Xe, Ve, Ae):
    """The loads at t_{n+1-alpha_f}, the inertia at n+1-alpha_m."""
    p, h = scheme[0], clock[0].h
    am, af = p.alpha_m, p.alpha_f
    for i in range(X1.shape[0]):
        for a in range(3):
            velocity, acceleration = _newmark(X, V, A, X1, i, a, h, p.gamma, p.beta)
            Xe[i, a] = (1 - af) * X1[i, a] + af * X[i, a]
            Ve[i, a] = (1 - af) * velocity + af * V[i, a]
            Ae[i, a] = (1 - am) * acceleration + am * A[i, a]


@njit(cache=True, inline="always", _nrt=False)
def accept(scheme, clock, X, V, A, memory, X1):
    """The Newmark update's state at t + h."""
    p, h = scheme[0], clock[0].h
    for i in range(X1.shape[0]):
        for a in range(3):
            V[i, a], A[i, a] = _newmark(X, V, A, X1, i, a, h, p.gamma, p.beta)
            X[i, a] = X1[i, a]


@njit(cache=True, inline="always", _nrt=False)
def error(scheme, clock, X, V, A, memory, X1, guess, out):
    """The local error of the Newmark family, (beta - 1/6) h^2 (A_{n+1} - A_n) (Zienkiewicz & Xie
    1991): the solution of lower order X1 less it."""
    p, h = scheme[0], clock[0].h
    for i in range(X1.shape[0]):
        for a in range(3):
            _, acceleration = _newmark(X, V, A, X1, i, a, h, p.gamma, p.beta)
            out[i, a] = X1[i, a] - (p.beta - 1.0 / 6.0) * h * h * (acceleration - A[i, a])
    return True


SCHEME = Scheme("generalized-alpha", PARAMETERS, MEMORY, True, begin, point, accept, error)


class GeneralizedAlpha(Integrator):
    """Generalised-alpha (Chung & Hulbert 1993) with spectral radius ``rho_inf`` at infinite
    frequency: second order, unconditionally stable for linear problems, tunable high-frequency
    damping. The end forces (``reactions``) are the rows M A + G where the scheme balances them, at
    t_{n+1-alpha_f}, carried on to t_{n+1} along the line through the last two balances
    (``policy.balance_lag``: second order; the rows as they are lag by alpha_f h, first order:
    verification/waves, case (e)). Not M A + G at the state X_{n+1}:
    the loads balance at X_{n+1-alpha_f} = (1 - alpha_f) X_{n+1} + alpha_f X_n, and a strain is not
    affine in the positions, so where a line turns by dtheta in a step the strain at X_{n+1} exceeds
    the balanced one by alpha_f dtheta^2 / 2 (of e = u' + w'^2 / 2), a tension error of EA alpha_f
    dtheta^2 / 2: second order in h, but EA / T times a balanced error (the lazy wave of
    validation/cables, EA / T ~ 3e4: hang-off tension 4x too large at 40 steps a period).

    Unconditional stability does not carry over to the nonlinear, tension-only axial stiffness of a
    line (Kuhl & Crisfield 1999; Erlicher et al. 2002): on a stiff chain (EA 5e11 N) pulled taut with
    omega dt ~ 1e2, rho_inf <= 0.5 stays bounded and rho_inf >= 0.6 pumps energy until the tension
    reaches 1e11 N (verification/stability, case 7b). Hence the default 0.5; BDF2 has no such limit."""

    name = "generalized-alpha"
    scheme = SCHEME

    def __init__(self, *args, rho_inf=0.5, **kwargs):
        r = self.rho_inf = float(rho_inf)
        self.alpha_m = (2 * r - 1) / (r + 1)
        self.alpha_f = r / (r + 1)
        self.gamma = 0.5 - self.alpha_m + self.alpha_f
        self.beta = 0.25 * (1 - self.alpha_m + self.alpha_f) ** 2
        super().__init__(*args, parameters=(self.alpha_m, self.alpha_f, self.gamma, self.beta), **kwargs)

    @staticmethod
    def options(solver):
        """Its keyword arguments from a scene's [solver]: the spectral radius rho_inf."""
        return {"rho_inf": solver.rho_inf}
