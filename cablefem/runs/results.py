"""What a solve reports for each line: end forces, tensions, node positions, touchdown.

End forces are the reactions of the discrete system (the residual rows of the
anchor and fairlead vertices), which for Galerkin FEM are more accurate than
tensions differentiated from the positions.
"""

from dataclasses import dataclass

import numpy as np

from cablefem.fem import clamp
from cablefem.runs.curvature import clamped_ends, node_curvature
from cablefem.loads import State
from cablefem.loads.rope import Rope


@dataclass
class LineReport:
    """Per-line results [SI]: forces the line exerts on its ends (3,), their magnitudes,
    vertex positions (n, 3) anchor first, the touchdown arc length (None if no contact), the
    tension at the vertices (n,), for a line in soil, ``soil``: the JSON fields of
    ``embedment`` (padeye, mudline crossing, embedded length) and of its pretension path, and the
    curvature [1/m] and bending moment [N m] at the vertices (n,) (``node_curvature``)."""

    name: str
    fairlead_force: np.ndarray
    anchor_force: np.ndarray
    nodes: np.ndarray
    touchdown_s: float | None
    tension: np.ndarray | None = None
    soil: dict | None = None
    curvature: np.ndarray | None = None
    bending_moment: np.ndarray | None = None

    @property
    def fairlead_tension(self):
        """Magnitude of the fairlead force [N]."""
        return float(np.linalg.norm(self.fairlead_force))

    @property
    def anchor_tension(self):
        """Magnitude of the anchor force [N]."""
        return float(np.linalg.norm(self.anchor_force))

    def as_dict(self):
        """The JSON fields of one line (docs/outputs.md, ``cablefem static``)."""
        return {
            "name": self.name,
            "fairlead_force": self.fairlead_force.tolist(),
            "anchor_force": self.anchor_force.tolist(),
            "fairlead_tension": self.fairlead_tension,
            "anchor_tension": self.anchor_tension,
            "nodes": self.nodes.tolist(),
            "touchdown_s": self.touchdown_s,
            **({} if self.tension is None else {"tension": self.tension.tolist()}),
            **(self.soil or {}),
            **({} if self.curvature is None else {"curvature": self.curvature.tolist(),
                                                  "bending_moment": self.bending_moment.tolist()}),
        }


def end_forces(system, X, inertia=None):
    """Forces (3,) the line exerts on its fairlead and anchor [N] at state X (N, 3): minus the
    residual rows there, less the load of a point riding on that end (``end_point_loads``: the
    line's own force, as on a prescribed end); ``inertia`` (N, 3) adds the M a rows in dynamics."""
    R = system.residual(X)
    if inertia is not None:
        R = R + inertia
    fairlead, anchor = -R[system.fem.fairlead_dof], -R[system.fem.anchor_dof]
    if system.points_at_ends:
        points = system.end_point_loads(X)
        fairlead, anchor = fairlead - points[0], anchor - points[1]
    return fairlead, anchor


def touchdown(system, X, samples_per_element=16):
    """Arc length [m] of the touchdown point: the last point, counted from the anchor, where the
    line penetrates the seabed (d_G <= 0), refined by root finding between samples; None without contact."""
    nodes = system.fem.mesh.p[0]
    fractions = np.linspace(0.0, 1.0, samples_per_element + 1)[:-1]
    s = np.append((nodes[:-1, None] + np.diff(nodes)[:, None] * fractions).ravel(), nodes[-1])
    gap = system.gap_at(X, s)
    touching = np.flatnonzero(gap <= 0.0)
    if touching.size == 0:
        return None
    last = touching[-1]
    if last == s.size - 1:
        return float(s[-1])
    def gap(q):
        return system.gap_at(X, np.array([q]))[0]

    from scipy.optimize import brentq

    a, b = s[last], s[last + 1]
    if gap(a) * gap(b) > 0:  # d_G touches zero without crossing: no root to refine
        return float(a)
    return float(brentq(gap, a, b, xtol=1e-12 * nodes[-1], rtol=1e-14))


def report(system, X, pretension=None):
    """The ``LineReport`` of one line system at state X. On a plane seabed under the anchor the
    touchdown is the resting length that the seabed's reaction carries (well conditioned); else
    the last point of contact (``touchdown``). A line in soil adds its ``embedment`` and, given its
    ``pretension`` result (``cablefem.statics.pretension.PretensionResult``), the path it took."""
    from cablefem.statics.touchdown import anchored_on_plane, resting_length

    fairlead, anchor = end_forces(system, X)
    td = resting_length(system, X) if anchored_on_plane(system.line, system.seabed) else None
    soil = None
    if system.has("soil"):
        soil = embedment(system, X, anchor)
        if pretension is not None:
            soil["pretension"] = {"installation": pretension.installation, "steps": pretension.steps,
                                  "halvings": pretension.halvings, "newton_iterations": pretension.iterations,
                                  "plastic_dissipation_J": float(np.sum(pretension.dissipation))}
    curvature, moment = node_curvature(system, X)
    clamped_ends(system, curvature, moment, clamp.reaction_moments(system, X))
    return LineReport(system.line.name, fairlead, anchor, X[: system.fem.n_vertices].copy(),
                      td if td is not None else touchdown(system, X),
                      node_tension(system, X, np.linalg.norm(anchor), np.linalg.norm(fairlead)), soil,
                      curvature, moment)


def node_tension(system, X, anchor_tension, fairlead_tension):
    """Tension [N] at the vertices (n,), anchor first (``LineSampler.tension``): the tension law's T
    averaged over the two elements that meet at an interior vertex (r' jumps there), the end
    tensions given at the ends."""
    return LineSampler(system, system.fem.mesh.p[0]).tension(X, ends=(fairlead_tension, anchor_tension))


def tension_law(system, element):
    """The line's tension law (its ``tension`` load: T = EA (e + beta de/dt), no compression but where
    a line type bends) at points of the elements ``element`` (n,): the load with its per-element
    values taken there."""
    from copy import copy

    law = copy(system.tension)
    for name in ("EA", "beta", "slack_damping", "rod"):  # per element (nel, 1): the points' elements
        if getattr(law, name, None) is not None:
            setattr(law, name, getattr(law, name)[element])
    law.compression = False
    return law


def point_tension(law, dr, dv=None):
    """Tension [N] (n,) of a ``tension_law`` at its points with dr/ds and dv/ds (n, 3)."""
    from cablefem.loads import State

    state = State(None, dr.T[:, :, None], dv=None if dv is None else dv.T[:, :, None])
    flux = law.evaluate(state, jacobian=False).flux[:, :, 0]
    return np.einsum("cn,nc->n", flux, dr) / np.linalg.norm(dr, axis=1)


def embedment(system, X, anchor_force):
    """The soil's JSON fields of a line (DESIGN.md): the force on the padeye (the anchor) and its
    magnitude, the tension [N] and the angle [deg] between the line and the local surface where the
    line crosses the seabed surface last (from below, counted from the padeye: where it leaves the
    soil; None if it never does) and the length [m] of line below the surface."""
    s, crossings, below = surface_crossings(system, X)
    leaving = [c for c, up in crossings if up]
    fields = {"padeye_force": np.asarray(anchor_force).tolist(),
              "padeye_tension": float(np.linalg.norm(anchor_force)),
              "mudline_tension": None, "mudline_angle_deg": None, "embedded_length": below}
    if leaving:
        at = np.array([leaving[-1]])
        tangent = system.fem.derivative(X, at)[0]
        normal = system.seabed.project(system.fem.evaluate(X, at)).direction[0]
        fields["mudline_tension"] = float(LineSampler(system, at).tension(X)[0])
        fields["mudline_angle_deg"] = float(np.degrees(np.arcsin(np.clip(
            tangent @ normal / np.linalg.norm(tangent), -1.0, 1.0))))
    return fields


def surface_crossings(system, X, samples_per_element=16):
    """Where the line crosses the seabed surface: the sample arc lengths (m,), the crossings
    [(s [m], True if rising out of the soil)] (each refined by root finding) and the length of
    line below the surface [m]."""
    from scipy.optimize import brentq

    nodes = system.fem.mesh.p[0]
    fractions = np.linspace(0.0, 1.0, samples_per_element + 1)[:-1]
    s = np.append((nodes[:-1, None] + np.diff(nodes)[:, None] * fractions).ravel(), nodes[-1])
    gap = system.gap_at(X, s)
    crossings, below, start = [], 0.0, (0.0 if gap[0] < 0.0 else None)

    def at(q):
        return system.gap_at(X, np.array([q]))[0]

    for k in np.flatnonzero((gap[:-1] < 0.0) != (gap[1:] < 0.0)):
        a, b = s[k], s[k + 1]
        root = float(brentq(at, a, b, xtol=1e-12 * nodes[-1], rtol=1e-14)) if at(a) * at(b) < 0 else float(b)
        rising = gap[k] < 0.0
        crossings.append((root, rising))
        if rising and start is not None:
            below += root - start
        start = None if rising else root
    if start is not None:
        below += float(nodes[-1]) - start
    return s, crossings, below


def sample_arc_lengths(system, per_element=None):
    """Arc lengths [m] for drawing a line: each element split into ``order`` pieces (n,)."""
    nodes = system.fem.mesh.p[0]
    pieces = per_element or system.fem.order
    fractions = np.linspace(0.0, 1.0, pieces + 1)[:-1]
    return np.append((nodes[:-1, None] + np.diff(nodes)[:, None] * fractions).ravel(), nodes[-1])


class LineSampler:
    """The basis of one line's FEM at fixed arc lengths s (n,) [m] (default: each element split
    into ``order`` pieces), evaluated once: frames of a run sample the same points every time.

    Positions are the FEM's own. Strain and tension are recovered from the points of each element
    where r' is superconvergent (``recovery_points``): the polynomial through the law's values there,
    evaluated at s. Differentiated directly, r' of a stiff line is poor between those points (its
    error is O(h^p) against 1, the strain's 1e-3: on a chain P2 x 10 tensions off by several times
    their size). At an interior vertex, where r' jumps, the two elements' values are averaged."""

    def __init__(self, system, s=None):
        fem = system.fem
        self.s = sample_arc_lengths(system) if s is None else np.asarray(s, dtype=float)
        self.values, self.gradients, self.element, self.dofs = _basis(fem, self.s)
        nodes = fem.mesh.p[0]
        self.anchor, self.fairlead = self.s == nodes[0], self.s == nodes[-1]
        self.vertices = np.flatnonzero(np.isin(self.s, nodes[1:-1]))
        inset = 1e-9 * float(np.min(np.diff(nodes)))
        at = self.s[self.vertices]
        # every point, then the interior vertices from the left and from the right: their elements
        rows = np.concatenate([self.s, at - inset, at + inset])
        elements = fem._locate(rows)[0]
        # each row's element's recovery points, and the weights of the polynomial through them at the row;
        # the law is evaluated once per element the rows lie in (``used``), at its points
        points, self.weights = recovery_points(fem, rows, elements)
        used, first, self.row_element = np.unique(elements, return_index=True, return_inverse=True)
        law_points = points[first].ravel()
        gradients, dofs = _basis(fem, law_points)[1::2]
        self.stacked = (gradients, dofs)
        self.law = tension_law(system, np.repeat(used, points.shape[1]))
        self.rope = RopeSampler(system, np.repeat(used, points.shape[1]), law_points)
        self.seconds = fem.local_second_basis(self.s) if fem.hermite else None  # (n, nloc)
        self.EI = system.props["EI"][self.element]

    def evaluate(self, X):
        """X (N, 3) at the sample points, (n, 3)."""
        return np.einsum("nl,nlc->nc", self.values, X[self.dofs])

    def derivative(self, X):
        """dX/ds (N, 3) at the sample points, (n, 3)."""
        return np.einsum("nl,nlc->nc", self.gradients, X[self.dofs])

    def curvature(self, X):
        """Curvature [1/m] at the sample points (n,) from r'' of the element holding each (zero on
        Lagrange elements)."""
        from cablefem.loads.bending import curvature

        if self.seconds is None:
            return np.zeros(len(self.s))
        return curvature(self.derivative(X).T, np.einsum("nl,nlc->nc", self.seconds, X[self.dofs]).T)

    def axial(self, X, V=None, ends=None):
        """Axial strain |r'| - 1 and tension [N] (n,) each at the sample points: inside an element
        recovered from its ``recovery_points`` (the tension from the line's law, ``tension_law``), at
        an interior vertex the mean of the two elements', and at the ends the line's tension there,
        ``ends`` = (fairlead, anchor): forces (3,) or their magnitudes (without, the law's there)."""
        dr = self._sides(X)
        dv = None if V is None else self._sides(V)
        strain = self._points(np.linalg.norm(dr, axis=1) - 1.0)
        tension = self._points(point_tension(self.law, dr, dv) + self.rope.tension(dr, dv))
        if ends is not None:
            tension[self.fairlead], tension[self.anchor] = (float(np.linalg.norm(end)) for end in ends)
        return strain, tension

    def tension(self, X, V=None, ends=None):
        """Tension [N] (n,) at the sample points (``axial``)."""
        return self.axial(X, V, ends)[1]

    def _sides(self, X):
        """dX/ds at the recovery points of the elements the points and the interior vertices' two
        sides lie in, (e k, 3) for those e elements and k recovery points per element."""
        gradients, dofs = self.stacked
        return np.einsum("nl,nlc->nc", gradients, X[dofs])

    def _points(self, values):
        """Values at the points (n,) from values at ``_sides``' rows: each point's polynomial through
        its element's recovery points, and at an interior vertex the mean of its two elements'."""
        values = values.reshape(-1, self.weights.shape[1])[self.row_element]
        values = np.einsum("rk,rk->r", self.weights, values)
        n, m = len(self.s), len(self.vertices)
        out = values[:n].copy()
        if m:
            out[self.vertices] = 0.5 * (values[n:n + m] + values[n + m:])
        return out


class RopeSampler:
    """The tension [N] of a line's rope elements (``cablefem.loads.rope``) at sample points: a table's
    law at the points' r' and v' (``Rope.tension``), a law with history the tension its nearest
    reduced point committed (the history's ``tension``: a frame or the static JSON comes after a
    commit); zero on the tension load's elements (and on a line without a rope)."""

    def __init__(self, system, elements, s):
        self.system = system
        self.rope = system.load("rope") if system.has("rope") else None
        if self.rope is None:
            return
        kind = self.rope.kind[elements]
        self.table = np.flatnonzero(kind == 1)
        self.history = np.flatnonzero(kind > 1)
        rule = system.fem.reduced.s[elements[self.history]]  # (m, nr) arc lengths of their reduced points
        self.at = (elements[self.history], np.argmin(np.abs(rule - s[self.history, None]), axis=1))
        self.law = Rope([self.rope.laws[e] for e in elements[self.table]], self.rope.EA[elements[self.table], 0],
                        self.rope.slack_damping[elements[self.table], 0]) if self.table.size else None

    def tension(self, dr, dv=None):
        """Tension [N] (n,) of the rope at points with dr/ds and dv/ds (n, 3)."""
        out = np.zeros(len(dr))
        if self.rope is None:
            return out
        if self.law is not None:
            rows = self.table
            state = State(None, dr[rows].T[:, :, None], dv=None if dv is None else dv[rows].T[:, :, None])
            out[rows] = self.law.tension(state)[0][:, 0]
        if self.history.size:
            out[self.history] = self.system.history["reduced"][0]["rope"]["tension"][self.at]
        return out


def recovery_points(fem, s, elements):
    """Arc lengths (n, k) [m] of the k points of each of the elements ``elements`` (n,) where r' is
    superconvergent, and the weights (n, k) of the polynomial through them at arc lengths s (n,):
    on Lagrange elements of order p the p Gauss-Legendre points (where the derivative of an
    interpolation error of degree p + 1 vanishes); on cubic Hermite elements, whose r' interpolates at the
    vertices, the ends and the middle (the interpolant's r' error, xi (xi^2 - 1) in xi on [-1, 1],
    vanishes there)."""
    if fem.hermite:
        local = np.array([-1.0, 0.0, 1.0])
    else:
        local = np.polynomial.legendre.leggauss(fem.order)[0]
    nodes = fem.mesh.p[0]
    left, right = nodes[fem.mesh.t[0, elements]], nodes[fem.mesh.t[1, elements]]
    xi = 2.0 * (np.asarray(s, dtype=float) - left) / (right - left) - 1.0
    weights = np.ones((len(xi), len(local)))
    for k, root in enumerate(local):
        for m, other in enumerate(local):
            if m != k:
                weights[:, k] *= (xi - other) / (root - other)
    # the ends of a Hermite element's pieces: just inside it, where _locate puts the element itself
    inset = 1e-9 if fem.hermite else 0.0
    ends = np.clip(local, -1.0 + inset, 1.0 - inset)
    points = left[:, None] + (right - left)[:, None] * 0.5 * (ends + 1.0)
    return points, weights


def _basis(fem, s):
    """Basis values and s-derivatives (n, nloc), element (n,) and its dofs (n, nloc) at arc lengths s."""
    values, gradients = fem._local_basis(s)
    element = fem._locate(s)[0]
    return values, gradients, element, fem.element_dofs[element]


def line_fields(system, X, V=None, s=None, sampler=None, ends=None):
    """Point data of a line for a VTK frame: positions and, per point, tension [N]
    (``LineSampler.tension``; ``ends``: the line's (fairlead, anchor) forces, whose magnitudes are
    the tension at its ends), strain, velocity [m/s], seabed gap d_G [m] and contact force per unit
    length [N/m]; at ``s`` or at a ``LineSampler``'s points."""
    sampler = sampler or LineSampler(system, s)
    element = sampler.element
    points = sampler.evaluate(X)
    proj = system.seabed.project(points)
    stiffness = system.contact.stiffness[element, 0] if system.has("contact") else 0.0 * element
    contact = (stiffness * np.maximum(-proj.gap, 0.0))[:, None] * proj.direction
    velocity = np.zeros_like(points) if V is None else sampler.evaluate(V)
    strain, tension = sampler.axial(X, V, ends)
    kappa = sampler.curvature(X)
    fields = {"points": points, "tension": tension, "strain": strain, "velocity": velocity, "seabed_gap": proj.gap,
              "contact_force": contact, "curvature": kappa, "bending_moment": sampler.EI * kappa}
    fields.update(history_fields(system, element))
    return fields


def history_fields(system, element):
    """The history fields the loads ask to see in frames (``LoadSpec.frames``), each point taking
    the mean over the quadrature points of its element ``element`` (n,): ``<load>_<field>``."""
    from cablefem.loads import catalog

    fields = {}
    for load in system.loads:
        spec = catalog.spec_of(load)
        if not spec.frames:
            continue
        old = system.history[spec.rule][0]
        for name in spec.frames:
            fields[f"{spec.name}_{name}"] = old[spec.name][name].mean(axis=1)[element]
    return fields

