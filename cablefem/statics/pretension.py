"""The pretension process of a line in soil (rui2025 Sec. 3.2, Fig. 3b): the statics of a scene
with ``[soil]``.

A line in clay has no single equilibrium: the soil's reaction depends on how the line got where it
is (``cablefem.loads.soil`` keeps it as history). So ``cablefem static`` does not jump to an
equilibrium; it follows the installation, as rui2025 Fig. 3b does in SIMA:

- ``installation = "laid"`` (the default): the line is laid first, straight from the padeye to the
  level of the lying chain (vertically, up for a padeye below it, down for one on the mudline:
  rui2025's L1), then along the surface towards the platform (L2). The lying part is laid where its
  bearing capacity carries its weight (``resting_depth``: with su(0) = 0 a chain sinks until
  E_n d_b N_c s_u = w), its soil springs at yield upwards; every other point's are unloaded. The
  laid state is solved with the line's end held where it lies; then the end is moved to the
  fairlead in load steps along the straight line between them, Newton per step from the last
  (``cablefem.statics.newton.newton``), the soil's history committed after each accepted step. A step
  that fails is halved (and the next ones grow back by doubling, up to the first step's size).
- ``installation = "catenary"``: no path. The line starts at the frictionless equilibrium (the
  conventional model: ``cablefem static`` without ``[soil]``, the seabed as a frictionless contact
  spring), the soil takes over there with every spring unloaded (each point held where it is), and
  one static solve lets the line settle into the soil (the lying part sinks to its resting depth).
  It is a line placed in its final shape without mobilising any friction: the conventional model's
  answer with the soil's bearing added, a bound on what the pretension path changes.

The final state is the static result and the start of ``cablefem run`` (``cablefem.runs.run``), whose
systems take over its history.
"""

import time
from dataclasses import dataclass, field

import numpy as np

from cablefem.errors import ConvergenceError
from cablefem.statics.newton import StaticResult, newton, pseudo_transient
from cablefem.statics.solve import solve_static

#: the largest strain of an element in an accepted load step (``validate.MAX_CHORD_STRAIN``: beyond
#: anything a line reaches; a folded line's elements do)
MAX_STRAIN = 0.2
#: the smallest load step, as a fraction of the path, before the path gives up
MIN_STEP = 1.0 / 4096.0
#: points per metre of lying line sampled to follow a curved surface
SURFACE_SAMPLES = 4.0
#: a relative residual within this factor of the tolerance is round-off (measured: 2-3e-8 at a
#: tolerance of 1e-8 on 0.5 m elements of EA 3.27e9 N), and only that close does a step count as
#: solved: pseudo-transient continuation that stops there is finished by Newton's round-off test
ROUNDOFF = 100.0


@dataclass
class PretensionResult(StaticResult):
    """A ``StaticResult`` of the pretension path, with its installation, the accepted load steps,
    the halvings of failed ones, the fairlead's positions (k, 3) after each accepted step and the
    plastic dissipation [J] of each (``soil.plastic_dissipation``)."""

    installation: str = "laid"
    steps: int = 0
    halvings: int = 0
    path: list = field(default_factory=list)
    dissipation: list = field(default_factory=list)


def soil_keys(system):
    """The scene's [soil] table of a system's line (its ``Setting``), with the defaults filled in."""
    from cablefem.loads.soil import DEFAULTS

    return dict(DEFAULTS, **system.setting.sections["soil"])


def resting_depth(system):
    """Depth [m] (nel,) below the surface at which each element's bearing yield force per unit length
    (E_n N_c d_b s_u, ``Soil``) carries its submerged weight; 0 for a buoyant element."""
    soil, props, env = system.load("soil"), system.props, system.environment
    w = (props["mass"] - env.water_density * props["area"]) * env.gravity
    low, high = np.zeros_like(w), np.full_like(w, 1.0)
    while True:  # bracket: the strength grows with depth (not both su0 and su1 zero: checked on reading)
        short = soil.a_n[:, 0] * soil.strength(high[:, None])[0][:, 0] < w
        if not np.any(short):
            break
        high = np.where(short, 2.0 * high, high)
    for _ in range(80):
        mid = 0.5 * (low + high)
        below = soil.a_n[:, 0] * soil.strength(mid[:, None])[0][:, 0] < w
        low, high = np.where(below, mid, low), np.where(below, high, mid)
    return np.where(w > 0.0, 0.5 * (low + high), 0.0)


def laid_shape(system):
    """The laid line (module docstring): positions X (N, 3) and the end's laid position (3,). Each
    element is laid straight at its own length between vertices on the route (padeye, the lying
    level above or below it, then along the surface), the one that holds the corner across it: no
    element starts stretched or squeezed, whatever the mesh."""
    line, seabed, fem = system.line, system.seabed, system.fem
    anchor, length = line.anchor, line.unstretched_length
    depth = float(np.max(resting_depth(system)))
    chord = line.fairlead[:2] - anchor[:2]
    span = float(np.hypot(*chord))
    u = chord / span if span > 1e-9 * length else np.array([1.0, 0.0])
    path = _surface_path(seabed, anchor[:2], u, depth, 1.5 * length)
    top = path(np.zeros(1))[0]
    hang = float(np.linalg.norm(top - anchor))
    if hang >= length:
        raise ConvergenceError(f"line '{line.name}': its {length:g} m do not reach from the padeye to the "
                               f"lying level {hang:.6g} m away: nothing to lay on the surface")

    def route(sigma):
        """The route at its own arc length sigma (n,) [m]: the climb, then the lying path."""
        sigma = np.asarray(sigma, dtype=float)
        out = path(np.maximum(sigma - hang, 0.0))
        climbing = sigma < hang
        out[climbing] = anchor + (sigma[climbing] / max(hang, 1e-300))[:, None] * (top - anchor)
        return out

    nodes = fem.mesh.p[0]
    vertices = _chord_walk(route, np.diff(nodes))

    def positions(s):
        return np.column_stack([np.interp(s, nodes, vertices[:, k]) for k in range(3)])

    return fem.interpolate(positions), vertices[-1]


def _chord_walk(route, lengths):
    """Vertices (n + 1, 3) along ``route(sigma)`` from sigma = 0, each at the straight distance
    ``lengths`` (n,) [m] from the one before (the route's own arc length where it is straight,
    bisection on sigma where it turns or curves)."""
    sigma = np.zeros(len(lengths) + 1)
    points = np.empty((len(lengths) + 1, 3))
    points[0] = route(np.zeros(1))[0]
    for k, h in enumerate(lengths):
        low, high = sigma[k], sigma[k] + h
        if np.linalg.norm(route(np.array([high]))[0] - points[k]) < h * (1.0 - 1e-12):
            low, high = high, sigma[k] + 2.0 * h  # a corner or a curve shortens the chord
            for _ in range(60):
                mid = 0.5 * (low + high)
                shorter = np.linalg.norm(route(np.array([mid]))[0] - points[k]) < h
                low, high = (mid, high) if shorter else (low, mid)
        sigma[k + 1] = high
        points[k + 1] = route(np.array([high]))[0]
    return points


def _surface_path(seabed, start_xy, u, depth, reach):
    """Points at arc length sigma (n,) [m] along the surface from above/below ``start_xy`` (2,)
    in the horizontal direction u (2,), ``depth`` [m] below it along its normal (n, 3)."""
    count = int(max(64, SURFACE_SAMPLES * reach))
    xy = start_xy + np.linspace(0.0, reach, count)[:, None] * u
    foot = np.column_stack([xy, seabed.elevation(xy)])
    normal = seabed.project(foot + np.array([0.0, 0.0, 1e-3])).direction
    points = foot - depth * normal
    sigma = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])

    def at(arc):
        arc = np.asarray(arc, dtype=float)
        return np.column_stack([np.interp(arc, sigma, points[:, k]) for k in range(3)])

    return at


def start_laid(system):
    """The laid state (``laid_shape``) and the soil's history there: every point below the surface
    held where its springs carry its weight as far as they can (``carrying_anchors``: the lying
    chain at its bearing yield, the buried part by its side friction). Returns (X, the end's
    position)."""
    X, end = laid_shape(system)
    system.reset_history(X)
    anchors = carrying_anchors(system, X)
    for records in system.history["full"]:
        records["soil"]["anchor"] = anchors
    return X, end


def carrying_anchors(system, X):
    """Anchors q (nel, nq, 3) at which the soil's reaction at X (N, 3) balances each full point's
    submerged weight w, along the line (clipped to the yield t_f) and across it (to n_f): with the
    springs of ``Soil`` f = -s_u (E_t d_b c t + E_n N_c d_b h e_n) = w e_z."""
    soil, props, env = system.load("soil"), system.props, system.environment
    state = system.state(X)
    depth, _ = soil.depth(state.r)
    s, _ = soil.strength(depth)
    w = ((props["mass"] - env.water_density * props["area"]) * env.gravity)[:, None]
    t = state.dr / np.linalg.norm(state.dr, axis=0)
    up = np.array([0.0, 0.0, 1.0])[:, None, None]
    along = t[2] * w  # R . t with R = w e_z
    across = w * up - along * t
    safe = np.where(s > 0.0, s, 1.0)
    c = np.clip(-along / (safe * soil.a_t), -1.0, 1.0)
    e_n = -across / (safe * soil.a_n * soil.k_n)
    size = np.sqrt(np.einsum("ceq,ceq->eq", e_n, e_n))
    e_n *= np.minimum(1.0, 1.0 / np.maximum(soil.k_n * size, 1e-300))
    offset = np.where(s > 0.0, c / soil.k_t * t + e_n, 0.0)
    return np.moveaxis(state.r - offset, 0, -1)


def start_catenary(system, tolerance, max_iterations):
    """The frictionless equilibrium of the line (the scene without [soil]) as the start, the soil's
    springs unloaded there. Returns (X, the end's position: the fairlead)."""
    from cablefem.fem.system import LineSystem

    sections = {k: v for k, v in system.setting.sections.items() if k != "soil"}
    frictionless = LineSystem(system.line, system.seabed, system.contact_settings, system.environment,
                              assembly=system.assembly, fem=system.fem, sections=sections)
    X = solve_static(frictionless, tolerance=tolerance, max_iterations=max_iterations).X
    system.reset_history(X)
    return X, system.line.fairlead.copy()


def solve_pretension(system, tolerance=1e-8, max_iterations=50, trace=None):
    """Static state of a line in soil by its installation (module docstring); a ``PretensionResult``.
    ConvergenceError when a step fails below ``MIN_STEP`` of the path or the start does not settle.

    The start and the path are solved with a chain that may push (``Tension.compression``, the
    statics' start-up law): the laid chain rests at zero strain, where the tension-only law has its
    kink and Newton's tangent and residual part ways at every element not yet pulled; in the clay,
    the links of the climb bear on one another where the side friction does not carry their weight
    (a few kN against the MN of the pull). The final state is solved once more with the
    tension-only law from there: the same state wherever no element pushes. ``trace``: a list that
    gets every accepted state (``LoadPath``)."""
    start = time.perf_counter()
    keys = soil_keys(system)
    installation = keys["installation"]
    path = LoadPath(system, tolerance, max_iterations, installation, trace)
    X, end = start_laid(system) if installation == "laid" else start_catenary(system, tolerance, max_iterations)
    anchor, fairlead = system.line.anchor, system.line.fairlead
    system.tension.compression = True
    try:
        path.settle(X, np.array([anchor, end]), "start")
        if installation == "laid":
            path.follow(np.array([anchor, end]), np.array([anchor, fairlead]), keys["installation_steps"])
    finally:
        system.tension.compression = False
    path.settle(path.X, np.array([anchor, fairlead]), "tension-only end")
    from cablefem.statics.newton import scale_free_residual

    result = path.result
    result.X = path.X
    result.increment = scale_free_residual(system, path.X)  # evaluates at X: the trial history is X's own
    result.strategy = f"pretension ({installation}, {result.steps} steps, {result.halvings} halved)"
    result.wall_time_s = time.perf_counter() - start
    return result


class LoadPath:
    """Quasi-static load steps of a line in soil, its ends moved: each step solved from the last
    accepted state, the soil's history committed when it is accepted (``result``, a
    ``PretensionResult``, counts them). Ends are (2, 3) arrays: the anchor's position, then the
    fairlead's (the line's end)."""

    def __init__(self, system, tolerance=1e-8, max_iterations=50, installation="laid", trace=None):
        self.system, self.tolerance, self.max_iterations = system, tolerance, max_iterations
        self.result = PretensionResult(None, 0, np.nan, installation=installation)
        self.X = None
        self.trace = trace  # a list: each accepted state's (X, ends, committed full-point history) goes there

    def solve(self, X, ends, guess=None):
        """Newton with the ends at ``ends`` from ``guess`` (or X), else pseudo-transient continuation
        from X (its mass term carries what has little stiffness: points at yield, slack chain);
        (X, iterations, residual, history, ok)."""
        system, rows = self.system, list(self.system.fem.end_dofs)
        trial = (X if guess is None else guess).copy()
        trial[rows] = ends
        X1, its, norm, hist, ok = newton(system, trial, self.tolerance, self.max_iterations)
        # Newton's round-off test (a full step below the tolerance of the line's length that no longer
        # halves the residual) also passes where a slack element's kink stops it far from the answer
        if ok and norm <= ROUNDOFF * self.tolerance and self.sane(X1):
            return X1, its, norm, hist, ok
        trial = X.copy()
        trial[rows] = ends
        # to the round-off band only: its pseudo time steps stop growing at the floor
        X1, its2, norm, hist2, ok = pseudo_transient(system, trial, ROUNDOFF * self.tolerance, 10 * self.max_iterations)
        if ok and norm > self.tolerance:  # Newton, and its round-off test, polish from there
            X2, its3, norm2, hist3, polished = newton(system, X1, self.tolerance, self.max_iterations)
            its2, hist2 = its2 + its3, hist2 + hist3
            if polished and norm2 <= norm:
                X1, norm = X2, norm2
        return X1, its + its2, norm, hist + hist2, ok and norm <= ROUNDOFF * self.tolerance and self.sane(X1)

    def sane(self, X):
        """Whether no element of X (N, 3) is stretched or squeezed beyond ``MAX_STRAIN``: a step too large
        lets Newton reach equilibria of a folded line (a line that may push has them)."""
        return bool(np.max(np.abs(self.system.tension_strain(X))) <= MAX_STRAIN)

    def accept(self, X1, its, norm, hist, where):
        """Commit the state X1 reached with the ends at ``where`` (the fairlead's is recorded)."""
        from cablefem.loads.soil import plastic_dissipation

        result, system = self.result, self.system
        old, new = system.history["full"]
        result.dissipation.append(plastic_dissipation(old, new, system.fem.full.dx))
        system.commit_history()
        result.iterations += its
        result.residual, result.history = norm, result.history + hist
        result.path.append(np.asarray(where, dtype=float)[1].copy())
        self.X = X1
        if self.trace is not None:
            self.trace.append((X1.copy(), np.asarray(where, dtype=float).copy(), old.copy()))

    def settle(self, X, ends, what):
        """One solve with the ends held at ``ends`` from X (the start, the last state)."""
        X1, its, norm, hist, ok = self.solve(X, ends)
        if not ok:
            raise ConvergenceError(f"line '{self.system.line.name}': the {what} of the pretension path did not "
                                   f"settle: relative residual {norm:.3g} after {its} Newton iterations",
                                   residual=norm, iterations=its)
        self.accept(X1, its, norm, hist, ends)

    def follow(self, start, final, steps):
        """The ends moved along straight lines from ``start`` to ``final`` (2, 3) in ``steps`` equal
        steps, halving failed ones (the next grow back by doubling, up to the first size)."""
        result = self.result
        done, step = 0.0, 1.0 / steps
        first, before, last = step, None, None
        while done < 1.0 - 1e-12:
            size = min(step, 1.0 - done)
            target = start + (done + size) * (final - start)
            # the path is straight and steady: the last step's motion, scaled, predicts this one's
            guess = None if before is None else self.X + (size / last) * (self.X - before)
            X1, its, norm, hist, ok = self.solve(self.X, target, guess)
            if not ok:
                result.iterations += its
                result.halvings += 1
                step = 0.5 * size
                if step < MIN_STEP:
                    raise ConvergenceError(
                        f"line '{self.system.line.name}': pretension step {result.steps + 1} failed at "
                        f"{100 * done:.3g} % of the path with steps down to {size:.3g} of it: relative "
                        f"residual {norm:.3g}", residual=norm, iterations=result.iterations)
                continue
            before, last = self.X, size
            self.accept(X1, its, norm, hist, target)
            done += size
            result.steps += 1
            step = min(first, 2.0 * size)
