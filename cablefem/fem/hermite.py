"""scikit-fem's C1 cubic Hermite line element, its basis evaluated in element coordinates.

``ElementLineHermite`` (scikit-fem) has the value u and the derivative u_x at each vertex as its
DOFs (H^2-conforming: the tangent r'(s) is continuous, so the curvature is square-integrable and a
bending energy int EI kappa^2 ds is defined). scikit-fem builds it as an ``ElementGlobal``: a power
basis 1, x, x^2, x^3 in the global coordinate, inverted per element through a Vandermonde matrix.
On a line's mesh over [0, L] that matrix is ill-conditioned where x >> h (600 m long, 1 m elements:
basis values wrong by 3e-7). ``ElementLineHermiteLocal`` is the same element, the same DOFs in the
same order, with the basis written in the element's own coordinate xi in [0, 1],

    H_0 = 1 - 3 xi^2 + 2 xi^3,   H_1 = h (xi - 2 xi^2 + xi^3),
    H_2 = 3 xi^2 - 2 xi^3,       H_3 = h (xi^3 - xi^2),

exact to round-off on any mesh (``hermite_basis``: values, first and second derivatives in s).
A line on it integrates its axial term by Simpson's rule (``lobatto_line``) and takes its start
shape's tangents from the shape's L2 projection (``hermite_tangents``).
"""

import numpy as np
from scipy.linalg import solve_banded
from skfem import ElementLineHermite
from skfem.element.discrete_field import DiscreteField

#: the local DOFs of an element in scikit-fem's order: (vertex, derivative) of u_a, u_x_a, u_b, u_x_b
LOCAL = ((0, False), (0, True), (1, False), (1, True))


def hermite_basis(xi, h):
    """Basis values, d/ds and d^2/ds^2 (4, ...) at element coordinates xi in [0, 1] of elements of
    length h [m] (broadcast with xi), in scikit-fem's local order (``LOCAL``)."""
    xi, h = np.broadcast_arrays(np.asarray(xi, dtype=float), np.asarray(h, dtype=float))
    x2, x3 = xi * xi, xi * xi * xi
    values = np.array([1.0 - 3.0 * x2 + 2.0 * x3, h * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, h * (x3 - x2)])
    first = np.array([(-6.0 * xi + 6.0 * x2) / h, 1.0 - 4.0 * xi + 3.0 * x2, (6.0 * xi - 6.0 * x2) / h,
                      3.0 * x2 - 2.0 * xi])
    second = np.array([(-6.0 + 12.0 * xi) / (h * h), (-4.0 + 6.0 * xi) / h, (6.0 - 12.0 * xi) / (h * h),
                       (6.0 * xi - 2.0) / h])
    return values, first, second


class ElementLineHermiteLocal(ElementLineHermite):
    """scikit-fem's ``ElementLineHermite`` with its basis in element coordinates (module docstring);
    on a ``MeshLine`` whose elements run left to right (h > 0)."""

    def gbasis(self, mapping, X, i, tind=None):
        h = mapping.DF(X, tind)[0, 0]  # (nel, nq): the element's length
        xi = np.broadcast_to(X[0], h.shape)
        values, first, second = hermite_basis(xi, h)
        return (DiscreteField(value=values[i], grad=first[i][None], hess=second[i][None, None]),)


def lobatto_line():
    """Simpson's rule, the 3-point Gauss-Lobatto rule on [0, 1]: (X (1, 3), W (3,)), the axial term
    of a C1 cubic Hermite line. Its points hold the strain at the n + 1 vertices (shared by two
    elements, where r' is continuous) and the n midpoints: 2n + 1 conditions on the 2n + 2 axial
    unknowns, one per mode but a rigid motion. Three Gauss points per element (3n) lock the
    inextensible elastica (tip error 4e-5 at 16 elements and EA L^2/EI = 1e8 against 2e-6 at
    1e6, verification/bending); two (2n) leave one mode of zero axial energy (every vertex's
    |r'| shifted alike, the strain vanishing at both Gauss points), singular on a straight line."""
    return np.array([[0.0, 0.5, 1.0]]), np.array([1.0, 4.0, 1.0]) / 6.0


def hermite_tangents(fem, X, positions):
    """X (N, 3) of a ``LineFEM`` on Hermite elements, its vertex positions given, with its tangent
    rows the L2 projection of ``positions`` (a function of arc length (n,) -> (n, 3)) onto the
    tangent basis functions (tridiagonal: each spans two elements)."""
    nv = fem.n_vertices
    target, _ = fem.at_quadrature_positions(positions)
    vertex_part, _ = fem.at_quadrature(X)
    phi_t, dx = fem.phi[2:], fem.dx  # the element's two tangent functions (2, nel, nq)
    local = np.einsum("ieq,jeq,eq->eij", phi_t, phi_t, dx)
    rhs_local = np.einsum("ieq,ceq,eq->eic", phi_t, target - vertex_part, dx)
    band = np.zeros((3, nv))
    band[1, :-1] += local[:, 0, 0]
    band[1, 1:] += local[:, 1, 1]
    band[0, 1:] = local[:, 0, 1]  # superdiagonal
    band[2, :-1] = local[:, 1, 0]  # subdiagonal
    rhs = np.zeros((nv, 3))
    np.add.at(rhs, np.arange(nv - 1), rhs_local[:, 0])
    np.add.at(rhs, np.arange(1, nv), rhs_local[:, 1])
    X[nv:] = solve_banded((1, 1), band, rhs)
    return X
