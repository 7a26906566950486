"""Pictures of a run (cablefem.post.render_run, ``cablefem render``): framed on the lines, nothing
clipped, one colour range for the whole run, one-line errors; sweep plots in kN with the units of
docs/scene.md and short statistic names."""

import re
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pandas as pd
import pytest

from cablefem.cli import main
from cablefem.errors import InputError
from cablefem.post import BAR_BAND, TITLE_BAND, render_frame, render_run
from cablefem.sweeps import plot as sweep_plot

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    """The default scene run for 0.5 s: 6 frames."""
    out = tmp_path_factory.mktemp("run")
    assert main(["run", "--out", str(out), "--duration", "0.5"]) == 0
    return out


def ink(image):
    """Mask of the pixels that are not white."""
    return image.min(axis=2) < 250


def test_a_frame_fills_its_picture_and_nothing_touches_an_edge(run_dir):
    """The scene band (between title and colour bar) is filled across >= 90 % of its width by the
    line and the seabed near it, and a picture's outermost 2 pixels are white all round: no label,
    tick or line is cut (the default size follows the scene's aspect)."""
    image = iio.imread(render_frame(str(run_dir), index=-1))
    height, width = image.shape[:2]
    scene = ink(image[TITLE_BAND:height - BAR_BAND])
    columns = np.flatnonzero(scene.any(axis=0))
    assert (columns[-1] - columns[0]) >= 0.9 * width
    rows = np.flatnonzero(scene.any(axis=1))
    assert (rows[-1] - rows[0]) >= 0.8 * scene.shape[0]
    border = np.concatenate([ink(image[:2]).ravel(), ink(image[-2:]).ravel(), ink(image[:, :2]).ravel(),
                             ink(image[:, -2:]).ravel()])
    assert not border.any()
    assert ink(image[:TITLE_BAND]).any()  # the title


def test_every_frame_shares_one_colour_range_and_one_framing(run_dir, tmp_path):
    """Rendered all at once, the frames' colour bars (range and ticks) are the same pixels and the
    pictures the same size; a colour range given changes the bar. Rendering every frame again
    replaces its pictures and leaves other files."""
    paths = render_run(str(run_dir), png_dir=str(tmp_path))
    assert [Path(p).name for p in paths] == [f"flume-steep-dynamic_{k:05d}.png" for k in range(6)]
    images = [iio.imread(p) for p in paths]
    bars = [image[-BAR_BAND:] for image in images]
    assert all(np.array_equal(bars[0], bar) for bar in bars[1:])
    assert len({image.shape for image in images}) == 1
    other = iio.imread(render_frame(str(run_dir), index=-1, png=str(tmp_path / "other.png"), clim=(0.0, 4e6)))
    assert not np.array_equal(other[-BAR_BAND:], bars[-1])
    # a render of every frame again replaces the pictures it wrote, and nothing else
    (tmp_path / "notes.png").write_bytes(b"x")
    assert render_run(str(run_dir), frames=[0, 2], png_dir=str(tmp_path))[1].endswith("_00002.png")
    assert len(render_run(str(run_dir), png_dir=str(tmp_path))) == 6
    assert sorted(p.name for p in tmp_path.glob("*.png")) == sorted([Path(p).name for p in paths] +
                                                                  ["notes.png", "other.png"])


def test_views_and_an_array_without_a_unit_render(run_dir, tmp_path):
    for camera, scalars in (("top", "seabed_gap"), ("iso", "velocity"), ("side", "strain")):
        image = iio.imread(render_frame(str(run_dir), index=3, png=str(tmp_path / f"{camera}.png"),
                                        scalars=scalars, camera=camera, size=(900, 500)))
        assert image.shape == (500, 900, 3)
        assert ink(image[TITLE_BAND:-BAR_BAND]).mean() > 0.05


def test_an_animation_has_one_picture_per_frame(run_dir, tmp_path):
    gif = tmp_path / "run.gif"
    assert main(["render", str(run_dir), "--every", "2", "--animation", str(gif)]) == 0
    frames = iio.imread(gif, index=None)
    assert frames.shape[0] == 3


@pytest.mark.parametrize("args, says", [
    (["--scalars", "tensions"], "no array 'tensions' in the frames; they have tension, strain, velocity"),
    (["--frame", "6"], "no frame 6: the run wrote 6 frames (0 to 5, or -1 for the last)"),
    (["--frame", "-7"], "no frame -7"),
    (["--clim", "2", "1"], "the colour range must be two numbers, low to high"),
    (["--animation", "x.avi"], "an animation is a .gif"),
])
def test_a_wrong_array_frame_or_range_is_one_line(run_dir, args, says, capsys):
    assert main(["render", str(run_dir), *args]) == 2
    error = capsys.readouterr().err
    assert says in error and error.count("\n") == 1


def test_a_folder_without_a_run_is_one_line(tmp_path, capsys):
    assert main(["render", str(tmp_path)]) == 2
    assert "no .pvd collection here" in capsys.readouterr().err
    with pytest.raises(InputError, match="no such folder"):
        render_frame(str(tmp_path / "missing"))


# ------------------------------------------------------------------ sweep plots
def scene_units():
    """(section, key) -> unit of docs/scene.md's key tables, keys that have a unit."""
    section, units = None, {}
    for line in (ROOT / "docs" / "scene.md").read_text().splitlines():
        heading = re.match(r"^#+ .*?`\[+([^\]]+)\]+`", line)
        if heading or line.startswith("#"):
            section = heading.group(1) if heading else None
        named = re.match(r"^\| key of `\[([^\]]+)\]`", line)
        if named:
            section = named.group(1)
        row = re.match(r"^\| `([A-Za-z_\[\]\.]+)` \| ([^|]*) \|", line)
        if row and section and row.group(2).strip() not in ("–", "-", ""):
            units[(section, re.sub(r"\[[^\]]*\]", "", row.group(1)))] = row.group(2).strip()
    return units


def test_parameter_units_are_docs_scene_md_units():
    assert sweep_plot.KEY_UNITS == scene_units()
    assert sweep_plot.key_unit("motion.period") == "s"
    assert sweep_plot.key_unit("lines[*].segments[0].length") == "m"
    assert sweep_plot.key_unit("line_types.chain.EA") == "N"
    assert sweep_plot.key_unit("lines[*].order") == ""


@pytest.fixture
def table(tmp_path):
    rows = [{"case": k, "case_id": f"c{k}", "kind": "dynamic", "status": "ok", "error": None,
             "motion.period": period, "motion.amplitude": amplitude, "wall_time_s": 1.0, "cpu_time_s": 1.0,
             "output_bytes": 10, "line1:fairlead_tension_max": 1e6 * period * amplitude,
             "line1:fairlead_tension_max_t": 3.0, "dir": f"cases/c{k}"}
            for k, (period, amplitude) in enumerate([(6.0, 2.0), (8.0, 2.0), (6.0, 5.0), (8.0, 5.0)])]
    path = tmp_path / "sweep.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    return path


def test_sweep_plot_draws_tensions_in_kn_with_units_and_short_names(table, monkeypatch):
    from matplotlib.axes import Axes

    drawn, labels = [], {}
    plot, xlabel, ylabel = Axes.plot, Axes.set_xlabel, Axes.set_ylabel
    monkeypatch.setattr(Axes, "plot", lambda self, x, y, *a, **k: drawn.append(np.asarray(y)) or plot(self, x, y, *a, **k))
    monkeypatch.setattr(Axes, "set_xlabel", lambda self, text, **k: labels.setdefault("x", text) and xlabel(self, text, **k))
    monkeypatch.setattr(Axes, "set_ylabel", lambda self, text, **k: labels.setdefault("y", text) and ylabel(self, text, **k))
    assert Path(sweep_plot.plot_sweep(str(table), y="fairlead_tension_max", x="motion.period",
                                      by="motion.amplitude")).is_file()
    assert np.allclose(np.concatenate(drawn), [12e3, 16e3, 30e3, 40e3])  # kN
    assert labels == {"x": "motion.period [s]", "y": "line1:fairlead_tension_max [kN]"}


def test_a_wrong_statistic_lists_the_statistics(table, capsys):
    assert main(["plot", str(table), "--y", "tension_max"]) == 2
    error = capsys.readouterr().err
    assert "no statistic 'tension_max' in the table; statistics: wall_time_s" in error
    assert "line1:fairlead_tension_max, line1:fairlead_tension_max_t" in error and error.count("\n") == 1
