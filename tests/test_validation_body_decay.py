"""validation/body_decay in its fast variant: a free body's heave decay against MoorDyn-C (issue 36's
target: the period within 1 %, the logarithmic decrement within 5 %), each side on a converged
discretisation (the study's README: MoorDyn-C on 40 segments per line, cablefem at 0.025 s)."""

import pytest

pytest.importorskip("moordyn")


def test_a_free_body_s_heave_decays_as_in_moordyn_c(tmp_path):
    from validation.body_decay.run import main

    row, = main(["--fast", "--out", str(tmp_path)])
    assert abs(row["period_difference"]) < 0.01
    assert abs(row["decrement_difference"]) < 0.05
