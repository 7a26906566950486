"""One number per quantity (docs/outputs.md): ``cablefem static`` reports the state a run starts
from (same mesh, same nodes, same tensions), and the tension at a line's node is one number in the
static JSON, the VTK frames and tensions.csv, at an end that carries a point too."""

import json
from pathlib import Path

import meshio
import numpy as np
import pytest

from cablefem.cli import main
from cablefem.io import load_scene
from cablefem.io.vtk import read_collection
from cablefem.post import collection, read_tensions

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted(p.name for p in (ROOT / "examples").iterdir() if p.suffix in (".toml", ".dat"))
PENDULUM = ROOT / "tests" / "data" / "moordyn" / "pendulum.txt"  # a 1e5 kg mass on a weightless line
CROWFOOT = ROOT / "benchmarks" / "crowfoot.toml"  # a clump at a junction, riding on a string's end


def static_json(scene, folder):
    path = folder / "static.json"
    assert main(["static", str(scene), "--json", str(path)]) == 0
    return json.loads(path.read_text())


def run(scene, folder, duration="0.02", dt="0.01"):
    """(tensions.csv columns, [(t, meshio frame)]) of a short run of ``scene``."""
    out = folder / "run"
    assert main(["run", str(scene), "--out", str(out), "--duration", duration, "--dt", dt]) == 0
    pvd = collection(str(out))  # the scene's (a run in waves also writes waves.pvd)
    times, paths = read_collection(pvd)
    return read_tensions(out), [(t, meshio.read(p)) for t, p in zip(times, paths)]


def line_points(frame, k):
    """Rows of line k's points in a frame, anchor first, and their point data."""
    cells = frame.cells[0].data[frame.cell_data["line"][0] == k]
    rows = np.unique(cells)
    return frame.points[rows], {name: values[rows] for name, values in frame.point_data.items()}


def column(table, lines, k, name):
    return table[name if len(lines) == 1 else f"{lines[k]['name']}:{name}"]


@pytest.mark.parametrize("example", EXAMPLES)
def test_static_reports_the_state_a_run_starts_from(example, tmp_path):
    """Every example scene: the static JSON's nodes are the first frame's vertices within 1e-9 m,
    its end tensions the first row of tensions.csv and its per-node tensions the first frame's
    within 1e-9 relative (the static JSON on the numpy path of small scenes, the run's start
    compiled: round-off apart; tensions.csv has 10 digits)."""
    scene = ROOT / "examples" / example
    static = static_json(scene, tmp_path)
    table, frames = run(scene, tmp_path)
    t0, frame = frames[0]
    assert t0 == 0.0 and table["t"][0] == 0.0
    for k, line in enumerate(static["lines"]):
        nodes = np.array(line["nodes"])
        points, data = line_points(frame, k)
        order = (len(points) - 1) // (len(nodes) - 1)
        assert len(points[::order]) == len(nodes)  # the same mesh
        assert np.max(np.abs(points[::order] - nodes)) <= 1e-9
        for end in ("fairlead_tension", "anchor_tension"):
            assert column(table, static["lines"], k, end)[0] == pytest.approx(line[end], rel=1e-9)
        assert np.allclose(data["tension"][::order], line["tension"], rtol=1e-9, atol=0.0)


def test_a_fitted_mesh_is_the_mesh_of_both(tmp_path):
    """With [solver] fit_touchdown = true the static and the run's start share the touchdown-fitted
    mesh: a vertex sits at the touchdown, where the even mesh has none."""
    text = (ROOT / "examples" / "flume_flat.toml").read_text()
    scene = tmp_path / "fitted.toml"
    scene.write_text(text.replace("[solver]\n", "[solver]\nfit_touchdown = true\n"))
    static = static_json(scene, tmp_path)
    even = static_json(ROOT / "examples" / "flume_flat.toml", tmp_path)
    table, frames = run(scene, tmp_path)
    line, points = static["lines"][0], line_points(frames[0][1], 0)[0]

    def miss(report):
        """Distance [m] along the line from the touchdown to the nearest vertex (stretched arc
        length: the resting part's strain, 2.5e-4, moves the touchdown's by 0.11 m)."""
        s = np.cumsum(np.r_[0.0, np.linalg.norm(np.diff(np.array(report["nodes"]), axis=0), axis=1)])
        return np.min(np.abs(s - report["touchdown_s"]))

    assert miss(line) < 0.5 < 2.0 < miss(even["lines"][0])  # elements of 15.9 m
    assert np.max(np.abs(points - np.array(line["nodes"]))) <= 1e-9
    assert table["fairlead_tension"][0] == pytest.approx(line["fairlead_tension"], rel=1e-9)


def test_a_point_on_a_free_end_leaves_the_line_its_tension(tmp_path):
    """MoorDyn's pendulum: a weightless line (its mass is the water it displaces, to 2e-7) holding
    a 1e5 kg mass at its free end carries m g at both ends, in statics and in a run at rest."""
    scene = load_scene(PENDULUM)
    mass = next(point.joint.mass for point in scene.points.values() if point.joint.mass > 0)
    weight = mass * scene.environment.gravity
    line = static_json(PENDULUM, tmp_path)["lines"][0]
    assert line["fairlead_tension"] == pytest.approx(weight, rel=1e-8)
    assert line["anchor_tension"] == pytest.approx(weight, rel=1e-8)
    assert np.allclose(line["tension"], weight, rtol=1e-8)
    table, _ = run(PENDULUM, tmp_path, duration="0.3")
    for end in ("fairlead_tension", "anchor_tension"):
        assert np.allclose(table[end], weight, rtol=1e-6)  # at rest; the run's tolerance 1e-8 of the weight


@pytest.mark.parametrize("scene, duration", [(None, "0.3"), (PENDULUM, "0.3"), (CROWFOOT, "3")],
                         ids=["default", "pendulum", "crowfoot"])
def test_frames_give_the_end_tension_of_tensions_csv(scene, duration, tmp_path):
    """At every frame time the frames' tension at each line's ends is tensions.csv's, within 1e-9
    (the CSV's 10 digits): on the default scene, at a free end carrying a mass (pendulum) and at a
    junction end carrying a clump (crowfoot, whose platform's 10 s period sets frames every 1 s)."""
    out = tmp_path / "run"
    assert main(["run", *([] if scene is None else [str(scene)]), "--out", str(out), "--duration", duration]) == 0
    table = read_tensions(out)
    names = [name[: -len("fairlead_tension")] for name in table if name.endswith("fairlead_tension")]
    times, paths = read_collection(next(out.glob("*.pvd")))
    assert len(times) == 4
    for t, path in zip(times, paths):
        row = int(np.argmin(np.abs(table["t"] - t)))
        assert table["t"][row] == pytest.approx(t, abs=1e-9)
        frame = meshio.read(path)
        for k, prefix in enumerate(names):
            tension = line_points(frame, k)[1]["tension"]
            assert tension[-1] == pytest.approx(table[prefix + "fairlead_tension"][row], rel=1e-9)
            assert tension[0] == pytest.approx(table[prefix + "anchor_tension"][row], rel=1e-9)


def test_the_summary_extremes_are_those_of_tensions_csv(tmp_path):
    """summary.json's largest and smallest end tensions per line, and when they first occur, are
    those of tensions.csv's columns (written to 10 digits), for every line of a network."""
    out = tmp_path / "run"
    assert main(["run", str(CROWFOOT), "--out", str(out), "--duration", "3.0"]) == 0
    table = read_tensions(out)
    extremes = json.loads((out / "summary.json").read_text())["tension_extremes"]
    for name, entry in extremes.items():
        for key in ("fairlead_tension", "anchor_tension"):
            values = table[f"{name}:{key}"]
            for which, pick in (("max", np.argmax), ("min", np.argmin)):
                k = pick(values)
                assert entry[f"{key}_{which}"] == pytest.approx(values[k], rel=1e-9)
                assert entry[f"{key}_{which}_t"] == pytest.approx(table["t"][k], abs=1e-9)
