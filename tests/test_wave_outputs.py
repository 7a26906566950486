"""What a run in waves writes (issue 35): waves.pvd (the free surface at the frames' times), the
elevation at the origin in tensions.csv, the sea state in summary.json, and ``cablefem plot
--elevation``."""

import json
import os

import meshio
import numpy as np
import pytest

from bad_input import BASE_TOML, Case, assert_refused
from cablefem.cli import main
from cablefem.io import load_scene
from cablefem.io.vtk import read_collection

WAVES = '[waves]\nkind = "regular"\namplitude = 2.0\nperiod = 9.0\ndirection = 20.0\nramp = 2.0\n'
SHORT = BASE_TOML.replace("duration = 10.0", "duration = 1.0").replace("every = 0.1", "every = 0.5")


def test_a_run_in_waves_writes_the_surface_the_elevation_and_the_sea_state(tmp_path, capsys):
    scene = tmp_path / "scene.toml"
    scene.write_text(SHORT + WAVES)
    out = tmp_path / "out"
    assert main(["run", str(scene), "--out", str(out), "--dt", "0.05"]) == 0
    sea = load_scene(str(scene)).environment.waves
    line_times, _ = read_collection(out / "corpus.pvd")
    times, frames = read_collection(out / "waves.pvd")
    assert np.array_equal(times, line_times) and len(times) == 3
    surface = meshio.read(frames[-1])
    x, y, z = surface.points.T
    assert np.allclose(z, sea.elevation(x, y, times[-1]), atol=1e-12)
    assert np.allclose(surface.point_data["eta"], z)
    assert x.min() < -560.0 and x.max() > 0.0  # the scene's extent
    table = np.genfromtxt(out / "tensions.csv", delimiter=",", names=True)
    assert np.allclose(table["eta"], sea.elevation(0.0, 0.0, table["t"]), atol=1e-9)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["waves"]["kind"] == "regular" and summary["waves"]["period"] == 9.0
    assert summary["surface_frames"] == 3
    capsys.readouterr()
    assert main(["plot", str(out), "--elevation"]) == 0
    assert os.path.getsize(out / "tensions.png") > 0


def test_plotting_the_elevation_of_a_run_without_waves_is_refused(tmp_path, capsys):
    scene = tmp_path / "scene.toml"
    scene.write_text(SHORT)
    out = tmp_path / "out"
    assert main(["run", str(scene), "--out", str(out), "--dt", "0.05"]) == 0
    assert not (out / "waves.pvd").exists()
    assert "eta" not in (out / "tensions.csv").read_text().splitlines()[0]
    capsys.readouterr()
    case = Case("no waves", "no elevation in tensions.csv: the run had no [waves]", argv=("plot", "{tmp}/out",
                "--elevation"), file="out")
    assert_refused(case, tmp_path, capsys)


def test_a_scene_in_waves_named_waves_is_refused(tmp_path, capsys):
    case = Case("named waves", "may not be named 'waves'", files={"scene.toml": 'name = "waves"\n' +
                SHORT.replace('name = "corpus"\n', "") + WAVES}, argv=("run", "{tmp}/scene.toml", "--out",
                                                                        "{tmp}/out"))
    assert_refused(case, tmp_path, capsys)
