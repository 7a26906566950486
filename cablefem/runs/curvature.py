"""The curvature [1/m] and bending moment [N m] of a line on Hermite elements at a state: at arc
lengths, at its vertices, its peak, and at its clamped ends (``cablefem.loads.bending``; zero on
Lagrange elements, whose tangent jumps at every vertex).
"""

import numpy as np


def curvature_at(system, X, s):
    """Curvature kappa = |r' x r''| / |r'|^3 [1/m] (n,) at arc lengths s (n,) [m], inside the element
    holding each s (``cablefem.loads.bending``); zero on Lagrange elements (no C1 curvature)."""
    from cablefem.loads.bending import curvature

    s = np.atleast_1d(np.asarray(s, dtype=float))
    if not system.fem.hermite:
        return np.zeros(s.shape)
    return curvature(system.fem.derivative(X, s).T, system.fem.second_derivative(X, s).T)


def node_curvature(system, X):
    """Curvature [1/m] and bending moment EI kappa [N m] at the vertices (n,), anchor first: r'' jumps
    at an interior vertex, so the two elements' values there are averaged; zero on Lagrange
    elements, and the moment zero where EI = 0 (a vertex between two types takes the mean of EI
    kappa of its two sides). ``cablefem.runs.results.report`` puts a clamped end's reaction at its end (``clamped_ends``)."""
    fem = system.fem
    nodes = fem.mesh.p[0]
    if not fem.hermite:
        zero = np.zeros(len(nodes))
        return zero, zero.copy()
    inset = 1e-9 * np.diff(nodes)
    sides = [nodes[:-1] + inset, nodes[1:] - inset]  # each element's left and right end
    EI = system.props["EI"]
    kappa = [curvature_at(system, X, s) for s in sides]
    moment = [EI * k for k in kappa]
    out = []
    for left, right in (kappa, moment):
        values = np.empty(len(nodes))
        values[1:-1] = 0.5 * (right[:-1] + left[1:])
        values[0], values[-1] = left[0], right[-1]
        out.append(values)
    return tuple(out)


#: where r'' of a cubic Hermite element is most accurate: its two Gauss points (the Barlow points of
#: the beam's moment), as fractions of the element
BARLOW = (0.5 - 0.5 / 3.0**0.5, 0.5 + 0.5 / 3.0**0.5)


def curvature_peak(system, X, within=None):
    """The largest curvature [1/m] of a Hermite line at state X and the arc length [m] where it is:
    kappa at each element's two Gauss points, the peak refined by the parabola through the largest and
    its two neighbours (the lazy wave's peak within 0.1 % at 5 m elements, where the largest of 16
    samples an element is 2.8 % high: validation/cables); ``within`` (lo, hi) [m]: only there. (0, None)
    on Lagrange elements."""
    fem = system.fem
    if not fem.hermite:
        return 0.0, None
    nodes = fem.mesh.p[0]
    s = np.sort(np.concatenate([nodes[:-1] + f * np.diff(nodes) for f in BARLOW]))
    if within is not None:
        s = s[(s >= within[0]) & (s <= within[1])]
    kappa = curvature_at(system, X, s)
    i = int(np.argmax(kappa))
    if 0 < i < len(s) - 1:
        x, y = s[i - 1:i + 2], kappa[i - 1:i + 2]
        a, b, c = np.polyfit(x - x[1], y, 2)
        if a < 0:
            at = float(np.clip(-b / (2.0 * a), x[0] - x[1], x[2] - x[1]))
            return float(a * at * at + b * at + c), float(x[1] + at)
    return float(kappa[i]), float(s[i])


def clamped_ends(system, curvature, moment, reactions):
    """At a clamped end, the bending moment (n,) [N m] is the clamp's reaction (``reactions`` (2, 3):
    ``cablefem.fem.clamp.reaction_moments``), far more accurate there than EI kappa read from r'', and
    the curvature (n,) [1/m] that moment over EI (in place)."""
    EI = system.props["EI"]
    for end, (direction, node, element) in enumerate(zip(system.fem.clamped, (0, -1), (0, -1))):
        if direction is not None:
            moment[node] = float(np.linalg.norm(reactions[end]))
            curvature[node] = moment[node] / EI[element] if EI[element] > 0 else curvature[node]
