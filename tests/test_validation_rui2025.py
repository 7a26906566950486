"""rui2025 Sec. 4 (``validation/rui2025``, fast variant): the conventional model against the paper and
the catenary, Cases 1-3 against the paper's fairlead tensions and ordering, Case 3's padeye.

Tolerances: the conventional model and the frictionless catenary agree with the paper's 2437 and
2436 kN to 0.1 % (measured 0.01 and 0.02 %); the cases' fairlead tensions are held to the issue's
5 % (measured -0.2, +0.8, +1.2 %). Case 3's padeye tension misses the paper's 960 kN by far (measured
140 kN): the lying chain sinks to its bearing depth, so even a padeye on the mudline has a drop below
it whose straightening slides the lying chain and mobilises its friction (README, "Case 3's padeye");
the test holds the explanation: the chain next to the padeye has slid well beyond the friction's
elastic offset 1/k_t = d_b, and the catenary start, which mobilises nothing, leaves the padeye the
pull of the frictionless line (1451 kN), the paper's number in between.
"""

import pytest

from validation.rui2025 import run as study


@pytest.fixture(scope="module")
def results():
    return study.run(fast=True)


def test_the_conventional_model_is_the_papers_and_the_catenarys(results):
    conventional = results["conventional"]
    assert conventional["fairlead_tension"] == pytest.approx(2437e3, rel=1e-3)
    assert conventional["catenary_tension"] == pytest.approx(2436e3, rel=1e-3)
    assert conventional["fairlead_angle_deg"] == pytest.approx(56.4, abs=0.1)


def test_fairlead_tensions_of_the_three_cases_are_within_5_percent_and_ordered_as_the_papers(results):
    comparison = results["comparison"]
    for case in study.CASES:
        assert abs(comparison[case]["fairlead_tension"]["relative"]) < 0.05, case
    assert comparison["ordering_holds"]


def test_case3_padeye_miss_comes_from_the_friction_the_path_mobilised(results):
    case3, catenary = results["cases"]["case3"], results["case3_catenary"]
    assert case3["padeye_tension"] < 0.5 * 960e3 < 960e3 < catenary["padeye_tension"]
    assert case3["padeye_slip"] > 2.0 * study.D_B  # slid far beyond the elastic offset 1/k_t = d_b
    assert case3["resting_depth"] == pytest.approx(1.108, abs=1e-3)  # E_n d_b N_c su_gradient z = w


def test_cyclic_surge_after_pretension_relaxes_the_padeye_tension():
    # validation/rui2025/cyclic.py, 3 periods: the first full pull cuts the embedded chain up through
    # the clay, which keeps its trench, and the next pull gives the padeye less (measured -12.9 % and
    # then steady to 0.1 %, the fairlead's peak -2.4 %)
    from validation.rui2025 import cyclic

    results = cyclic.run(cycles=3)
    assert results["status"] == "completed"
    first, second = results["peaks"][1], results["peaks"][2]
    assert second["padeye_max"] < 0.95 * first["padeye_max"]
    assert abs(second["fairlead_max"] / first["fairlead_max"] - 1.0) < 0.05  # the same motion, the same pull
