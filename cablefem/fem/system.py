"""The discrete system of one line: FEM + the loads a scene needs, as residual and tangent.

The residual of the weak form of desire2023 Eq. 1 over unstretched arc
length is

    G(X) = int (N . phi' - f . phi) ds  (+ M a in dynamics),

with the flux N and the force f summed over the loads. The line's own
anchor and fairlead rows are the reactions: the force the line exerts on a
support is -G at that vertex. "Model only what a scene needs": the loads come
from the catalog (``cablefem.loads.catalog.build_loads``), each deciding from
the ``Setting`` whether the line needs it (statics: tension, weight and seabed
contact; dynamics adds friction, drag and added mass).
"""

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp

from cablefem.fem import clamp, forms
from cablefem.fem.discretisation import LineFEM
from cablefem.fem.evaluator import NumpyEvaluator
from cablefem.loads import State, add, catalog
from cablefem.loads.tension import axial_tension, strain


def element_properties(line):
    """Per-element line-type properties, each an array of shape (n_elements,); ``nominal_diameter``
    [m] is NaN where a line type does not give it; ``rope``: the element's type has an axial law of
    its own (``cablefem.loads.rope``), whose ``axial`` laws and SYROPE ``syrope_initial`` (Tmax0,
    Tmean0) [N] (nel, 2) come only where one does."""
    types = [seg.type for seg in line.segments]
    index = line.element_segments()
    names = ("diameter", "mass", "EA", "damping", "Cd_normal", "Cd_tangential",
             "Ca_normal", "Ca_tangential", "area", "damping_when_slack", "EI")
    props = {name: np.array([getattr(t, name) for t in types])[index] for name in names}
    props["nominal_diameter"] = np.array([np.nan if t.nominal_diameter is None else t.nominal_diameter
                                          for t in types])[index]
    if any(t.axial is not None for t in types):  # a law of its own: the rope load, not the tension's
        props["axial"] = [types[k].axial for k in index]
        props["rope"] = np.array([types[k].axial is not None for k in index])
        props["syrope_initial"] = np.array([line.segments[k].syrope or (0.0, 0.0) for k in index])
    else:
        props["rope"] = np.zeros(len(index), dtype=bool)
    return props


@dataclass(frozen=True)
class Setting:
    """What a load's builder (``LoadSpec.build``) sees of a scene for one line: its per-element
    properties, the seabed, the scene's contact, environment and friction (None in statics),
    whether the run is dynamic, the scene's load tables by section, (``with_keys``) the table
    of the load's own section, and the ``Line`` itself (its joints, its ends)."""

    props: dict
    seabed: object
    contact: object
    environment: object
    friction: object = None
    dynamic: bool = False
    sections: dict = field(default_factory=dict)
    keys: dict | None = None
    line: object = None

    def with_keys(self, keys):
        return replace(self, keys=keys)


class LineSystem:
    """Residual and tangent of one line over a seabed, for statics and dynamics; ``fem``: the
    ``LineFEM`` of a line with the same segments and order, to share instead of building one.
    ``friction`` (a ``scene.Friction``) and ``dynamic`` say what the catalog's loads build,
    ``sections`` the scene's load tables; ``extra_loads`` are added after them."""

    def __init__(self, line, seabed, contact, environment, quadrature_points=None,
                 extra_loads=(), assembly="kernel", friction=None, fem=None, dynamic=None, sections=None):
        self.line = line
        self.assembly = assembly
        self.contact_settings = contact  # the scene's ``Contact``, for another system of this line
        self.seabed = seabed
        self.environment = environment
        # a line moved to another fairlead has the same mesh in arc length: its FEM can be shared
        self.fem = fem or LineFEM(line, quadrature_points)
        self.props = element_properties(line)
        self.setting = Setting(self.props, seabed, contact, environment, friction,
                               friction is not None if dynamic is None else dynamic, dict(sections or {}),
                               line=line)
        self.loads = catalog.build_loads(self.setting) + list(extra_loads)
        self.history = _history_records(self.fem)  # {"full": (old, new), "reduced": (old, new)}
        self.reset_history(None)
        self.clamps = clamp.clamps(self.fem, self.props["EA"])  # the clamped ends' constraints

    def load(self, name):
        """The system's load of catalog name ``name`` (the first, if a test added another)."""
        for load in self.loads:
            if catalog.spec_of(load).name == name:
                return load
        raise KeyError(f"line '{self.line.name}' has no '{name}' load")

    def has(self, name):
        """Whether the system has a load of catalog name ``name``."""
        return any(catalog.spec_of(load).name == name for load in self.loads)

    tension = property(lambda self: self.load("tension"))
    weight = property(lambda self: self.load("weight"))
    contact = property(lambda self: self.load("contact"))

    def reset_history(self, X):
        """Start the history of every point afresh: zero, or what a load's ``initial_history(state)``
        says at state X (N, 3) (None: zero)."""
        for old, new in self.history.values():
            old[...] = 0
            new[...] = 0
        if X is None:
            return
        state = self.state(X)
        for load in self.loads:
            start = getattr(load, "initial_history", None)
            if start is None:
                continue
            name = catalog.spec_of(load).name
            rule = getattr(load, "rule", "full")
            old, new = self.history[rule]
            for key, value in start(state.reduced if rule == "reduced" else state).items():
                old[name][key] = value
                new[name][key] = value

    def kept_history(self):
        """The rules ("full", "reduced") at whose points a load of the system keeps history: the
        others' trial history is never written, and committing it would copy zeros."""
        return {spec.rule for spec in map(catalog.spec_of, self.loads) if spec.history}

    def commit_history(self):
        """Make the trial history the committed one (an accepted step or load increment)."""
        for rule in self.kept_history():
            old, new = self.history[rule]
            old[...] = new

    @property
    def fixed_rows(self):
        """Rows of the anchor and fairlead vertices in a state array."""
        return list(self.fem.end_dofs)

    def state(self, X, V=None, A=None, t=0.0, inv_h=0.0):
        """Kinematics at the full quadrature points for state X (N, 3), velocity V and
        acceleration A; ``.reduced`` holds them at the reduced points (see ``LineFEM``); ``inv_h``:
        1 / the step's size [1/s] (0: statics)."""
        columns = [X] + [Y for Y in (V, A) if Y is not None]
        stacked = np.hstack(columns) if len(columns) > 1 else X
        states = []
        for rule in (self.fem.full, self.fem.reduced):
            values, derivatives = rule.interpolate(stacked)
            shape = (3,) + rule.s.shape
            parts = [(values[:, 3 * k:3 * k + 3].T.reshape(shape),
                      derivatives[:, 3 * k:3 * k + 3].T.reshape(shape)) for k in range(len(columns))]
            (r, dr), rest = parts[0], parts[1:]
            v = dv = a = None
            if V is not None:
                v, dv = rest.pop(0)
            if A is not None:
                a = rest.pop(0)[0]
            old, new = self.history["full" if rule is self.fem.full else "reduced"]
            states.append(State(r, dr, v, dv, a, t, old=old, new=new, inv_h=inv_h))
        full, reduced = states
        full.reduced = reduced
        full.X = X
        if self.fem.hermite:  # the curvature's r'' at the full points
            full.ddr = self.fem.full.second(X).T.reshape((3,) + self.fem.full.s.shape)
        vertices = self.line.joint_vertices()
        if len(vertices):  # the joints' own kinematics (3, k), for the node loads
            at = lambda Y: None if Y is None else np.ascontiguousarray(Y[vertices].T)  # noqa: E731
            full.nodes = State(at(X), None, at(V), None, at(A), t)
        return full

    def evaluator(self, compiled=True, lumped=False):
        """The evaluator of this system (``cablefem.fem.evaluator``): compiled (``FusedEvaluator``)
        unless ``compiled`` is False, the mass is lumped (only the numpy face assembles it) or the line
        has no unknowns (one element between prescribed ends: the band would be empty)."""
        if compiled and not lumped and self.fem.free_dofs.size:
            from cablefem.compiled.evaluator import FusedEvaluator  # numba only where it is used

            return FusedEvaluator(self, self.props["mass"])
        numpy = NumpyEvaluator(self, lumped)
        if lumped:
            numpy.M  # a lumped mass checks the element order now, not at the first step
        return numpy

    def evaluate(self, state, jacobian=True, velocity_factor=0.0, acceleration_factor=0.0, constrained=True):
        """Residual rows (N, 3) of the loads and, with ``jacobian``, the tangent blocks
        (A, B, C, D, E, F, G) of dG/dX at quadrature points (see ``cablefem.fem.forms``), per rule,
        where dV/dX = velocity_factor and dA/dX = acceleration_factor (both 0 in statics). A
        clamped end's tangent row is its constraint (``cablefem.fem.clamp``): its blocks are under
        "clamp", and an integrator's inertia rows there are projected as these are
        (``clamp.project``); ``constrained=False`` leaves the loads' own rows there (the clamp's
        reaction, ``clamp.reaction_moments``)."""
        sums = {}  # rule name -> [force, flux, moment, A, B, C, D, E, F, G]
        residual = np.zeros((self.fem.n_dofs, 3))
        for load in self.loads:
            rule = getattr(load, "rule", "full")
            if rule == "node":  # a concentrated force: its rows and 3 x 3 blocks at its vertices
                node = self._node_terms(load, state.nodes, jacobian, velocity_factor, acceleration_factor)
                residual[load.vertices] -= node[0]
                if node[1] is not None:
                    sums.setdefault("node", [None] * 10)[3] = node[1]
                continue
            terms = load.evaluate(state.reduced if rule == "reduced" else state, jacobian)
            acc = sums.setdefault(rule, [None] * 10)
            acc[0], acc[1] = add(acc[0], terms.force), add(acc[1], terms.flux)
            acc[2] = add(acc[2], terms.moment)
            if not jacobian:
                continue
            for i, (base, rate, accel, sign) in enumerate((
                    (terms.force_r, terms.force_v, terms.force_a, -1.0),
                    (terms.force_dr, terms.force_dv, None, -1.0),
                    (None, None, None, 1.0),
                    (terms.flux_dr, terms.flux_dv, None, 1.0),
                    (terms.flux_ddr, None, None, 1.0),
                    (terms.moment_dr, None, None, 1.0),
                    (terms.moment_ddr, None, None, 1.0))):
                block = _combine(base, rate, velocity_factor, accel, acceleration_factor)
                if block is not None:
                    acc[3 + i] = add(acc[3 + i], sign * block)
        for rule, acc in sums.items():
            if rule == "node":
                continue
            if self.assembly == "forms":
                residual += self._forms_vector(acc[0], acc[1], rule, acc[2])
            else:
                residual += self.fem.assemble_vector(acc[0], acc[1], self._rule(rule), moment=acc[2])
        blocks = {rule: tuple(acc[3:]) for rule, acc in sums.items()} if jacobian else None
        if self.clamps and constrained:
            if state.X is None:
                raise ValueError("a line with a clamped end needs the state's rows (LineSystem.state)")
            clamp.constrain_rows(self.clamps, state.X, residual)
            if jacobian:
                blocks["clamp"] = self.clamps
        return residual, blocks

    @staticmethod
    def _node_terms(load, nodes, jacobian, velocity_factor, acceleration_factor):
        """A node load's forces (k, 3) at its vertices and, with ``jacobian``, its blocks
        A = -(f_r + v_x f_v + a_x f_a) (3, 3, k)."""
        terms = load.evaluate(nodes, jacobian)
        if not jacobian:
            return terms.force.T, None
        block = _combine(terms.force_r, terms.force_v, velocity_factor, terms.force_a, acceleration_factor)
        return terms.force.T, (None if block is None else -block)

    def _node_matrix(self, block, free_only):
        """The node loads' 3 x 3 blocks (3, 3, k) on the diagonal of the tangent (CSR)."""
        load = next(load for load in self.loads if getattr(load, "rule", "full") == "node")
        vertices = load.vertices
        rows = (3 * vertices[None, None, :] + np.arange(3)[:, None, None]) * np.ones((1, 3, 1), dtype=np.int64)
        cols = (3 * vertices[None, None, :] + np.arange(3)[None, :, None]) * np.ones((3, 1, 1), dtype=np.int64)
        size = 3 * self.fem.n_dofs
        K = sp.csr_matrix((block.ravel(), (rows.ravel(), cols.ravel())), shape=(size, size))
        if free_only:
            free = self.fem.free_vector_dofs
            K = K[free][:, free]
        return K

    def _rule(self, name):
        return self.fem.reduced if name == "reduced" else self.fem.full

    def matrix(self, blocks, free_only=True):
        """Sparse tangent (CSR) from the blocks returned by ``evaluate``, free DOFs by default."""
        if "clamp" in blocks:
            rest = {rule: parts for rule, parts in blocks.items() if rule != "clamp"}
            return clamp.constrain_matrix(blocks["clamp"], self.matrix(rest, free_only), self.fem, free_only)
        if "node" in blocks:
            node = blocks["node"][0]
            rest = {rule: parts for rule, parts in blocks.items() if rule != "node"}
            size = len(self.fem.free_vector_dofs) if free_only else 3 * self.fem.n_dofs
            K = self.matrix(rest, free_only) if rest else sp.csr_matrix((size, size))
            return K if node is None else (K + self._node_matrix(node, free_only)).tocsr()
        if self.assembly == "forms":
            K = 0
            for rule, parts in blocks.items():
                basis = self.fem.reduced_basis if rule == "reduced" else self.fem.basis
                zero = np.zeros((3, 3) + self._rule(rule).s.shape)
                A, B, C, D, E, F, G = (zero if b is None else b for b in parts)
                K = K + forms.tangent.assemble(basis, A=A, B=B, C=C, D=D).tocsr()
                if any(b is not None for b in parts[4:]):
                    K = K + forms.curvature_tangent.assemble(basis, E=E, F=F, G=G).tocsr()
            K = self.fem.matrix_from_skfem(K)
            if free_only:
                free = self.fem.free_vector_dofs
                K = K[free][:, free]
            return K
        local = None
        for rule, parts in blocks.items():
            local = self.fem.element_matrices(*parts, rule=self._rule(rule), out=local)
        return self.fem.assemble_matrix(local, free_only)

    def _forms_vector(self, force, flux, rule, moment=None):
        basis = self.fem.reduced_basis if rule == "reduced" else self.fem.basis
        zero = np.zeros((3,) + self._rule(rule).s.shape)
        force = zero if force is None else force
        flux = zero if flux is None else flux
        rows = forms.load_vector.assemble(basis, force=force, flux=flux).reshape(-1, 3)
        if moment is not None:
            rows = rows + forms.moment_vector.assemble(basis, moment=moment).reshape(-1, 3)
        return self.fem.from_skfem(rows)

    def energy(self, X):
        """Total potential energy [J] at X (N, 3) of the loads that have one (their numpy face's
        ``energy(state)``, ``cablefem.loads.LoadSpec``: strain energy, weight, the seabed spring,
        the joints; with soil, its springs' merit function), whose gradient is the static residual:
        the merit of statics' line search."""
        state = self.state(X)
        total = 0.0
        for load in self.loads:
            energy = getattr(load, "energy", None)
            if energy is None:
                continue
            rule = getattr(load, "rule", "full")
            if rule == "node":
                total += np.sum(energy(state.nodes))
            else:
                total += np.sum(energy(state.reduced if rule == "reduced" else state) * self._rule(rule).dx)
        return float(total)

    def residual(self, X, V=None, A=None, t=0.0):
        """Load residual rows (N, 3) [N] at state X (inertia not included)."""
        return self.evaluate(self.state(X, V, A, t), jacobian=False)[0]

    @property
    def points_at_ends(self):
        """Whether a node load (a point) rides on the fairlead or the anchor vertex."""
        return any(np.isin(self.fem.end_dofs, load.vertices).any()
                   for load in self.loads if getattr(load, "rule", "full") == "node")

    def end_point_loads(self, X, V=None, A=None, t=0.0):
        """The node loads' forces [N] at the fairlead and the anchor vertex (2, 3), zero where none
        rides there: a point at a free end (or a run's junction end) rides on the line's end vertex,
        and the line's own force there leaves its load out (docs/outputs.md)."""
        forces = np.zeros((2, 3))
        for load in self.loads:
            if getattr(load, "rule", "full") != "node":
                continue
            at = load.vertices
            pick = lambda Y: None if Y is None else np.ascontiguousarray(Y[at].T)  # noqa: E731
            force = load.evaluate(State(pick(X), None, pick(V), None, pick(A), t), jacobian=False).force
            for row, dof in enumerate((self.fem.fairlead_dof, self.fem.anchor_dof)):
                forces[row] += force[:, at == dof].sum(axis=1)
        return forces

    def tension_at(self, X, s, V=None):
        """Axial tension [N] at unstretched arc lengths s (n,), from the element holding each s."""
        dr = self.fem.derivative(X, s).T[:, :, None]
        EA = self.props["EA"][self.fem._locate(s)[0]][:, None]
        return axial_tension(dr, EA)[:, 0]

    def tension_strain(self, X):
        """Strain |r'| - 1 at the points (nel, nq) where the tension is evaluated, state X."""
        return strain(self.fem.at_quadrature(X, self.fem.reduced)[1])[0]

    def gap_at(self, X, s):
        """Seabed penetration depth d_G [m] at arc lengths s (n,) (> 0 above the seabed)."""
        return self.seabed.gap_only(self.fem.evaluate(X, s))

    def weight_vector(self):
        """Assembled weight load rows (N, 3) of the line fully submerged [N] (a force scale)."""
        r = np.zeros((3,) + self.fem.s.shape)
        r[2] = -1.0 - float(np.max(self.weight.diameter))  # fully submerged
        return self.fem.assemble_vector(force=self.weight.evaluate(State(r, r)).force)


def _combine(base, rate, velocity_factor, accel, acceleration_factor):
    block = base
    if rate is not None and velocity_factor:
        block = add(block, velocity_factor * rate)
    if accel is not None and acceleration_factor:
        block = add(block, acceleration_factor * accel)
    return block


def _history_records(fem):
    """Committed and trial history records of a line's full and reduced points (the catalog's
    history dtypes, ``cablefem.loads.catalog.Layout``), shared with the compiled path."""
    layout = catalog.layout()
    nel, nq, nr = fem.n_elements, fem.full.dx.shape[1], fem.reduced.dx.shape[1]
    return {"full": (np.zeros((nel, nq), layout.full_history), np.zeros((nel, nq), layout.full_history)),
            "reduced": (np.zeros((nel, nr), layout.reduced_history), np.zeros((nel, nr), layout.reduced_history))}


def build_system(scene, line, dynamic=True, fem=None):
    """The ``LineSystem`` of one line of a scene, its loads from the catalog; ``dynamic`` adds
    friction, drag and added mass; ``fem`` shares the FEM of another system of the same line."""
    return LineSystem(line, scene.seabed, scene.contact, scene.environment, assembly=scene.solver.assembly,
                      friction=scene.friction if dynamic else None, fem=fem, dynamic=dynamic,
                      sections=scene.load_settings)
