"""Pseudo-transient continuation of a network's coupling unknowns (Kelley & Keyes 1998, as
``cablefem.statics.newton.pseudo_transient`` does for one line): Newton on the balance r(q) = 0 of
``cablefem.statics.network`` with a pseudo-inertia, (J - D / tau) dq = -r, the pseudo time step tau
[s^2] grown as the residual falls (switched evolution relaxation), so that the first steps follow
a damped motion of the points and bodies and the last ones are Newton's.

Where Newton alone cannot go: a free body whose equilibrium is not near where the file puts it,
reached through a configuration where its lines are slack and the balance has no stiffness (a
Newton step from the slack tangent is ~1e6 m; MoorDyn's ``body_tests/bodyDrag.txt``: a 10 kg body
above its anchor, its weight and its line both pulling it down, hangs 10.4 m lower, below the
anchor). D is each unknown's mass (a body's mass and moments of inertia, a junction's own mass and
half its strings'); a neutral degree of freedom (a body whose forces all act at its reference
point has no moment about it) stays where it is.
"""

from dataclasses import dataclass, field

import numpy as np

from cablefem.errors import ConvergenceError


@dataclass
class Relaxed:
    """The result of ``relax``: the unknowns, the strings' states, the final relative residual,
    its history, the strings' Newton iterations and whether it converged."""

    q: np.ndarray
    states: list
    norm: float
    history: list = field(default_factory=list)
    iterations: int = 0
    converged: bool = False


def balance_norm(r, net, scale, length):
    """The balance's residual relative to the force scale (moments over the length scale)."""
    out = 0.0
    for name in net.junctions:
        o = net.offsets[name]
        out = max(out, np.linalg.norm(r[o:o + 3]))
    for name in net.bodies:
        o = net.offsets[name]
        out = max(out, np.linalg.norm(r[o:o + 3]), np.linalg.norm(r[o + 3:o + 6]) / length)
    return out / scale


def pseudo_masses(net):
    """D (size,): each coupling unknown's mass [kg] (translations) or moment of inertia [kg m^2]
    (rotations); a massless junction takes half the mass of its strings."""
    D = np.zeros(net.size)
    strings = {}
    for k, _, name in net.ends:
        system = net.systems[k]
        strings[name] = strings.get(name, 0.0) + 0.5 * float(np.sum(system.props["mass"] * np.diff(
            system.fem.mesh.p[0])))
    for name in net.junctions:
        o = net.offsets[name]
        D[o:o + 3] = net.scene.points[name].mass + strings.get(name, 0.0)
    for name in net.bodies:
        o, body = net.offsets[name], net.scene.bodies[name]
        share = sum(value for point, value in strings.items() if net.scene.points[point].body == name)
        D[o:o + 3] = body.mass + share
        D[o + 3:o + 6] = np.where(body.inertia > 0.0, body.inertia, D[o] * net.length() ** 2)
    return np.where(D > 0.0, D, 1.0)


def relax(net, q, states, tolerance, max_iterations):
    """Pseudo-transient continuation from q (``Network``'s unknowns) and the strings' ``states``
    (None: from their start shapes); a ``Relaxed``."""
    scale, length = net.scale(), net.length()
    D = pseudo_masses(net)
    places = net.place(q)
    iterations = net.solve_strings(places, states, tolerance, 50)
    r, J = net.balance(q, states, places)
    norm = balance_norm(r, net, scale, length)
    history = [norm]
    # the first step moves the most loaded unknown by a tenth of the shortest string
    tau = 0.1 * length * float(np.min(D / np.maximum(np.abs(r), 1e-300)))
    for _ in range(max_iterations):
        if norm <= tolerance:
            return Relaxed(q, states, norm, history, iterations, True)
        step = np.linalg.lstsq(J - np.diag(D / tau), -r, rcond=None)[0]
        trial_states = list(states)
        trial_q = q + step
        trial_places = net.place(trial_q)
        try:
            iterations += net.solve_strings(trial_places, trial_states, tolerance, 50)
        except ConvergenceError:
            tau *= 0.25
            continue
        r_t, J_t = net.balance(trial_q, trial_states, trial_places)
        norm_t = balance_norm(r_t, net, scale, length)
        if not np.isfinite(norm_t):
            tau *= 0.25
            continue
        tau *= min(10.0, max(norm / norm_t, 0.1))  # switched evolution relaxation
        q, states, places, r, J, norm = trial_q, trial_states, trial_places, r_t, J_t, norm_t
        history.append(norm)
        if np.max(np.abs(step)) <= tolerance * length and norm <= 1e-3:  # Newton's last steps at round-off
            return Relaxed(q, states, norm, history, iterations, True)
    return Relaxed(q, states, norm, history, iterations, norm <= tolerance)
