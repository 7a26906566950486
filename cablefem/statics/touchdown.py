"""Static equilibrium of a line with its mesh fitted to where the solution kinks: the touchdown
point of a line that touches down (from the seabed's reaction), the feet of the vertical parts of
a line longer than it needs (from the slack layout). ``solve_line`` is the statics a scene runs
(``cablefem static``); ``cablefem.statics.newton`` solves one mesh.
"""

import time

import numpy as np

from cablefem.statics.start_shape import mean_weight, resting_sink, slack_hangs
from cablefem.statics.newton import StaticResult, tension_only, scale_free_residual
from cablefem.statics.solve import solve_static


def solve_line(line, seabed, contact, environment, fit_touchdown=True, tolerance=1e-8,
               max_iterations=50, assembly="kernel", max_fits=4, sections=None, fem=None):
    """Static equilibrium of one line; returns (LineSystem, StaticResult).

    The solution has a jump of curvature at the touchdown point (straight on the seabed,
    a catenary above it) that no element can hold inside itself: unfitted, it limits every
    element order to the slow convergence of obstacle problems. With ``fit_touchdown``, on a
    plane seabed under the anchor, the mesh gets a vertex at the touchdown and is re-solved
    until that vertex stops moving, so each element holds a smooth piece and the element
    order pays off (verification/elastic_catenary). The touchdown is located from the
    seabed's total reaction: on a frictionless plane the resting part carries exactly its own
    normal weight, so the reaction fixes the resting length, where the place at which the
    gap changes sign (tangent to the seabed there) is ill-conditioned. ``sections``: the scene's
    tables of the catalog's loads (``Scene.load_settings``); ``fem``: the ``LineFEM`` of another
    system of the line as given, shared.
    """
    from cablefem.fem.system import LineSystem

    def build(candidate, fem=None):
        return LineSystem(candidate, seabed, contact, environment, assembly=assembly, sections=sections, fem=fem)

    system = build(line, fem)
    if fit_touchdown:
        system = _fit_slack(build, system)
    result = solve_static(system, tolerance=tolerance, max_iterations=max_iterations)
    length = line.unstretched_length
    if result.slack_start or not (fit_touchdown and anchored_on_plane(line, seabed)):
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
        refit = _refit(build, line, system, result, vertex, tolerance, max_iterations)
        if refit is None:  # a refinement only: keep the last converged solution
            break
        system, fitted = refit
        iterations += fitted.iterations
        elapsed += fitted.wall_time_s
        result = fitted
    if not settled:
        result.strategy += " (touchdown vertex did not settle)"
    result.iterations, result.wall_time_s = iterations, elapsed
    return system, result


def _refit(build, line, system, result, vertex, tolerance, max_iterations):
    """``line`` with a mesh vertex at the arc length ``vertex`` [m], solved from the solution
    ``result`` of ``system`` interpolated onto it: (LineSystem, StaticResult), or None if Newton
    failed."""
    fitted = build(line.split_at(vertex))
    guess = fitted.fem.interpolate(lambda s: system.fem.evaluate(result.X, s))
    start = time.perf_counter()
    X, its, norm, history, ok = tension_only(fitted, guess, tolerance, max_iterations)
    if not ok:
        return None
    return fitted, StaticResult(X, its, norm, history, "newton", time.perf_counter() - start,
                                result.slack_start, scale_free_residual(fitted, X))


def _fit_slack(build, system):
    """The system of a line longer than it needs, built with mesh vertices where the slack layout
    (``cablefem.statics.start_shape``) puts the feet of its vertical parts on the seabed; ``system``
    itself for any other line. There the line bends through a right angle, which no element
    holds inside itself (and which the resting length, a fixed-point iteration, does not settle
    on): the layout's vertices are where the solution has them."""
    line = system.line
    weight, EA = mean_weight(line, system.environment)
    hangs = slack_hangs(line, system.seabed, weight, EA, resting_sink(system, weight))
    if weight <= 0.0 or hangs is None:
        return system
    length = line.unstretched_length
    for s in (hangs[0], length - hangs[1]):
        if 0.0 < s < length:
            line = line.split_at(s)
    return build(line)


def anchored_on_plane(line, seabed):
    """True when the seabed is a plane and the line's anchor lies on it (within its resting
    penetration): the setting where the resting length locates the touchdown."""
    from cablefem.geometry import Plane

    if not isinstance(seabed, Plane):
        return False
    return abs(seabed.gap_only(line.anchor[None])[0]) <= 1e-3 * line.unstretched_length / len(
        line.node_arc_lengths())


def resting_length(system, X):
    """Arc length [m] from the anchor that the seabed's reaction (contact force plus the anchor's
    normal reaction) can carry at the line's normal weight, on a plane seabed; None without contact."""
    if not system.has("contact"):
        return None
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
