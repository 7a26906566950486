"""The compiled evaluation of one line system, from Python: residual, banded tangent, LU and solve.

``FusedEvaluator`` packs a ``LineSystem`` for ``cablefem.compiled.kernels``: the mesh in band order (the
unknowns ordered along the line: each element's left vertex, its interior, its right), the
parameter record of every load from its ``params()`` (``cablefem.loads.catalog``), the per-point
records (branch state, holds, history) and scratch, and the seabed (a plane is evaluated in the
loop; grids and meshes are projected in numpy here, or in the compiled steps by
``cablefem.compiled.steps``). The reference assembly (``LineSystem.evaluate`` / ``matrix``: one numpy face
per load, scikit-fem's forms) spends most of a time step in Python overhead on small arrays; this
evaluates the same residual M A + G and tangent in one compiled loop (a residual of 80 P2
elements ~45 us, verification/work_precision/README.md), equal to it to round-off
(``tests/test_fused.py``, ``tests/test_catalog.py``).
"""

import numpy as np
from scipy.linalg import lapack

from cablefem.compiled import kernels
from cablefem.compiled.hermite import CLAMP_LOCAL
from cablefem.fem.evaluator import Evaluator
from cablefem.geometry import Plane
from cablefem.loads import catalog
from cablefem.waves.compiled import water_of


def pack_params(loads, nel):
    """The parameter record (nel,) of ``cablefem.compiled.kernels`` for a system's ``loads``: each load's
    ``params()`` under its catalog name, its ``active`` flag set. A load with no catalog entry, a
    load twice, or a parameter missing or unknown, is an error: the compiled path never falls back."""
    record = kernels.records(kernels.LAYOUT.params, nel)
    seen = set()
    for load in loads:
        spec = catalog.spec_of(load)
        if spec.rule == "node":
            continue
        if spec.name in seen:
            raise ValueError(f"two '{spec.name}' loads in one system: the compiled path holds one of each")
        seen.add(spec.name)
        values = load.params()
        expected = {field[0] for field in spec.params}
        if set(values) != expected:
            raise ValueError(f"load '{spec.name}': params() gives {sorted(values)}, its LoadSpec declares "
                             f"{sorted(expected)}")
        part = record[spec.name]
        part["active"] = True
        for name, value in values.items():
            part[name] = value
    return record


def pack_nodes(loads):
    """The node loads' vertices (k,) and parameter record (k,) (``pack_params`` for the loads of
    rule "node"; at most one such load per line, all of its vertices)."""
    nodes = [load for load in loads if catalog.spec_of(load).rule == "node"]
    if len(nodes) > 1:
        raise ValueError("two node loads in one system: the compiled path holds one")
    if not nodes:
        return np.zeros(0, dtype=np.int64), kernels.records(kernels.LAYOUT.node_params, 0)
    load, spec = nodes[0], catalog.spec_of(nodes[0])
    vertices = np.asarray(load.vertices, dtype=np.int64)
    record = kernels.records(kernels.LAYOUT.node_params, len(vertices))
    values = load.params()
    expected = {field[0] for field in spec.params}
    if set(values) != expected:
        raise ValueError(f"load '{spec.name}': params() gives {sorted(values)}, its LoadSpec declares "
                         f"{sorted(expected)}")
    record[spec.name]["active"] = True
    for name, value in values.items():
        record[spec.name][name] = value
    return vertices, record


def band_order(fem, dofs):
    """The rows of ``fem`` in band order (N,): along the line, each element's left vertex, its
    interior, its right vertex. On Hermite elements a vertex is its position and its tangent, the
    last vertex its tangent first, so that the prescribed end positions are the band's first and
    last rows and the unknowns between them contiguous."""
    order = []
    if fem.hermite:
        nv = fem.n_vertices
        for v in range(nv):
            order.extend((v, nv + v) if v < nv - 1 else (nv + v, v))
        return order
    for e in range(fem.n_elements):
        for i in (fem.mesh.t[0, e], *dofs[e, 2:], fem.mesh.t[1, e]):
            if not order or order[-1] != i:
                order.append(int(i))
    return order


class FusedEvaluator(Evaluator):
    """Compiled residual and banded tangent of one ``LineSystem`` (see the module docstring), behind
    the evaluator interface of ``cablefem.fem.evaluator``."""

    compiled = True
    full_newton_pays = True  # a compiled tangent costs about a residual, its banded LU a few microseconds

    def __init__(self, system, mass):
        super().__init__(system)
        fem = system.fem
        dofs = fem.element_dofs.astype(np.int64)
        order = band_order(fem, dofs)
        position = np.empty(fem.n_dofs, dtype=np.int64)
        position[np.array(order)] = np.arange(len(order))
        nloc = dofs.shape[1]
        self.kl = self.ku = 3 * nloc - 1
        # the unknowns along the line: from the first vertex, or the second if the anchor is prescribed
        lo, hi = (1 if fem.prescribed[0] else 0), fem.n_dofs - (2 if fem.prescribed[1] else 1)
        self.n = 3 * (hi - lo + 1)
        self.free_order = np.array(order[lo:hi + 1], dtype=np.int64)  # free scalar DOFs in band order
        self.band_of_free = position[fem.free_dofs] - lo  # band position of fem.free_dofs
        self.full, self.reduced = fem.full, fem.reduced
        vertices, node_params = pack_nodes(system.loads)
        # r'' at the full points only where a load reads it (bending on Hermite elements)
        second = fem.full.ddphi if system.has("bending") else np.zeros((0, 0, 0))
        clamp = np.zeros((2, 8))  # ``kernels.Points``
        clamp[:, CLAMP_LOCAL] = (2, 3)  # the tangents' local DOFs in the end elements
        for c in system.clamps:
            end = fem.tangent_dofs.index(c.row)
            clamp[end, :CLAMP_LOCAL] = (*c.direction, c.scale)
        # every array C-ordered: the kernels' types are then the same for every line (scikit-fem's
        # weights are Fortran-ordered, a single column both: P1 and Hermite strings of one junction
        # would otherwise need two compiled loops)
        c = np.ascontiguousarray
        self.mesh = kernels.Mesh(dofs, position, c(fem.full.phi), c(fem.full.dphi), c(fem.full.dx), c(fem.reduced.phi),
                                 c(fem.reduced.dphi), c(fem.reduced.dx), np.asarray(mass, dtype=float), self.kl,
                                 self.ku, lo, hi, vertices)
        nel, nq, nr = fem.n_elements, fem.full.dx.shape[1], fem.reduced.dx.shape[1]
        self.points = kernels.points(pack_params(system.loads, nel), system.history, nq, nr, node_params, c(second),
                                     clamp)
        # the branch state where the last Newton step started (``keep``), for the holds (``hold``)
        self.base_full = self.points.full_state.copy()
        self.base_reduced = self.points.reduced_state.copy()
        self.work = kernels.work(nloc)
        # on a plane the kernel computes the gap itself: no interpolation or projection in numpy
        self.plane = np.zeros(0)
        if isinstance(system.seabed, Plane):
            self.plane = np.append(system.seabed.normal, system.seabed.offset).astype(float)
        self.unused = (np.zeros((1, 1)), np.zeros((1, 1, 3)), np.zeros((1, 1, 3)), np.zeros((1, 1, 3, 3)))
        # the sea of a line whose loads see waves (the Morison load, points in waves); none otherwise
        seas = [load.sea for load in system.loads if getattr(load, "sea", None) is not None]
        self.water = water_of(seas[0] if seas else None, fem.n_elements * fem.full.dx.shape[1] + len(vertices))
        self.elements = np.arange(nel, dtype=np.int64)

    @classmethod
    def for_system(cls, system, mass):
        """The evaluator of ``system``; every load must be in the catalog (``pack_params``)."""
        return cls(system, mass)

    def bed(self, X):
        """The seabed for the kernel at state X (N, 3): the plane, or the projection of the full points."""
        if self.plane.size:
            return kernels.Bed(self.plane, *self.unused)
        fem = self.system.fem
        shape = fem.full.s.shape
        proj = self.system.seabed.project(fem.full.interpolate(X)[0])
        return kernels.Bed(self.plane, np.ascontiguousarray(proj.gap.reshape(shape)),
                           np.ascontiguousarray(proj.direction.reshape(shape + (3,))),
                           np.ascontiguousarray(proj.gap_gradient.reshape(shape + (3,))),
                           np.ascontiguousarray(proj.direction_gradient.reshape(shape + (3, 3))))

    def evaluate(self, X, V, A, v_x, a_x, jacobian=True, held=False, t=0.0, h=0.0):
        """Rows M A + G (N, 3) at time t [s] and, with ``jacobian``, the banded K + v_x C + a_x M (LAPACK
        layout); with ``held``, the loads on the branches the hold records hold; ``h``: the step's size
        [s] (0: none, statics). The branch state and the trial history of every point go to
        ``self.points``."""
        rows = np.zeros((self.system.fem.n_dofs, 3))
        # Fortran order, as LAPACK and the compiled steps hold it (one compiled kernel for both;
        # the unused band is 2 x 2, since numba would type a 1 x 1 array as C-ordered)
        band = np.zeros((2 * self.kl + self.ku + 1, self.n) if jacobian else (2, 2), order="F")
        state, factors = (X, V, A, float(t)), (float(v_x), float(a_x), float(h))
        kernels.assemble(self.mesh, self.bed(X), self.water, self.points, self.work, state, factors,
                         bool(jacobian), bool(held), rows, band, self.elements)
        if self.mesh.nodes.size:
            kernels.assemble_nodes(self.mesh, self.water, self.points, self.work, state, factors,
                                   bool(jacobian), rows, band)
        return rows, (band if jacobian else None)

    def add_constraints(self, band):
        """Add the clamped ends' constraint blocks k (I - d d^T) to a band (in place): a difference
        of two tangents (the mass from K + M and K) loses them."""
        for c in self.system.clamps:
            j = self.mesh.position[c.row] - self.mesh.lo
            block = c.scale * (np.eye(3) - np.outer(c.direction, c.direction))
            for a in range(3):
                for b in range(3):
                    band[self.kl + self.ku + a - b, 3 * j + b] += block[a, b]
        return band

    def keep(self):
        """Remember the branch state of the last evaluation as the base of Newton's corrections."""
        self.base_full[...] = self.points.full_state
        self.base_reduced[...] = self.points.reduced_state

    def hold(self, again):
        """Hold the branches the last evaluation (a rejected trial) reached against the base
        (``kernels.hold_points``); whether anything is held and the holds changed."""
        return kernels.hold_points(self.points, self.base_full, self.base_reduced, bool(again))

    def release(self):
        """Hold no branch."""
        self.points.full_hold[...] = 0
        self.points.reduced_hold[...] = 0

    def mass_factors(self, X, V, A, tangent, t=0.0):
        """Factors of the free rows' mass at a state at time t [s]: the a_x = 1 tangent less the a_x = 0
        one, the clamps' constraint added back (``add_constraints``)."""
        return self.factorize(self.add_constraints(tangent - self.evaluate(X, V, A, 0.0, 0.0, t=t)[1]))

    def factorize(self, band, scale=1.0):
        """LU factors of scale x band (dgbtrf); None if singular."""
        lu, piv, info = lapack.dgbtrf(scale * band, self.kl, self.ku)
        return None if info != 0 else (lu, piv)

    def solve(self, factors, rows):
        """Increment (N_free, 3) of the free DOFs (in ``fem.free_dofs`` order) for residual rows."""
        lu, piv = factors
        rhs = -rows[self.free_order].ravel()
        x, info = lapack.dgbtrs(lu, self.kl, self.ku, rhs, piv)
        return x.reshape(-1, 3)[self.band_of_free]

    def solve_many(self, factors, rows):
        """Increments (m, N_free, 3) for m residuals ``rows`` (m, N, 3): one banded solve."""
        lu, piv = factors
        rhs = -rows[:, self.free_order].reshape(len(rows), -1).T
        x, info = lapack.dgbtrs(lu, self.kl, self.ku, np.asfortranarray(rhs), piv)
        return x.T.reshape(len(rows), -1, 3)[:, self.band_of_free]

    def dense(self, band):
        """The banded tangent as a dense matrix in ``fem.free_vector_dofs`` order (for tests)."""
        n, kl, ku = self.n, self.kl, self.ku
        dense = np.zeros((n, n))
        for j in range(n):
            for i in range(max(0, j - ku), min(n, j + kl + 1)):
                dense[i, j] = band[kl + ku + i - j, j]
        index = (3 * self.band_of_free[:, None] + np.arange(3)).ravel()
        return dense[np.ix_(index, index)]
