"""verification/bending in its fast mode, asserted (a study and its test cannot drift apart): bending on
Hermite elements against the closed forms of the cantilever, the elastica (Bisshopp & Drucker 1945),
the arc of a pure end moment, beam frequencies, a free vibration and the catenary limit. Tolerances
sit a little above the numbers measured, quoted beside them."""

import math

import pytest

from verification.bending import run as bending


@pytest.fixture(scope="module")
def study():
    return bending.run(fast=True, out=False)


def _row(rows, elements):
    found = [r for r in rows if r["elements"] == elements]
    assert len(found) == 1
    return found[0]


def test_cantilever_under_its_weight_is_w_l4_over_8_ei_at_one_element(study):
    # Hermite cubics hold the Euler-Bernoulli cantilever's vertices exactly: what is left is the
    # geometric nonlinearity, ~(drop / L)^2 ~ 1e-8 (1.2e-8 measured at 2-8 elements)
    for row in study["cantilever"]["rows"]:
        assert row["converged"] and abs(row["tip_error"]) < 3e-8 and row["node_error"] < 3e-8


def test_elastica_tip_within_1e_5_at_10_elements_for_tip_angles_up_to_45_degrees(study):
    # measured: alpha = 1 7.1e-7 (26 deg at the tip); alpha = 5 (70 deg) 2.6e-5 misses the 1e-5
    small = next(case for case in study["elastica"] if case["alpha"] == 1.0)
    assert _row(small["rows"], 10)["tip_error"] < 1e-6
    large = next(case for case in study["elastica"] if case["alpha"] == 5.0)
    assert 1e-5 < _row(large["rows"], 10)["tip_error"] < 3e-5


def test_elastica_tip_and_clamp_moment_converge_at_order_4(study):
    # fitted over 4-16 elements: tip 3.97 / 3.88, clamp reaction 3.90 / 3.84 (alpha 1 / 5)
    for case in study["elastica"]:
        assert all(r["converged"] for r in case["rows"])
        assert case["orders"]["tip_error"]["fitted"] >= 3.5
        assert case["orders"]["moment_error"]["fitted"] >= 3.5
        # the curvature read from r'' at the clamp converges slowly (order ~1.4): the reaction is reported
        assert case["orders"]["curvature_error"]["fitted"] < 2.0


def test_pure_end_moment_bends_the_line_into_its_arc_at_order_4(study):
    # tip against the stretched arc: 4.0 (90 and 180 deg); the vertices' curvature converges at order 2
    for case in study["end_moment"]:
        assert all(r["converged"] for r in case["rows"])
        assert case["orders"]["tip_error"]["fitted"] > 3.8
        assert 1.8 < case["orders"]["curvature_error"]["fitted"] < 2.2
        assert _row(case["rows"], 16)["tip_error"] < 1e-6  # 2.9e-8 (90 deg), 3.3e-7 (180 deg)


def test_pinned_and_taut_beam_frequencies_converge_at_order_4(study):
    for name in ("pinned", "taut"):
        f = study["frequencies"][name]
        assert _row(f["rows"], 16)["errors"][0] < 2e-6  # 1.0e-6 / 1.3e-6
        for mode in ("mode_1", "mode_2", "mode_3"):
            assert f["orders"][mode]["fitted"] > 3.7  # 3.87-4.13


def test_free_vibration_keeps_its_period_with_both_compiled_integrators(study):
    v = study["vibration"]
    assert abs(v["omega_error"]) < 1e-5  # 2.1e-6 at 8 elements
    h = 2.0 * math.pi / v["steps_per_period"]
    alpha = v["runs"]["generalized-alpha"]
    # rho_inf = 1 is the trapezoidal rule: its period is (omega dt)^2 / 12 long, 8.03e-4 here (8.01e-4 measured)
    assert abs(alpha["period_error_fem"] - h * h / 12) < 5e-5
    assert abs(alpha["amplitude_ratio"] - 1.0) < 1e-3
    bdf2 = v["runs"]["bdf2"]
    assert 0 < bdf2["period_error"] < 5e-3 and 0.99 < bdf2["amplitude_ratio"] < 1.0  # 3.2e-3, 0.9948 over 5


def test_the_line_tends_to_the_catenary_as_ei_goes_to_zero(study):
    rows = study["catenary_limit"]["rows"]
    by_ei = {r["EI"]: r for r in rows}
    # the bending boundary layers shrink with EI: a hundred times less EI, ~a hundred times closer
    assert by_ei[1e2]["node_error"] < 0.02 * by_ei[1e4]["node_error"]
    # EI = 0 on Hermite elements is the catenary to the discretisation's 3e-6 m and 5e-9 of T_F
    assert by_ei[0.0]["node_error"] < 1e-5 and abs(by_ei[0.0]["fairlead_tension_error"]) < 1e-7
