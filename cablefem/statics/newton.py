"""Static equilibrium by Newton's method, written once, with its globalisations as strategies
(desire2023 Sec. 2.3; Kelley 2003).

``iterate`` is the one Newton loop of statics: a problem gives its residual, tangent and relative
residual at a point, its Newton direction and its trial points; a globalisation says how a step is
taken and when a step that no longer reduces the residual means round-off rather than failure:

- ``LineSearch``: the residual's Armijo test with Kelley's safeguarded parabola, and the potential
  energy's Armijo test along a descent direction (a stiff seabed makes the residual jump where a
  step presses a point into the ground, while the energy still measures progress);
- ``PseudoTransient``: Newton on G(X) + M (X - X_k) / tau = 0 with tau grown as the residual falls
  (Kelley & Keyes 1998, switched evolution relaxation): a damped motion of the line towards
  equilibrium whose late steps are Newton's;
- ``Halving``: halving steps, a trial point that cannot be evaluated halved too (the network's
  coupling unknowns, ``cablefem.statics.network``).

The continuations (``cablefem.statics.continuation``: a sequence of problems rising to the
scene's) and the order a solve tries them in (``cablefem.statics.solve``) are built on it. A line's
Newton starts from a shape close to the answer (``cablefem.statics.start_shape``: the elastic
catenary that touches the seabed, never the straight chord, which converges to the inverse catenary
of Fig. 5; the slack layout of a line longer than it needs; the inverted catenary of a buoyant
line; the hang of a line with one free end). It stops when the residual relative to the line's weight falls below the tolerance, or when
a full Newton step no longer reduces it and the step itself, the scale-free residual K^-1 G
relative to the line's length, is below the tolerance (round-off: a position known to eps |X|
leaves forces of eps |X| EA / h, which at large EA or seabed stiffness are far above any force
tolerance).
"""

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as spla

from cablefem.errors import ConvergenceError
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


def iterate(problem, point, tolerance, max_iterations, globalisation):
    """Newton's method on ``problem`` from ``point``, each step taken as ``globalisation`` says (the
    module docstring); returns (point, iterations, relative residual, history, converged).

    A problem has ``evaluate(point) -> (residual, tangent, relative residual)``, ``solve(tangent,
    residual) -> step`` (None if singular), ``trial(point, step, lam) -> point`` and
    ``small(step) -> bool`` (the step below the tolerance in the problem's own units); a
    globalisation ``direction``, ``search`` and ``stalled`` (``LineSearch`` is the pattern)."""
    residual, tangent, norm = problem.evaluate(point)
    history = [norm]
    for iteration in range(1, max_iterations + 1):
        if norm <= tolerance:
            return point, iteration - 1, norm, history, True
        step = globalisation.direction(problem, tangent, residual)
        if step is None or not np.all(np.isfinite(step)):
            return point, iteration, norm, history, False
        found = globalisation.search(problem, point, residual, norm, step)
        if found is None:
            return point, iteration, norm, history, False
        trial, residual, tangent, norm_t, lam = found
        stalled = globalisation.stalled(problem, step, lam, norm, norm_t)
        point, norm = trial, norm_t
        history.append(norm)
        if norm <= tolerance or stalled:
            return point, iteration, norm, history, True
    return point, max_iterations, norm, history, norm <= tolerance


class LineSearch:
    """Newton's step cut back until the residual passes Armijo's test (Kelley 2003 Sec. 8.1: the
    next length from his safeguarded three-point parabola, at most ``TRIES`` trials), or, along a
    descent direction, until the potential energy does. A full step that no longer halves the
    residual has hit round-off: converged if the step itself, the residual in the tangent's own
    units (K^-1 G [m], free of the stiffnesses' scale), is small (``problem.small``); not if Newton
    merely stalls above it (a residual floor scaled by EA and G_K accepted anything at large EA)."""

    TRIES = 30

    def __init__(self):
        self.energy = self.next_energy = None  # the potential energy at the point, when a search needed it

    def direction(self, problem, tangent, residual):
        return problem.solve(tangent, residual)

    def search(self, problem, point, residual, norm, step):
        small = problem.small(step)
        slope = problem.slope(residual, step)  # d(energy)/d(lambda) at lambda = 0
        lam = 1.0
        for _ in range(self.TRIES):
            trial = problem.trial(point, step, lam)
            residual_t, tangent_t, norm_t = problem.evaluate(trial)
            if small or norm_t <= (1.0 - 1e-4 * lam) * norm:
                self.next_energy = None
                return trial, residual_t, tangent_t, norm_t, lam
            if slope < 0:
                self.energy = problem.energy(point) if self.energy is None else self.energy
                energy_t = problem.energy(trial)
                if energy_t <= self.energy + 1e-4 * lam * slope:
                    self.next_energy = energy_t
                    return trial, residual_t, tangent_t, norm_t, lam
            lam = _parabolic_step(lam, norm, norm_t)
        return None

    def stalled(self, problem, step, lam, norm, norm_t):
        self.energy = self.next_energy
        return lam == 1.0 and norm_t > 0.5 * norm and problem.small(step)


#: Newton on a line that bends: full steps taken without a line search while the residual stays
#: above the lowest one seen for at most this many in a row, then back to that point and its line
#: search (Chamberlain et al.'s watchdog, 1982). A bending line far stiffer axially than in bending
#: (EA L^2 / EI ~ 1e8) needs its full steps: the first one from a straight start stretches it by
#: (deflection / L)^2, a residual ~1e4 times its load, and Newton then converges in a few
#: iterations, where the line search crawls along the inextensible shapes (verification/bending)
WATCHDOG = 8


class Watchdog(LineSearch):
    """Full Newton steps while one of every ``WATCHDOG`` in a row lowers the lowest residual seen;
    else back to the point that has it and one step of ``LineSearch`` from there (a line that
    bends, ``WATCHDOG``). Small steps are line searched."""

    def __init__(self, limit=WATCHDOG):
        super().__init__()
        self.limit, self.unimproved = limit, 0  # unimproved < 0: the full steps are over
        self.best = self.restore = None  # (point, residual, tangent, norm)
        self.tangent = None

    def direction(self, problem, tangent, residual):
        if self.unimproved >= self.limit:  # the full steps did not pay: back to the best point
            self.restore, self.unimproved = self.best, -1
            _, residual, tangent, _ = self.best
        self.tangent = tangent
        return problem.solve(tangent, residual)

    def search(self, problem, point, residual, norm, step):
        if self.best is None:
            self.best = (point, residual, self.tangent, norm)
        if self.restore is not None:
            (point, residual, _, norm), self.restore, self.energy = self.restore, None, None
        if self.unimproved < 0 or problem.small(step):  # a line search, then full steps again
            self.unimproved = max(self.unimproved, 0)
            found = super().search(problem, point, residual, norm, step)
            if found is not None and found[3] < self.best[3]:
                self.best = (found[0], found[1], found[2], found[3])
            return found
        trial = problem.trial(point, step, 1.0)
        residual_t, tangent_t, norm_t = problem.evaluate(trial)
        self.unimproved = self.unimproved + 1 if norm_t > (1.0 - 1e-4) * self.best[3] else 0
        if not self.unimproved:
            self.best = (trial, residual_t, tangent_t, norm_t)
        self.energy = self.next_energy = None
        return trial, residual_t, tangent_t, norm_t, 1.0


class PseudoTransient:
    """Pseudo-transient continuation (Kelley & Keyes 1998): Newton on G(X) + M (X - X_k) / tau = 0
    with the pseudo time step tau [s^2] grown as the residual falls (switched evolution relaxation,
    by at most 10x a step), so early steps follow a damped motion of the line towards equilibrium
    and late ones are Newton's; it starts with steps the size of a free fall over a tenth of an
    element. Every step is taken whole; it has stalled on round-off when tau is large, the residual
    no longer halves and the step is small. The structural mass and the loads' numpy faces (the
    problem's evaluator is ``NumpyEvaluator``)."""

    def __init__(self, system):
        fem = system.fem
        self.system = system
        self.mass = fem.vector_mass(system.props["mass"])
        # a scene without gravity (g = 0) takes the free fall of the standard g
        self.tau = 0.1 * float(np.min(np.diff(fem.mesh.p[0]))) / (system.environment.gravity or 9.80665)

    def direction(self, problem, tangent, residual):
        blocks, _ = tangent
        K = self.system.matrix(blocks) + self.mass / self.tau
        try:
            return spla.spsolve(K.tocsc(), -residual[self.system.fem.free_dofs].ravel()).reshape(-1, 3)
        except RuntimeError:
            return None

    def search(self, problem, point, residual, norm, step):
        trial = problem.trial(point, step, 1.0)
        return (trial, *problem.evaluate(trial), 1.0)

    def stalled(self, problem, step, lam, norm, norm_t):
        self.tau *= min(norm / norm_t, 10.0) if norm_t > 0 else 10.0
        return self.tau > 1e6 and norm_t > 0.5 * norm and problem.small(step)


class Halving:
    """Newton's step halved until the residual passes Armijo's test or the step is small (at most
    ``TRIES`` trials); a trial point that cannot be evaluated (``ConvergenceError``) is halved too. A
    full step that is small has converged. It gives up (``search`` None) when the residual has not
    halved over the last ``WINDOW`` steps: Newton crawling with cut steps far from the answer, where a
    globalisation that follows the physics does better (network statics' pseudo-transient:
    complex_system.txt's network crawled from 6 to 1.3 in 47 halved steps)."""

    TRIES = 12
    WINDOW = 8

    def __init__(self):
        self.norms = []  # the residual at each step's start

    def direction(self, problem, tangent, residual):
        return problem.solve(tangent, residual)

    def search(self, problem, point, residual, norm, step):
        self.norms.append(norm)
        if len(self.norms) > self.WINDOW and norm > 0.5 * self.norms[-1 - self.WINDOW]:
            return None
        lam = 1.0
        for _ in range(self.TRIES):
            try:
                trial = problem.trial(point, step, lam)
            except ConvergenceError:
                lam *= 0.5
                continue
            residual_t, tangent_t, norm_t = problem.evaluate(trial)
            if norm_t <= (1.0 - 1e-4 * lam) * norm or problem.small(lam * step):
                return trial, residual_t, tangent_t, norm_t, lam
            lam *= 0.5
        return None

    def stalled(self, problem, step, lam, norm, norm_t):
        return lam == 1.0 and problem.small(lam * step)


class LineProblem:
    """One line's static residual on its free rows, as ``iterate`` solves it: positions X (N, 3), the
    residual relative to ``scale`` (default ``force_scale``), steps small below ``tolerance`` of the
    line's length; evaluated by the system's evaluator (``_Linearisation``), or by the loads' numpy
    faces (``numpy``)."""

    def __init__(self, system, tolerance, scale=None, numpy=False):
        fem = system.fem
        self.system, self.free, self.tolerance = system, fem.free_dofs, tolerance
        self.length = system.line.unstretched_length
        self.scale = scale or force_scale(system)
        self.linear = _Linearisation(system, numpy)

    def evaluate(self, X):
        residual, tangent = self.linear.evaluate(X)
        return residual, tangent, np.linalg.norm(residual[self.free]) / self.scale

    def solve(self, tangent, residual):
        return self.linear.solve(tangent, residual)

    def trial(self, X, step, lam):
        trial = X.copy()
        trial[self.free] += lam * step
        return trial

    def small(self, step):
        return np.max(np.abs(step)) <= self.tolerance * self.length

    def slope(self, residual, step):
        return float(np.sum(residual[self.free] * step))

    def energy(self, X):
        return self.system.energy(X)


def force_scale(system):
    """The force [N] a line's static residual is relative to: the weight of its free rows, or its
    points' weight less their buoyancy on its free rows where that is larger (a line as dense as the
    water weighs nothing: the mass on its free end is what it carries)."""
    free = system.fem.free_dofs
    scale = float(np.linalg.norm(system.weight_vector()[free]))
    points = point_loads(system)
    if points is not None:
        held = np.isin(points.vertices, free)
        scale = max(scale, float(np.linalg.norm((points.dry - points.buoyancy)[held])))
    return scale or 1.0


def newton(system, X, tolerance=1e-8, max_iterations=50, scale=None):
    """Newton with the line search (``LineSearch``; under a ``Watchdog`` on a line that bends) on the
    free rows of system's residual from X (N, 3), its clamped tangents turned onto their directions;
    returns (X, iterations, relative residual, history, converged)."""
    globalisation = Watchdog() if system.has("bending") else LineSearch()
    return iterate(LineProblem(system, tolerance, scale), clamp.satisfy(system.clamps, X.copy()), tolerance,
                   max_iterations, globalisation)


def pseudo_transient(system, X, tolerance=1e-8, max_iterations=500):
    """Newton as pseudo-transient continuation (``PseudoTransient``) from X (N, 3); the same returns
    as ``newton``."""
    return iterate(LineProblem(system, tolerance, numpy=True), X.copy(), tolerance, max_iterations,
                   PseudoTransient(system))


class _Linearisation:
    """The static residual rows (N, 3) at X with their tangent, and the Newton step from them, from
    the system's evaluator (``cablefem.fem.evaluator``): compiled when the system assembles with its
    kernel, else the loads' numpy faces with a sparse LU (the reference: precomputed basis data with
    ``assembly="numpy"``, scikit-fem's forms with ``assembly="forms"``); the same numbers to round-off
    (tests/test_statics.py). Built per Newton solve: the compiled kernel copies the seabed
    stiffness, which stiffness continuation changes between solves."""

    def __init__(self, system, numpy=False):
        self.evaluator = system.evaluator(compiled=system.assembly == "kernel" and not numpy)
        self.zeros = np.zeros((system.fem.n_dofs, 3))

    def evaluate(self, X):
        return self.evaluator.evaluate(X, self.zeros, self.zeros, 0.0, 0.0)

    def solve(self, tangent, residual):
        """Newton step (N_free, 3) of the free DOFs, or None when the tangent is singular."""
        factors = self.evaluator.factorize(tangent)
        return None if factors is None else self.evaluator.solve(factors, residual)


def scale_free_residual(system, X):
    """The residual at X (N, 3) in the tangent's own units: the largest entry of the Newton step
    K^-1 G [m] over the line's length. A force residual relative to the weight depends on the
    stiffnesses (a position known to round-off eps |X| leaves forces eps |X| EA / h); this does not."""
    if system.fem.free_dofs.size == 0:  # a line of one element between prescribed ends: nothing to solve
        return 0.0
    linear = _Linearisation(system)
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
    axial = axial_loads(system)
    for load in axial:
        load.compression = True
    try:
        X1, its, norm, history, ok = newton(system, X, tolerance, max_iterations)
    finally:
        for load in axial:
            load.compression = False
    if ok and np.all(system.tension_strain(X1) > 0.0):
        return X1, its, norm, history, ok
    start = X1 if ok else X
    X2, its2, norm2, history2, ok2 = newton(system, start, tolerance, max_iterations)
    return X2, its + its2, norm2, history + history2, ok2


def axial_loads(system):
    """The line's axial loads: its tension and, where a line type has a law of its own, its rope
    (``cablefem.loads.rope``)."""
    return [system.tension] + ([system.load("rope")] if system.has("rope") else [])


def point_loads(system):
    """The system's point loads (clump weights, buoys: ``cablefem.loads.points``), or None."""
    return next((load for load in system.loads if getattr(load, "rule", "full") == "node"), None)
