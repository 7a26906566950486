"""What the command line says is true (docs/outputs.md): its version, where it wrote, what a file
given as a scene is, the static wall time, a README example run as a script, numbers without
negative zeros or float noise, a line of one element."""

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import cablefem
from cablefem.cli import main
from cablefem.io import load_scene

ROOT = Path(__file__).resolve().parents[1]


def test_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out.strip() == f"cablefem {cablefem.__version__}"


@pytest.mark.parametrize("file, says", [
    ("examples/sweeps/flume_flat_motions.toml", "a sweep file, not a scene: run it with `cablefem sweep`"),
    ("examples/flume_steep_seabed.vtu", "not a scene (a mesh or point file: a scene names it in [seabed] file)"),
    ("examples/flume_slow_drift.csv", "not a scene (a table: a scene names a motion table in [motion] file)"),
])
def test_a_file_that_is_not_a_scene_says_what_it_is(file, says, capsys):
    assert main(["static", str(ROOT / file)]) == 2
    error = capsys.readouterr().err
    assert says in error and error.count("\n") == 1


def test_static_json_says_where_it_wrote(tmp_path, capsys):
    path = tmp_path / "static.json"
    assert main(["static", str(ROOT / "examples" / "flume_flat.toml"), "--json", str(path)]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == f"wrote {path}" and path.is_file()


def test_the_static_wall_time_times_the_solve_and_no_import():
    """In a fresh process, the solve that ``wall_time_s`` times imports no module: the imports a
    first solve needs (scipy.optimize, ~0.4 s) are start-up, done before the clock starts."""
    script = """
import json, sys
import cablefem.statics.scene as statics
solve = statics.static_network
def watched(scene):
    before = set(sys.modules)
    out = solve(scene)
    print(json.dumps(sorted(set(sys.modules) - before)))
    return out
statics.static_network = watched
from cablefem.cli import main
main(["static", sys.argv[1]])
"""
    out = subprocess.run([sys.executable, "-c", script, str(ROOT / "examples" / "flume_flat.toml")],
                         capture_output=True, text=True, check=True).stdout
    imported = json.loads(next(line for line in out.splitlines() if line.startswith("[")))
    assert imported == []


def test_readme_sweep_example_runs_as_a_script(tmp_path):
    """The README's Python sweep, as a script (its guard: Dask's workers import the script again),
    run shorter: four cases of 0.5 s, each a row with status ok."""
    readme = (ROOT / "README.md").read_text()
    block = next(b for b in re.findall(r"```python\n(.*?)```", readme, re.S) if "cablefem.sweep(" in b)
    assert 'if __name__ == "__main__":' in block
    block = block.replace('"solver.duration": 30.0', '"solver.duration": 0.5').replace("print(table)", "")
    script = tmp_path / "sweep_script.py"
    script.write_text(block.replace("fixed=", f"out={str(tmp_path / 'out')!r}, workers=2, progress=False, fixed=")
                      + "    table.to_csv(" + repr(str(tmp_path / "table.csv")) + ")\n")
    subprocess.run([sys.executable, str(script)], cwd=ROOT, check=True, capture_output=True, timeout=600)
    import pandas as pd

    table = pd.read_csv(tmp_path / "table.csv")
    assert len(table) == 4 and (table["status"] == "ok").all()


def test_outputs_have_no_negative_zero_and_no_float_noise(tmp_path):
    """tensions.csv, summary.json, the .pvd's times and the static JSON: no "-0" and no number like
    29.310000000000002 (a time summed from steps), while every value keeps 15 digits."""
    out = tmp_path / "run"
    assert main(["run", str(ROOT / "examples" / "flume_flat.toml"), "--out", str(out), "--duration", "0.6"]) == 0
    assert main(["static", str(ROOT / "examples" / "flume_flat.toml"), "--json", str(tmp_path / "s.json")]) == 0
    noise = re.compile(r"\d\.\d*(0000000|9999999)\d")
    for path in (out / "tensions.csv", out / "summary.json", next(out.glob("*.pvd")), tmp_path / "s.json"):
        text = path.read_text()
        numbers = re.findall(r"-?\d+\.?\d*(?:e[-+]?\d+)?", text)
        assert not [n for n in numbers if re.fullmatch(r"-0(\.0*)?", n)], path
        assert not noise.search(text), (path, noise.search(text))
    times = [float(t) for t in re.findall(r'timestep="([^"]+)"', next(out.glob("*.pvd")).read_text())]
    assert times == [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
    assert json.loads((out / "summary.json").read_text())["simulated_time_s"] == 0.6


def test_a_line_of_one_element_is_solved_and_run(tmp_path):
    """One P1 element between the flat flume's anchor and fairlead (635 m over a 608 m chord: the
    straight element is slack): its ends carry half the line's weight in water each, in statics and
    at the start of a run, which completes."""
    scene_file = tmp_path / "one.toml"
    scene_file.write_text((ROOT / "examples" / "flume_flat.toml").read_text().replace("elements = 40", "elements = 1"))
    assert main(["static", str(scene_file), "--json", str(tmp_path / "s.json")]) == 0
    line = json.loads((tmp_path / "s.json").read_text())["lines"][0]
    scene = load_scene(scene_file)
    kind, env = scene.lines[0].segments[0].type, scene.environment
    weight = (kind.mass - env.water_density * np.pi / 4 * kind.diameter**2) * env.gravity * 635.0
    assert np.allclose(line["fairlead_force"], [0.0, 0.0, -weight / 2], rtol=0, atol=1e-9 * weight)
    assert np.allclose(line["anchor_force"], [0.0, 0.0, -weight / 2], rtol=0, atol=1e-9 * weight)
    assert main(["run", str(scene_file), "--out", str(tmp_path / "run"), "--duration", "1.0"]) == 0
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["completed"] and summary["steps"] == 100
    first = np.loadtxt(tmp_path / "run" / "tensions.csv", delimiter=",", skiprows=1)[0]
    assert first[1] == pytest.approx(weight / 2, rel=1e-9)
