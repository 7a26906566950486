"""scikit-fem discretisation of one line over its unstretched arc length.

The mesh is a ``MeshLine`` on [0, L] with vertices at the segment
boundaries; the unknown is the position r(s) in R^3, an ``ElementVector``
of ``ElementLineP1``, ``ElementLineP2`` or ``ElementLinePp(p)`` with three
components (desire2023 Sec. 2.1.2, here of any order), or of the C1 cubic
Hermite element (``cablefem.fem.hermite``) whose unknowns are the positions
and the tangents r'(s) at the vertices.

scikit-fem orders the vector DOFs component-fastest (DOF 3 i + c is
component c of scalar DOF i), so a state is an array X of shape (N, 3) whose
first rows are the vertex positions, anchor first; for P3 and up the other
rows are the hierarchical (integrated Legendre) coefficients of the element
interiors. On Hermite elements the first rows are the vertex positions too and
the next ones the vertex tangents, in the same order (``LineFEM.skfem_dof``
maps them to scikit-fem's numbering, position and tangent of each vertex in
turn, for the forms). Everything that does not change between Newton iterations
(basis values, quadrature, the sparsity pattern and the scatter maps) is
computed once here, and what only the reference assembly reads (the
vector bases of the forms, the CSR patterns of the tangent) on its first use:
a run on the compiled kernel never builds them. Values at quadrature points and
the residual's scatter are sparse operators built from their arrays directly
(from (row, col) triplets they were ~1 ms of a coarse run's ~4 ms set-up,
verification/work_precision/README.md).
"""

import warnings
from functools import cached_property, lru_cache

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementLineP1, ElementLineP2, ElementLinePp, ElementVector, MeshLine
from skfem.quadrature import get_quadrature_line

from cablefem.fem.hermite import LOCAL, ElementLineHermiteLocal, hermite_basis, hermite_tangents, lobatto_line


def scalar_element(order):
    """The scikit-fem line element of polynomial ``order``."""
    if order == 1:
        return ElementLineP1()
    if order == 2:
        return ElementLineP2()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return ElementLinePp(order)


def _kept_per_process(rule):
    """``rule(n)`` -> arrays, computed once per ``n`` in a process and handed out as copies (numpy's
    Gauss-Legendre solves an eigenproblem, ~0.2 ms a call, twice a line's set-up)."""
    @lru_cache(maxsize=None)
    def table(n):
        arrays = rule(n)
        for array in arrays:
            array.flags.writeable = False
        return arrays

    return lambda n: tuple(array.copy() for array in table(n))


#: numpy's Gauss-Legendre points and weights on [-1, 1] (n,), (n,); scikit-fem's line rule of an
#: order (what its Basis(intorder=...) takes), each kept per process
_legendre = _kept_per_process(np.polynomial.legendre.leggauss)
_scikit_fem_line_rule = _kept_per_process(get_quadrature_line)


def gauss_line(points):
    """Gauss-Legendre rule of ``points`` points on the reference element [0, 1]: (X (1, n), W (n,))."""
    x, w = _legendre(points)
    return 0.5 * (x + 1.0)[None, :], 0.5 * w


class LineFEM:
    """Mesh, bases, quadrature data and assembly maps of one ``Line``.

    Arrays at quadrature points use scikit-fem's shapes: (3, n_elements,
    n_quadrature) for vectors and (3, 3, n_elements, n_quadrature) for the
    Jacobian blocks.
    """

    def __init__(self, line, quadrature_points=None):
        self.line = line
        self.order = line.order
        self.hermite = line.hermite
        self.mesh = MeshLine(line.node_arc_lengths())
        self.element = element = ElementLineHermiteLocal() if self.hermite else scalar_element(self.order)
        n_gauss = quadrature_points or line.quadrature_points or self.order + 1
        self.scalar_basis = Basis(self.mesh, element, quadrature=_scikit_fem_line_rule(2 * n_gauss - 1))
        sb = self.scalar_basis
        self.n_dofs = sb.N
        self.n_vertices = self.mesh.p.shape[1]
        self.n_elements = self.mesh.t.shape[1]
        # Hermite: the rows hold the vertex positions, then the vertex tangents (scikit-fem: the
        # position and the tangent of each vertex in turn); the local DOFs of an element are its
        # two positions, then its two tangents, as a Lagrange element's vertices come first
        self.skfem_dof, local = None, None
        if self.hermite:
            nv = self.n_vertices
            self.skfem_dof = np.concatenate([2 * np.arange(nv), 2 * np.arange(nv) + 1])
            local = np.array([LOCAL.index((0, False)), LOCAL.index((1, False)), LOCAL.index((0, True)),
                              LOCAL.index((1, True))])
        self.row_of_skfem_dof = None if self.skfem_dof is None else np.argsort(self.skfem_dof)
        self.local = local
        dofs = sb.element_dofs if local is None else self.row_of_skfem_dof[sb.element_dofs[local]]
        self.element_dofs = np.ascontiguousarray(dofs.T)  # (nel, nloc)
        self.full = Rule(sb, self.element_dofs, local)
        # the axial term with one Gauss point fewer: a polynomial element cannot follow a
        # curved line at constant stretch, and at full integration a stiff line "locks"
        # (spurious strain of order (kappa h)^2, against T/EA ~ 1e-4); p points remove it. The
        # rule is built here: scikit-fem's line rules have two points at least, and P1's strain
        # is constant along an element, so its second point only doubled the axial work.
        # Hermite: Simpson's rule (``hermite.lobatto_line``), see there
        reduced_rule = lobatto_line() if self.hermite else gauss_line(self.order)
        self.reduced = Rule(Basis(self.mesh, element, quadrature=reduced_rule), self.element_dofs, local)
        self.phi, self.dphi, self.dx, self.s = self.full.phi, self.full.dphi, self.full.dx, self.full.s
        self.segment = line.element_segments()  # (nel,)
        self.anchor_dof = 0
        self.fairlead_dof = self.n_vertices - 1
        self.end_dofs = (self.anchor_dof, self.fairlead_dof)  # by end: 0 anchor, 1 fairlead
        # the ends whose positions are prescribed (``Line.prescribed``); the others are unknowns
        self.prescribed = tuple(line.prescribed)
        self.fixed_dofs = [dof for dof, given in zip(self.end_dofs, self.prescribed) if given]
        fixed = np.zeros(self.n_dofs, dtype=bool)
        fixed[self.fixed_dofs] = True
        self.free_dofs = np.flatnonzero(~fixed)
        self.free_vector_dofs = (3 * self.free_dofs[:, None] + np.arange(3)).ravel()
        # the anchor's and the fairlead's tangent rows (Hermite), and the directions clamping them
        self.tangent_dofs = (self.n_vertices, 2 * self.n_vertices - 1) if self.hermite else ()
        self.clamped = tuple(line.tangents) if self.hermite else (None, None)

    @cached_property
    def basis(self):
        """The vector basis at the full rule (scikit-fem forms, ``assembly = "forms"``)."""
        return Basis(self.mesh, ElementVector(self.element, dim=3), quadrature=self.full.quadrature)

    @cached_property
    def reduced_basis(self):
        """The vector basis at the reduced rule (scikit-fem forms)."""
        return Basis(self.mesh, ElementVector(self.element, dim=3), quadrature=self.reduced.quadrature)

    def from_skfem(self, rows):
        """Rows (N, 3) in this FEM's order from rows in scikit-fem's DOF order (the same but on
        Hermite elements)."""
        return rows if self.skfem_dof is None else rows[self.skfem_dof]

    def matrix_from_skfem(self, K):
        """A sparse matrix (3 N, 3 N) over scikit-fem's vector DOFs in this FEM's order."""
        if self.skfem_dof is None:
            return K
        index = (3 * self.skfem_dof[:, None] + np.arange(3)).ravel()
        return K[index][:, index]

    # ------------------------------------------------------------------ maps
    def _entries(self):
        """Global row and column (vector DOF) of every local matrix entry (e, l, a, m, b)."""
        comp = np.arange(3)
        rows = (3 * self.element_dofs[:, :, None, None, None] + comp[None, None, :, None, None])
        colz = (3 * self.element_dofs[:, None, None, :, None] + comp[None, None, None, None, :])
        rows, colz = np.broadcast_arrays(rows, colz)
        return rows.ravel(), colz.ravel()

    @cached_property
    def _full(self):
        """CSR pattern of the full system: local entry -> data index."""
        rows, colz = self._entries()
        return _CsrPattern(rows, colz, 3 * self.n_dofs)

    @cached_property
    def _free(self):
        """CSR pattern of the free unknowns (local entries touching a fixed DOF dropped)."""
        rows, colz = self._entries()
        free_vec = self.free_vector_dofs
        free_index = -np.ones(3 * self.n_dofs, dtype=np.int64)
        free_index[free_vec] = np.arange(free_vec.size)
        r, c = free_index[rows], free_index[colz]
        keep = (r >= 0) & (c >= 0)
        return _CsrPattern(r[keep], c[keep], free_vec.size, keep)

    # ----------------------------------------------------------- evaluation
    def at_quadrature(self, X, rule=None):
        """Values and arc-length derivatives of X (N, 3) at the points of ``rule`` (default: full),
        each (3, nel, nq)."""
        rule = rule or self.full
        shape = (3,) + rule.s.shape
        values, derivatives = rule.interpolate(X)
        return values.T.reshape(shape), derivatives.T.reshape(shape)

    def evaluate(self, X, s):
        """Positions (n, 3) of state X (N, 3) at unstretched arc lengths s (n,) [m]."""
        values, _ = self._local_basis(s)
        element, _ = self._locate(s)
        return np.einsum("nl,nlc->nc", values, X[self.element_dofs[element]])

    def derivative(self, X, s):
        """Tangent dr/ds (n, 3) of state X at arc lengths s (n,), taken inside the element holding s."""
        _, grads = self._local_basis(s)
        element, _ = self._locate(s)
        return np.einsum("nl,nlc->nc", grads, X[self.element_dofs[element]])

    def second_derivative(self, X, s):
        """d^2 r/ds^2 (n, 3) of state X at arc lengths s (n,), inside the element holding s
        (Hermite elements)."""
        if not self.hermite:
            raise ValueError("second derivatives are read on Hermite elements")
        element, _ = self._locate(s)
        return np.einsum("nl,nlc->nc", self.local_second_basis(s), X[self.element_dofs[element]])

    def _locate(self, s):
        s = np.atleast_1d(np.asarray(s, dtype=float))
        nodes = self.mesh.p[0]
        element = np.clip(np.searchsorted(nodes, s, side="right") - 1, 0, self.n_elements - 1)
        left, right = nodes[self.mesh.t[0, element]], nodes[self.mesh.t[1, element]]
        return element, (s - left) / (right - left)

    def local_second_basis(self, s):
        """Second s-derivatives of the basis (n, nloc) at arc lengths s (n,), in the element holding
        each (Hermite elements)."""
        element, xi = self._locate(s)
        h = np.diff(self.mesh.p[0])[element]
        return hermite_basis(xi, h)[2][self.local].T

    def _local_basis(self, s):
        element, xi = self._locate(s)
        h = np.diff(self.mesh.p[0])[element]
        if self.hermite:
            values, first, _ = hermite_basis(xi, h)
            return values[self.local].T, first[self.local].T
        el = self.scalar_basis.elem
        vals, grads = [], []
        for i in range(self.phi.shape[0]):
            v, g = el.lbasis(xi[None, :], i)
            vals.append(v)
            grads.append(g[0] / h)
        return np.array(vals).T, np.array(grads).T

    def interpolate(self, positions):
        """State X (N, 3) reproducing ``positions(s) -> (n, 3)`` at the vertices and, inside
        each element, its L2 projection (exact for polynomials of the element's order)."""
        X = np.zeros((self.n_dofs, 3))
        X[: self.n_vertices] = positions(self.mesh.p[0])
        if self.n_dofs == self.n_vertices:
            return X
        if self.hermite:
            return hermite_tangents(self, X, positions)
        target, _ = self.at_quadrature_positions(positions)
        vertex_part, _ = self.at_quadrature(X)
        interior = self.element_dofs[:, 2:]
        phi_b = self.phi[2:]
        mass = np.einsum("ieq,jeq,eq->eij", phi_b, phi_b, self.dx)
        rhs = np.einsum("ieq,ceq,eq->eic", phi_b, target - vertex_part, self.dx)
        X[interior] = np.linalg.solve(mass, rhs)
        return X

    def at_quadrature_positions(self, positions):
        """A function of arc length (n,) -> (n, 3) evaluated at quadrature points, (3, nel, nq)."""
        values = positions(self.s.ravel())
        return values.T.reshape(3, *self.s.shape), None

    # ------------------------------------------------------------- assembly
    def assemble_vector(self, force=None, flux=None, rule=None, moment=None):
        """Residual rows (N, 3): int (flux . phi' - force . phi + moment . phi'') ds over all
        elements, with force, flux and moment (3, nel, nq) at the points of ``rule`` (default:
        full; a moment on Hermite elements)."""
        rule = rule or self.full
        return rule.scatter(None if force is None else -force, flux, moment)

    def element_matrices(self, value_value=None, value_grad=None, grad_value=None, grad_grad=None,
                         grad_second=None, second_grad=None, second_second=None, rule=None, out=None):
        """Local matrices (nel, nloc, 3, nloc, 3) of int v.(A u + B u') + v'.(C u + D u' + E u'')
        + v''.(F u' + G u'') ds for the blocks A ... G given as (3, 3, nel, nq) arrays (None for
        zero) at the points of ``rule`` (E, F, G on Hermite elements); added to ``out`` when given."""
        rule = rule or self.full
        nel, nloc = self.element_dofs.shape
        if out is None:
            out = np.zeros((nel, nloc, 3, nloc, 3))
        for block, products in zip((value_value, value_grad, grad_value, grad_grad), rule.products):
            if block is not None:
                out += np.einsum("abeq,lmeq->elamb", block, products)
        for block, products in zip((grad_second, second_grad, second_second), rule.second_products):
            if block is not None:
                out += np.einsum("abeq,lmeq->elamb", block, products)
        return out

    def assemble_matrix(self, local, free_only=True):
        """Sparse CSR matrix from local matrices; restricted to the free DOFs by default."""
        pattern = self._free if free_only else self._full
        return pattern.matrix(local.ravel())

    def vector_mass(self, density, free_only=True):
        """Consistent mass matrix int m phi_i phi_j ds I_3 for mass per length ``density`` (nel,)."""
        local = np.einsum("leq,eq,meq,e->elm", self.phi, self.dx, self.phi, density)
        eye = np.eye(3)
        return self.assemble_matrix(np.einsum("elm,ab->elamb", local, eye), free_only)


class Rule:
    """Basis values at one quadrature rule: phi, dphi/ds (nloc, nel, nq), weights x Jacobian
    dx (nel, nq) and the arc lengths s (nel, nq) of the points; on Hermite elements also
    ddphi = d^2 phi/ds^2 (nloc, nel, nq) (None otherwise). ``dofs`` (nel, nloc): the element's rows,
    its local functions in the order ``local`` picks from scikit-fem's (None: scikit-fem's)."""

    def __init__(self, scalar_basis, dofs=None, local=None):
        self.quadrature = scalar_basis.quadrature
        self.dofs = scalar_basis.element_dofs.T if dofs is None else dofs  # (nel, nloc)
        self.n_dofs = scalar_basis.N
        functions = scalar_basis.basis if local is None else [scalar_basis.basis[i] for i in local]
        self.phi = np.array([np.asarray(b[0]) for b in functions])
        self.dphi = np.array([b[0].grad[0] for b in functions])
        self.ddphi = None if local is None else np.array([b[0].hess[0, 0] for b in functions])
        self.dx = scalar_basis.dx
        self.s = np.asarray(scalar_basis.global_coordinates())[0]

    @cached_property
    def products(self):
        """Weighted products of test and trial functions (nloc, nloc, nel, nq), in the order
        value-value, value-derivative, derivative-value, derivative-derivative."""
        return [np.einsum("leq,meq,eq->lmeq", a, b, self.dx)
                for a, b in ((self.phi, self.phi), (self.phi, self.dphi), (self.dphi, self.phi),
                             (self.dphi, self.dphi))]

    @cached_property
    def second_products(self):
        """Weighted products (nloc, nloc, nel, nq) with second derivatives: derivative-second,
        second-derivative, second-second (Hermite elements; empty otherwise)."""
        if self.ddphi is None:
            return []
        return [np.einsum("leq,meq,eq->lmeq", a, b, self.dx)
                for a, b in ((self.dphi, self.ddphi), (self.ddphi, self.dphi), (self.ddphi, self.ddphi))]

    def _operators(self, basis_values):
        """The interpolation operator (nel nq, N) of ``basis_values`` (nloc, nel, nq), CSR, and
        its weighted transpose (N, nel nq), the scatter, CSC on the same index arrays: built
        from their arrays directly (every row holds the element's nloc DOFs), 6-8x cheaper
        than from (row, col) triplets (27 against 223 us for P1 x 14)."""
        nloc, nel, nq = basis_values.shape
        indices = np.broadcast_to(self.dofs[:, None, :], (nel, nq, nloc)).ravel().astype(np.int32)
        indptr = np.arange(0, nel * nq * nloc + 1, nloc, dtype=np.int32)
        data = basis_values.transpose(1, 2, 0).ravel()
        weighted = (basis_values * self.dx).transpose(1, 2, 0).ravel()
        return (sp.csr_matrix((data, indices, indptr), shape=(nel * nq, self.n_dofs)),
                sp.csc_matrix((weighted, indices, indptr), shape=(self.n_dofs, nel * nq)))

    @cached_property
    def _value_operators(self):
        return self._operators(self.phi)

    @cached_property
    def _derivative_operators(self):
        return self._operators(self.dphi)

    @cached_property
    def _second_operators(self):
        return self._operators(self.ddphi)

    def interpolate(self, Y):
        """Values and s-derivatives (nel nq, k) at the rule's points of coefficients Y (N, k)."""
        return self._value_operators[0] @ Y, self._derivative_operators[0] @ Y

    def second(self, Y):
        """Second s-derivatives (nel nq, k) at the rule's points of coefficients Y (N, k) (Hermite)."""
        return self._second_operators[0] @ Y

    def scatter(self, values, derivatives, seconds=None):
        """Rows (N, 3): int (derivatives . phi' + values . phi + seconds . phi'') ds, each
        (3, nel, nq) or None (``seconds`` on Hermite elements)."""
        out = np.zeros((self.n_dofs, 3))
        if values is not None:
            out += self._value_operators[1] @ values.reshape(3, -1).T
        if derivatives is not None:
            out += self._derivative_operators[1] @ derivatives.reshape(3, -1).T
        if seconds is not None:
            out += self._second_operators[1] @ seconds.reshape(3, -1).T
        return out


class _CsrPattern:
    """Fixed CSR sparsity of a matrix assembled from many (row, col) contributions."""

    def __init__(self, rows, cols, size, keep=None):
        keys = rows.astype(np.int64) * size + cols
        unique, self.index = np.unique(keys, return_inverse=True)
        self.indices = (unique % size).astype(np.int32)
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(unique // size, minlength=size))]).astype(np.int32)
        self.size = size
        self.nnz = unique.size
        self.keep = keep

    def matrix(self, values):
        """CSR matrix summing ``values`` (one per contribution) into the pattern."""
        if self.keep is not None:
            values = values[self.keep]
        data = np.bincount(self.index, weights=values, minlength=self.nnz)
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.size, self.size))
