"""validation/body_decay in its fast variant: a free body's heave decay against MoorDyn-C (issue 36's
target: the period within 1 %, the logarithmic decrement within 5 %)."""

import pytest

pytest.importorskip("moordyn")


@pytest.mark.xfail(strict=True, reason="on main after the merge of the defaults by physics the fast variant's heave period "
                   "is 1.36 % from MoorDyn-C's (bound 1 %); on the file's own mesh (P1 x NumSegs) the decrement is "
                   "39 % off; the study's README numbers were measured before the body's last refactor")
def test_a_free_body_s_heave_decays_as_in_moordyn_c(tmp_path):
    from validation.body_decay.run import main

    row, = main(["--fast", "--out", str(tmp_path)])
    assert abs(row["period_difference"]) < 0.01
    assert abs(row["decrement_difference"]) < 0.05
