"""cablefem against MoorDyn-C on the same MoorDyn input files (``validation/moordyn``, fast variant:
the flume line at the file's 40 segments / 40 P1 elements, the housner2022 flat and up-slope systems
at the files' 25 m segments, cablefem dt 0.05 s, one period after the ramp; ~25 s in all).

Tolerances: the converged comparison (validation/moordyn/README.md) plus what the coarse settings
of the fast variant add, each measured:

- flat flume, quasi-static motion: at the full settings (160 segments/elements) the codes differ
  by 0.00 % in the mean and 0.05 % in the peak. At the fast settings the mean still agrees to
  0.001 % (the coarse touchdown errs alike in both), but MoorDyn's 40-segment peak is 1 % above
  its 160-segment one while cablefem's moves by 0.03 %: mean 0.2 %, peak 2 % (measured +0.01 % and
  -1.03 %).
- flat semi-taut system: at 12.5 m segments the codes agree within 0.03 % in the mean and 0.17 %
  in the peak; at the files' 25 m both are ~1.4 % low in pretension and their peaks part by up to
  2.6 % (measured: means +0.12, +0.25, +0.02 %, peaks -1.68, -2.56, -0.38 %, RMS 1.1, 2.0, 0.4 %):
  mean 0.5 %, peak 3.5 %, RMS 2.5 %. Reading CdAx without its pi (peak -18 %), a 20 % error in the
  normal drag (peak -4.4 %) or a 10 % error in EA (peak -4.3 %) fails it.
- up-slope system with MoorDyn's vertical contact switched on in cablefem: lines 2 and 3 agree
  within 0.1 % in the mean and 0.5 % in the peak (measured -0.01 %/-0.46 % and -0.02 %/-0.20 %),
  where cablefem's own contact along the seabed normal is 8-9 % above: mean 0.5 %, peak 1.5 %,
  and the unswitched difference must exceed 5 % (the physics the switch removes). Line 1, the
  slack line up the slope (67 kN mean against its neighbours' 0.58 MN), agrees within 0.1 % in
  the mean and 0.2 % in the peak either way (its lying chain cannot slide down a slope that rises
  towards its anchor): mean 1 %, peak 2 %.
- static pretension: MoorDyn's initial condition is its own equilibrium (the force moves by
  1e-5 over 5 s with the fairlead held; tolerance 1e-4, the threshold of its IC solver is 1e-5),
  and it is within 1.5e-3 of MoorPy's catenary: MoorPy's seabed is rigid, MoorDyn's kBot = 3e5
  N/m^3 lets the line sink 6.8 cm, which raises the converged tension by 8e-4 (cablefem, 640 P1
  elements, against a 1e4 times stiffer seabed); measured -8.2e-4 at 40 segments, +1.0e-3 at 160.
"""

import filecmp
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("moordyn")
pytest.importorskip("moorpy")

from cablefem.io import load_scene  # noqa: E402

from validation.moordyn import peer  # noqa: E402
from validation.moordyn import run as study  # noqa: E402

COMMITTED = Path(study.__file__).resolve().parent / "inputs"


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    out = tmp_path_factory.mktemp("moordyn")
    found, _ = study.run(fast=True, out_dir=out, log=lambda *args: None)
    found["out"] = out
    return found


def test_flat_quasi_static_flume_mean_and_peak_tension_agree_with_moordyn(results):
    d = results["cases"]["flume-quasi-static"]["differences"][0]
    assert d["reference_mean_N"] == pytest.approx(2.99e6, rel=0.02)  # the 15 m drift case, not a rest state
    assert abs(d["mean"]) <= 2e-3
    assert abs(d["peak"]) <= 2e-2


def test_flat_semi_taut_system_agrees_with_moordyn(results):
    case = results["cases"]["housner-flat"]
    for k, d in enumerate(case["differences"]):
        assert d["reference_mean_N"] == pytest.approx(0.20e6, rel=0.05), case["lines"][k]  # 200 kN pretension
        assert abs(d["mean"]) <= 5e-3, case["lines"][k]
        assert abs(d["peak"]) <= 3.5e-2, case["lines"][k]
        assert d["rms"] <= 2.5e-2, case["lines"][k]


def test_upslope_agrees_with_moordyn_once_cablefem_contact_is_vertical(results):
    case = results["cases"]["housner-upslope"]
    switched = case["switches"]["vertical_contact"]["differences"]
    for k in (1, 2):  # lines 2 and 3: anchors down the slope, chain lying on it
        assert abs(switched[k]["mean"]) <= 5e-3, case["lines"][k]
        assert abs(switched[k]["peak"]) <= 1.5e-2, case["lines"][k]
        assert case["differences"][k]["mean"] > 5e-2, case["lines"][k]  # along d_P the chain pulls more
    assert abs(switched[0]["mean"]) <= 1e-2
    assert abs(switched[0]["peak"]) <= 2e-2


def test_peer_static_pretension_is_moordyn_equilibrium_near_moorpy_catenary(results):
    statics = results["statics"]
    assert statics["moordyn_hold_5s_change"] <= 1e-4
    assert abs(statics["moordyn_vs_moorpy"]) <= 1.5e-3


def test_both_codes_read_the_one_moordyn_file(results):
    inputs = results["out"] / "inputs"
    scene = load_scene(inputs / "flume-quasi-static.toml")
    direct = load_scene(inputs / "flume_flat.dat")
    assert len(scene.lines) == 1 and scene.lines[0].unstretched_length == pytest.approx(635.0)
    assert np.allclose(scene.lines[0].anchor, [-595.0, 0.0, -100.0])
    assert scene.contact == direct.contact and scene.friction == direct.friction
    assert scene.motion.period == pytest.approx(17.0) and scene.motion.offset[0] == pytest.approx(15.0)
    upslope = load_scene(inputs / "housner-upslope.toml")
    assert [line.name for line in upslope.lines] == ["line1+4", "line2+5", "line3+6"]
    assert upslope.contact.stiffness == pytest.approx(3.0e6)  # MoorDyn's default kBot, no kBot in the file
    assert upslope.seabed.kind == "plane"  # the 12.5 % grid is planar: point-to-plane projection


def test_committed_inputs_are_what_the_script_writes(results):
    written = sorted(p.name for p in (results["out"] / "inputs").iterdir())
    committed = sorted(p.name for p in COMMITTED.iterdir())
    assert written == committed
    match, mismatch, errors = filecmp.cmpfiles(results["out"] / "inputs", COMMITTED, written, shallow=False)
    assert not mismatch and not errors


def test_peer_rewrites_segments_time_step_and_options_and_keeps_a_closing_header():
    text = (COMMITTED / "housner_upslope.dat").read_text()
    new = peer.rewrite_input(text, dtM=2.5e-4, segments={"1": 7}, options={"kBot": 1e7, "dtIC": 3.0},
                             base_dir=str(COMMITTED))
    assert peer.line_segments(new) == {"1": 7, "2": 20, "3": 20, "4": 40, "5": 40, "6": 40}
    assert float(peer.option_value(new, "dtM")) == 2.5e-4
    assert float(peer.option_value(new, "kBot")) == 1e7 and float(peer.option_value(new, "dtIC")) == 3.0
    assert Path(peer.option_value(new, "SeafloorFile")).is_absolute()
    lines = new.splitlines()
    options_end = max(i for i, row in enumerate(lines) if "dtIC" in row or "kBot" in row)
    assert any("---" in row for row in lines[options_end + 1:])  # MoorDyn 2.7 crashes without it
    ids, points = peer.coupled_points(COMMITTED / "housner_upslope.dat")
    assert ids == [4, 5, 6] and np.allclose(points[:, 2], -14.0)
    assert peer.line_ends(text)[4] == [(4, "B")]


def test_peer_moves_coupled_points_along_the_motion_continuously(tmp_path):
    # secant coupling: MoorDyn's point is at the motion's position at every coupling time
    path = COMMITTED / "flume_flat.dat"
    motion = lambda t: (np.array([[0.2 * np.sin(t), 0.0, 0.0]]), np.array([[0.2 * np.cos(t), 0.0, 0.0]]))  # noqa: E731
    result = peer.run_moordyn(path, motion, duration=0.5, dt_out=0.1, dtM=4e-4,
                              options={"threshIC": 1e-3}, ic_dtM=4e-4)
    assert result["forces"].shape == (6, 1, 3) and result["end_mass"].shape == (6, 1, 3, 3)
    assert np.allclose(result["positions"][:, 0, 0], 0.2 * np.sin(result["t"]))
    assert np.all(result["forces"][:, 0, 0] < 0.0)  # the line pulls the fairlead towards the anchor
    # restarted from the state its initial-condition solve reached, MoorDyn repeats the run exactly
    again = peer.run_moordyn(path, motion, duration=0.5, dt_out=0.1, dtM=4e-4, options={"threshIC": 1e-3},
                             initial_state=result["initial_state"])
    assert np.array_equal(again["forces"], result["forces"])
