"""Pseudo-transient continuation of a network's coupling unknowns (Kelley & Keyes 1998, as
``cablefem.statics.newton.PseudoTransient`` does for one line), a globalisation of the statics'
one Newton loop (``cablefem.statics.newton.iterate``) on the balance r(q) = 0 of
``cablefem.statics.network``: the step solves (J - D / tau) dq = -r, a pseudo-inertia D with the
pseudo time step tau [s^2] grown as the residual falls (switched evolution relaxation, tau times the
residual's fall, and at least doubled by a step that lowers it: with the fall alone riser_ic1.txt
crept at 10 % a step for 25 steps, 83 steps in all against 49), so that the first steps follow a
damped motion of the points and bodies and the last ones are Newton's.

Where Newton alone cannot go: a free body whose equilibrium is not near where the file puts it,
reached through a configuration where its lines are slack and the balance has no stiffness (a
Newton step from the slack tangent is ~1e6 m; MoorDyn's ``body_tests/bodyDrag.txt``: a 10 kg body
above its anchor, its weight and its line both pulling it down, hangs 10.4 m lower, below the
anchor). D is each unknown's mass (a body's mass and moments of inertia, a junction's own mass and
half its strings'); a neutral degree of freedom (a body whose forces all act at its reference
point has no moment about it) stays where it is.
"""

import numpy as np

from cablefem.errors import ConvergenceError


class NetworkPseudoTransient:
    """The globalisation (``iterate``'s ``direction``, ``search``, ``stalled``): the first step
    moves the most loaded unknown by a tenth of the shortest string; every step is taken whole, and
    one whose strings cannot be solved, or whose residual is not finite, is taken again with tau a
    quarter (at most ``TRIES`` times). It has converged when the step is small (Newton's last steps
    at round-off) and the residual below 1e-3."""

    TRIES = 30

    def __init__(self, net):
        self.D, self.length = pseudo_masses(net), net.length()
        self.tau = None
        self.tangent = self.residual = self.step = None

    def direction(self, problem, tangent, residual):
        if self.tau is None:
            self.tau = 0.1 * self.length * float(np.min(self.D / np.maximum(np.abs(residual), 1e-300)))
        self.tangent, self.residual = tangent, residual
        return self._step()

    def _step(self):
        self.step = np.linalg.lstsq(self.tangent - np.diag(self.D / self.tau), -self.residual, rcond=None)[0]
        return self.step

    def search(self, problem, point, residual, norm, step):
        for _ in range(self.TRIES):
            try:
                trial = problem.trial(point, self.step, 1.0)
                residual_t, tangent_t, norm_t = problem.evaluate(trial)
                if np.isfinite(norm_t):
                    return trial, residual_t, tangent_t, norm_t, 1.0
            except ConvergenceError:
                pass
            self.tau *= 0.25
            self._step()
        return None

    def stalled(self, problem, step, lam, norm, norm_t):
        self.tau *= min(10.0, max(norm / norm_t, 2.0 if norm_t < norm else 0.1)) if norm_t > 0.0 else 10.0
        return problem.small(self.step) and norm_t <= 1e-3


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
        if body.rod is not None:  # a rod's unknowns are its two ends
            D[o + 3:o + 6] = D[o]
    return np.where(D > 0.0, D, 1.0)
