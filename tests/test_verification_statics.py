"""The statics verification studies, run in their fast mode and asserted (scikit-fem's
test_examples pattern, so a study and its test cannot drift apart):
verification/batista_perkovic (desire2023 Sec. 3, Tables 2-4) and verification/elastic_catenary.
Tolerances sit a little above the measured numbers quoted beside them."""

import pytest

from verification.batista_perkovic import run as batista_perkovic
from verification.elastic_catenary import run as elastic_catenary


@pytest.fixture(scope="module")
def slope():
    return batista_perkovic.run(fast=True)


@pytest.fixture(scope="module")
def catenary():
    return elastic_catenary.run(fast=True)


def _run(study, mesh, order, elements, key="fairlead_tension_error", reference="elastic"):
    found = [r for r in study["runs"] if r["mesh"] == mesh and r["order"] == order and r["elements"] == elements]
    assert len(found) == 1, (mesh, order, elements)
    run = found[0]
    return run[reference][key] if reference else run[key]


# ---- Batista & Perkovic, desire2023 Sec. 3 ------------------------------------------------------

def test_table4_geometry_gives_the_papers_T_A_with_H_reversed():
    # the inferred geometry (h = 83.766 m, slope -15 deg, H at the fairlead) against the printed kN
    for row in batista_perkovic.evidence():
        assert abs(row["relative"]) < 5e-5, row  # worst measured 4.8e-5: the paper's rounding to 1 kN


def test_p1_with_the_papers_32_nodes_beats_the_papers_tension_error(slope):
    rows = slope["setups"][0]["rows"]
    assert len(rows) == 5 and all(r["converged"] for r in rows)
    # the paper's dT reaches 9e-4 against the inextensible line; ours 6.2e-4 (5.3e-4 against
    # the elastic one the FEM solves)
    assert max(abs(r["inextensible"]["fairlead_tension_error"]) for r in rows) < 7e-4
    assert max(abs(r["elastic"]["fairlead_tension_error"]) for r in rows) < 6e-4


def test_p1_with_the_papers_32_nodes_beats_the_papers_position_error(slope):
    # the paper's Table 3 reaches 0.28 m; ours 0.077 m at most over all 32 nodes and five H,
    # bounded by the chord sag kappa h^2 / 8 ~ 0.1 m of straight elements
    rows = slope["setups"][0]["rows"]
    assert max(r["inextensible"]["max_delta_32_nodes_m"] for r in rows) < 0.09
    assert max(max(r["inextensible"]["table3_delta_m"]) for r in rows) < 0.08


@pytest.mark.xfail(strict=True, reason="P1 cannot: its chords make the line as slack as one longer by "
                   "(h^2/24) int kappa^2 ds, -4.7e-4 to -5.4e-4 in tension at 31 elements "
                   "(verification/batista_perkovic/README.md); ~70 elements reach 1e-4")
def test_p1_with_32_nodes_meets_the_issue_targets(slope):
    targets = slope["targets"]
    assert targets["p1_32_nodes_tension_vs_elastic"]["met"]
    assert targets["p1_32_nodes_position_vs_elastic"]["met"]


def test_p1_error_is_the_chord_surplus_of_straight_elements(slope):
    # with a vertex at the touchdown, P1 x 31 misses the closed form by what a line longer by
    # (h^2/24) int kappa^2 ds gives: measured within 6 % of the prediction for all five H
    for row in slope["p1_diagnosis"]:
        assert row["exact_vertex"] == pytest.approx(row["predicted"], rel=0.1), row


def test_p1_converges_at_order_2(slope):
    orders = slope["convergence"]["orders"]
    for mesh in ("uniform", "exact-vertex"):
        # measured 1.99 and 1.99 over 16, 31, 62 elements
        assert orders[f"{mesh} P1"]["fairlead_tension_error"]["fitted"] == pytest.approx(2.0, abs=0.15)
        assert orders[f"{mesh} P1"]["node_position_error_m"]["fitted"] == pytest.approx(2.0, abs=0.15)


def test_p2_and_p3_reach_1e_6_at_16_elements_with_a_vertex_at_the_touchdown(slope):
    study = slope["convergence"]
    for mesh in ("exact-vertex", "fitted"):
        assert abs(_run(study, mesh, 2, 16)) < 1e-6  # measured 3.2e-7 on both meshes
        assert abs(_run(study, mesh, 3, 16)) < 1e-8  # measured 5e-10 and 6e-10: the penetration floor


def test_p2_tension_converges_at_order_4_with_the_touchdown_on_a_vertex(slope):
    orders = slope["convergence"]["orders"]["exact-vertex P2"]
    # theory: order 4 for the tension (2p); measured 3.9-5.0 from 16 to 31 elements depending on
    # where Newton stops near round-off (the 31-element error is ~1e-8)
    assert orders["fairlead_tension_error"]["pairwise"][0] > 3.5
    assert orders["curve_position_error_m"]["fitted"] == pytest.approx(3.0, abs=0.2)  # measured 2.99


def test_a_touchdown_inside_an_element_holds_p2_and_p3_back(slope):
    # uniform mesh: the line lies on to the vertex past the true touchdown (6.2e-6 in tension,
    # 6e-4 m in position) whatever the order: the fitted vertex is what buys accuracy
    study = slope["convergence"]
    for order in (2, 3):
        assert abs(_run(study, "uniform", order, 62)) > 1e-6
        assert abs(_run(study, "uniform", order, 62, "curve_position_error_m")) > 1e-4


# ---- elastic catenary, flat and inclined -------------------------------------------------------------

def test_flat_p2_with_40_elements_meets_1e_6(catenary):
    target = catenary["target"]
    assert target["met"], target  # measured 9.0e-7 on the fitted mesh
    assert abs(target["P2x40_flat_by_mesh"]["uniform"]) > 1e-4  # 1.1e-3 with the touchdown inside an element


def test_flat_penetration_at_the_chosen_stiffness_is_negligible(catenary):
    table = catenary["cases"]["flat"]["stiffness_table"]
    used = [r for r in table if r["stiffness"] == catenary["cases"]["flat"]["stiffness"]][0]
    assert abs(used["tension_effect"]) < 1e-8  # 1.6e-9 at G_K = 3e11 N/m^3
    assert used["roundoff_force_per_weight"] < 1e-4  # 1.9e-6 w: Newton's residual can reach 1e-7


@pytest.mark.parametrize("case", ["flat", "inclined"])
def test_p2_and_p3_converge_at_high_order_with_the_touchdown_on_a_vertex(catenary, case):
    orders = catenary["cases"][case]["orders"]
    # 10 -> 20 -> 40 elements; measured flat (inclined): P2 tension 3.84 (3.54), P3 6.25 (8.0),
    # P2 curve positions 2.79 (2.69), P3 3.61 (3.42)
    assert orders["exact-vertex P2"]["fairlead_tension_error"]["fitted"] > 3.3
    assert orders["exact-vertex P3"]["fairlead_tension_error"]["fitted"] > 4.5
    assert orders["exact-vertex P2"]["curve_position_error_m"]["fitted"] > 2.4
    assert orders["exact-vertex P3"]["curve_position_error_m"]["fitted"] > 3.2
    assert orders["uniform P1"]["curve_position_error_m"]["fitted"] == pytest.approx(2.0, abs=0.15)


def test_inclined_fitted_p3_with_20_elements_is_within_1e_7(catenary):
    study = catenary["cases"]["inclined"]
    assert abs(_run(study, "fitted", 3, 20, reference=None)) < 1e-7  # measured 1.2e-8
    assert abs(_run(study, "fitted", 2, 40, reference=None)) < 5e-6  # measured 2.1e-6
