"""validation/moordyn_failure in its fast variant: MoorDyn-C 2.7 reads a FAILURE section but its line
does not let go (its run is the intact run), where cablefem's released anchor end swings away."""

import pytest

pytest.importorskip("moordyn")


def test_moordyn_c_does_not_let_go_where_cablefem_does(tmp_path):
    """5 s after the anchor lets go: MoorDyn-C's forces equal its run without the failure exactly and
    its anchor end has not moved; cablefem's anchor end has moved more than 1 m (the chain swinging to
    hang below its fairlead, 4 m aside), its fairlead's horizontal pull smaller than MoorDyn-C's."""
    from validation.moordyn_failure.run import main

    results = main(["--fast", "--out", str(tmp_path)])
    assert results["moordyn_failing_minus_intact_N"] == 0.0
    assert results["moordyn_anchor_moved_m"] == 0.0
    assert results["cablefem_anchor_moved_m"] > 1.0
    assert abs(results["cablefem_fairlead_fx_N"]) < abs(results["moordyn_fairlead_fx_N"])
