"""Static equilibrium by Newton's method with Armijo line search (desire2023 Sec. 2.3; Kelley 2003).

Newton starts from an elastic catenary that touches the seabed, never from
the straight chord, which converges to the inverse catenary (Fig. 5). It
stops when the residual relative to the line's weight, or a full Newton
increment relative to the line's length, falls below the tolerance. When
Newton stalls (a guess far from the answer, say the one-weight catenary of
a chain + polyester line), it falls back to pseudo-transient continuation,
a damped pseudo-motion that ends in Newton, and then to continuation on the
seabed stiffness (soft ground first, stiffened in steps); if that fails too,
it stops with the residual and what to try.
"""

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as spla

from .catenary import elastic_catenary, inclined_catenary
from .errors import ConvergenceError
from .geometry import Plane


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


def catenary_guess(system):
    """Initial state (N, 3): the elastic catenary between anchor and fairlead in their vertical
    plane, on the seabed's slope when the seabed is a plane under the anchor, lifted onto the
    seabed wherever it would be buried."""
    line, seabed, fem = system.line, system.seabed, system.fem
    anchor, fairlead = line.anchor, line.fairlead
    length = line.unstretched_length
    chord = fairlead - anchor
    span = float(np.hypot(*chord[:2]))
    u = np.append(chord[:2] / span, 0.0) if span > 1e-9 * length else np.array([1.0, 0.0, 0.0])
    pieces = np.array([seg.length for seg in line.segments])
    env = system.environment
    weight = float(pieces @ [s.type.submerged_weight(env.water_density, env.gravity)
                             for s in line.segments] / length)
    EA = float(length / np.sum(pieces / [seg.type.EA for seg in line.segments]))
    gap = float(seabed.gap_only(anchor[None])[0])
    on_seabed = abs(gap) <= 1e-6 * length
    if isinstance(seabed, Plane) and on_seabed:
        rise = seabed.elevation((anchor[:2] + u[:2])[None])[0] - seabed.elevation(anchor[:2][None])[0]
        solution = inclined_catenary(span, chord[2], length, weight, np.arctan(rise), EA)
    else:
        solution = elastic_catenary(span, chord[2], length, EA, weight, seabed=on_seabed)

    def positions(s):
        x, z = solution.profile(s)
        return anchor + x[:, None] * u + z[:, None] * np.array([0.0, 0.0, 1.0])

    X = fem.interpolate(positions)
    lagrange = fem.order <= 2
    rows = slice(None) if lagrange else slice(0, fem.n_vertices)
    points = X[rows]
    proj = seabed.project(points)
    # what rests on the seabed starts at the penetration that carries its weight, w n_z / (G_K d)
    resting = proj.gap <= 1e-9 * length
    sink = weight * proj.direction[:, 2] / float(np.max(system.contact.stiffness))
    points[resting] = proj.closest[resting] - (sink[resting])[:, None] * proj.direction[resting]
    X[rows] = points
    X[fem.anchor_dof], X[fem.fairlead_dof] = anchor, fairlead
    return X


def newton(system, X, tolerance=1e-8, max_iterations=50, scale=None):
    """Newton-Armijo on the free rows of system's residual from X (N, 3); returns
    (X, iterations, relative residual, history, converged)."""
    fem = system.fem
    free = fem.free_dofs
    length = system.line.unstretched_length
    scale = scale or float(np.linalg.norm(system.weight_vector()[free])) or 1.0
    X = X.copy()
    floor = residual_floor(system, X, scale)
    linear = _Linearisation.of(system)
    residual, tangent = linear.evaluate(X)
    norm = np.linalg.norm(residual[free]) / scale
    energy = None  # the potential energy at X, computed when a line search needs it
    history = [norm]
    for iteration in range(1, max_iterations + 1):
        if norm <= tolerance:
            return X, iteration - 1, norm, history, True
        step = linear.solve(tangent, residual)
        if step is None or not np.all(np.isfinite(step)):
            return X, iteration, norm, history, False
        small = np.max(np.abs(step)) <= tolerance * length
        slope = float(np.sum(residual[free] * step))  # d(energy)/d(lambda) at lambda = 0
        lam, accepted = 1.0, False
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
        # a full Newton step that no longer halves the residual has hit round-off: converged
        # if that is where the residual stands, not if Newton merely stalls above it
        stalled = lam == 1.0 and norm_t > 0.5 * norm and norm_t <= floor
        X, residual, tangent, norm, energy = trial, residual_t, tangent_t, norm_t, energy_t
        history.append(norm)
        if norm <= tolerance or stalled:
            return X, iteration, norm, history, True
    return X, max_iterations, norm, history, norm <= tolerance


class _Linearisation:
    """The static residual rows (N, 3) at X with their tangent, and the Newton step from them:
    through ``cablefem.fused`` (compiled, banded LU) when the system assembles with its kernel
    and holds only loads the fused kernel knows, else through ``LineSystem.evaluate`` and a
    sparse LU (the reference path, and scikit-fem's forms with ``assembly="forms"``). Both give
    the same numbers to round-off (tests/test_statics.py). Built per Newton solve: the fused
    kernel copies the seabed stiffness, which stiffness continuation changes between solves."""

    def __init__(self, system, fused):
        self.system, self.fused = system, fused
        self.zeros = np.zeros((system.fem.n_dofs, 3))

    @classmethod
    def of(cls, system):
        fused = None
        if system.assembly == "kernel":
            from .fused import FusedEvaluator
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


def residual_floor(system, X, scale):
    """A bound on the relative residual that round-off alone leaves at state X: a position
    known to eps |X| makes forces of eps |X| (EA / h + G_K d h) in a row (tension and seabed
    springs), summed over the rows in the 2-norm; measured floors sit 1-100 times below."""
    nodes = system.fem.mesh.p[0]
    h = np.diff(nodes)
    stiffness = float(np.max(system.props["EA"] / h) + np.max(system.contact.stiffness[:, 0] * h))
    eps = np.finfo(float).eps
    rows = 3 * len(system.fem.free_dofs)
    return eps * float(np.max(np.abs(X))) * stiffness * np.sqrt(rows) / scale


def _parabolic_step(lam, f0, f1):
    """Kelley's safeguarded three-point parabola for the next step length, in [0.1, 0.5] lam."""
    denominator = 2.0 * (f1 - f0 * (1.0 - lam) - f0 * lam)
    candidate = lam * lam * f0 / denominator if denominator > 0 else 0.5 * lam
    return float(np.clip(candidate, 0.1 * lam, 0.5 * lam))


def solve_static(system, X0=None, tolerance=1e-8, max_iterations=50):
    """Static equilibrium of one line system from the catenary guess (or X0); a StaticResult."""
    start = time.perf_counter()
    X = catenary_guess(system) if X0 is None else X0
    X1, its, norm, history, ok = _tension_only(system, X, tolerance, max_iterations)
    if ok:
        return StaticResult(X1, its, norm, history, "newton", time.perf_counter() - start)
    X2, its2, norm2, history2, ok = pseudo_transient(system, X, tolerance, 10 * max_iterations)
    total, history = its + its2, history + history2
    if ok:
        return StaticResult(X2, total, norm2, history, "pseudo-transient", time.perf_counter() - start)
    X3, its3, norm3, history3, ok = _stiffness_continuation(system, X, tolerance, max_iterations)
    total, history, norm2 = total + its3, history + history3, min(norm2, norm3)
    if ok:
        return StaticResult(X3, total, norm3, history, "continuation", time.perf_counter() - start)
    raise ConvergenceError(
        f"line '{system.line.name}': static solve did not converge: relative residual "
        f"{min(norm, norm2):.3g} after {total} Newton iterations (tolerance {tolerance:g}); "
        "try more elements, a lower element order, a softer seabed stiffness, or check that "
        "the fairlead is within reach of the line",
        residual=min(norm, norm2), iterations=total)


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
    floor = residual_floor(system, X, scale)
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
        stalled = tau > 1e6 and new > 0.5 * norm and new <= floor
        norm = new
        history.append(norm)
        if stalled:
            return X, iteration, norm, history, True
    return X, max_iterations, norm, history, norm <= tolerance


def _tension_only(system, X, tolerance, max_iterations):
    """Newton with a line that may push first, then with the real tension-only line.

    A piecewise-linear guess of a curved line has chords shorter than their arcs, so some
    elements of the guess are slack: the tension-only law gives them no stiffness and Newton
    crawls. Letting them push removes the kink; if no element is compressed at that solution
    it is also the tension-only one, otherwise Newton continues from it without compression.
    """
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


def _stiffness_continuation(system, X, tolerance, max_iterations, factor=10.0):
    """Newton through a sequence of seabed stiffnesses rising geometrically to the scene's."""
    contact = system.contact
    target_k = contact.stiffness.copy()
    target_c = contact.damping.copy()
    soft = 1e-3 * float(np.max(np.abs(system.weight.dry))) / float(np.max(target_k))
    stages = np.geomspace(min(soft, 1.0), 1.0, max(2, int(np.ceil(-np.log10(min(soft, 1.0)))) + 1))
    history, total = [], 0
    try:
        for scale in stages:
            contact.stiffness = target_k * scale
            contact.damping = target_c * np.sqrt(scale)
            X, its, norm, hist, ok = newton(system, X, tolerance, max_iterations)
            total += its
            history += hist
            if not ok:
                return X, total, norm, history, False
    finally:
        contact.stiffness, contact.damping = target_k, target_c
    return X, total, norm, history, True


def solve_line(line, seabed, contact, environment, fit_touchdown=True, tolerance=1e-8,
               max_iterations=50, assembly="kernel", max_fits=4):
    """Static equilibrium of one line; returns (LineSystem, StaticResult).

    The solution has a jump of curvature at the touchdown point (straight on the seabed,
    a catenary above it) that no element can hold inside itself: unfitted, it limits every
    element order to the slow convergence of obstacle problems. With ``fit_touchdown``, on a
    plane seabed under the anchor, the mesh gets a vertex at the touchdown and is re-solved
    until that vertex stops moving, so each element holds a smooth piece and the element
    order pays off (verification/elastic_catenary). The touchdown is located from the
    seabed's total reaction: on a frictionless plane the resting part carries exactly its own
    normal weight, so the reaction fixes the resting length, where the place at which the
    gap changes sign (tangent to the seabed there) is ill-conditioned.
    """
    from .system import LineSystem

    def build(candidate):
        return LineSystem(candidate, seabed, contact, environment, assembly=assembly)

    system = build(line)
    result = solve_static(system, tolerance=tolerance, max_iterations=max_iterations)
    length = line.unstretched_length
    if not (fit_touchdown and anchored_on_plane(line, seabed)):
        return system, result
    iterations, elapsed = result.iterations, result.wall_time_s
    vertex, settled = None, False
    for _ in range(max_fits):
        estimate = resting_length(system, result.X)
        settled = estimate is None or not (0.0 < estimate < length) or (
            vertex is not None and abs(estimate - vertex) <= 1e-6 * length)
        if settled:
            break
        vertex = estimate
        fitted = build(line.split_at(vertex))
        previous_system, previous = system, result
        guess = fitted.fem.interpolate(lambda s: previous_system.fem.evaluate(previous.X, s))
        start = time.perf_counter()
        X, its, norm, history, ok = _tension_only(fitted, guess, tolerance, max_iterations)
        iterations += its
        elapsed += time.perf_counter() - start
        if not ok:  # a refinement only: keep the last converged solution
            break
        system, result = fitted, StaticResult(X, its, norm, history, "newton")
    if not settled:
        result.strategy += " (touchdown vertex did not settle)"
    result.iterations, result.wall_time_s = iterations, elapsed
    return system, result


def anchored_on_plane(line, seabed):
    """True when the seabed is a plane and the line's anchor lies on it (within its resting
    penetration): the setting where the resting length locates the touchdown."""
    from .geometry import Plane

    if not isinstance(seabed, Plane):
        return False
    return abs(seabed.gap_only(line.anchor[None])[0]) <= 1e-3 * line.unstretched_length / len(
        line.node_arc_lengths())


def resting_length(system, X):
    """Arc length [m] from the anchor that the seabed's reaction (contact force plus the anchor's
    normal reaction) can carry at the line's normal weight, on a plane seabed; None without contact."""
    state = system.state(X)
    normal = system.seabed.normal
    force = system.contact.evaluate(state, jacobian=False).force
    reaction = np.sum(np.einsum("ceq,c->eq", force, normal) * system.fem.full.dx)
    if reaction <= 0.0:
        return None
    reaction += system.residual(X)[system.fem.anchor_dof] @ normal
    # cumulative normal weight along the line, element by element (piecewise constant w)
    env = system.environment
    props = system.props
    w = (props["mass"] - env.water_density * props["area"]) * env.gravity * normal[2]
    nodes = system.fem.mesh.p[0]
    cumulative = np.concatenate([[0.0], np.cumsum(w * np.diff(nodes))])
    k = int(np.searchsorted(cumulative, reaction)) - 1
    if k < 0 or k >= len(w):
        return None
    return float(nodes[k] + (reaction - cumulative[k]) / w[k])
