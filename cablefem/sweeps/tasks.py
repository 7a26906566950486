"""What a worker does with one case of a sweep: build the scene from its TOML data, run it, write
its folder, summarise it as a row, and mark it done.

A task is a small dict (``task_of``): the case's index, identity, kind, the base scene's path,
the case's TOML data (a few kB) and its output folder; no scene object and no result arrays
travel. The worker writes the run's files into the case's folder (``cablefem run``'s:
tensions.csv, summary.json, the .pvd frames; ``cablefem static --json``'s for a static case) and,
last, ``row.json``, atomically: the marker that the case is done, which a re-run of the sweep
reads instead of running the case again. Imports neither dask nor pandas.
"""

import copy
import importlib
import json
import os
import shutil
import tempfile
import time

from cablefem.errors import ConvergenceError, InputError
from cablefem.io.vtk import write_atomic
from cablefem.sweeps.paths import set_path
from cablefem.sweeps.stats import fatigue_area, fatigue_damage, tension_statistics

MARKER = "row.json"
STATISTICS = ("max", "max_t", "min", "min_t", "mean", "std")


def post_key(stats_from, fatigue):
    """The post-processing settings a row's statistics depend on, as a comparable text."""
    return json.dumps({"stats_from": stats_from, "fatigue": fatigue}, sort_keys=True)


def task_of(case, sweep, folder):
    """The task (a plain dict) that runs ``case`` of ``sweep`` into ``folder`` (absolute)."""
    return {"index": case.index, "case_id": case.case_id, "kind": case.kind, "alone": case.alone,
            "base": sweep.base, "data": case.data, "dir": folder, "stats_from": sweep.stats_from,
            "fatigue": sweep.fatigue, "post": post_key(sweep.stats_from, sweep.fatigue)}


def run_task(task):
    """Run one case (``task_of``) and return its row: status "ok" or "failed" with the error on
    one line, the task's wall time and its worker process's CPU time [s], the bytes it wrote, and
    the kind's columns; the row is also written to the case folder's ``row.json``."""
    from cablefem.io.toml_scene import read_toml_scene

    start, cpu = time.perf_counter(), time.process_time()
    folder = task["dir"]
    shutil.rmtree(folder, ignore_errors=True)  # what an interrupted attempt left
    os.makedirs(folder)
    row = {"status": "ok", "error": None}
    try:
        scene = read_toml_scene(task["base"], task["data"])
        if task["kind"] == "static":
            row.update(static_columns(scene, folder))
        elif task["kind"] == "dynamic":
            row.update(dynamic_columns(scene, folder, task))
        else:
            row.update(custom_columns(task["kind"], scene, folder))
    except InputError as error:
        row.update(status="failed", error=error.message())
    except ConvergenceError as error:
        row.update(status="failed", error=f"ConvergenceError: {one_line(error)}")
    except Exception as error:  # noqa: BLE001 - any failure of a case is a row of the table
        row.update(status="failed", error=f"{type(error).__name__}: {one_line(error)}")
    row["wall_time_s"] = time.perf_counter() - start
    row["cpu_time_s"] = time.process_time() - cpu  # below wall_time_s: the worker did not have a core to itself
    row["output_bytes"] = folder_bytes(folder)
    write_atomic(os.path.join(folder, MARKER), json.dumps({"case_id": task["case_id"], "post": task["post"],
                                                           "row": row}))
    return row


def one_line(error, limit=500):
    """An exception's text on one line, at most ``limit`` characters."""
    text = " ".join(str(error).split())
    return text if len(text) <= limit else text[:limit - 3] + "..."


def folder_bytes(folder):
    """Bytes of the files in ``folder`` (not below it)."""
    with os.scandir(folder) as entries:
        return sum(e.stat().st_size for e in entries if e.is_file())


def static_columns(scene, folder):
    """Static equilibrium: ``static.json`` as ``cablefem static --json`` writes it, and per line the
    fairlead and anchor tension [N] and touchdown arc length [m] (NaN without contact)."""
    from cablefem.statics.scene import solve_scene_static
    from cablefem.io.output import write_json

    begin = time.perf_counter()
    reports, iterations, results = solve_scene_static(scene)
    wall = time.perf_counter() - begin
    write_json(os.path.join(folder, "static.json"), {
        "lines": [rep.as_dict() for rep in reports], "newton_iterations": iterations, "wall_time_s": wall,
        "scene": scene.name, "seabed": scene.seabed.describe(), "residuals": [r.residual for r in results]})
    columns = {"run_wall_time_s": wall, "newton_iterations": iterations}
    for rep in reports:
        columns.update({f"{rep.name}:fairlead_tension": rep.fairlead_tension,
                        f"{rep.name}:anchor_tension": rep.anchor_tension,
                        f"{rep.name}:touchdown_s": float("nan") if rep.touchdown_s is None else rep.touchdown_s})
    return columns


def dynamic_columns(scene, folder, task):
    """A time-domain run (``cablefem.runs.run.run_scene``, no progress bar) and its statistics."""
    from cablefem.runs.run import run_scene

    summary = run_scene(scene, folder, progress=False)
    columns = {"run_wall_time_s": summary["wall_time_s"], "simulated_time_s": summary["simulated_time_s"],
               "steps": summary["steps"], "newton_iterations": summary["newton_iterations"]}
    columns.update(series_columns(scene, folder, task["stats_from"], task["fatigue"]))
    return columns


def series_columns(scene, folder, stats_from, fatigue):
    """From a run's tensions.csv, per line and end (fairlead, anchor): the tension statistics over
    t >= stats_from [s] (``cablefem.sweeps.stats``), and with ``fatigue`` the fairlead's damage."""
    from cablefem.post import read_tensions

    series = read_tensions(folder)
    columns = {}
    for line in scene.lines:
        prefix = "" if len(scene.lines) == 1 else f"{line.name}:"
        for end in ("fairlead", "anchor"):
            stats = tension_statistics(series["t"], series[f"{prefix}{end}_tension"], stats_from)
            columns.update({f"{line.name}:{end}_tension_{key}": stats[key] for key in STATISTICS})
        if fatigue is not None:
            area = fatigue_area(fatigue, line)
            damage = fatigue_damage(series["t"], series[f"{prefix}fairlead_tension"], area, fatigue["a_D"],
                                    fatigue["m"], stats_from)
            columns.update({f"{line.name}:fatigue_damage": damage["damage"],
                            f"{line.name}:fatigue_damage_per_year": damage["damage_per_year"]})
    return columns


def custom_columns(kind, scene, folder):
    """A run kind ``module:function``: function(scene, folder) -> dict of scalar columns."""
    module, _, name = kind.partition(":")
    columns = getattr(importlib.import_module(module), name)(scene, folder)
    if not isinstance(columns, dict):
        raise TypeError(f"run kind {kind} returned {type(columns).__name__}, not a dict of columns")
    return columns


def read_marker(task):
    """The row a finished case left (``run_task``), or None when it has none or another identity;
    a row of a dynamic case whose statistics were taken with other settings is summarised again
    from its files (no re-run)."""
    path = os.path.join(task["dir"], MARKER)
    try:
        with open(path) as handle:
            marker = json.load(handle)
    except (OSError, ValueError):
        return None
    if marker.get("case_id") != task["case_id"]:
        return None
    row = marker["row"]
    if marker.get("post") != task["post"] and task["kind"] == "dynamic" and row["status"] == "ok":
        from cablefem.io.toml_scene import read_toml_scene

        scene = read_toml_scene(task["base"], task["data"])
        row = {key: value for key, value in row.items() if ":" not in key}  # the per-line columns go
        row.update(series_columns(scene, task["dir"], task["stats_from"], task["fatigue"]))
        write_atomic(path, json.dumps(dict(marker, post=task["post"], row=row)))
    return row


def warm(tasks):
    """Load (or, the first time on this machine, compile) the compiled kernels the ``tasks`` need
    by solving each one's scene, on two elements per segment, statically and for two time steps,
    in a scratch folder; returns the seconds it took."""
    from cablefem.statics.scene import solve_scene_static
    from cablefem.io.toml_scene import read_toml_scene
    from cablefem.runs.run import run_scene

    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="cablefem-warm-") as scratch:
        for task in tasks:
            scene = read_toml_scene(task["base"], task["data"])
            try:  # the same kernels on two elements per segment: quicker, compiled types unchanged
                data = copy.deepcopy(task["data"])
                set_path(data, "lines[*].segments[*].elements", 2)
                scene = read_toml_scene(task["base"], data)
            except InputError:
                pass  # a MoorDyn base, or a scene that needs its own mesh: warm on the case as it is
            try:
                solve_scene_static(scene)
                if task["kind"] != "static":
                    run_scene(scene, scratch, duration=2 * scene.solver.dt, progress=False)
            except ConvergenceError:
                pass  # the case itself will say so; the kernels are loaded either way
    return time.perf_counter() - start
