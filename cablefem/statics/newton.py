"""Static equilibrium by Newton's method with Armijo line search (desire2023 Sec. 2.3; Kelley 2003).

Newton starts from a shape close to the answer (``cablefem.statics.start_shape``: the elastic catenary
that touches the seabed, never the straight chord, which converges to the inverse catenary of
Fig. 5; the slack layout of a line longer than it needs; the inverted catenary of a buoyant
line). It stops when the residual relative to the line's weight falls below the tolerance, or
when a full Newton step no longer reduces it and the step itself, the scale-free residual
K^-1 G relative to the line's length, is below the tolerance (round-off: a position known to
eps |X| leaves forces of eps |X| EA / h, which at large EA or seabed stiffness are far above any
force tolerance). The strategies a solve tries when Newton fails are in
``cablefem.statics.solve``; pseudo-transient continuation, the damped pseudo-motion that ends in
Newton, is here.
"""

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as spla

from cablefem.fem import clamp
from cablefem.statics.start_shape import initial_shape


@dataclass
class StaticResult:
    """A static solution: state X (N, 3), Newton iterations, final relative residual,
    the residual history and how it was reached ("newton" or "continuation")."""

    X: np.ndarray
    iterations: int
    residual: float
    history: list = field(default_factory=list)
    strategy: str = "newton"
    wall_time_s: float = 0.0
    slack_start: bool = False  # started from the slack layout of a line longer than it needs
    increment: float = float("nan")  # the scale-free residual: |K^-1 G|_max / L at X (``scale_free_residual``)


def catenary_guess(system):
    """Initial state (N, 3) of a static solve (``cablefem.statics.start_shape.initial_shape``): the elastic
    catenary that touches the seabed, the slack layout of a line longer than it needs, or the
    inverted catenary of a buoyant line."""
    return initial_shape(system)[0]


#: Newton on a line that bends: full steps taken without a line search while the residual stays
#: above the lowest one seen for at most this many in a row, then back to that point and its line
#: search (Chamberlain et al.'s watchdog, 1982). A bending line far stiffer axially than in bending
#: (EA L^2 / EI ~ 1e8) needs its full steps: the first one from a straight start stretches it by
#: (deflection / L)^2, a residual ~1e4 times its load, and Newton then converges in a few
#: iterations, where the line search crawls along the inextensible shapes (verification/bending)
WATCHDOG = 8


def newton(system, X, tolerance=1e-8, max_iterations=50, scale=None):
    """Newton-Armijo on the free rows of system's residual from X (N, 3); returns
    (X, iterations, relative residual, history, converged). A line that bends takes full steps
    under a watchdog first (``WATCHDOG``)."""
    fem = system.fem
    free = fem.free_dofs
    length = system.line.unstretched_length
    scale = scale or float(np.linalg.norm(system.weight_vector()[free])) or 1.0
    X = clamp.satisfy(system.clamps, X.copy())
    linear = _Linearisation.of(system)
    residual, tangent = linear.evaluate(X)
    norm = np.linalg.norm(residual[free]) / scale
    energy = None  # the potential energy at X, computed when a line search needs it
    history = [norm]
    watchdog = WATCHDOG if system.has("bending") else 0
    best, unimproved = (X, residual, tangent, norm), 0  # the watchdog's lowest residual
    for iteration in range(1, max_iterations + 1):
        if norm <= tolerance:
            return X, iteration - 1, norm, history, True
        if watchdog and unimproved >= watchdog:  # the full steps did not pay: back to the best point
            (X, residual, tangent, norm), energy, unimproved = best, None, -1
        step = linear.solve(tangent, residual)
        if step is None or not np.all(np.isfinite(step)):
            return X, iteration, norm, history, False
        small = np.max(np.abs(step)) <= tolerance * length
        slope = float(np.sum(residual[free] * step))  # d(energy)/d(lambda) at lambda = 0
        lam, accepted = 1.0, False
        if watchdog and unimproved >= 0 and not small:
            trial = X.copy()
            trial[free] += step
            residual_t, tangent_t = linear.evaluate(trial)
            norm_t = np.linalg.norm(residual_t[free]) / scale
            unimproved = unimproved + 1 if norm_t > (1.0 - 1e-4) * best[3] else 0
            if not unimproved:
                best = (trial, residual_t, tangent_t, norm_t)
            X, residual, tangent, norm, energy = trial, residual_t, tangent_t, norm_t, None
            history.append(norm)
            if norm <= tolerance:
                return X, iteration, norm, history, True
            continue
        unimproved = max(unimproved, 0)
        for _ in range(30):
            trial = X.copy()
            trial[free] += lam * step
            residual_t, tangent_t = linear.evaluate(trial)
            norm_t = np.linalg.norm(residual_t[free]) / scale
            # Armijo on the residual (Kelley 2003), or on the potential energy along a descent
            # direction: with a stiff seabed the residual jumps when a step presses a point
            # into the ground, while the energy still measures progress
            if small or norm_t <= (1.0 - 1e-4 * lam) * norm:
                accepted, energy_t = True, None
                break
            if slope < 0:
                energy = system.energy(X) if energy is None else energy
                energy_t = system.energy(trial)
                if energy_t <= energy + 1e-4 * lam * slope:
                    accepted = True
                    break
            lam = _parabolic_step(lam, norm, norm_t)
        if not accepted:
            return X, iteration, norm, history, False
        # a full Newton step that no longer halves the residual has hit round-off: converged if
        # the step itself, the residual in the tangent's own units (K^-1 G [m], free of the
        # stiffnesses' scale), is below the tolerance of the line's length; not if Newton merely
        # stalls above it (a residual floor scaled by EA and G_K accepted anything at large EA)
        stalled = lam == 1.0 and norm_t > 0.5 * norm and small
        X, residual, tangent, norm, energy = trial, residual_t, tangent_t, norm_t, energy_t
        if watchdog and norm < best[3]:
            best = (X, residual, tangent, norm)
        history.append(norm)
        if norm <= tolerance or stalled:
            return X, iteration, norm, history, True
    return X, max_iterations, norm, history, norm <= tolerance


class _Linearisation:
    """The static residual rows (N, 3) at X with their tangent, and the Newton step from them:
    through ``cablefem.compiled.evaluator`` (compiled, banded LU) when the system assembles with its kernel
    and holds only loads the fused kernel knows, else through ``LineSystem.evaluate`` and a
    sparse LU (the reference path: the loads' numpy faces on precomputed basis data with
    ``assembly="numpy"``, scikit-fem's forms with ``assembly="forms"``). Both give
    the same numbers to round-off (tests/test_statics.py). Built per Newton solve: the fused
    kernel copies the seabed stiffness, which stiffness continuation changes between solves."""

    def __init__(self, system, fused):
        self.system, self.fused = system, fused
        self.zeros = np.zeros((system.fem.n_dofs, 3))

    @classmethod
    def of(cls, system):
        fused = None
        if system.assembly == "kernel":
            from cablefem.compiled.evaluator import FusedEvaluator
            fused = FusedEvaluator.for_system(system, system.props["mass"])
        return cls(system, fused)

    def evaluate(self, X):
        if self.fused is None:
            return self.system.evaluate(self.system.state(X))
        return self.fused.evaluate(X, self.zeros, self.zeros, 0.0, 0.0)

    def solve(self, tangent, residual):
        """Newton step (N_free, 3) of the free DOFs, or None when the tangent is singular."""
        if self.fused is None:
            try:
                K = self.system.matrix(tangent).tocsc()
                return spla.spsolve(K, -residual[self.system.fem.free_dofs].ravel()).reshape(-1, 3)
            except RuntimeError:
                return None
        factors = self.fused.factorize(tangent)
        return None if factors is None else self.fused.solve(factors, residual)


def scale_free_residual(system, X):
    """The residual at X (N, 3) in the tangent's own units: the largest entry of the Newton step
    K^-1 G [m] over the line's length. A force residual relative to the weight depends on the
    stiffnesses (a position known to round-off eps |X| leaves forces eps |X| EA / h); this does not."""
    if system.fem.free_dofs.size == 0:  # a line of one element between prescribed ends: nothing to solve
        return 0.0
    linear = _Linearisation.of(system)
    residual, tangent = linear.evaluate(X)
    step = linear.solve(tangent, residual)
    if step is None:
        return float("inf")
    return float(np.max(np.abs(step))) / system.line.unstretched_length


def _parabolic_step(lam, f0, f1):
    """Kelley's safeguarded three-point parabola for the next step length, in [0.1, 0.5] lam."""
    denominator = 2.0 * (f1 - f0 * (1.0 - lam) - f0 * lam)
    candidate = lam * lam * f0 / denominator if denominator > 0 else 0.5 * lam
    return float(np.clip(candidate, 0.1 * lam, 0.5 * lam))


def pseudo_transient(system, X, tolerance=1e-8, max_iterations=500):
    """Pseudo-transient continuation (Kelley & Keyes 1998): Newton on G(X) + M (X - X_k) / tau = 0
    with the pseudo time step tau [s^2] grown as the residual falls (switched evolution
    relaxation), so early steps follow a damped motion of the line towards equilibrium and
    late ones are Newton's. Same returns as ``newton``."""
    fem = system.fem
    free = fem.free_dofs
    length = system.line.unstretched_length
    mass = fem.vector_mass(system.props["mass"])
    scale = float(np.linalg.norm(system.weight_vector()[free])) or 1.0
    residual, blocks = system.evaluate(system.state(X))
    norm = np.linalg.norm(residual[free]) / scale
    history = [norm]
    # start with steps the size of a free fall over a tenth of an element
    tau = 0.1 * float(np.min(np.diff(fem.mesh.p[0]))) / system.environment.gravity
    X = X.copy()
    for iteration in range(1, max_iterations + 1):
        if norm <= tolerance:
            return X, iteration - 1, norm, history, True
        K = system.matrix(blocks) + mass / tau
        try:
            step = spla.spsolve(K.tocsc(), -residual[free].ravel()).reshape(-1, 3)
        except RuntimeError:
            return X, iteration, norm, history, False
        if not np.all(np.isfinite(step)):
            return X, iteration, norm, history, False
        X[free] += step
        residual, blocks = system.evaluate(system.state(X))
        new = np.linalg.norm(residual[free]) / scale
        tau *= min(norm / new, 10.0) if new > 0 else 10.0
        stalled = tau > 1e6 and new > 0.5 * norm and np.max(np.abs(step)) <= tolerance * length
        norm = new
        history.append(norm)
        if stalled:
            return X, iteration, norm, history, True
    return X, max_iterations, norm, history, norm <= tolerance


def tension_only(system, X, tolerance, max_iterations, push=True):
    """Newton with a line that may push first (``push``), then with the real tension-only line.

    A piecewise-linear guess of a curved line has chords shorter than their arcs, so some
    elements of the guess are slack: the tension-only law gives them no stiffness and Newton
    crawls. Letting them push removes the kink; if no element is compressed at that solution
    it is also the tension-only one, otherwise Newton continues from it without compression.
    A guess that lays out slack line on purpose (``cablefem.statics.start_shape``) starts without: there
    pushing would straighten what must lie slack.
    """
    if not push:
        return newton(system, X, tolerance, max_iterations)
    tension = system.tension
    tension.compression = True
    try:
        X1, its, norm, history, ok = newton(system, X, tolerance, max_iterations)
    finally:
        tension.compression = False
    if ok and np.all(system.tension_strain(X1) > 0.0):
        return X1, its, norm, history, ok
    start = X1 if ok else X
    X2, its2, norm2, history2, ok2 = newton(system, start, tolerance, max_iterations)
    return X2, its + its2, norm2, history + history2, ok2


def point_loads(system):
    """The system's point loads (clump weights, buoys: ``cablefem.loads.points``), or None."""
    return next((load for load in system.loads if getattr(load, "rule", "full") == "node"), None)
