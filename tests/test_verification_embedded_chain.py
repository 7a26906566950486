"""The embedded chain against Neubecker & Randolph's equations (``verification/embedded_chain``, fast
variant, P1 and P2): every point fully mobilised, the padeye force within 1 % at P1 x 16 and P2 x 8, and the
errors falling at the element order's rate.

Tolerances: the reference is integrated to rtol 1e-13, far below what is asserted; the observed orders
are asserted within 0.3 of 2p (the end force of p-th order elements with the axial term's reduced
integration converges at 2p: measured 1.98 and 4.08); the closed form's errors (+6.9 % tension,
+5.9 % angle: it drops the weight, takes sin(theta) ~ theta and the tension as T_a) are asserted
between 3 and 10 %: the approximation is that coarse, and no coarser.
"""

import numpy as np
import pytest

from verification.embedded_chain import run as study


@pytest.fixture(scope="module")
def results():
    return study.run(fast=True)


def test_the_reference_is_an_inverse_catenary_that_reaches_the_mudline_flatter_and_pulled_harder(results):
    ref = results["reference"]
    assert 0.0 < ref["theta0"] < study.PADEYE_ANGLE and ref["T0"] > study.PADEYE_TENSION
    assert ref["length"] > np.hypot(ref["x"], study.PADEYE_DEPTH)  # curved: longer than its chord


def test_every_point_is_fully_mobilised_in_the_directions_the_equations_assume(results):
    for row in results["rows"]:
        assert row["mobilised_along"] == 1.0 and row["mobilised_across"] == 1.0


def test_padeye_tension_and_angle_are_within_1_percent_and_converge_at_order_2p(results):
    rows = {(r["order"], r["elements"]): r for r in results["rows"]}
    for key in ((1, 16), (2, 8)):
        assert abs(rows[key]["tension_error"]) < 1e-2 and abs(rows[key]["angle_error"]) < 1e-2
    assert abs(rows[(2, 8)]["tension_error"]) < 2e-4  # measured 9.0e-5
    for order, observed in results["observed_orders"].items():  # P1 and P2 (P3: 6.6 and 7.1, the full run)
        assert observed["tension_error"] == pytest.approx(2 * order, abs=0.3)
        assert observed["angle_error"] == pytest.approx(2 * order, abs=0.3)


def test_the_approximate_closed_form_is_off_by_several_percent(results):
    closed = results["closed_form"]
    assert 0.03 < closed["tension_error"] < 0.10 and 0.03 < closed["angle_error"] < 0.10
    assert closed["mu"] == pytest.approx(8.0 / (2.5 * 7.6), rel=1e-12)
