"""The FEM assembly: kernel against scikit-fem's forms, tangent against finite differences,
mass and rigid-motion invariants."""

import numpy as np
import pytest

from cablefem.geometry import Horizontal, Plane
from cablefem.model.scene import Contact, Environment
from cablefem.fem.system import LineSystem

from conftest import make_line


def perturbed_state(system, rng, amplitude=0.5):
    """A stretched, wiggly state partly buried in the seabed, with a velocity."""
    fem = system.fem
    line = system.line
    L = line.unstretched_length

    def positions(s):
        f = s / L
        base = line.anchor + f[:, None] * (line.fairlead - line.anchor) * 1.02
        sag = -30.0 * np.sin(np.pi * f)
        return base + np.column_stack([0 * f, 3.0 * np.sin(3 * np.pi * f), sag])

    X = fem.interpolate(positions)
    X += amplitude * rng.standard_normal(X.shape)
    V = rng.standard_normal(X.shape)
    return X, V


@pytest.mark.parametrize("order", [1, 2, 3])
def test_kernel_assembly_equals_scikit_fem_forms(chain, rng, order):
    seabed = Plane.from_slope([0.0, 0.0, -100.0], np.radians(10.0), azimuth=0.3)
    line = make_line(chain, order, elements=8)
    kernel = LineSystem(line, seabed, Contact(), Environment())
    forms = LineSystem(line, seabed, Contact(), Environment(), assembly="forms")
    X, V = perturbed_state(kernel, rng)
    for velocity_factor in (0.0, 150.0):
        Rk, bk = kernel.evaluate(kernel.state(X, V), velocity_factor=velocity_factor)
        Rf, bf = forms.evaluate(forms.state(X, V), velocity_factor=velocity_factor)
        scale = np.abs(Rk).max()
        np.testing.assert_allclose(Rk, Rf, rtol=0, atol=1e-12 * scale)
        Kk = kernel.matrix(bk, free_only=False).toarray()
        Kf = forms.matrix(bf, free_only=False).toarray()
        np.testing.assert_allclose(Kk, Kf, rtol=0, atol=1e-12 * np.abs(Kk).max())


@pytest.mark.parametrize("order", [1, 2, 3])
def test_static_tangent_matches_finite_differences(chain, rng, order):
    seabed = Plane.from_slope([0.0, 0.0, -100.0], np.radians(15.0))
    system = LineSystem(make_line(chain, order, elements=6), seabed, Contact(), Environment())
    X, _ = perturbed_state(system, rng)
    R, blocks = system.evaluate(system.state(X))
    K = system.matrix(blocks, free_only=False).toarray()
    h = 1e-6
    for column in rng.choice(X.size, 12, replace=False):
        dX = np.zeros(X.size)
        dX[column] = h
        Rp = system.residual(X + dX.reshape(X.shape))
        Rm = system.residual(X - dX.reshape(X.shape))
        fd = ((Rp - Rm) / (2 * h)).ravel()
        # central differences of a smooth residual: error O(h^2 K''), far below 1e-5 of K
        np.testing.assert_allclose(K[:, column], fd, rtol=0, atol=1e-5 * np.abs(K).max())


@pytest.mark.parametrize("order", [1, 2, 4])
def test_consistent_mass_sums_to_three_times_line_mass(chain, order):
    system = LineSystem(make_line(chain, order, elements=7), Horizontal(100.0), Contact(), Environment())
    M = system.fem.vector_mass(system.props["mass"], free_only=False)
    ones = np.ones(M.shape[0])
    # sum over all entries of the P1/P2 mass is 3 m L exactly; hierarchical Pp shape functions
    # are not a partition of unity, so only the vertex functions are summed there
    if order <= 2:
        assert ones @ M @ ones == pytest.approx(3 * chain.mass * 635.0, rel=1e-12)
    else:
        vertex = np.zeros(M.shape[0])
        vertex[: 3 * system.fem.n_vertices] = 1.0
        assert vertex @ M @ vertex == pytest.approx(3 * chain.mass * 635.0, rel=1e-12)


@pytest.mark.parametrize("order", [1, 2, 4])
def test_mass_matrix_per_component_equals_the_vector_forms_bit_for_bit(chain, order):
    from cablefem.fem import forms

    system = LineSystem(make_line(chain, order, elements=7), Horizontal(100.0), Contact(), Environment())
    m = system.props["mass"][:, None] * np.ones_like(system.fem.full.dx)
    reference = forms.mass.assemble(system.fem.basis, m=m).tocsr()
    M = forms.mass_matrix(system)
    # the vector form's u . v adds exact zeros to phi_a phi_b: the same entries, the same pattern
    assert M.nnz == reference.nnz
    assert M.toarray().tobytes() == reference.toarray().tobytes()


def test_line_rule_kept_per_process_is_scikit_fems_bit_for_bit():
    from skfem.quadrature import get_quadrature_line

    from cablefem.fem.discretisation import _scikit_fem_line_rule

    for intorder in range(30):
        (x, w), (x_ref, w_ref) = _scikit_fem_line_rule(intorder), get_quadrature_line(intorder)
        assert x.tobytes() == x_ref.tobytes() and w.tobytes() == w_ref.tobytes()


def test_internal_force_rotates_with_a_rigid_motion(chain, rng):
    system = LineSystem(make_line(chain, 3, elements=5), Horizontal(1e4), Contact(), Environment())
    fem = system.fem
    Q, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    shift = rng.standard_normal(3) * 100

    def arc(s):  # a stretched circular arc
        radius, stretch = 400.0, 1.01
        phi = stretch * s / radius
        return np.column_stack([radius * np.sin(phi), np.zeros_like(s), radius * (1 - np.cos(phi))])

    X = fem.interpolate(arc)
    moved = fem.interpolate(lambda s: arc(s) @ Q.T + shift)
    flux = system.tension.evaluate(system.state(X)).flux
    flux_moved = system.tension.evaluate(system.state(moved)).flux
    # frame invariance: N(Q r + c) = Q N(r), to round-off of EA * strain
    np.testing.assert_allclose(flux_moved, np.einsum("ab,beq->aeq", Q, flux), rtol=0,
                               atol=1e-9 * np.abs(flux).max())
    assert np.abs(flux).max() > 0.009 * system.props["EA"].max()  # the arc is really stretched
