"""MoorDyn's own polyester input in both codes under a smooth surge
(``validation/moordyn_parity``, fast variant: each code at the file's mesh; ~15 s).

Issue 36's bar: fairlead forces within 2 % RMS. The full study (validation/moordyn_parity/README.md)
has MoorDyn-C at the file's mesh 0.025 % RMS from its refined run and both of cablefem's meshes
within 0.015 % of it: a difference near 2 % is one of physics, not of resolution."""

import math

import pytest

pytest.importorskip("moordyn")

from validation.moordyn_parity import run as study  # noqa: E402


@pytest.fixture(scope="module")
def results():
    return study.run(fast=True)


@pytest.mark.parametrize("case", sorted(study.CASES))
def test_fairlead_force_agrees_with_moordyn_within_two_percent_rms(results, case):
    row = results[case]["cablefem, file"]
    assert row["rms"] < 0.02
    assert abs(row["mean"]) < 2e-3


def test_refined_moordyn_keeps_the_files_damping_in_newton_seconds():
    """BA = -1 is a critical ratio per segment, BA = zeta (L / N) sqrt(EA m): written as N s for a
    run at other segments, it is the file's (1400 m in 70 segments, EA 3.339e8 N, 52 kg/m)."""
    scene = study.scene_of("polyester")
    text = (study.INPUTS / study.CASES["polyester"]["file"]).read_text()
    row = next(r for r in study.absolute_damping(text, scene).splitlines() if r.startswith("Polyester_290mm"))
    assert float(row.split()[4]) == pytest.approx(1400.0 / 70 * math.sqrt(3.339e8 * 52.0), rel=1e-8)
