"""Table 6 of validation/irregular_seabed: the wall time of a horizontal seabed against the same
seabed triangulated, through ``run_scene`` and the numpy path, and the cost of one projection."""

import os
import shutil
import time
from pathlib import Path

import numpy as np

from cablefem import study
from cablefem.geometry import DepthGrid, Horizontal, TriangulatedSurface
from cablefem.post import read_tensions

from validation.irregular_seabed.model import (CONTACT, ENVIRONMENT, EXTENT, LEVELS, MEAN_DEPTH, PAPER, line_on,
                                               run_scene_quiet, scene_on)


def cost_seabeds():
    """Table 6's two models of the horizontal seabed z = -93.5 m: the plane, and the Fig. 18
    grid's nodes at that depth triangulated (built directly: ``simplify`` would undo it)."""
    (x0, x1), (y0, y1) = EXTENT
    x, y = np.linspace(x0, x1, 2 ** LEVELS + 1), np.linspace(y0, y1, 2 ** LEVELS + 1)
    flat = DepthGrid(x, y, np.full((len(y), len(x)), -MEAN_DEPTH))
    return {"horizontal": Horizontal(MEAN_DEPTH), "general": TriangulatedSurface(*flat.surface())}


def projection_call_cost(seabed, points, repeats=200):
    """Median wall time [s] of one ``project`` call (with derivatives) for points (n, 3)."""
    seabed.project(points)  # warm start state, as in a run
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        seabed.project(points)
        times.append(time.perf_counter() - start)
    return float(np.median(times))


#: Table 6's two ways of running: "run_scene" is what ``cablefem run`` does (the compiled
#: kernel of ``cablefem.compiled.evaluator`` when the loads allow it, frames and tensions.csv written);
#: "numpy" is the reference numpy assembly (``compiled=False``), the time loop alone
COST_PATHS = ("run_scene", "numpy")


def numpy_path_run(scene):
    """A run of ``scene`` on the reference numpy assembly, time loop only (no output): dict with
    wall_time_s, steps, newton_iterations and the fairlead tension after each step (k,) [N]."""
    solver = scene.solver
    start = time.perf_counter()
    integrator = study.start_line(scene, newton="auto", compiled=False)
    tensions = [np.linalg.norm(integrator.reactions()[0])]
    for _ in range(int(round(solver.duration / solver.dt))):
        integrator.step(solver.dt)
        tensions.append(np.linalg.norm(integrator.reactions()[0]))
    stats = integrator.statistics()
    return {"wall_time_s": time.perf_counter() - start, "steps": stats["steps"], "rejected_steps": stats["rejected"],
            "newton_iterations": stats["newton_iterations"], "tension": np.array(tensions)}


def timed_run(path, seabed, name, settings, duration, runs_dir):
    """One Table 6 run on ``path`` ("run_scene" or "numpy"): (row dict, fairlead tensions (k,) [N])."""
    scene = scene_on(seabed, name, settings["elements"], settings["dt"], duration, every=max(1.0, settings["every"]))
    # other work on the machine is the wall time's main noise: its load average, and the
    # process's CPU time, which other processes disturb much less
    load, cpu = os.getloadavg()[0], time.process_time()
    if path == "numpy":
        try:
            result = numpy_path_run(scene)
        except Exception as failure:  # recorded, not hidden
            return {"error": f"{type(failure).__name__}: {failure}", "completed": False,
                    "load_average": load}, np.array([np.nan])
        tension = result.pop("tension")
        return {**result, "cpu_time_s": time.process_time() - cpu, "load_average": load, "error": None,
                "completed": True}, tension
    out_dir = Path(runs_dir) / name
    summary, error = run_scene_quiet(scene, out_dir)
    cpu = time.process_time() - cpu
    tension = read_tensions(out_dir)["fairlead_tension"]
    shutil.rmtree(out_dir, ignore_errors=True)
    return {"wall_time_s": summary["wall_time_s"], "cpu_time_s": cpu, "steps": summary["steps"],
            "rejected_steps": sum(s.get("rejected", 0) for s in summary.get("integrator", [])),
            "newton_iterations": summary["newton_iterations"], "load_average": load, "error": error,
            "completed": error is None and summary["completed"]}, tension


def cost_study(settings, runs_dir):
    """Table 6: the two horizontal-seabed models, on each path, run alternately ``repeats``
    times; wall times, ratios, and the largest relative difference of the fairlead tensions."""
    from cablefem.runs.results import report
    from cablefem.statics.touchdown import solve_line

    duration, repeats = settings["cost_duration"], settings["repeats"]
    tree = study.provenance()
    paths = {}
    for path in COST_PATHS:
        rows = []
        for k in range(repeats):
            row, tensions = {"repeat": k}, {}
            # alternate which goes first; a fresh seabed per run (no warm-start state carried over)
            for method in ("horizontal", "general") if k % 2 == 0 else ("general", "horizontal"):
                row[method], tensions[method] = timed_run(path, cost_seabeds()[method], f"table6-{path}-{k}-{method}",
                                                          settings, duration, runs_dir)
            a, b = tensions["horizontal"], tensions["general"]
            done = row["general"]["completed"] and row["horizontal"]["completed"]
            row["ratio"] = row["general"]["wall_time_s"] / row["horizontal"]["wall_time_s"] if done else float("nan")
            row["cpu_ratio"] = row["general"]["cpu_time_s"] / row["horizontal"]["cpu_time_s"] if done else float("nan")
            row["max_relative_tension_difference"] = (float(np.max(np.abs(a - b)) / np.max(np.abs(a)))
                                                      if a.shape == b.shape else float("inf"))
            rows.append(row)
        ratios, cpu_ratios = np.array([r["ratio"] for r in rows]), np.array([r["cpu_ratio"] for r in rows])
        paths[path] = {"rows": rows, "ratio_mean": float(ratios.mean()), "ratio_min": float(ratios.min()),
                       "ratio_max": float(ratios.max()), "cpu_ratio_mean": float(cpu_ratios.mean()),
                       "cpu_ratio_min": float(cpu_ratios.min()), "cpu_ratio_max": float(cpu_ratios.max()),
                       "max_relative_tension_difference": float(max(r["max_relative_tension_difference"]
                                                                    for r in rows))}
    seabeds = cost_seabeds()
    line = line_on(seabeds["horizontal"], settings["elements"])
    system, static = solve_line(line, seabeds["horizontal"], CONTACT, ENVIRONMENT)
    nodes = report(system, static.X).nodes  # the static line: the points a run projects
    calls = {m: projection_call_cost(s, nodes) for m, s in seabeds.items()}
    return {"duration_s": duration, "dt": settings["dt"], "elements": settings["elements"],
            "triangles": int(len(seabeds["general"].triangles)), "paths": paths,
            "max_relative_tension_difference": float(max(p["max_relative_tension_difference"]
                                                         for p in paths.values())),
            "projection_call_s": calls, "projection_call_ratio": calls["general"] / calls["horizontal"],
            "paper_ratio": PAPER["table6_wall_time_s"]["general"] / PAPER["table6_wall_time_s"]["horizontal"],
            "provenance": tree,
            "tree_changed_during_measurement": study.provenance()["cablefem_sha256"] != tree["cablefem_sha256"]}
