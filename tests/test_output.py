"""Output written whole or not at all (cablefem.io.output): atomic files with open()'s mode, the
.pvd's swap (and its fallback), whole CSV rows after a failed write, signals held while files
are written."""

import errno
import os
import signal

import numpy as np
import pytest

from cablefem.errors import OutputError, Terminated
from cablefem.io import output
from cablefem.io.vtk import TimeSeriesWriter, polyline_mesh, read_collection

LINE = {"points": np.array([[0.0, 0, 0], [1.0, 0, 0]]), "tension": np.array([1.0, 2.0])}


@pytest.mark.parametrize("swap", [True, False], ids=["renameat2", "rename"])
def test_a_rerun_in_the_same_folder_lists_only_its_own_frames(tmp_path, monkeypatch, swap):
    """The swap leaves the older, longer collection at the temporary name; the next, shorter one
    must not keep its tail. Without the swap (file systems that lack it) the same holds."""
    if not swap:
        monkeypatch.setattr(output, "_exchange", None)
    elif output._exchange is None:
        pytest.skip("no renameat2 here")
    first = TimeSeriesWriter(str(tmp_path), "run")
    for k in range(30):
        first.write(0.1 * k, polyline_mesh([LINE]))
    first.close()
    second = TimeSeriesWriter(str(tmp_path), "run")
    listed = []
    for k in range(3):
        second.write(0.5 * k, polyline_mesh([LINE]))
        listed.append(read_collection(tmp_path / "run.pvd")[0].tolist())
    assert listed == [[0.0], [0.0, 0.5], [0.0, 0.5, 1.0]]
    second.close()
    assert not any(name.endswith(".partial") for name in os.listdir(tmp_path))


def test_files_get_the_mode_open_gives(tmp_path):
    previous = os.umask(0o027)
    try:
        output.write_atomic(str(tmp_path / "a.json"), "{}")
        rows = output.RowsFile(str(tmp_path / "t.csv"), ["t"])
        rows.close()
        writer = TimeSeriesWriter(str(tmp_path), "run")
        writer.write(0.0, polyline_mesh([LINE]))
        writer.write(0.1, polyline_mesh([LINE]))  # the swapped collection
        writer.close()
        with open(tmp_path / "plain", "w"):
            pass
    finally:
        os.umask(previous)
    modes = {name: os.stat(tmp_path / name).st_mode & 0o777 for name in os.listdir(tmp_path)}
    assert set(modes.values()) == {0o640}, modes  # 0o666 & ~0o027, as open() gave "plain"


def test_a_failed_write_leaves_whole_rows_only(tmp_path, monkeypatch):
    table = output.RowsFile(str(tmp_path / "t.csv"), ["t", "x"])
    table.write([["0", "1"], ["1", "2"]])
    real = os.write

    def half_then_full(handle, data):  # the disk fills in the middle of a batch
        monkeypatch.setattr(os, "write", full)
        return real(handle, bytes(data)[:len(data) // 2])

    def full(handle, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "write", half_then_full)
    with pytest.raises(OutputError, match="No space left on device"):
        table.write([["2", "3"], ["3", "4"], ["4", "5"]])
    monkeypatch.setattr(os, "write", real)
    table.close()
    assert (tmp_path / "t.csv").read_bytes() == b"t,x\r\n0,1\r\n1,2\r\n"


def test_a_failed_atomic_write_keeps_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    output.write_atomic(str(tmp_path / "s.json"), "old")

    def full(handle, data):
        raise OSError(errno.EFBIG, os.strerror(errno.EFBIG))

    monkeypatch.setattr(os, "write", full)
    with pytest.raises(OutputError, match=f"{tmp_path / 's.json'}: cannot write: File too large"):
        output.write_atomic(str(tmp_path / "s.json"), "new")
    monkeypatch.undo()
    assert os.listdir(tmp_path) == ["s.json"] and (tmp_path / "s.json").read_text() == "old"


def test_signals_are_held_while_files_are_written_then_raised():
    previous = output.raise_on_sigterm()
    try:
        done = []
        with pytest.raises(Terminated):
            with output.deferred_signals():
                os.kill(os.getpid(), signal.SIGTERM)
                done.append("written")
        assert done == ["written"]
        with pytest.raises(KeyboardInterrupt):
            with output.deferred_signals():
                os.kill(os.getpid(), signal.SIGINT)
        with output.deferred_signals(reraise=False):
            os.kill(os.getpid(), signal.SIGINT)  # recorded, not raised: another failure is on its way
    finally:
        signal.signal(signal.SIGTERM, previous)
    ignored = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        with output.deferred_signals():  # an ignored signal stays ignored
            os.kill(os.getpid(), signal.SIGINT)
    finally:
        signal.signal(signal.SIGINT, ignored)


def test_a_frame_of_lines_alone_has_no_network_cell_data():
    # docs/outputs.md: cell data "network" tells a network's points and bodies from its lines, so a
    # frame of lines alone carries only "line" (an all-zero array in every frame cost ~4 % of a
    # frame's writing); with a point, "network" marks its vertex cell
    lines = polyline_mesh([LINE, LINE])
    assert set(lines.cell_data) == {"line"}
    assert np.concatenate(lines.cell_data["line"]).tolist() == [0, 1]
    network = polyline_mesh([LINE, LINE], points=[(1, -1)])
    assert np.concatenate(network.cell_data["network"]).tolist() == [0, 0, 1]
    assert network.cells[1].data.tolist() == [[3]]  # the second line's last point


def test_a_run_replaces_an_earlier_run_of_its_scene_and_nothing_else(tmp_path):
    """A 0.3 s run into the folder of a 0.6 s run of the same scene leaves its own 4 frames only
    (not the 7 before, nor a picture of them), and every other file as it was: another scene's
    frames and collection, a file whose name only starts like a frame's, a folder named like one,
    the user's notes."""
    from cablefem.cli import main

    def run(duration):
        assert main(["run", "--out", str(tmp_path), "--duration", duration]) == 0

    run("0.6")
    name = next(tmp_path.glob("*.pvd")).stem
    others = {"other.pvd": "<VTKFile/>", "other_00000.vtu": "x", f"{name}_00001.vtu.bak": "mine",
              f"{name}_last.vtu": "mine too", "notes.txt": "keep", f"{name}_00002_b.vtu": "kept"}
    for file, text in others.items():
        (tmp_path / file).write_text(text)
    (tmp_path / f"{name}_00099.vtu.d").mkdir()
    (tmp_path / f"{name}_00006.png").write_bytes(b"a picture of the earlier run's last frame")
    assert len(list(tmp_path.glob(f"{name}_?????.vtu"))) == 7
    run("0.3")
    frames = sorted(p.name for p in tmp_path.glob(f"{name}_?????.vtu"))
    assert frames == [f"{name}_{k:05d}.vtu" for k in range(4)]
    assert not (tmp_path / f"{name}_00006.png").exists()
    assert read_collection(tmp_path / f"{name}.pvd")[0].tolist() == pytest.approx([0.0, 0.1, 0.2, 0.3])
    assert {file: (tmp_path / file).read_text() for file in others} == others
    assert (tmp_path / f"{name}_00099.vtu.d").is_dir()
    assert len(np.loadtxt(tmp_path / "tensions.csv", delimiter=",", skiprows=1)) == 31


def test_a_frame_reads_back_as_meshio_writes_it(tmp_path):
    """``write_vtu`` (raw appended arrays, one write) against meshio's own writer: the same points,
    cells, point and cell data, read back by meshio, for lines with a network's points and bodies
    and for the waves' surface of quads."""
    import meshio

    from cablefem.io.vtk import write_vtu
    from cablefem.runs.surface import surface_mesh

    rng = np.random.default_rng(3)
    line = {"points": rng.random((9, 3)), "tension": rng.random(9), "velocity": rng.random((9, 3))}
    meshes = [polyline_mesh([line, line], points=[(0, 3), (1, -1)], bodies=[(np.zeros(3), [(0, -1), (1, -1)])]),
              surface_mesh(np.linspace(0, 1, 4), np.linspace(0, 2, 3), rng.random((3, 4)))]
    for k, mesh in enumerate(meshes):
        write_vtu(tmp_path / f"raw{k}.vtu", mesh)
        meshio.write(tmp_path / f"meshio{k}.vtu", mesh)
        ours, theirs = meshio.read(tmp_path / f"raw{k}.vtu"), meshio.read(tmp_path / f"meshio{k}.vtu")
        assert np.array_equal(ours.points, theirs.points)
        assert [(c.type, c.data.tolist()) for c in ours.cells] == [(c.type, c.data.tolist()) for c in theirs.cells]
        assert ours.point_data.keys() == theirs.point_data.keys()
        assert all(np.array_equal(ours.point_data[name], theirs.point_data[name]) for name in theirs.point_data)
        assert ours.cell_data.keys() == theirs.cell_data.keys()
        assert all(np.array_equal(a, b) for name in theirs.cell_data
                   for a, b in zip(ours.cell_data[name], theirs.cell_data[name]))
