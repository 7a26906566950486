"""Motion tables (docs/scene.md, [motion] table): a smooth spline through the rows whose velocity and
acceleration are its derivatives, so a harmonic motion given as a table runs as the harmonic motion."""

import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cablefem.errors import InputError
from cablefem.io import load_scene
from cablefem.model.motion import fairlead_motion
from cablefem.model.scene import Motion
from cablefem.post import read_tensions
from cablefem.runs.run import run_scene

ROOT = Path(__file__).resolve().parents[1]


def harmonic_table(amplitude, period, spacing, end):
    """A table motion (no ramp) sampling amplitude sin(2 pi t / period) along x every ``spacing`` s."""
    times = np.arange(0.0, end + 0.5 * spacing, spacing)
    positions = np.zeros((len(times), 3))
    positions[:, 0] = amplitude * np.sin(2 * np.pi * times / period)
    return Motion(kind="table", times=times, positions=positions)


def test_a_table_passes_its_rows_and_its_derivatives_are_its_velocity_and_acceleration():
    """Rows reproduced to round-off; velocity and acceleration equal central differences of the
    positions (step 1e-4 s: their error 1e-8 relative) between and across rows (continuous
    acceleration there: C2 and more); the harmonic's own derivatives within the spline's error
    (h = 0.5 s, omega = 1.05/s: accelerations O(h^4) ~ 1e-3 of their amplitude)."""
    motion = harmonic_table(5.0, 6.0, 0.5, 24.0)
    d, v, a = fairlead_motion(motion, motion.times)
    assert np.max(np.abs(d - motion.positions)) < 1e-12
    t = np.linspace(3.0, 21.0, 1001)  # rows among them (every 0.018 s: 3.0, 3.504, ...) and between
    step = 1e-4
    (dm, _, _), (d0, v0, a0), (dp, _, _) = (fairlead_motion(motion, t + k * step) for k in (-1, 0, 1))
    assert np.max(np.abs((dp - dm) / (2 * step) - v0)) < 1e-6 * np.max(np.abs(v0))
    assert np.max(np.abs((dp - 2 * d0 + dm) / step**2 - a0)) < 1e-4 * np.max(np.abs(a0))
    row = motion.times[10]  # left and right of a row
    left, right = fairlead_motion(motion, row - 1e-9)[2], fairlead_motion(motion, row + 1e-9)[2]
    assert np.max(np.abs(left - right)) < 1e-6
    omega = 2 * np.pi / 6.0
    assert np.max(np.abs(a0[:, 0] + 5.0 * omega**2 * np.sin(omega * t))) < 2e-3 * 5.0 * omega**2


def test_a_table_holds_its_ends_and_a_short_one_is_linear():
    """Before the first row and after the last the fairlead stays (zero velocity and acceleration);
    two rows are joined by a line, its slope the velocity."""
    motion = Motion(kind="table", times=np.array([1.0, 3.0]), positions=np.array([[0.0, 0, 0], [4.0, 2, 0]]))
    d, v, a = fairlead_motion(motion, np.array([0.0, 2.0, 5.0]))
    assert np.allclose(d, [[0, 0, 0], [2, 1, 0], [4, 2, 0]])
    assert np.allclose(v, [[0, 0, 0], [2, 1, 0], [0, 0, 0]]) and np.all(a == 0.0)


def test_a_linear_table_jumps_in_velocity_at_its_rows(tmp_path):
    """interpolation = "linear": straight lines, the velocity their slopes, no acceleration; the key
    belongs to tables only."""
    motion = Motion(kind="table", times=np.array([0.0, 1.0, 2.0, 3.0]),
                    positions=np.array([[0.0, 0, 0], [1.0, 0, 0], [1.0, 0, 0], [3.0, 0, 0]]), interpolation="linear")
    d, v, a = fairlead_motion(motion, np.array([0.5, 0.999, 1.001, 2.5]))
    assert np.allclose(d[:, 0], [0.5, 0.999, 1.0, 2.0]) and np.allclose(v[:, 0], [1.0, 1.0, 0.0, 2.0])
    assert not a.any()
    (tmp_path / "motion.csv").write_text("0,0,0,0\n1,1,0,0\n2,1,0,0\n3,3,0,0\n")
    text = (ROOT / "examples" / "flume_flat.toml").read_text()
    start = text.index("[motion]")
    end = text.index("[solver]")
    for motion_table, says in (('kind = "table"\nfile = "motion.csv"\ninterpolation = "linear"\n', None),
                               ('kind = "table"\nfile = "motion.csv"\ninterpolation = "cubic"\n', "motion.interpolation"),
                               ('kind = "harmonic"\namplitude = [1.0, 0, 0]\nperiod = 6.0\ninterpolation = "linear"\n',
                                "does not apply to motion kind 'harmonic'")):
        scene_file = tmp_path / "scene.toml"
        scene_file.write_text(text[:start] + "[motion]\n" + motion_table + "\n" + text[end:])
        if says is None:
            assert load_scene(scene_file).motion.interpolation == "linear"
        else:
            with pytest.raises(InputError, match=says):
                load_scene(scene_file)


def test_a_harmonic_motion_as_a_table_runs_as_the_harmonic_motion():
    """The flat flume's 5 m / 6 s surge (6 s ramp, 18 s) and the same surge as a table of rows 0.5 s
    apart: the largest fairlead tension within 0.5 % and no step-to-step jump larger than the
    harmonic run's largest (the snap's; linear rows with zero acceleration made 82 % and 17x) by
    more than 0.1 %. Measured: the largest jump 0.006 % above the harmonic run's."""
    scene = load_scene(ROOT / "examples" / "flume_flat.toml")
    table = harmonic_table(5.0, 6.0, 0.5, 19.0)
    table = replace(scene.motion, kind="table", times=table.times, positions=table.positions)
    tensions = {}
    for name, motion in (("harmonic", scene.motion), ("table", table)):
        with tempfile.TemporaryDirectory() as out:
            run_scene(replace(scene, motion=motion), out, duration=18.0, progress=False)
            tensions[name] = read_tensions(out)["fairlead_tension"]
    harmonic, tabled = tensions["harmonic"], tensions["table"]
    assert tabled.max() == pytest.approx(harmonic.max(), rel=5e-3)
    assert np.max(np.abs(np.diff(tabled))) <= 1.001 * np.max(np.abs(np.diff(harmonic)))
