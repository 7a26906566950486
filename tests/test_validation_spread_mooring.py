"""barreiro2015 catenary moorings: single lines and a three-line spread mooring, FEM statics against
closed forms (``validation/spread_mooring``, fast variant).

Tolerances: 1e-4 relative between FEM and closed form (the study's claim; measured 1e-5 to 4e-5:
the touchdown falls inside a 0.25 m P2 element, and EA = 1e12 N against EA = inf costs up to
4e-5 at the stiffest span); 1e-9 between Barreiro's formula and ``elastic_catenary`` with
EA = inf (both closed forms, solved to ~1e-13 of the line length; measured 3e-13); 1e-6 for
zero offset and the symmetries of the spread mooring (solver round-off: residuals of EA x 1e-16
strain, 1e-7 of the line tension at EA = 1e12 N; measured 2e-7).
"""

import math

import numpy as np
import pytest

from cablefem.statics.catenary import elastic_catenary

from validation.spread_mooring import run as study


@pytest.fixture(scope="module")
def results():
    return study.run(fast=True)


@pytest.mark.parametrize("name", sorted(study.WEIGHTS))
def test_fem_fairlead_tension_matches_closed_forms_to_1e4(results, name):
    rows = results["single_lines"]["lines"][name]["rows"]
    assert {r["regime"] for r in rows} == {"touchdown", "suspended"}
    for r in rows:
        assert r["fem_vs_catenary_tension"] <= 1e-4, r["span_m"]
        assert r["fem_vs_catenary_horizontal"] <= 1e-4, r["span_m"]
        assert r["fem_vs_elastic_tension"] <= 1e-4, r["span_m"]
        if r["barreiro_tension_N"] is not None:
            assert r["fem_vs_barreiro_tension"] <= 1e-4, r["span_m"]
            assert r["fem_vs_barreiro_horizontal"] <= 1e-4, r["span_m"]
    assert sum(r["barreiro_tension_N"] is not None for r in rows) >= 3


def test_fem_tension_rises_from_slack_to_nearly_taut(results):
    for data in results["single_lines"]["lines"].values():
        tensions = [r["fem_tension_N"] for r in data["rows"]]
        assert np.all(np.diff(tensions) > 0.0)
        assert data["rows"][0]["lying_length_m"] > 0.75 * study.LENGTH
        assert tensions[-1] > 3.0 * data["weight_N_per_m"] * study.LENGTH


def test_barreiro_formula_equals_inextensible_elastic_catenary_to_1e9(results):
    check = results["single_lines"]["formula_check"]
    assert check["spans"] >= 100
    assert max(check["max_relative"].values()) <= 1e-9


@pytest.mark.parametrize("a", [0.05, 1.0, 10.0, 100.0, 239.0])
@pytest.mark.parametrize("weight", sorted(study.WEIGHTS.values()))
def test_barreiro_span_of_a_gives_back_th_equal_a_w_in_our_catenary(a, weight):
    span = study.barreiro_span(a)
    ours = elastic_catenary(span, study.HEIGHT, study.LENGTH, np.inf, weight)
    assert ours.regime == "touchdown"
    assert ours.fairlead_horizontal == pytest.approx(a * weight, rel=1e-9)
    assert ours.fairlead_tension == pytest.approx(a * weight + weight * study.HEIGHT, rel=1e-9)


def test_barreiro_formula_ends_where_the_touchdown_reaches_the_anchor():
    a_max, span = study.barreiro_limit()
    ours = elastic_catenary(span, study.HEIGHT, study.LENGTH, np.inf, 850.0)
    assert ours.lying_length == pytest.approx(0.0, abs=1e-6)
    assert study.barreiro_line(span + 1e-3, 850.0) is None
    assert study.barreiro_line(study.LENGTH - study.HEIGHT, 850.0) is None


def test_line_type_has_exactly_the_papers_submerged_weight():
    env = study.ENVIRONMENT
    for weight in study.WEIGHTS.values():
        line_type = study.line_type(weight)
        assert line_type.submerged_weight(env.water_density, env.gravity) == pytest.approx(weight, rel=1e-14)


def test_spread_force_at_zero_offset_is_zero_to_solver_tolerance(results):
    checks = results["spread"]["checks"]
    assert checks["zero_offset_relative_to_H0"] <= 1e-6
    closed = study.spread_forces(np.zeros(3), fem=False)["closed_form"]
    assert np.linalg.norm(closed[:2]) <= 1e-9 * results["spread"]["layout"]["pretension_horizontal_N"]
    # the vertical load is the weight of the three suspended lengths, not zero
    assert -closed[2] > 3 * study.SPREAD_WEIGHT * study.HEIGHT


def test_spread_fem_force_points_back_towards_the_origin_for_every_offset(results):
    moving = [r for r in results["spread"]["rows"] if r["offset_m"] > 0]
    assert len(moving) >= 8
    for r in moving:
        offset = r["offset_m"] * study._unit(r["direction_deg"])
        assert np.dot(r["fem_force_N"][:2], offset[:2]) < 0.0, r["direction_deg"]
        assert r["angle_from_minus_offset_deg"] < 20.0


@pytest.mark.parametrize("offset", [0.5, 2.5, 5.0])
def test_spread_closed_form_force_points_back_towards_the_origin_in_every_direction(offset):
    for direction in np.arange(0.0, 360.0, 7.5):
        displacement = offset * study._unit(direction)
        force = study.spread_forces(displacement, fem=False)["closed_form"]
        assert np.dot(force[:2], displacement[:2]) < -0.5 * np.linalg.norm(force[:2]) * offset


def test_spread_fem_restoring_force_matches_closed_form_sum_to_1e4(results):
    spread = results["spread"]
    assert spread["max_fem_vs_closed_form"] <= 1e-4
    assert spread["max_fem_vs_closed_form_vertical"] <= 1e-4


def test_spread_fem_forces_rotate_with_the_layout_by_120_degrees_to_1e6(results):
    rotation = results["spread"]["checks"]["rotation"]
    assert len(rotation) >= 4
    assert max(c["relative"] for c in rotation) <= 1e-6
    assert max(c["vertical_relative"] for c in rotation) <= 1e-6


def test_spread_fem_forces_mirror_about_the_0_and_60_degree_axes_to_1e6(results):
    mirror = results["spread"]["checks"]["mirror"]
    assert {c["check"] for c in mirror} >= {"F(0) = M0 F(0)", "F(60) = M60 F(60)", "F(90) = M60 F(30)",
                                            "F(330) = M0 F(30)"}
    assert max(c["relative"] for c in mirror) <= 1e-6


def test_rotation_and_mirror_matrices_map_the_layout_onto_itself():
    anchors, _ = study.spread_layout()
    for matrix in (study._rotation(120.0), study._mirror(0.0), study._mirror(60.0)):
        mapped = anchors @ matrix.T
        distance = np.linalg.norm(mapped[:, None, :] - anchors[None, :, :], axis=2).min(axis=1)
        assert np.all(distance <= 1e-12 * study.ANCHOR_RADIUS)
    assert math.isclose(np.linalg.det(study._mirror(60.0)), -1.0)


def test_touchdown_fitted_solve_line_matches_elastic_catenary_to_1e6_where_it_converges(results):
    # a mesh vertex at the touchdown removes the curvature jump inside an element: measured 1e-7
    # to 3e-7 in T and T_H against the closed form at the same EA (1e12 N)
    for data in results["single_lines"]["lines"].values():
        converged = [r for r in data["rows"] if "fitted_error" not in r]
        assert len(converged) >= 3
        for r in converged:
            assert r["fitted_vs_elastic_tension"] <= 1e-6, r["span_m"]
            assert r["fitted_vs_elastic_horizontal"] <= 1e-6, r["span_m"]
