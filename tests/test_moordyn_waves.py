"""MoorDyn-C's wave inputs (issue 35): WaveKin 7, 2 and 3 read from MoorDyn's own test files give the
kinematics MoorDyn-C gives through its API (``GetWavesKin``), a TOML that wraps a MoorDyn file may give
[waves] instead of the file's, and what stays unread is refused with one line."""

import os
import shutil

import numpy as np
import pytest

from bad_input import BASE_MOORDYN, Case, assert_refused, edit
from cablefem.io import load_scene
from validation.moordyn.peer import silenced_stdout

moordyn = pytest.importorskip("moordyn")
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "moordyn")


def moordyn_kinematics(path, points, times):
    """MoorDyn-C's (U, Ud, zeta) at points (n, 3) at each of ``times`` (stepping its system there), run
    from the file's folder as MoorDyn's own tests run; its output on file descriptor 1 discarded."""
    cwd = os.getcwd()
    try:
        with silenced_stdout():
            os.chdir(os.path.dirname(path))
            system = moordyn.Create(os.path.basename(path))
            n = moordyn.NCoupledDOF(system)
            moordyn.Init(system, [0.0] * n, [0.0] * n)
            waves, t, out = moordyn.GetWaves(system), 0.0, []
            for time in times:
                if time > t:
                    moordyn.Step(system, [0.0] * n, [0.0] * n, t, time - t)
                    t = time
                out.append([moordyn.GetWavesKin(waves, *point)[:3] for point in points])
            moordyn.Close(system)
    finally:
        os.chdir(cwd)
    return out


def test_wavekin_7_gives_moordyn_cs_kinematics():
    path = os.path.join(DATA, "wavekin_7", "wavekin_7.txt")
    sea = load_scene(path).environment.waves
    assert (sea.kind, sea.stretching, sea.depth) == ("MoorDyn WaveKin 7", "wheeler", 50.0)
    points = np.array([[-300.0, 0.0, -20.0], [-100.0, 1.0, -5.0], [0.0, 0.0, -1.0], [-50.0, 0.0, -45.0]])
    times = [0.0, 1.3, 7.7]
    for t, theirs in zip(times, moordyn_kinematics(path, points, times)):
        ours = sea.kinematics(points, t)
        for i, (U, Ud, zeta) in enumerate(theirs):
            # MoorDyn-C's wave numbers come from Newman's approximation (7 digits)
            assert ours.eta[i] == pytest.approx(zeta, abs=1e-7)
            assert np.allclose(ours.velocity[i], U, atol=1e-7) and np.allclose(ours.acceleration[i], Ud, atol=1e-7)


@pytest.mark.parametrize("name", ["wavekin_2.txt", "wavekin_3.txt"])
def test_wavekin_2_and_3_equal_moordyn_cs_grid_at_its_nodes(name):
    """At t = 0 and a node of water_grid.txt in x and y MoorDyn-C's interpolation is exact there, but for
    the stretched height between its z nodes: its kinematics are the same sum of components. These files
    add a Currents 1 profile, which MoorDyn-C adds to its wave grid (UnifyCurrentGrid) and so looks up
    at the stretched height too."""
    path = os.path.join(DATA, "wavekin_2", name)
    scene = load_scene(path)
    sea, profile = scene.environment.waves, scene.environment.current_profile
    points = np.array([[-300.0, 0.0, -20.0], [-100.0, 1.0, -5.0], [0.0, 0.0, -1.0], [-50.0, 0.0, -45.0]])
    (theirs,) = moordyn_kinematics(path, points, [0.0])
    ours = sea.kinematics(points, 0.0)
    current = profile.at(ours.stretched)[0].T
    for i, (U, Ud, zeta) in enumerate(theirs):
        assert ours.eta[i] == pytest.approx(zeta, abs=1e-6)
        # the stretched height falls between the grid's 1 m z nodes: MoorDyn-C interpolates linearly in z
        assert np.allclose(ours.velocity[i] + current[i], U, atol=1e-3 * np.abs(U).max())
        assert np.allclose(ours.acceleration[i], Ud, atol=1e-3 * np.abs(Ud).max())


def test_wavekin_1_is_still_water_as_moordyn_c_runs_the_file_alone(tmp_path):
    """WaveKin 1 takes the kinematics through MoorDyn-C's API; run from the file alone MoorDyn-C's water
    stays still (its own kinematics at a point, before and after a step), and cablefem reads the file as
    the same file with WaveKin 0, saying so in a note."""
    path = os.path.join(DATA, "wavekin_wave_1.txt")
    points = np.array([[200.0, 0.0, -10.0], [0.0, 0.0, -1.0]])
    for kinematics in moordyn_kinematics(path, points, [0.0, 1.0]):
        assert np.all(np.abs(np.array([np.concatenate((U, Ud, [zeta])) for U, Ud, zeta in kinematics])) == 0.0)
    still = tmp_path / "still.txt"
    with open(path) as source:
        still.write_text(source.read().replace("1             WaveKin", "0             WaveKin"))
    ours, theirs = load_scene(path), load_scene(str(still))
    assert ours.environment.waves is None
    assert any(note.startswith("WaveKin 1: ") and "still water" in note for note in ours.notes)
    assert repr((ours.lines, ours.environment)) == repr((theirs.lines, theirs.environment))


def test_a_toml_wrapping_a_moordyn_file_may_give_waves_instead(tmp_path):
    source = os.path.join(DATA, "wavekin_7", "wavekin_7.txt")
    shutil.copy(source, tmp_path / "lines.txt")  # without its wave_frequencies.txt
    scene = tmp_path / "scene.toml"
    scene.write_text('[moordyn]\nfile = "lines.txt"\n[waves]\nkind = "regular"\namplitude = 1.0\nperiod = 8.0\n')
    loaded = load_scene(str(scene))
    assert loaded.environment.waves.kind == "regular" and loaded.environment.waves.depth == 50.0
    assert any("replaced by the TOML's [waves]" in note for note in loaded.notes)


BAD = [
    ("4   WaveKin", {}, "line 22: OPTIONS.WaveKin", "wave kinematics other than WaveKin 0, 1, 2, 3 and 7"),
    ("5   WaveKin", {}, "line 22: OPTIONS.WaveKin", "wave kinematics other than WaveKin 0, 1, 2, 3 and 7"),
    ("7   WaveKin", {}, "line 22: OPTIONS.WaveKin (wave_frequencies.txt beside the file)", "file not found"),
    ("7   WaveKin", {"wave_frequencies.txt": "0.1 0.0 0.0\n0.3 1.0 0.0\n"}, "line 22: OPTIONS.WaveKin",
     "wave_frequencies.txt: the first frequency must be 0 rad/s"),
    ("7   WaveKin", {"wave_frequencies.txt": "0.0 0.0 0.0\n0.3 1.0\n"}, "line 22: OPTIONS.WaveKin",
     "wave_frequencies.txt line 2: expected omega re im [beta]"),
    ("7   WaveKin", {"wave_frequencies.txt": "0.0 0.0 0.0\n0.3 1.0 0.0 45\n"}, "line 22: OPTIONS.WaveKin",
     "wave_frequencies.txt line 2: a direction beyond +-2 pi (45): MoorDyn-C takes radians"),
    ("2   WaveKin", {"wave_frequencies.txt": "0.0 0.0 0.0\n0.3 1.0 0.0\n"}, "line 22: OPTIONS.WaveKin "
     "(water_grid.txt beside the file)", "file not found"),
    ("3   WaveKin", {"wave_elevation.txt": "0 0\n1 0.1\n", "water_grid.txt": "a\nb\nc\n1\n0 1\n0\n\n3\n"},
     "line 22: OPTIONS.WaveKin", "water_grid.txt: MoorDyn-C needs 9 rows"),
]


@pytest.mark.parametrize("option, files, key, reason", BAD, ids=[case[3][:30] for case in BAD])
def test_bad_moordyn_waves_give_one_line(tmp_path, capsys, option, files, key, reason):
    text = edit(BASE_MOORDYN, {"850.0     WtrDpth": "850.0     WtrDpth\n" + option})
    case = Case("waves", f"{key}: {reason}", files={"lines.dat": text, **files}, argv=("static", "{tmp}/lines.dat"),
                file="lines.dat")
    assert_refused(case, tmp_path, capsys)


def test_a_seafloor_file_is_found_from_the_working_directory_first_then_beside_the_file(tmp_path, monkeypatch):
    """MoorDyn-C opens a SeafloorFile by the name as given, from the working directory (its tests name
    theirs from their Mooring folder); cablefem too, and otherwise beside the MoorDyn file."""
    from bad_input import GRID_C

    text = edit(BASE_MOORDYN, {"850.0     WtrDpth": "Mooring/bathy.txt SeafloorFile"})
    beside = tmp_path / "run" / "Mooring"
    beside.mkdir(parents=True)
    (beside / "lines.dat").write_text(text)
    (beside / "Mooring").mkdir()
    deep = GRID_C.replace("-150\n", "-850\n")  # the file's lines are in 850 m of water
    (beside / "Mooring" / "bathy.txt").write_text(deep)  # beside the file: Mooring/bathy.txt
    monkeypatch.chdir(tmp_path)
    assert load_scene(str(beside / "lines.dat")).seabed.depth == 850.0
    (tmp_path / "Mooring").mkdir()  # from the working directory: Mooring/bathy.txt there wins
    (tmp_path / "Mooring" / "bathy.txt").write_text(GRID_C.replace("-150\n", "-860\n"))
    assert load_scene(str(beside / "lines.dat")).seabed.depth == 860.0
