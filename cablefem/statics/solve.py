"""The static solve of one line: Newton from a start shape, and the strategies tried in turn when it
fails (desire2023 Sec. 2.3).

Newton first (``cablefem.statics.newton``); if it fails, pseudo-transient continuation (a damped
pseudo-motion that ends in Newton), continuation on the axial stiffness (a line far stiffer than its
loads, soft first), letting the line settle in water (``settle``: a lazy wave's buoyant section rising
into its arch, slack chain sliding down a slope), then continuation on the seabed stiffness (soft
ground first, stiffened in steps, ``cablefem.statics.continuation``); if that fails too, it stops with
the residual and what to try.
"""

import time

import numpy as np

from cablefem.errors import ConvergenceError
from cablefem.statics.continuation import (axial_continuation, point_continuation,
    stiffness_continuation)
from cablefem.statics.newton import (StaticResult, newton, point_loads, pseudo_transient,
    scale_free_residual, tension_only)
from cablefem.statics.start_shape import hangs, initial_shape

#: ``settle``: the time step [s] of the damped motion and the simulated time [s] between attempts of
#: Newton to finish from where the line has got to (at most ``max_iterations`` of them: a lazy wave
#: took 6-17, 1200 m of chain slack on a frictionless 5 deg slope 33-39)
SETTLE_DT, SETTLE_CHUNK = 0.5, 10.0


def solve_static(system, X0=None, tolerance=1e-8, max_iterations=50):
    """Static equilibrium of one line system from the catenary guess (or X0); a StaticResult.

    Newton first; if it fails, pseudo-transient continuation (a damped pseudo-motion), then
    continuation on the axial stiffness (a line far stiffer than its loads), then the line let go
    in water until it settles (``settle``: a buoyant section rising off the seabed into its arch,
    which Newton cannot reach from a start with the section lying slack), then continuation on
    the seabed stiffness (``cablefem.statics.continuation``), each from the start. From the hang of a
    line with one free end (``cablefem.statics.hang``) the points' loads are there from the first
    Newton and axial continuation comes before pseudo-transient."""
    start = time.perf_counter()
    X, slack = initial_shape(system) if X0 is None else (X0, False)
    system.reset_history(X)  # a load's history starts at the start shape (``initial_history``)
    hanging = X0 is None and hangs(system)
    # the points' loads by continuation from none, unless the start already carries them (a hang)
    first = tension_only if point_loads(system) is None or hanging else point_continuation
    strategies = [("newton", lambda: first(system, X, tolerance, max_iterations, push=not (slack or hanging))),
                  ("pseudo-transient", lambda: pseudo_transient(system, X, tolerance, 10 * max_iterations)),
                  ("axial continuation", lambda: axial_continuation(system, X, tolerance, max_iterations)),
                  ("settling", lambda: settle(system, X, tolerance, max_iterations)),
                  ("continuation", lambda: stiffness_continuation(system, X, tolerance, max_iterations))]
    # the hang has the shape; what Newton misses is a stiff line's swing to where its end rests. A line
    # stiff axially against its bending: soft EA first too (a lazy wave from the catenary start: 182
    # iterations, where pseudo-transient spent 500)
    if hanging or system.has("bending"):
        strategies.insert(1, strategies.pop(2))
    total, history, best = 0, [], np.inf
    for name, strategy in strategies:
        X1, its, norm, hist, ok = strategy()
        total, history, best = total + its, history + hist, min(best, norm)
        if ok:
            increment = scale_free_residual(system, X1)  # evaluated at X1: the history's trial there
            system.commit_history()
            return StaticResult(X1, total, norm, history, name, time.perf_counter() - start, slack, increment)
    raise ConvergenceError(
        f"line '{system.line.name}': static solve did not converge: relative residual "
        f"{best:.3g} after {total} Newton iterations (tolerance {tolerance:g}); "
        "try more elements, a lower element order, a softer seabed stiffness, or check that "
        "the fairlead is within reach of the line",
        residual=best, iterations=total)


def settle(system, X, tolerance=1e-8, max_iterations=50):
    """Let the line go from X (N, 3) in still water, ends held, and follow it (BDF2 with large steps:
    strongly damped) with drag, added mass and seabed damping until Newton on the static residual
    converges from where it has got to: however the physics settles it (a buoyant section rising
    into its arch, slack chain folding). Drag coefficients below 1.2 normal and 0.5 tangential
    are raised to them for the settling; at most ``max_iterations`` rounds of ``SETTLE_CHUNK``. Same
    returns as ``newton``."""
    from cablefem.dynamics.bdf2 import BDF2
    from cablefem.loads.added_mass import AddedMass
    from cablefem.loads.drag import Drag
    from cablefem.fem.system import LineSystem

    props, env = system.props, system.environment
    drag = Drag(props["diameter"], np.maximum(props["Cd_normal"], 1.2), np.maximum(props["Cd_tangential"], 0.5),
                env.water_density)
    added = AddedMass(props["diameter"], props["Ca_normal"], props["Ca_tangential"], env.water_density)
    moving = LineSystem(system.line, system.seabed, system.contact_settings, env, extra_loads=[drag, added],
                        assembly=system.assembly, fem=system.fem, sections=system.setting.sections)
    fairlead = system.line.fairlead.copy()
    zero = np.zeros(3)
    integ = BDF2(moving, X, lambda t: (fairlead, zero, zero), dt=SETTLE_DT, tolerance=1e-6)
    total, history, norm = 0, [], np.inf
    try:
        for _ in range(max_iterations):
            integ.march(integ.t + SETTLE_DT * np.arange(1, int(SETTLE_CHUNK / SETTLE_DT) + 1))
            X1, its, norm, hist, ok = newton(system, integ.X, tolerance, max_iterations)
            total, history = total + its + integ.steps, history + hist
            integ.steps = 0
            if ok:
                return X1, total, norm, history, True
    except ConvergenceError:
        pass
    return integ.X, total, norm, history, False
