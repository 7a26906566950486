"""Currents that vary in time (issue 36, MoorDyn-C's Currents 2 and 5): the velocities MoorDyn-C gives
through its API for its own test inputs, the compiled face against the numpy face with exact gradients,
a run in a current held constant on a grid against the same run in that current as a steady profile,
and bad grids refused with one line."""

import os
import shutil
from dataclasses import replace

import numpy as np
import pytest

from bad_input import Case, assert_refused
from cablefem.errors import InputError
from cablefem.io import load_scene
from cablefem.io.currents import read_current_grid
from cablefem.waves import Sea
from cablefem.waves.compiled import water_at, water_of
from test_moordyn_waves import moordyn_kinematics

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "moordyn")
DYNAMIC = os.path.join(DATA, "wavekin_3", "test_dynamic_currents.txt")
FOUR_D = os.path.join(DATA, "wavekin_4", "hanging_lines.txt")


def velocities(path, points, times):
    """MoorDyn-C's current velocity (len(times), n, 3) at points (n, 3)."""
    return np.array([[U for U, _, _ in row] for row in moordyn_kinematics(path, points, times)])


def test_currents_2_gives_moordyn_cs_velocities_inside_beyond_and_after_its_record(tmp_path):
    """Heights inside the profile, above and below it (held), and times inside the record, in its last
    interval (the first sample's velocity, MoorDyn-C's wrap) and after it (the record repeats). The
    file's record cut to its first 6 s, so that MoorDyn-C steps little to get past it."""
    scene = load_scene(DYNAMIC)
    sea = scene.environment.waves
    assert sea.count == 0 and sea.current.velocity.shape[:4] == (1, 1, 42, 60) and sea.current.dt == 1.0
    assert any(note.startswith("Currents 2: a current varying in time") for note in scene.notes)
    shutil.copy(DYNAMIC, tmp_path / "line.txt")
    rows = open(os.path.join(os.path.dirname(DYNAMIC), "current_profile_dynamic.txt")).read().splitlines()
    (tmp_path / "current_profile_dynamic.txt").write_text("\n".join(rows[:12]) + "\n")
    path = str(tmp_path / "line.txt")
    sea = load_scene(path).environment.waves
    assert sea.current.velocity.shape[3] == 6
    points = np.array([[0.0, 0.0, -40.5], [10.0, 3.0, -20.2], [0.0, 0.0, -0.5], [0.0, 0.0, 5.0], [0.0, 0.0, -100.0]])
    times = [0.0, 0.7, 3.3, 5.5, 7.2]
    theirs = velocities(path, points, times)
    for t, at_t in zip(times, theirs):
        ours = sea.kinematics(points, t)
        assert np.abs(ours.velocity - at_t).max() < 1e-9 * max(1.0, np.abs(at_t).max())
        assert np.all(ours.acceleration == 0.0)
    assert np.abs(theirs[2]).max() > 0.1 and np.allclose(theirs[3], theirs[0])  # it flows, and wraps


def test_currents_5_gives_moordyn_cs_velocities_but_for_the_grid_point_moordyn_c_skips():
    """MoorDyn-C reads current_profile_4d.txt's rows from its seventh line, one past the first row, and
    leaves that grid point's velocity zero: with it zeroed here the two agree everywhere; as read, they
    agree away from the cells around that point."""
    sea = load_scene(FOUR_D).environment.waves
    grid = sea.current
    points = np.array([[-45.0, -1.0, -29.5], [12.5, 0.3, -10.2], [0.0, 0.0, 2.0], [60.0, 5.0, -40.0],
                       [-49.0, -1.9, -29.9], [-40.0, -2.0, -20.0]])
    near = np.array([True, False, False, False, True, False])  # in a cell around (x0, y0, z0)
    skipped = grid.velocity.copy()
    skipped[0, 0, 0, 0] = 0.0
    as_moordyn = replace(sea, current=replace(grid, velocity=skipped))
    times = [0.0, 7.9, 14.0]
    for t, theirs in zip(times, velocities(FOUR_D, points, times)):
        scale = np.abs(theirs).max()
        assert np.abs(as_moordyn.kinematics(points, t).velocity - theirs).max() < 1e-9 * scale
        ours = sea.kinematics(points, t).velocity
        assert np.abs(ours[~near] - theirs[~near]).max() < 1e-9 * scale
        assert np.abs(ours[near] - theirs[near]).max() > 0.1  # the skipped row
    # the grid as the file writes it: ux = 0.1 x + 0.1 t (make_4d_currents.py)
    assert sea.kinematics(np.array([[20.0, 0.0, -10.0]]), 10.0).velocity[0, 0] == pytest.approx(3.0, abs=1e-12)


def test_waves_and_a_4d_current_add_as_moordyn_c_adds_them_on_its_wave_grid():
    """wavekin_2_curr5.txt: WaveKin 2 and Currents 5. MoorDyn-C adds the current to its wave grid and
    interpolates both there (at the stretched height); cablefem sums the components at the point and adds
    the current at the point's own height. At the wave grid's nodes, away from the skipped grid point,
    the two agree to MoorDyn-C's interpolation in z between 1 m nodes."""
    path = os.path.join(DATA, "wavekin_2", "wavekin_2_curr5.txt")
    sea = load_scene(path).environment.waves
    assert sea.count > 0 and sea.current is not None
    points = np.array([[-300.0, 0.0, -20.0], [-100.0, 1.0, -5.0], [0.0, 0.0, -1.0], [20.0, 0.0, -10.0]])
    (theirs,) = velocities(path, points, [0.0])
    ours = sea.kinematics(points, 0.0).velocity
    assert np.allclose(ours, theirs, atol=1e-3 * np.abs(theirs).max())
    assert np.abs(sea.current.at(points, 0.0)[0]).max() > 1.0  # the current is a large part of it


def test_the_compiled_water_equals_the_numpy_face_and_its_gradient_is_exact():
    """A 4D current under a ramped regular wave: velocity and gradient of the compiled face against the
    numpy face, and the gradient against central differences inside a grid cell."""
    grid = load_scene(FOUR_D).environment.waves.current
    sea = replace(Sea.regular(0.5, 7.0, direction=0.3, depth=40.0, ramp=5.0), current=grid)
    water = water_of(sea)
    u, a, du, da = np.zeros(3), np.zeros(3), np.zeros((3, 3)), np.zeros((3, 3))
    worst, gradient = 0.0, 0.0
    for point in ([-45.3, -1.1, -29.4], [12.6, 0.35, -10.2], [33.0, 1.9, -3.3], [70.0, 3.0, -35.0]):
        for t in (0.0, 2.5, 8.1, 31.0):
            r = np.array(point)
            water_at(water, r, t, u, a, du, da, True)
            K = sea.kinematics(r[None], t, gradients=True)
            worst = max(worst, np.abs(u - K.velocity[0]).max(), np.abs(a - K.acceleration[0]).max(),
                        np.abs(du - K.velocity_gradient[0]).max(), np.abs(da - K.acceleration_gradient[0]).max())
            step = 1e-5
            for j in range(3):
                e = np.eye(3)[j] * step
                central = (sea.kinematics((r + e)[None], t).velocity[0] - sea.kinematics((r - e)[None], t).velocity[0])
                gradient = max(gradient, np.abs(central / (2 * step) - K.velocity_gradient[0][:, j]).max())
    assert worst < 1e-12
    assert gradient < 1e-5


def _flume(tmp_path, currents, profile_name, profile):
    """The WaveKin 7 test file's line in still water with ``Currents currents`` and ``profile`` written as
    ``profile_name`` beside it."""
    text = open(os.path.join(DATA, "wavekin_7", "wavekin_7.txt")).read()
    folder = tmp_path / f"currents_{currents}"
    folder.mkdir()
    text = text.replace("7             WaveKin", "0             WaveKin")
    lines = text.splitlines()
    at = next(i for i, row in enumerate(lines) if "WaveKin" in row)
    lines.insert(at + 1, f"{currents}             Currents")
    (folder / "line.txt").write_text("\n".join(lines) + "\n")
    (folder / profile_name).write_text(profile)
    return str(folder / "line.txt")


def test_a_run_in_a_grid_current_held_constant_equals_the_run_in_that_steady_profile(tmp_path):
    """The same current two ways: Currents 1 (a steady profile: the drag and added-mass loads) and
    Currents 2 with that profile at every time (the Morison load on the current's grid). The lines'
    tensions agree to round-off over a run, compiled, and the numpy face gives the compiled one's."""
    from cablefem.runs.run import run_scene

    heights = [-50.0, -30.0, -10.0, 0.0]
    speeds = [0.2, 0.5, 0.9, 1.0]
    steady = "a\nb\nc\n" + "".join(f"{z} {u} 0.1 0.0\n" for z, u in zip(heights, speeds))
    row = " ".join(str(u) for u in speeds) + " " + " ".join("0.1" for _ in speeds)
    dynamic = "a\nb\nc\nd\n" + " ".join(str(z) for z in heights) + "\n\n" + "".join(
        f"{t} {row}\n" for t in (0.0, 5.0, 10.0))
    tensions = []
    for currents, name, text in ((1, "current_profile.txt", steady), (2, "current_profile_dynamic.txt", dynamic)):
        scene = load_scene(_flume(tmp_path, currents, name, text))
        out = tmp_path / f"out_{currents}"
        run_scene(scene, str(out), duration=4.0, dt=0.05)
        tensions.append(np.loadtxt(out / "tensions.csv", delimiter=",", skiprows=1))
    profile, grid = tensions
    assert profile.shape == grid.shape
    assert np.abs(grid[:, 1] - profile[:, 1]).max() < 1e-7 * np.abs(profile[:, 1]).max()
    assert np.abs(grid[-1, 1] - grid[0, 1]) > 1e-3 * grid[0, 1]  # the current moved the line


@pytest.mark.parametrize("mode, name, text, reason", [
    (2, "current_profile_dynamic.txt", "a\nb\nc\nd\n-10 0\n\n", "needs at least 7 lines"),
    (2, "current_profile_dynamic.txt", "a\nb\nc\nd\n-10 0\n\n0 0.1\n1 0.2 0.3\n1 0.1 0.1\n",
     "line 7: expected t and 2 velocities ux"),
    (2, "current_profile_dynamic.txt", "a\nb\nc\nd\n-10 0\n\n0 0.1 0.1\n1 0.2 0.3\n1 0.1 0.1\n",
     "the times must increase"),
    (2, "current_profile_dynamic.txt", "a\nb\nc\nd\n0 -10\n\n0 0.1 0.1\n1 0.2 0.3\n", "the z values must increase"),
    (5, "current_profile_4d.txt", "1 1 2 1\n0\n0\n-10 0\n0\n0 0 -10 0 1 0 0\n0 0 -5 0 1 0 0\n",
     "line 7: z = -5 is not one of the grid's z values"),
    (5, "current_profile_4d.txt", "1 1 2 1\n0\n0\n-10 0\n0\n", "expected nx ny nz nt"),
    (5, "current_profile_4d.txt", "1 1 2 1\n0\n0\n-10 0\n0\n0 0 -10 0 1 0 0\n0 0 -10 0 1 0 0\n",
     "1 of the 2 grid points have no row"),
])
def test_bad_current_grids_are_refused_naming_the_file_and_line(tmp_path, mode, name, text, reason):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(InputError, match=reason) as error:
        read_current_grid(mode, str(path), "OPTIONS.Currents")
    assert error.value.key == "OPTIONS.Currents"


def test_currents_3_and_4_are_refused_with_what_to_do(tmp_path, capsys):
    text = open(DYNAMIC).read().replace("2         Currents", "3         Currents")
    case = Case("Currents 3", "node approach to currents (Currents 3 and 4", files={"line.txt": text},
                argv=("static", "{tmp}/line.txt"), file="line.txt")
    assert_refused(case, tmp_path, capsys)


def test_a_bad_grid_in_a_moordyn_file_names_the_file_its_option_and_the_line(tmp_path, capsys):
    text = open(FOUR_D).read()
    grid = open(os.path.join(DATA, "wavekin_4", "current_profile_4d.txt")).read().replace("-30.0 15.0 -3.5", "-31.0 15.0 -3.5", 1)
    case = Case("Currents 5 off its grid", "current_profile_4d.txt line 7: z = -31 is not one of the grid's z values",
                files={"line.txt": text, "current_profile_4d.txt": grid}, argv=("static", "{tmp}/line.txt"),
                file="line.txt")
    assert_refused(case, tmp_path, capsys)
