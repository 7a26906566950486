"""Sweeps on Dask with real components (cablefem.sweeps, docs/sweep.md): a LocalCluster of worker
processes, a `dask scheduler` and a `dask worker` started as separate processes, an interrupted
sweep resumed, a case that fails. The runs are 2 s of the flume chain on 10 and 20 elements."""

import dataclasses
import json
import os
import shutil
import socket
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import cablefem
from cablefem.cli import main
from cablefem.statics.scene import solve_scene_static
from cablefem.errors import ConvergenceError
from cablefem.io.toml_scene import read_toml_scene
from cablefem.runs.run import run_scene
from cablefem.sweeps import read_sweep, run
from cablefem.sweeps.table import read_table
from cablefem.sweeps.tasks import series_columns

ROOT = Path(__file__).resolve().parents[1]
FLAT = ROOT / "examples" / "flume_flat.toml"
SWEEP = f"""
base = "{FLAT}"

[set]
solver.duration = 2.0
output.every = 1.0

[fatigue]
area = 0.061                    # m^2: 2 pi d_b^2 / 4 of a chain of d_b = 0.197 m

[[blocks]]                      # 4 dynamic cases
axes = {{ "motion.period" = [6.0, 8.0], "lines[*].segments[*].elements" = [10, 20] }}

[[blocks]]                      # 2 static cases
set = {{ kind = "static" }}
axes = {{ "lines[*].segments[*].elements" = [10, 20] }}
"""
#: columns that differ between any two runs: timings, and the bytes written (summary.json and
#: static.json hold a wall time)
TIMINGS = ("wall_time_s", "cpu_time_s", "run_wall_time_s", "output_bytes")


def write(folder, name, text):
    path = Path(folder) / name
    path.write_text(text)
    return str(path)


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    return write(tmp_path_factory.mktemp("sweep"), "sweep.toml", SWEEP)


@pytest.fixture(scope="module")
def local(sweep_file, dask_client, tmp_path_factory):
    """The sweep run on the session's LocalCluster (two worker processes): (spec, table, out)."""
    out = tmp_path_factory.mktemp("local")
    spec = read_sweep(sweep_file)
    return spec, run(spec, out=str(out), client=dask_client), out


def results(table):
    """The table without its timing columns, for comparing two runs of a sweep."""
    return table.drop(columns=[c for c in TIMINGS if c in table.columns])


def test_sweep_on_a_local_cluster_equals_each_case_run_alone(local, tmp_path, dask_client):
    spec, table, out = local
    assert dask_client.run(os.getpid).keys() and os.getpid() not in dask_client.run(os.getpid).values()
    assert len(table) == 6 and set(table["status"]) == {"ok"}
    assert list(table["kind"]) == ["dynamic"] * 4 + ["static"] * 2
    for case, row in zip(spec.cases, table.to_dict("records")):
        scene = read_toml_scene(spec.base, case.data)
        alone = tmp_path / case.case_id
        if case.kind == "dynamic":
            run_scene(scene, str(alone), progress=False)
            # the same time series to the last digit written, and the same statistics exactly
            assert (alone / "tensions.csv").read_bytes() == (out / row["dir"] / "tensions.csv").read_bytes()
            for key, value in series_columns(scene, str(alone), spec.stats_from, spec.fatigue).items():
                assert row[key] == value, key
        else:
            reports, iterations, _ = solve_scene_static(scene)
            assert row["line1:fairlead_tension"] == reports[0].fairlead_tension
            assert row["newton_iterations"] == iterations
    # the parameters are columns, and the finer mesh changes the answer (the cases differ)
    assert list(table["lines[*].segments[*].elements"]) == [10, 20, 10, 20, 10, 20]
    assert table["line1:fairlead_tension_max"][0] != table["line1:fairlead_tension_max"][1]
    assert (table["line1:fatigue_damage"][:4] > 0).all()


def test_python_api_runs_the_same_case_as_the_sweep_file(local, tmp_path, dask_client):
    spec, table, _ = local
    frame = cablefem.sweep(FLAT, {"motion.period": [8.0]}, client=dask_client, out=tmp_path,
                           fixed={"solver.duration": 2.0, "output.every": 1.0, "lines[*].segments[*].elements": 20},
                           fatigue={"area": 0.061}, progress=False)
    row, same = frame.iloc[0], table.iloc[3]
    assert row["case_id"] == same["case_id"]  # the identity is the scene's, however the sweep was written
    assert row["line1:fairlead_tension_max"] == same["line1:fairlead_tension_max"]
    assert row["line1:fatigue_damage"] == same["line1:fatigue_damage"]


def test_new_statistics_settings_recompute_done_rows_without_running_them(local, tmp_path, dask_client):
    spec, table, out = local
    shutil.copytree(out, tmp_path, dirs_exist_ok=True)
    later = dataclasses.replace(spec, stats_from=1.0, fatigue=None)
    again = run(later, out=str(tmp_path), client=dask_client)
    assert again.attrs["sweep"]["ran"] == 0 and again.attrs["sweep"]["skipped"] == len(spec.cases)
    dynamic = again["kind"] == "dynamic"
    assert (again["line1:fairlead_tension_min_t"][dynamic] >= 1.0).all()
    assert "line1:fatigue_damage" not in again.columns
    assert again["line1:fairlead_tension"][~dynamic].equals(table["line1:fairlead_tension"][~dynamic])


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.fixture
def dask_processes():
    """`dask scheduler` and one `dask worker` (one thread) as separate processes on a free port, as a
    user starts them on a cluster; the scheduler's address. Both are stopped afterwards."""
    from distributed import Client

    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT)] + sys.path))
    started = [subprocess.Popen([sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1", "--port",
                                 str(port), "--no-dashboard"], env=env, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)]
    try:
        started.append(subprocess.Popen([sys.executable, "-m", "dask", "worker", address, "--nworkers", "1",
                                         "--nthreads", "1", "--no-dashboard"], env=env, cwd=ROOT,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(1, timeout=60)
        yield address
    finally:
        for process in reversed(started):  # the worker first, then its scheduler
            process.terminate()
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def test_sweep_on_a_separate_scheduler_and_worker_gives_the_same_table(local, sweep_file, dask_processes,
                                                                         tmp_path, capsys):
    _, table, _ = local
    assert main(["sweep", sweep_file, "--scheduler", dask_processes, "--out", str(tmp_path)]) == 0
    assert "6 ran, 0 done before, 0 failed, 0 lost" in capsys.readouterr().out
    remote = read_table(str(tmp_path))
    assert results(remote).equals(results(table))
    facts = json.loads((tmp_path / "sweep.json").read_text())
    assert facts["scheduler"] == dask_processes and len(facts["warm_up_s"]) == 1


def test_interrupted_sweep_resumes_without_running_the_finished_cases(local, sweep_file, tmp_path, dask_client):
    spec, table, _ = local
    seen = []

    def interrupt(row):  # Ctrl-C in the client when the first case has come back
        seen.append(row)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run(spec, out=str(tmp_path), workers=1, on_row=interrupt)  # its own cluster, closed by the interrupt
    markers = sorted(tmp_path.glob("cases/*/row.json"))
    finished = {path: path.stat().st_mtime_ns for path in markers}
    assert len(seen) == 1 and 1 <= len(finished) < len(spec.cases)
    resumed = run(spec, out=str(tmp_path), client=dask_client)
    facts = resumed.attrs["sweep"]
    assert facts["skipped"] == len(finished) and facts["ran"] == len(spec.cases) - len(finished)
    assert {path: path.stat().st_mtime_ns for path in markers} == finished  # not run again
    assert results(resumed).equals(results(table))
    again = run(spec, out=str(tmp_path), client=dask_client)
    assert again.attrs["sweep"]["ran"] == 0 and again.attrs["sweep"]["skipped"] == len(spec.cases)


def test_failed_case_leaves_its_error_in_the_table(tmp_path, dask_client):
    path = write(tmp_path, "fails.toml", f"""
base = "{FLAT}"
kind = "static"
[set]
"lines[*].segments[*].elements" = 10
solver.max_iterations = 3
[axes]
solver.tolerance = [1e-8, 1e-30]    # 1e-30: Newton cannot get there
""")
    table = run(read_sweep(path), out=str(tmp_path / "out"), client=dask_client)
    assert list(table["status"]) == ["ok", "failed"]
    scene = read_toml_scene(str(FLAT), read_sweep(path).cases[1].data)
    with pytest.raises(ConvergenceError) as alone:
        solve_scene_static(scene)
    assert table["error"][1] == f"ConvergenceError: {alone.value}"
    assert np.isnan(table["line1:fairlead_tension"][1]) and table["line1:fairlead_tension"][0] > 1e6
    assert run(read_sweep(path), out=str(tmp_path / "out"), client=dask_client).attrs["sweep"]["ran"] == 0
    retried = run(read_sweep(path), out=str(tmp_path / "out"), client=dask_client, retry_failed=True)
    assert retried.attrs["sweep"]["ran"] == 1 and list(retried["status"]) == ["ok", "failed"]


@pytest.mark.parametrize("text, message", [
    ('[axes]\n"motion.period" = [6.0, -8.0]', "case 1 (motion.period = -8.0): motion.period: must be > 0, got -8"),
    ('[axes]\n"trench.depth" = [1.5]', "case 0 (trench.depth = 1.5): trench: unknown key"),
    ('combine = "zip"\n[axes]\n"motion.period" = [6.0, 8.0]\n"solver.dt" = [0.01]',
     "axes.solver.dt: has 1 values where the keys it is zipped with have 2"),
    ('[axes]\n"lines[3].order" = [1]', "case 0 (lines[3].order = 1): lines[3].order: index 3 out of range"),
    ('kind = "dynamc"', "kind: unknown kind 'dynamc' (did you mean 'dynamic'?)"),
    ('[axes]\n"lines[0].segments[0].elements" = [10, 0]',
     "case 1 (lines[0].segments[0].elements = 0): lines[0].segments[0].elements: must be at least 1"),
])
def test_bad_sweep_value_names_the_sweep_file_the_case_and_the_key(tmp_path, capsys, text, message):
    path = write(tmp_path, "bad.toml", f'base = "{FLAT}"\n{text}\n')
    assert main(["sweep", path, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"cablefem: error: {path}: {message}")
    assert err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "out").exists()  # nothing ran


def test_moordyn_base_takes_scene_keys_and_refuses_its_lines(tmp_path, capsys):
    dat = ROOT / "examples" / "flume_flat.dat"
    good = read_sweep(write(tmp_path, "md.toml", f'base = "{dat}"\n[axes]\n"moordyn.order" = [1, 2]\n'
                                                  '"solver.dt" = [0.01, 0.02]\n'))
    assert len(good.cases) == 4 and good.cases[3].params == {"moordyn.order": 2, "solver.dt": 0.02}
    bad = write(tmp_path, "mdbad.toml", f'base = "{dat}"\n[axes]\n"lines[*].order" = [2]\n')
    assert main(["sweep", bad]) == 2
    assert "use moordyn.order" in capsys.readouterr().err


def test_identity_follows_the_content_of_the_files_a_case_names(tmp_path):
    mesh = ROOT / "examples" / "flume_steep_seabed.vtu"
    copy = tmp_path / "bed.vtu"
    copy.write_bytes(mesh.read_bytes())
    text = f'base = "{ROOT / "examples" / "flume_steep.toml"}"\n[set]\n"seabed.file" = "bed.vtu"\n'
    first = read_sweep(write(tmp_path, "a.toml", text)).cases[0].case_id
    assert read_sweep(write(tmp_path, "b.toml", text)).cases[0].case_id == first  # stable
    copy.write_bytes(mesh.read_bytes().replace(b"meshio", b"MESHIO"))  # a different file, the same name
    assert read_sweep(write(tmp_path, "c.toml", text)).cases[0].case_id != first


@pytest.mark.parametrize("flags, message", [
    (["--workers", "0"], "--workers: must be a whole number >= 1, got 0"),
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--workers: applies to the local cluster only"),
])
def test_bad_cluster_flags_are_one_line_errors(sweep_file, capsys, flags, message):
    assert main(["sweep", sweep_file, *flags]) == 2
    assert capsys.readouterr().err.startswith(f"cablefem: error: {message}")
