"""cablefem against MoorDyn-C and MoorPy on a crowfoot with a free junction (``validation/junction``,
fast variant: the dynamic case, surge 3 m and heave 1.5 m at 5 s, over its ramp and one period;
MoorDyn at 10 m segments and dtM 8e-4 s, cablefem 4/7/7 P2 elements and dt 0.02 s; ~20 s).

Tolerances, each measured (validation/junction/README.md):

- statics: cablefem's network statics match MoorPy's System to 1.1e-7 in every tension and 1e-5 m
  in the junction's position (P2, 8/14/14 elements): 1e-6 and 1e-4 m. MoorDyn's initial condition
  at 10 m segments is within 0.03 % of MoorPy (its lumped masses at 10 m): 0.1 %, 0.05 m.
- dynamics: converged (cablefem 32/56/56 P2 elements, dt 0.005 s; MoorDyn 2.5 m, dtM 1e-4 s) the
  codes agree to 0.1-0.3 % RMS of the mean tension. At the fast settings: fairlead and anchors
  1.06-1.07 % RMS and < 0.1 % in the mean, the junction 0.72 % of its RMS excursion (1.7 cm of
  2.4 m): the issue's target, 2 % RMS, and 0.5 % in the mean, 2 % of the excursion. The clump
  without its added mass or drag, or 10 % heavier, moves the tensions by more
  (README, "Switches").
"""

import filecmp

import pytest

pytest.importorskip("moordyn")
pytest.importorskip("moorpy")

from validation.junction import run as junction  # noqa: E402


@pytest.fixture(scope="module")
def results():
    return junction.run(fast=True, log=lambda line: None)


def test_the_committed_inputs_are_what_the_script_writes(tmp_path):
    dat, tomls = junction.write_inputs(tmp_path)
    for path in [dat, *tomls.values()]:
        assert filecmp.cmp(path, junction.HERE / "inputs" / path.name, shallow=False), path.name


def test_statics_match_moorpy(results):
    statics = results["statics"]
    assert max(abs(row["cablefem_rel"]) for row in statics["rows"]) < 1e-6
    assert statics["junction_cablefem_error_m"] < 1e-4
    mp = {row["quantity"]: row["moorpy_N"] for row in statics["rows"]}
    ic = results["cases"]["dynamic"]["initial_conditions"][0]
    for name in junction.QUANTITIES:
        assert abs(ic[f"{name}_N"] / mp[name] - 1.0) < 1e-3, name
    assert abs(ic["junction_m"] - statics["junction_moorpy_m"]).max() < 0.05


def test_dynamics_agree_with_moordyn(results):
    comparison = results["cases"]["dynamic"]["comparison"]
    for name in junction.QUANTITIES:
        assert comparison[name]["rms"] < 0.02, name
        assert abs(comparison[name]["mean"]) < 5e-3, name
    assert comparison["junction"]["rms"] < 0.02
    assert comparison["junction"]["excursion_rms_m"] > 1.0  # the junction moves
