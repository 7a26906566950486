"""The time integrators (schemes) and their one registry, ``INTEGRATORS``.

A scheme says how a step of size h maps its unknown positions X_{n+1} to the point where the loads
are evaluated (``begin``: coefficients, the predictor; ``point``: X1 -> (X, V, A); ``factors``:
(v_x, a_x, g_x) with d(X, V, A)/dX1 = g_x (1, v_x, a_x)) and how the state moves on (``accept``).
Newton, the retries and the step control are shared (``cablefem.dynamics.integrator``, ``cablefem.dynamics.policy``).
Adding an integrator: a class here with those three methods and one ``INTEGRATORS`` entry
(docs/architecture.md). ``integrator_options`` is the one place that turns a scene's [solver]
into an integrator's arguments.
"""

import numpy as np

from cablefem.compiled.problem import Marcher
from cablefem.compiled.steps import BDF2 as COMPILED_BDF2, GENERALIZED_ALPHA as COMPILED_GENERALIZED_ALPHA
from cablefem.dynamics import policy
from cablefem.dynamics.integrator import Integrator
from cablefem.errors import ConvergenceError


class CompiledSteps(Integrator):
    """An integrator whose attempts and runs of steps go through ``cablefem.compiled.steps`` (the policy
    compiled, the seabed projected in the loop) where it evaluates with the compiled kernel on a
    plane, a depth grid or a triangulated surface; through the Python ops elsewhere, and where the
    compiled loop stops. The numbers are those of the Python ops to round-off
    (``tests/test_march.py``, ``tests/test_march_alpha.py``). A subclass names its compiled face:
    ``compiled_scheme()``, its ``cablefem.compiled.steps.SCHEME`` record."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.marcher = Marcher.for_integrator(self)

    def attempt(self, h):
        """One attempt of size h: compiled (``cablefem.compiled.steps``) where it can, in Python where the seabed
        walk lost a point (the Python projection searches)."""
        if self.marcher is not None:
            outcome = self.marcher.attempt(self, h)
            if outcome == policy.CONVERGED:
                self.last_h = h  # the step the Python ops asked for (the compiled one is (t + h) - t)
            if outcome != policy.LOST:
                return outcome == policy.CONVERGED
            # the two paths keep factors of their own: a contraction measured with one set says
            # nothing of the other's (policy.newton's first-iteration stop), on the way in or out
            self.contraction = -1.0
            converged = super().attempt(h)
            self.contraction = -1.0
            return converged
        return super().attempt(h)

    def march(self, times):
        """Steps to ``times`` in compiled runs (``cablefem.compiled.steps``); where the compiled loop stops (an
        attempt it cannot place the ends for, a point the seabed walk lost) that step goes on
        through the Python ops. Returns the forces (m, 2, 3) on fairlead and anchor."""
        if self.marcher is None:
            return super().march(times)
        times = np.asarray(times, dtype=float)
        ends, fractions = self.marcher.ends(self, times)
        forces = np.empty((len(times), 2, 3))
        k = 0
        while k < len(times):
            status, done, stopped = self.marcher.run(self, times[k:], ends[k:], fractions[k:], forces[k:])
            k += done
            if status == policy.DONE:
                break
            if status != policy.REACTIONS:  # REACTIONS: step k was taken, only its forces are missing
                try:
                    if status == policy.FAILED:
                        raise self.too_small(stopped)
                    self.step(times[k] - self.t, first=stopped)
                except ConvergenceError as error:
                    error.forces = forces[:k]
                    raise
            forces[k] = self.reactions()  # the Python projection searches where the walk lost a point
            k += 1
        return forces


class BDF2(CompiledSteps):
    """Variable-step BDF2 on X and V (desire2023 Sec. 2.1.2), started by one backward-Euler step.

    Compiled where ``CompiledSteps`` says."""

    name = "bdf2"

    def __init__(self, *args, **kwargs):
        self.previous = None  # (h, X, V) of the step before
        super().__init__(*args, **kwargs)

    def compiled_scheme(self):
        return (COMPILED_BDF2, 0.0, 0.0, 0.0, 0.0)

    def coefficients(self, h):
        """(c0, c1, c2) with y' ~ c0 y_{n+1} + c1 y_n + c2 y_{n-1}; backward Euler at the start."""
        if self.previous is None:
            return 1.0 / h, -1.0 / h, 0.0
        w = h / self.previous[0]
        return (1 + 2 * w) / ((1 + w) * h), -(1 + w) / h, w * w / ((1 + w) * h)

    def begin(self, h):
        c0, c1, c2 = self.coefficients(h)
        Xp, Vp = (self.X, self.V) if self.previous is None else self.previous[1:]
        self.x_hist = c1 * self.X + c2 * Xp
        self.v_hist = c1 * self.V + c2 * Vp
        self.c0, self.t_eval, self.factors = c0, self.t + h, (c0, c0 * c0, 1.0)
        self.predict(h)

    def point(self, X):
        V = self.c0 * X + self.x_hist
        return X, V, self.c0 * V + self.v_hist

    def accept(self, h):
        self.prediction = self.guess
        self.previous = (h, self.X, self.V)
        _, self.V, self.A = self.point(self.X1)
        self.X, self.t, self.residual_rows, self.last_h = self.X1, self.t + h, self.rows, h

    def memory(self):
        return self.previous

    def set_memory(self, memory):
        self.previous = memory

    def error_estimate(self):
        """Relative tension error of the last step by Milne's device: the Taylor predictor P
        and BDF2 have local errors h^3 X^(3) / 6 and -2 h^3 X^(3) / 9, so LTE = 4/7 (X - P)."""
        return self.tension_error(self.X - 4.0 / 7.0 * (self.X - self.prediction))


class GeneralizedAlpha(CompiledSteps):
    """Generalised-alpha (Chung & Hulbert 1993) with spectral radius ``rho_inf`` at infinite
    frequency: second order, unconditionally stable for linear problems, tunable
    high-frequency damping.

    Unconditional stability does not carry over to the nonlinear, tension-only axial
    stiffness of a line (Kuhl & Crisfield 1999; Erlicher et al. 2002): on a stiff chain
    (EA 5e11 N) pulled taut with omega dt ~ 1e2, rho_inf <= 0.5 stays bounded and rho_inf >=
    0.6 pumps energy until the tension reaches 1e11 N (verification/stability, case 7b).
    Hence the default 0.5; BDF2 has no such limit.

    Compiled where ``CompiledSteps`` says, BDF2's loop with its own ``begin``, ``point`` and
    ``accept`` (``cablefem.compiled.steps``): Newton's iterates, halvings and numbers are the Python ops'
    to round-off. The end forces (``reactions``) are M A + G at the state at t_{n+1}, evaluated
    again after the step (the balance holds at t_{n+1-alpha_f}), on both paths."""

    name = "generalized-alpha"
    rows_at_state = False  # the balance holds at t_{n+1-alpha_f}: the reactions evaluate again

    def __init__(self, *args, rho_inf=0.5, **kwargs):
        self.rho_inf = float(rho_inf)
        r = self.rho_inf
        self.alpha_m = (2 * r - 1) / (r + 1)
        self.alpha_f = r / (r + 1)
        self.gamma = 0.5 - self.alpha_m + self.alpha_f
        self.beta = 0.25 * (1 - self.alpha_m + self.alpha_f) ** 2
        super().__init__(*args, **kwargs)

    def begin(self, h):
        am, af, g, b = self.alpha_m, self.alpha_f, self.gamma, self.beta
        self.h = h
        self.factors = (g / (b * h), (1 - am) / ((1 - af) * b * h * h), 1 - af)
        self.t_eval = self.t + h - af * h
        self.predict(h)

    def newmark(self, X1):
        """V and A at t + h of the Newmark update from the state at t."""
        h, g, b = self.h, self.gamma, self.beta
        A1 = (X1 - self.X - h * self.V) / (b * h * h) - (0.5 / b - 1.0) * self.A
        return self.V + h * ((1 - g) * self.A + g * A1), A1

    def point(self, X1):
        """Loads at t_{n+1-af}, inertia at n+1-am."""
        am, af = self.alpha_m, self.alpha_f
        V1, A1 = self.newmark(X1)
        return (1 - af) * X1 + af * self.X, (1 - af) * V1 + af * self.V, (1 - am) * A1 + am * self.A

    def compiled_scheme(self):
        return (COMPILED_GENERALIZED_ALPHA, self.alpha_m, self.alpha_f, self.gamma, self.beta)

    def accept(self, h):
        self.V, self.A = self.newmark(self.X1)
        self.X, self.t, self.last_h = self.X1, self.t + h, h
        self.residual_rows = None  # the balance holds at n+1-af; reactions re-evaluate at n+1


def integrator_options(solver, name=None):
    """Keyword arguments of ``INTEGRATORS[name]`` (default: ``solver.integrator``) from a scene's
    ``Solver``: the one place that knows which scene option goes to which integrator."""
    options = {"tolerance": solver.tolerance, "newton": solver.newton}
    if (name or solver.integrator) == "generalized-alpha":
        options["rho_inf"] = solver.rho_inf
    return options
