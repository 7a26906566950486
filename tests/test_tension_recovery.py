"""Tension along a line (``LineSampler``: the static JSON's vertex tensions, VTK frames) against the
elastic catenary's closed form: the desire2023 Table 5 chain (EA 3.15e9 N, strain ~3e-4) on the flat
seabed of verification/elastic_catenary. Differentiated directly, r' of so stiff a line is off by
more than the strain itself between the points where it is superconvergent (P2 x 20: vertex
tensions off by 17 times their size); recovered from those points, a few 1e-3 or better."""

import numpy as np
import pytest

import verification.elastic_catenary.run as ec
from cablefem.model.line import Line, Segment
from cablefem.runs.results import LineSampler, recovery_points, report


def _solve(order, elements, hermite=False):
    case = ec.Case("flat")
    if hermite:  # the case's own line, on cubic Hermite elements (EI 0: a string on C1 elements)
        anchor = case.anchor - case.penetration() * case.seabed.normal
        case.line = lambda order, elements, touchdown=None: Line(
            case.name, anchor, case.fairlead, [Segment(ec.chain(), ec.LENGTH, elements)], 3, element="hermite")
    system, result, _ = ec.solve(case, order, elements, "uniform" if hermite else "exact-vertex")
    return case, system, result.X


# measured: P2 5.3e-3, P3 2.7e-5, Hermite 1.5e-3 at the vertices (the old vertex tensions: 17, 6.7, -)
@pytest.mark.parametrize("order, hermite, bound", [(2, False, 1e-2), (3, False, 1e-4), (3, True, 3e-3)])
def test_vertex_tensions_of_a_stiff_chain_follow_the_closed_form(order, hermite, bound):
    case, system, X = _solve(order, 20, hermite)
    nodes = system.fem.mesh.p[0]
    error = report(system, X).tension / case.exact.tension(nodes) - 1.0
    assert np.max(np.abs(error)) < bound


def test_tension_between_the_vertices_converges_at_p3():
    # P3 on a mesh with a vertex at the touchdown: 8.4e-4, 1.2e-4, 1.6e-5 at 10, 20, 40 elements
    errors = []
    for elements in (10, 20, 40):
        case, system, X = _solve(3, elements)
        s = np.linspace(0.0, ec.LENGTH, 301)
        rep = report(system, X)
        tension = LineSampler(system, s).tension(X, ends=(rep.fairlead_force, rep.anchor_force))
        errors.append(np.max(np.abs(tension / case.exact.tension(s) - 1.0)))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert errors[-1] < 5e-5 and np.all(orders > 2.5), (errors, orders)


@pytest.mark.parametrize("order", [1, 2, 3])
def test_recovery_weights_reproduce_polynomials_of_the_recovered_degree(order):
    # the weights interpolate through the element's p Gauss points: exact for degree p - 1
    case, system, _ = _solve(order, 10)
    fem = system.fem
    s = np.linspace(0.0, ec.LENGTH, 57)
    points, weights = recovery_points(fem, s, fem._locate(s)[0])
    for degree in range(order):
        np.testing.assert_allclose(np.sum(weights * points ** degree, axis=1), s ** degree, rtol=1e-10, atol=1e-8)
