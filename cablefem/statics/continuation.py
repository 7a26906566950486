"""Continuation strategies of the static solve (``cablefem.statics.solve.solve_static``): Newton through a
sequence of problems that rises to the scene's, each stage started from the last one's answer:
the line's points' weight and buoyancy from none to theirs, the seabed stiffness from soft to the
scene's, the axial stiffness from soft to the line's."""

import numpy as np

from cablefem.statics.newton import point_loads, tension_only, newton, pseudo_transient


def point_continuation(system, X, tolerance, max_iterations, push=True):
    """Newton with the weight and buoyancy of the line's points raised from none to theirs: the start
    shape (a catenary of the line alone) is far from the shape a clump weight or a buoy gives it,
    and each stage starts from the last one's solution; a stage that fails is halved (down to
    1/64 of the way)."""
    points = point_loads(system)
    dry, buoyancy = points.dry.copy(), points.buoyancy.copy()
    done, step, total, history = 0.0, 0.25, 0, []
    try:
        X, its, norm, hist, ok = tension_only(system, _scaled(points, dry, buoyancy, 0.0, X), tolerance,
                                              max_iterations, push)
        total, history = total + its, history + hist
        while ok and done < 1.0:
            target = min(1.0, done + step)
            X1, its, norm, hist, ok1 = tension_only(system, _scaled(points, dry, buoyancy, target, X), tolerance,
                                                    max_iterations, push)
            total, history = total + its, history + hist
            if ok1:
                X, done, step = X1, target, min(2.0 * step, 1.0)
            elif step > 1.0 / 64.0:
                step *= 0.5
            else:
                ok = False
    finally:
        points.dry, points.buoyancy = dry, buoyancy
    return X, total, norm, history, ok and done >= 1.0


def _scaled(points, dry, buoyancy, factor, X):
    """Set the points' weight and buoyancy to ``factor`` of theirs; returns X (for chaining)."""
    points.dry, points.buoyancy = factor * dry, factor * buoyancy
    return X


def stiffness_continuation(system, X, tolerance, max_iterations, factor=10.0):
    """Newton through a sequence of seabed stiffnesses rising geometrically to the scene's (a line in
    soil has no contact spring to soften: no continuation)."""
    if not system.has("contact"):
        return X, 0, np.inf, [], False
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


def axial_continuation(system, X, tolerance, max_iterations):
    """Newton through axial stiffnesses EA rising from a hundred times the line's submerged weight
    to the scene's, a decade a stage, a stage that fails halved (to an eighth of a decade, then
    pseudo-transient). A line far stiffer than its loads (a float of EA 2e9 N on 0.2 m elements
    swinging onto the surface) leaves Newton a basin of micrometres: a transverse step d stretches
    an element by d^2 / 2h, a force EA d^2 / 2h^2. Soft, the shape settles; each stiffer stage
    starts from the last one's answer. Same returns as ``newton``."""
    tension = system.tension
    target = tension.EA.copy()
    if not np.any(target > 0.0):  # a rope of a law of its own (cablefem.loads.rope) throughout: no EA to scale
        return X, 0, np.inf, [], False
    level = np.log10(100.0 * float(np.linalg.norm(system.weight_vector())) / float(np.max(target)))
    if level >= -1.0:  # not stiff against its loads: nothing to gain over Newton and its fallbacks
        return X, 0, np.inf, [], False
    total, history, done, step = 0, [], None, 1.0  # done: the last level solved
    try:
        while True:
            tension.EA = target * 10.0 ** level
            X1, its, norm, hist, ok = tension_only(system, X, tolerance, max_iterations, push=done is None)
            if not ok and (done is None or level - done <= 0.125):
                X1, more, norm, hist_pt, ok = pseudo_transient(system, X, tolerance, 10 * max_iterations)
                its, hist = its + more, hist + hist_pt
            total, history = total + its, history + hist
            if ok:
                if level == 0.0:
                    return X1, total, norm, history, True
                X, done, step = X1, level, min(2.0 * step, 1.0)
            elif done is not None and level - done > 0.125:
                step = 0.5 * (level - done)
            else:
                return X, total, norm, history, False
            level = min(done + step, 0.0)
    finally:
        tension.EA = target
