"""Linear waves (issue 35): kinematics against closed forms, the compiled face, irregular seas' spectra,
the dispersion relation, elevation records, the ramp, and the scene's [waves] table."""

import numpy as np
import pytest

from bad_input import BASE_TOML, assert_refused, edit, toml_case
from cablefem.errors import InputError
from cablefem.io import load_scene
from cablefem.waves import Sea, wave_number
from cablefem.waves.series import from_record
from cablefem.waves.spectra import irregular
from verification.waves import run as study


@pytest.fixture(scope="module")
def results():
    return study.run(fast=True)


def test_kinematics_match_the_closed_forms_above_and_below_the_mean_level(results):
    rows = results["closed_forms"]
    assert {row["stretching"] for row in rows} == {"wheeler", "vertical", "none"}
    assert all(row["above_mean_level"] > 0 for row in rows)  # points in the crests were checked
    # the target is 1e-4; both sides evaluate the same formulas, so round-off is what remains
    assert max(max(row["eta"], row["velocity"], row["acceleration"]) for row in rows) < 1e-11


def test_compiled_kinematics_equal_the_numpy_face_and_their_gradients_are_exact(results):
    assert results["faces"]["compiled_vs_numpy"] < 1e-13
    # central differences of step 1e-4 h: truncation ~ (k step)^2 ~ 1e-6 relative
    assert results["faces"]["gradient_vs_central_difference"] < 1e-5


def test_irregular_records_hold_m0_within_2_percent_and_peak_at_tp(results):
    spectrum = results["spectrum"]
    assert abs(spectrum["m0_error"]) < 0.02  # the target, over 20 seeds of an hour each
    assert abs(spectrum["peak_error"]) < spectrum["resolution"]  # within the smoothing window


def test_cos_2s_spreading_gives_the_mean_cosine_of_the_law(results):
    for row in results["spreading"]:  # 2000 headings: sampling error ~ 1 / sqrt(2000) of the spread
        assert abs(row["error"]) < 0.01


def test_dispersion_relation_is_solved_to_round_off_from_shallow_to_deep_water():
    omega = np.array([1e-3, 0.05, 0.3, 1.0, 3.0, 10.0])
    for depth in (2.0, 50.0, 3000.0):
        k = wave_number(omega, depth, 9.81)
        assert np.allclose(9.81 * k * np.tanh(k * depth), omega ** 2, rtol=1e-13, atol=0.0)
    assert wave_number(0.0, 50.0, 9.81) == 0.0


def test_components_of_one_realisation_hold_m0_exactly():
    sea = irregular(4.0, 9.0, 80.0, components=150, seed=7)
    assert sea.spectrum_moments()[0] == pytest.approx(1.0, rel=1e-12)  # Hs^2 / 16
    assert sea.count == 150 and len(set(sea.omega)) == 150
    again = irregular(4.0, 9.0, 80.0, components=150, seed=7)
    assert again == sea  # a seed repeats its sea


def test_an_elevation_record_is_reproduced_at_its_samples_and_repeats():
    t = 5.0 + 0.4 * np.arange(300)
    eta = 1.2 * np.cos(0.6 * t + 0.2) + 0.4 * np.sin(1.7 * t - 1.0) + 0.1
    sea = from_record(t, eta, 60.0)
    mean = dict(sea.state)["mean_removed"]
    assert np.abs(sea.elevation(0.0, 0.0, t) + mean - eta).max() < 1e-12
    period = dict(sea.state)["record_period"]
    assert np.abs(sea.elevation(0.0, 0.0, t + period) - sea.elevation(0.0, 0.0, t)).max() < 1e-12


def test_the_ramp_scales_the_waves_and_the_acceleration_is_the_velocitys_rate():
    sea = Sea.regular(2.0, 9.0, 0.3, 0.0, 70.0, stretching="vertical", ramp=30.0)
    still = Sea.regular(2.0, 9.0, 0.3, 0.0, 70.0, stretching="vertical")
    points = np.array([[10.0, 5.0, -20.0], [-40.0, 0.0, -3.0]])
    for t in (0.0, 12.0, 31.0):
        R = np.clip(t / 30.0, 0, 1) ** 2 * (3 - 2 * np.clip(t / 30.0, 0, 1))
        assert np.allclose(sea.kinematics(points, t).velocity, R * still.kinematics(points, t).velocity, atol=1e-14)
    h = 1e-5
    for t in (7.0, 20.0):  # inside the ramp: a = R a + dR/dt u, the velocity's time derivative at fixed z
        rate = (sea.kinematics(points, t + h).velocity - sea.kinematics(points, t - h).velocity) / (2 * h)
        assert np.allclose(sea.kinematics(points, t).acceleration, rate, rtol=1e-7, atol=1e-9)


def test_a_line_above_the_surface_is_dry():
    sea = Sea.regular(1.0, 8.0, 0.0, 0.0, 50.0)
    kin = sea.kinematics(np.array([[0.0, 0.0, 0.9], [0.0, 0.0, 1.1], [0.0, 0.0, -0.5]]), 0.0)
    assert kin.wet.tolist() == [True, False, True]  # eta(0, 0, 0) = 1 m


WAVES = "[waves]\nkind = \"regular\"\namplitude = 2.0\nperiod = 10.0\ndirection = 30.0\n"


def test_a_toml_regular_sea_reads_its_keys_and_takes_the_depth_at_the_origin(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(BASE_TOML + WAVES + "phase = 90.0\nramp = 20.0\nstretching = \"none\"\n")
    sea = load_scene(str(path)).environment.waves
    assert (sea.amplitude, sea.depth, sea.stretching, sea.ramp) == ((2.0,), 150.0, "none", 20.0)
    assert sea.omega[0] == pytest.approx(2 * np.pi / 10) and sea.direction[0] == pytest.approx(np.pi / 6)
    assert sea.elevation(0.0, 0.0, 0.0) == pytest.approx(0.0, abs=1e-12)  # cos(90 deg)


def test_toml_components_and_elevation_kinds(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(BASE_TOML + "[waves]\nkind = \"components\"\namplitude = [1.0, 0.5]\nperiod = [10.0, 6.0]\n"
                    "direction = [0.0, 45.0]\ndepth = 120.0\n")
    sea = load_scene(str(path)).environment.waves
    assert sea.count == 2 and sea.depth == 120.0 and sea.phase == (0.0, 0.0)
    t = np.arange(0, 60, 0.5)
    (tmp_path / "eta.csv").write_text("t,eta\n" + "".join(f"{a},{np.cos(0.5 * a)}\n" for a in t))
    path.write_text(BASE_TOML + "[waves]\nkind = \"elevation\"\nfile = \"eta.csv\"\n")
    sea = load_scene(str(path)).environment.waves
    assert np.abs(sea.elevation(0, 0, t) + dict(sea.state)["mean_removed"] - np.cos(0.5 * t)).max() < 1e-12


BAD_WAVES = [
    ("kind = \"regular\"", "kind = \"swell\"", "waves.kind: unknown value 'swell'"),
    ("amplitude = 2.0\n", "amplitude = 2.0\nHs = 3.0\n", "waves.Hs: does not apply to waves kind 'regular'"),
    ("period = 10.0\n", "", "waves.period: missing required key"),
    ("amplitude = 2.0", "amplitude = -2.0", "waves.amplitude: must be >= 0"),
    ("amplitude = 2.0", "amplitude = 200.0", "troughs of 200 m would reach the seabed 150 m down"),
    ("direction = 30.0\n", "direction = 30.0\nstretching = \"linear\"\n", "waves.stretching: unknown value"),
    ("kind = \"regular\"\namplitude = 2.0", "kind = \"components\"\namplitude = [2.0, 1.0]",
     "waves.period: expected an array of numbers"),
    ("kind = \"regular\"\namplitude = 2.0\nperiod = 10.0\ndirection = 30.0", "kind = \"components\"\n"
     "amplitude = [2.0, 1.0]\nperiod = [10.0]", "waves.period: expected 2 values, one per amplitude"),
    ("kind = \"regular\"\namplitude = 2.0\nperiod = 10.0\n", "kind = \"irregular\"\nHs = 4.0\nTp = 9.0\n"
     "spectrum = \"pierson-moskowitz\"\ngamma = 2.0\n", "waves.gamma: applies to the JONSWAP spectrum only"),
    ("kind = \"regular\"\namplitude = 2.0\nperiod = 10.0\n", "kind = \"elevation\"\nfile = \"eta.csv\"\n",
     "waves.file: file not found"),
]


@pytest.mark.parametrize("old, new, reason", BAD_WAVES, ids=[case[2][:40] for case in BAD_WAVES])
def test_bad_waves_give_one_line_naming_the_key(tmp_path, capsys, old, new, reason):
    case = toml_case("waves", reason, text=edit(BASE_TOML + WAVES, {old: new}))
    assert_refused(case, tmp_path, capsys)


def test_an_elevation_file_whose_times_do_not_increase_is_refused_at_its_line(tmp_path, capsys):
    files = {"eta.csv": "0 0\n1 0.1\n1 0.2\n2 0.1\n3 0\n"}
    text = edit(BASE_TOML + WAVES, {"kind = \"regular\"\namplitude = 2.0\nperiod = 10.0\n":
                                    "kind = \"elevation\"\nfile = \"eta.csv\"\n"})
    assert_refused(toml_case("times", "eta.csv line 3: times must strictly increase", text=text, files=files),
                   tmp_path, capsys)


def test_a_sea_needs_water_below_the_origin():
    from cablefem.geometry import Plane
    from cablefem.io.waves import water_depth

    with pytest.raises(InputError, match="waves.depth"):
        water_depth(Plane([0.0, 0.0, 5.0], [0.1, 0.0, 1.0]))
