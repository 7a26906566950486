"""What survives a stopped run (issue 14): SIGINT, SIGTERM and SIGKILL sent to a real ``cablefem run``
mid-run, a full disk (a file size limit in the child, writes fail with EFBIG), and output folders
that cannot be written. Whatever the fault, the .pvd parses and lists only frames that meshio and
pyvista read, no .vtu in the folder is partial, tensions.csv holds whole rows, and (unless the
process was killed outright) summary.json says why the run stopped."""

import json
import os
import resource
import signal
import subprocess
import sys
import time

import meshio
import numpy as np
import pytest

from bad_input import BASE_TOML, edit
from cablefem.cli import main
from cablefem.compiled.progress import NOTICE
from cablefem.io.vtk import read_collection

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: a frame every step of a 60 s run: frames keep coming for the whole run
SCENE = edit(BASE_TOML, {"elements = 40": "elements = 20", "duration = 10.0": "duration = 60.0",
                         "every = 0.1": "every = 0.01",
                         "[solver]": '[motion]\nkind = "harmonic"\namplitude = [5.0, 0.0, 0.0]\nperiod = 6.0\n'
                                     'ramp = 6.0\n[solver]'})


def start_run(folder, preexec_fn=None, *options):
    """``cablefem run`` on SCENE in a child process writing to folder/out."""
    (folder / "scene.toml").write_text(SCENE)
    argv = [sys.executable, "-m", "cablefem.cli", "run", str(folder / "scene.toml"), "--out", str(folder / "out"),
            *options]
    return subprocess.Popen(argv, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, preexec_fn=preexec_fn)


def wait_for_frames(process, out, count, timeout=240.0):
    """Wait until ``count`` frames exist in out (the run is under way)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if out.is_dir() and sum(name.endswith(".vtu") for name in os.listdir(out)) > count:
            return
        if process.poll() is not None:
            pytest.fail(f"the run ended before {count} frames: {process.communicate()}")
        time.sleep(0.05)
    process.kill()
    pytest.fail("no frames in time")


def assert_what_survives(out, killed=False):
    """The invariants of any stopped run; returns (frames listed, tension rows, summary or None)."""
    import pyvista

    times, listed = read_collection(out / "corpus.pvd")  # parses
    assert len(listed) > 0 and np.all(np.diff(times) > 0)
    for path in listed:
        assert meshio.read(path).points.shape[1] == 3
        assert pyvista.read(path).n_points == 21
    for name in os.listdir(out):  # every .vtu in the folder reads, listed or not
        if name.endswith(".vtu"):
            try:
                meshio.read(out / name)
            except SystemExit:  # meshio calls exit() on a truncated file
                pytest.fail(f"{name} is partial")
    partial = [name for name in os.listdir(out) if name.endswith(".partial")]
    if killed:  # a temporary name may stay, hidden, never a .vtu; the next run removes it
        assert all(name.startswith(".") for name in partial), partial
    else:
        assert partial == []
    raw = (out / "tensions.csv").read_bytes()
    assert raw.endswith(b"\r\n")  # the last row is whole
    rows = [row.split(",") for row in raw.decode().splitlines()]
    assert rows[0] == ["t", "fairlead_tension", "anchor_tension", "fx", "fy", "fz"]
    values = np.array(rows[1:], dtype=float)  # every row has every column, as numbers
    assert len(values) >= len(listed) and np.all(np.diff(values[:, 0]) > 0)
    mask = os.umask(0)
    os.umask(mask)
    for name in ("corpus.pvd", "tensions.csv", "seabed.vtu", os.path.basename(listed[0])):
        assert os.stat(out / name).st_mode & 0o777 == 0o666 & ~mask, name  # as open() makes them
    summary = None
    if (out / "summary.json").exists():
        summary = json.loads((out / "summary.json").read_text())
        assert summary["frames"] == len(listed) and summary["completed"] is False
    return listed, values, summary


@pytest.mark.parametrize("signum, status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)], ids=["SIGINT", "SIGTERM"])
def test_an_interrupted_run_closes_its_outputs(tmp_path, signum, status):
    process = start_run(tmp_path)
    wait_for_frames(process, tmp_path / "out", 20)
    process.send_signal(signum)
    stdout, stderr = process.communicate(timeout=120)
    assert process.returncode == status, stderr
    # the one line, besides numba's notice if the child compiled (cablefem.compiled.progress)
    assert [line for line in stderr.splitlines() if line != NOTICE] == [f"cablefem: interrupted ({signal.Signals(signum).name})"]
    listed, rows, summary = assert_what_survives(tmp_path / "out")
    assert summary["status"] == "interrupted" and summary["steps"] == len(rows) - 1
    assert os.path.getmtime(tmp_path / "out" / "summary.json") >= os.path.getmtime(listed[-1])


@pytest.mark.parametrize("after", [5, 60], ids=["early", "later"])
def test_a_killed_run_leaves_a_collection_of_complete_frames(tmp_path, after):
    process = start_run(tmp_path)
    wait_for_frames(process, tmp_path / "out", after)
    process.kill()
    process.communicate(timeout=60)
    assert process.returncode == -signal.SIGKILL
    listed, _, summary = assert_what_survives(tmp_path / "out", killed=True)
    assert summary is None and len(listed) >= after - 1  # the .pvd kept up with the frames


def test_a_full_disk_stops_the_run_in_one_line_and_keeps_whole_files(tmp_path):
    (tmp_path / "warm").mkdir()
    warm = start_run(tmp_path / "warm", None, "--duration", "0.05")  # numba's cache, written without a limit
    assert warm.communicate(timeout=300) and warm.returncode == 0

    def limit():  # every file the child writes stops growing at 40 kB: EFBIG, as ENOSPC would
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (40_000, 40_000))

    process = start_run(tmp_path, limit)
    stdout, stderr = process.communicate(timeout=300)
    lines = stderr.splitlines()
    assert process.returncode == 2 and len(lines) == 1, stderr
    assert "File too large" in lines[0] and str(tmp_path / "out") in lines[0]
    listed, rows, summary = assert_what_survives(tmp_path / "out")
    assert summary["status"].startswith("stopped:") and "File too large" in summary["status"]
    assert os.path.getsize(tmp_path / "out" / "tensions.csv") <= 40_000


def test_output_onto_a_file_leaves_the_file_alone(tmp_path, capsys):
    (tmp_path / "scene.toml").write_text(BASE_TOML)
    (tmp_path / "results").write_text("keep me\n")
    assert main(["run", str(tmp_path / "scene.toml"), "--out", str(tmp_path / "results" / "sub")]) == 2
    assert main(["run", str(tmp_path / "scene.toml"), "--out", str(tmp_path / "results")]) == 2
    assert (tmp_path / "results").read_text() == "keep me\n"
    assert sorted(os.listdir(tmp_path)) == ["results", "scene.toml"]
    assert len(capsys.readouterr().err.splitlines()) == 2


def test_an_unwritable_output_folder_is_refused_before_any_work():
    """Checked by writing, not by the permission bits (root ignores them): run as nobody when root,
    in a folder nobody can read (pytest's own are private to their owner)."""
    import importlib
    import shutil
    import tempfile

    from cablefem.io import load_scene

    importlib.import_module("cablefem.runs.run")  # while the installation can still be read

    folder = tempfile.mkdtemp(prefix="cablefem-locked-")
    out = os.path.join(folder, "locked")
    try:
        os.chmod(folder, 0o755)
        os.mkdir(out, 0o555)
        os.chmod(out, 0o555)
        with open(os.path.join(folder, "scene.toml"), "w") as handle:
            handle.write(BASE_TOML)
        os.chmod(os.path.join(folder, "scene.toml"), 0o644)
        load_scene(os.path.join(folder, "scene.toml"))
        root = os.geteuid() == 0
        stderr = __import__("io").StringIO()
        with __import__("contextlib").redirect_stderr(stderr):
            try:
                if root:
                    os.seteuid(65534)
                status = main(["run", os.path.join(folder, "scene.toml"), "--out", out])
            finally:
                if root:
                    os.seteuid(0)
        err = stderr.getvalue().splitlines()
        assert status == 2 and len(err) == 1, err
        assert err[0] == f"cablefem: error: {out}: cannot write in this folder: Permission denied"
        assert os.listdir(out) == []
    finally:
        os.chmod(out, 0o755)
        shutil.rmtree(folder)
