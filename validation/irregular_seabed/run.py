"""A line on an irregular seabed, three ways: desire2023 Sec. 5 (Figs. 18-20, Table 6).

Run ``python -m validation.irregular_seabed.run [--fast] [--out DIR] [--runs DIR]``
(``--convergence``: the element / time-step study instead; ``--table6``: only Table 6,
merged into results.json); ``run(fast=True)`` returns the numbers
tests/test_validation_irregular_seabed.py asserts on.

1. A diamond-square seabed (smoothness 0.3, seeded, ``generators.diamond_square``):
   irregular in x and y, inclined, mean elevation -93.5 m, under the Table 5 line
   (635 m, anchor at negative x, the origin at the fairlead's projection). The line
   runs on it three ways, each with its own projection:
   (a) "general": the grid triangulated, ``TriangulatedSurface`` with the continuous
       vertex-normal projection (desire2023 Sec. 2.2.2.2), not simplified;
   (b) "inclined": the grid's least-squares plane, point-to-plane projection;
   (c) "horizontal": the horizontal plane at the grid's mean elevation (z-bar).
   The fairlead circles in the horizontal plane, radius 2.5 m, period 12 s, around
   (10, 0, 0), ramped in over half a period; Table 5 properties, isotropic friction 0.3.
2. Line positions at t = 6 s (Fig. 19) and fairlead tensions (Fig. 20: dynamic =
   total minus its mean, and total), over several seeds of the random surface; the
   paper's three qualitative findings checked on each.
3. Table 6: wall time of ``Horizontal(93.5)`` against the same horizontal seabed
   triangulated (``TriangulatedSurface`` built directly, no ``simplify``), same line and
   motion, 120 s simulated, alternated and repeated 3 times; the two must give the
   same tensions (the vertex-normal projection is exact on a plane).
"""

import argparse
import json
import os
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem import study
from cablefem.geometry import DepthGrid, Horizontal, TriangulatedSurface
from cablefem.geometry.generators import diamond_square
from cablefem.line import Line, Segment
from cablefem.post import read_tensions
from cablefem.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver
from cablefem.scenes import table5_chain

HERE = Path(__file__).resolve().parent
METHODS = ("general", "inclined", "horizontal")
LENGTH = 635.0  # m, Table 5

# ---- the seabed (Fig. 18). The paper gives smoothness 0.3 and z-bar = -93.5 m only.
SMOOTHNESS = 0.3
LEVELS = 6  # 2^6 + 1 = 65 nodes a side: 12.5 m cells, 8192 triangles
EXTENT = ((-700.0, 100.0), (-400.0, 400.0))  # m: 100 m beyond the anchor (x = -597 m), 88 m beyond the fairlead
MEAN_DEPTH = 93.5  # m, Fig. 18's z-bar
#: corner half-range of the fractal before detrending [m]: about its plane the surface then has
#: an RMS of 2.5-4.7 m and a range of 20-30 m, local slopes of 4 deg (median) to 13-21 deg (README)
AMPLITUDE = 20.0
#: amplitudes and seeds of the static sweep (the spread of the realisations)
SWEEP_AMPLITUDES = (10.0, 20.0, 30.0)
#: gradient (dz/dx, dz/dy) of the least-squares plane: rises 1.1 deg towards the fairlead
#: (shallower than z-bar under the touchdown, as Sec. 5 explains the horizontal > inclined
#: tensions) and 0.6 deg towards +y (inclined in both directions, as Fig. 18)
TILT = (0.02, 0.01)

# ---- the line and the motion (Sec. 5: circle in XY of 2.5 m, 12 s, origin at x = 10 m)
ANCHOR_XY = (-597.0, 0.0)  # m; z on each seabed model. Chosen for the horizontal total peak ~2.4 MN
CENTRE = (10.0, 0.0, 0.0)  # m: the scene's fairlead; the motion circles around it
PERIOD = 12.0
MOTION = Motion(kind="circular", radius=2.5, period=PERIOD, plane="xy", ramp=PERIOD / 2)
SNAPSHOT_T = 6.0  # s, Fig. 19
CONTACT = Contact(stiffness=3.0e5, damping_ratio=1.0)  # Table 5 G_K
FRICTION = Friction(model="isotropic", mu=0.3, v_threshold=0.01)  # Table 5 C_K, U_c
ENVIRONMENT = Environment(water_density=1025.0, gravity=9.81)

#: desire2023 Sec. 5, read from the text (Fig. 20) and Table 6
PAPER = {
    "dynamic_peak_N": {"general": 5.0e5, "inclined": 4.0e5, "horizontal": 4.0e5},  # approximations "< 4e5"
    "total_peak_N": {"general": 2.8e6, "inclined": 2.2e6, "horizontal": 2.4e6},
    "table6_wall_time_s": {"horizontal": 11236.0, "general": 13488.0},
}

SETTINGS = {
    "full": {"elements": 80, "dt": 0.01, "duration": 60.0, "seeds": (0, 1, 2, 3, 4), "every": 0.5,
             "cost_duration": 120.0, "repeats": 3, "sweep_seeds": 20, "sweep_amplitudes": SWEEP_AMPLITUDES},
    "fast": {"elements": 40, "dt": 0.02, "duration": 24.0, "seeds": (0, 1, 2), "every": 1.0,
             "cost_duration": 6.0, "repeats": 3, "sweep_seeds": 10, "sweep_amplitudes": (AMPLITUDE,)},
}
#: the seed drawn in the figures (the first one: not chosen for its numbers)
PRIMARY_SEED = 0
#: statistics "after the ramp": from the end of the ramp plus one period
STEADY_FROM = MOTION.ramp + PERIOD


def seabed_grid(seed, amplitude=AMPLITUDE, tilt=TILT):
    """The Fig. 18-like diamond-square DepthGrid of ``seed`` [m]."""
    return diamond_square(LEVELS, SMOOTHNESS, amplitude, seed, EXTENT, MEAN_DEPTH, tilt)


def seabed_models(grid):
    """The three seabed models of Sec. 5 for ``grid``: dict method -> Seabed."""
    return {"general": TriangulatedSurface(*grid.surface()),
            "inclined": grid.least_squares_plane(),
            "horizontal": grid.mean_depth_horizontal()}


def surface_statistics(grid):
    """Numbers that describe a seabed grid [m, deg]: mean, the plane, the roughness about it."""
    plane = grid.least_squares_plane()
    vertices = grid.vertices
    residual = vertices[:, 2] - plane.elevation(vertices[:, :2])
    slope_y, slope_x = np.gradient(grid.z, grid.y, grid.x)
    local = np.degrees(np.arctan(np.hypot(slope_x, slope_y)))
    cut = np.column_stack([grid.x, np.zeros_like(grid.x)])
    cut_residual = grid.elevation(cut) - plane.elevation(cut)
    return {"mean_elevation_m": float(vertices[:, 2].mean()),
            "plane_gradient": [float(-plane.normal[0] / plane.normal[2]),
                               float(-plane.normal[1] / plane.normal[2])],
            "plane_slope_deg": float(np.degrees(plane.slope_angle())),
            "roughness_rms_m": float(residual.std()), "roughness_range_m": float(np.ptp(residual)),
            "cut_y0_roughness_rms_m": float(cut_residual.std()),
            "cut_y0_roughness_range_m": float(np.ptp(cut_residual)),
            "local_slope_deg_median": float(np.median(local)), "local_slope_deg_max": float(local.max()),
            "elevation_range_m": [float(grid.z.min()), float(grid.z.max())]}


def line_on(seabed, elements, anchor_xy=ANCHOR_XY):
    """The Table 5 line from its anchor resting on ``seabed`` at anchor_xy to the circle's centre."""
    anchor = (anchor_xy[0], anchor_xy[1], float(seabed.elevation(np.array([anchor_xy]))[0]))
    return Line("line1", anchor, CENTRE, (Segment(table5_chain(), LENGTH, elements),), 1)


def scene_on(seabed, name, elements, dt, duration, every):
    """The Sec. 5 scene on ``seabed``: Table 5 line and friction, circular fairlead motion."""
    return Scene(name=name, lines=[line_on(seabed, elements)], seabed=seabed, contact=CONTACT,
                 environment=ENVIRONMENT, friction=FRICTION, motion=MOTION,
                 solver=Solver(integrator="bdf2", dt=dt, duration=duration),
                 output=Output(dir="out", every=every), notes=[f"desire2023 Sec. 5: {name}"])


def run_scene_quiet(scene, out_dir):
    """``run_scene`` without a progress bar; (summary, error message or None)."""
    from cablefem.run import run_scene

    try:
        return run_scene(scene, str(out_dir), progress=False), None
    except Exception as failure:  # a solver failure is a result here, recorded in the table
        summary = json.loads((Path(out_dir) / "summary.json").read_text())
        return summary, f"{type(failure).__name__}: {failure}"


def frame_at(out_dir, t):
    """(time [s], line points (m, 3) [m], seabed gap (m,) [m]) of the output frame nearest t."""
    import meshio

    from cablefem.io.vtk import read_collection

    times, files = read_collection(str(next(Path(out_dir).glob("*.pvd"))))
    k = int(np.argmin(np.abs(times - t)))
    mesh = meshio.read(files[k])
    return float(times[k]), mesh.points, mesh.point_data["seabed_gap"]


def touchdown(points, gap):
    """(x [m], arc position along the polyline [m]) of the touchdown: the last point from the
    anchor with d_G <= 0, refined linearly to d_G = 0 towards the next point; NaNs without contact."""
    touching = np.flatnonzero(gap <= 0.0)
    if touching.size == 0:
        return float("nan"), float("nan")
    k = touching[-1]
    chord = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    if k == len(gap) - 1:
        return float(points[k, 0]), float(chord[k])
    w = gap[k] / (gap[k] - gap[k + 1])
    return (float(points[k, 0] + w * (points[k + 1, 0] - points[k, 0])),
            float(chord[k] + w * (chord[k + 1] - chord[k])))


def grounded_length(points, gap):
    """Length [m] of the polyline in contact (d_G <= 0), linear in d_G along each segment."""
    lengths = np.linalg.norm(np.diff(points, axis=0), axis=1)
    g0, g1 = gap[:-1], gap[1:]
    both = (g0 <= 0) & (g1 <= 0)
    one = (g0 <= 0) != (g1 <= 0)
    fraction = np.where(one, np.where(g0 <= 0, g0, g1) / np.where(one, g0 - g1, 1.0), 0.0)
    return float(lengths[both].sum() + (np.abs(fraction) * lengths)[one].sum())


def run_method(method, seabed, seed, settings, runs_dir):
    """Run one seabed model and return its statistics (dict, SI); series under "_series"."""
    duration = settings["duration"]
    out_dir = Path(runs_dir) / f"seed{seed}-{method}"
    scene = scene_on(seabed, f"irregular-{method}", settings["elements"], settings["dt"], duration,
                     settings["every"])
    summary, error = run_scene_quiet(scene, out_dir)
    data = read_tensions(out_dir)
    t, tension = data["t"], data["fairlead_tension"]
    stats = {"method": method, "seed": seed, "seabed": seabed.describe(), "status": summary["status"],
             "error": error, "wall_time_s": summary["wall_time_s"], "steps": summary["steps"],
             "newton_iterations": summary["newton_iterations"], "run_dir": str(out_dir),
             # steps whose Newton failed and that cablefem split into halves (dynamics.Integrator.step)
             "rejected_steps": sum(s.get("rejected", 0) for s in summary.get("integrator", [])),
             "anchor": list(scene.lines[0].anchor)}
    if error is not None or not np.all(np.isfinite(tension)) or t[-1] < duration - 1e-6:
        stats["completed"] = False
        return stats
    mean = float(tension.mean())  # the paper's pretension: the mean of the whole series
    dynamic = tension - mean
    steady = t >= STEADY_FROM - 1e-9
    t_static, points0, gap0 = frame_at(out_dir, 0.0)
    t_snap, points, gap = frame_at(out_dir, SNAPSHOT_T)
    td_x, td_s = touchdown(points, gap)
    stats.update({
        "completed": True,
        "mean_N": mean, "total_peak_N": float(tension.max()), "total_min_N": float(tension.min()),
        "t_total_peak_s": float(t[np.argmax(tension)]),
        "dynamic_peak_N": float(dynamic.max()), "dynamic_min_N": float(dynamic.min()),
        "steady_mean_N": float(tension[steady].mean()), "steady_total_peak_N": float(tension[steady].max()),
        "steady_dynamic_peak_N": float(tension[steady].max() - tension[steady].mean()),
        "steady_range_N": float(np.ptp(tension[steady])),
        "static_tension_N": float(tension[0]),
        "snapshot_t_s": t_snap, "touchdown_x_m": td_x, "touchdown_arc_m": td_s,
        "grounded_length_m": grounded_length(points, gap),
        "static_touchdown_x_m": touchdown(points0, gap0)[0],
        "static_grounded_length_m": grounded_length(points0, gap0),
        "contact_points_at_snapshot": int((gap <= 0).sum()),
    })
    stats["_series"] = {"t": t, "fairlead_tension": tension, "snapshot": points, "snapshot_gap": gap}
    return stats


def findings(by_method):
    """desire2023 Sec. 5's three qualitative findings on one seed's runs: dict with numbers and ``passed``."""
    if not all(by_method[m].get("completed") for m in METHODS):
        return {"error": "not every method completed; no findings checked"}
    dyn = {m: by_method[m]["dynamic_peak_N"] for m in METHODS}
    tot = {m: by_method[m]["total_peak_N"] for m in METHODS}
    td = {m: by_method[m]["touchdown_x_m"] for m in METHODS}
    return {
        "general_highest_dynamic_peak": {
            "passed": bool(dyn["general"] > max(dyn["inclined"], dyn["horizontal"])), "dynamic_peak_N": dyn},
        "horizontal_total_above_inclined": {
            "passed": bool(tot["horizontal"] > tot["inclined"]), "total_peak_N": tot,
            "mean_N": {m: by_method[m]["mean_N"] for m in METHODS}},
        "general_highest_total": {
            "passed": bool(tot["general"] > max(tot["inclined"], tot["horizontal"])), "total_peak_N": tot},
        "touchdowns_differ": {
            # 1 m: well above the touchdown's interpolation error, far below the differences found
            "passed": bool(min(abs(td[a] - td[b]) for a, b in
                               (("general", "inclined"), ("general", "horizontal"), ("inclined", "horizontal"))) > 1.0),
            "touchdown_x_m": td},
        "inclined_touchdown_nearer_fairlead_than_horizontal": {
            # Sec. 5 reads Fig. 19 as: the inclined plane's touchdown is "higher" than the horizontal one's
            "passed": bool(td["inclined"] > td["horizontal"]), "touchdown_x_m": td},
    }


# ---------------------------------------------------------------- static sweep over realisations
def static_tension(seabed, elements, fairlead_x):
    """(fairlead tension [N], touchdown x [m]) of the line in static equilibrium with its
    fairlead at (fairlead_x, 0, 0) [m], solved as ``cablefem static`` does (``solve_line``)."""
    from cablefem.results import report
    from cablefem.statics import solve_line

    line = line_on(seabed, elements)
    line = Line(line.name, line.anchor, (fairlead_x, 0.0, 0.0), line.segments, line.order)
    system, result = solve_line(line, seabed, CONTACT, ENVIRONMENT)
    r = report(system, result.X)
    x = np.interp(r.touchdown_s, np.linspace(0.0, LENGTH, len(r.nodes)), r.nodes[:, 0]) \
        if r.touchdown_s is not None else float("nan")
    return r.fairlead_tension, float(x)


def static_sweep(settings):
    """Statics at the circle's largest surge (x = 12.5 m, where the total peaks) on many
    realisations: the spread of general vs the two planes, per amplitude (the planes depend
    on neither seed nor amplitude: ``diamond_square`` imposes them)."""
    surge = CENTRE[0] + MOTION.radius
    elements = settings["elements"]
    planes = seabed_models(seabed_grid(0))
    reference = {m: static_tension(planes[m], elements, surge) for m in ("inclined", "horizontal")}
    rows = []
    for amplitude in settings["sweep_amplitudes"]:
        general, failures, roughness = [], [], []
        for seed in range(settings["sweep_seeds"]):
            grid = seabed_grid(seed, amplitude=amplitude)
            roughness.append(surface_statistics(grid)["roughness_rms_m"])
            try:
                general.append(static_tension(TriangulatedSurface(*grid.surface()), elements, surge))
            except Exception as failure:  # recorded, not hidden
                failures.append({"seed": seed, "error": f"{type(failure).__name__}: {failure}"})
        tension = np.array([g[0] for g in general])
        rows.append({
            "amplitude_m": amplitude, "seeds": settings["sweep_seeds"], "failures": failures,
            "roughness_rms_m": [float(np.min(roughness)), float(np.max(roughness))],
            "general_tension_N": tension.tolist(), "general_touchdown_x_m": [g[1] for g in general],
            "general_median_N": float(np.median(tension)),
            "general_range_N": [float(tension.min()), float(tension.max())],
            "fraction_above_inclined": float(np.mean(tension > reference["inclined"][0])),
            "fraction_above_horizontal": float(np.mean(tension > reference["horizontal"][0])),
            "fraction_above_both": float(np.mean(tension > max(reference["inclined"][0],
                                                                reference["horizontal"][0])))})
    return {"fairlead_x_m": surge, "elements": elements,
            "inclined": {"tension_N": reference["inclined"][0], "touchdown_x_m": reference["inclined"][1]},
            "horizontal": {"tension_N": reference["horizontal"][0], "touchdown_x_m": reference["horizontal"][1]},
            "amplitudes": rows}


# ---------------------------------------------------------------- Table 6
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
#: kernel of ``cablefem.fused`` when the loads allow it, frames and tensions.csv written);
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
    from cablefem.results import report
    from cablefem.statics import solve_line

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


# ---------------------------------------------------------------- study
def run(fast=False, runs_dir=None, cost=True):
    """The whole study; returns the results dict (private "_..." keys hold series and grids
    for the figures). Runs go to ``runs_dir`` (kept) or a temporary folder (removed)."""
    settings = SETTINGS["fast" if fast else "full"]
    keep_runs = runs_dir is not None
    runs_dir = Path(runs_dir) if keep_runs else Path(tempfile.mkdtemp(prefix="irregular_seabed_"))
    runs_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    try:
        seeds = []
        for seed in settings["seeds"]:
            grid = seabed_grid(seed)
            models = seabed_models(grid)
            by_method = {m: run_method(m, models[m], seed, settings, runs_dir) for m in METHODS}
            seeds.append({"seed": seed, "surface": surface_statistics(grid), "methods": by_method,
                          "findings": findings(by_method), "_grid": grid})
        results = {"fast": fast, "settings": {k: list(v) if isinstance(v, tuple) else v for k, v in settings.items()},
                   "setup": setup_description(), "provenance": study.provenance(), "paper": PAPER, "primary_seed": PRIMARY_SEED,
                   "seeds": seeds, "robustness": robustness(seeds)}
        results["static_sweep"] = static_sweep(settings)
        if cost:
            results["table6"] = cost_study(settings, runs_dir)
    finally:
        if not keep_runs:
            shutil.rmtree(runs_dir, ignore_errors=True)
    results["total_wall_time_s"] = time.perf_counter() - start
    return results


def write_outputs(results, target):
    """results.json and the PNGs into the folder ``target``; returns the file names."""
    target = Path(target)
    target.mkdir(parents=True, exist_ok=True)
    results["figures"] = make_figures(results, target)
    study.write_json(target / "results.json", results)
    return results["figures"] + ["results.json"]


def setup_description():
    """The choices of this study, for results.json."""
    return {"smoothness": SMOOTHNESS, "levels": LEVELS, "nodes_per_side": 2 ** LEVELS + 1, "extent_m": EXTENT,
            "amplitude_m": AMPLITUDE, "tilt": TILT, "mean_depth_m": MEAN_DEPTH, "anchor_xy_m": ANCHOR_XY,
            "circle_centre_m": CENTRE, "radius_m": MOTION.radius, "period_s": MOTION.period,
            "ramp_s": MOTION.ramp, "snapshot_t_s": SNAPSHOT_T, "steady_from_s": STEADY_FROM,
            "ground_stiffness_N_m3": CONTACT.stiffness, "friction_mu": FRICTION.mu,
            "friction_v_threshold_m_s": FRICTION.v_threshold}


def robustness(seeds):
    """How many seeds satisfy each finding: dict finding -> [passed, checked]."""
    counts = {}
    for entry in seeds:
        for name, finding in entry["findings"].items():
            if isinstance(finding, dict) and "passed" in finding:
                passed, total = counts.get(name, (0, 0))
                counts[name] = (passed + int(finding["passed"]), total + 1)
    return {name: list(v) for name, v in counts.items()}


# ---------------------------------------------------------------- figures
COLOURS = {"general": "tab:blue", "inclined": "tab:green", "horizontal": "tab:red"}
LABELS = {"general": "general (triangulated, vertex normals)", "inclined": "inclined (least-squares plane)",
          "horizontal": "horizontal (z-bar)"}


def make_figures(results, target):
    """Fig. 19-, Fig. 20-like PNGs, the seed summary and a 3-D render; returns their names."""
    import matplotlib

    matplotlib.use("Agg")
    target.mkdir(parents=True, exist_ok=True)
    entry = next(e for e in results["seeds"] if e["seed"] == results["primary_seed"])
    names = [figure_positions(entry, target / "fig19_positions.png"),
             figure_tensions(entry, target / "fig20_tensions.png"),
             figure_seeds(results, target / "seeds.png")]
    try:
        names.append(render_3d(entry, target / "surface_3d.png"))
    except Exception as failure:  # no OpenGL context: the PNGs above are still written
        print(f"3-D render skipped: {type(failure).__name__}: {failure}")
    return [Path(n).name for n in names]


def figure_positions(entry, png):
    """Fig. 19: the cut y = 0 of the seabed models and the three lines at t = 6 s, and a zoom."""
    import matplotlib.pyplot as plt

    grid, runs = entry["_grid"], entry["methods"]
    models = {"inclined": grid.least_squares_plane(), "horizontal": grid.mean_depth_horizontal()}
    x = np.linspace(EXTENT[0][0], 20.0, 1601)
    cut = np.column_stack([x, np.zeros_like(x)])
    general = TriangulatedSurface(*grid.surface())
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.2), gridspec_kw={"width_ratios": [1.3, 1]})
    done = [m for m in METHODS if runs[m].get("completed")]
    tds = [runs[m]["touchdown_x_m"] for m in done]
    zoom = (min(tds) - 60.0, max(tds) + 60.0) if tds else (-300.0, -100.0)
    for ax in axes:
        ax.plot(x, general.elevation(cut), color=COLOURS["general"], lw=1.0, alpha=0.55, label="seabed, irregular (y = 0)")
        for m, bed in models.items():
            ax.plot(x, bed.elevation(cut), color=COLOURS[m], lw=1.0, ls="--", alpha=0.7,
                    label=f"seabed, {m} (y = 0)")
        for m in done:
            p = runs[m]["_series"]["snapshot"]
            ax.plot(p[:, 0], p[:, 2], "o-", color=COLOURS[m], ms=2.5, lw=1.6,
                    label=f"line, {LABELS[m]}")
            ax.plot(runs[m]["touchdown_x_m"], np.interp(runs[m]["touchdown_x_m"], p[:, 0], p[:, 2]),
                    "v", color=COLOURS[m], ms=10, mec="k")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]")
        ax.grid(True, alpha=0.3)
    axes[0].set_xlim(EXTENT[0][0], 25)
    axes[0].legend(fontsize=8, loc="upper left")
    axes[1].set_xlim(*zoom)
    z_zoom = [general.elevation(np.array([[zoom[0], 0.0], [zoom[1], 0.0]]))]
    low = min(np.min(z_zoom), *(bed.elevation(np.array([[zoom[0], 0.0], [zoom[1], 0.0]])).min()
                                 for bed in models.values()))
    axes[1].set_ylim(low - 6.0, low + 24.0)
    axes[1].set_title("zoom near the touchdown points (triangles)")
    t = runs[done[0]]["snapshot_t_s"] if done else SNAPSHOT_T
    axes[0].set_title(f"Fig. 19-like: line nodes at t = {t:g} s, seed {entry['seed']} (x-z view; seabed cut y = 0)")
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    plt.close(fig)
    return png


def figure_tensions(entry, png):
    """Fig. 20: dynamic (total minus its mean) and total fairlead tension of the three models."""
    import matplotlib.pyplot as plt

    runs = entry["methods"]
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.8))
    for m in METHODS:
        if not runs[m].get("completed"):
            continue
        s = runs[m]["_series"]
        axes[0].plot(s["t"], (s["fairlead_tension"] - runs[m]["mean_N"]) / 1e6, color=COLOURS[m], lw=1.2,
                     label=f"{m}: peak {runs[m]['dynamic_peak_N'] / 1e6:.2f} MN")
        axes[1].plot(s["t"], s["fairlead_tension"] / 1e6, color=COLOURS[m], lw=1.2,
                     label=f"{m}: peak {runs[m]['total_peak_N'] / 1e6:.2f} MN")
    for m in METHODS:
        axes[0].axhline(PAPER["dynamic_peak_N"][m] / 1e6, color=COLOURS[m], ls=":", lw=1)
        axes[1].axhline(PAPER["total_peak_N"][m] / 1e6, color=COLOURS[m], ls=":", lw=1)
    for ax, title in zip(axes, ("dynamic tension T - mean(T)", "total tension T")):
        ax.axvspan(0, MOTION.ramp, color="0.9", zorder=0)
        ax.axvline(SNAPSHOT_T, color="0.5", lw=0.8)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("fairlead tension [MN]")
        ax.set_title(f"Fig. 20-like, seed {entry['seed']}: {title}\n(dotted: the paper's peaks; grey: ramp)",
                     fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    plt.close(fig)
    return png


def figure_seeds(results, png):
    """Dynamic and total peaks and touchdown x of the three models for every seed."""
    import matplotlib.pyplot as plt

    seeds = results["seeds"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    keys = (("dynamic_peak_N", 1e6, "dynamic peak [MN]"), ("total_peak_N", 1e6, "total peak [MN]"),
            ("touchdown_x_m", 1.0, f"touchdown x at t = {SNAPSHOT_T:g} s [m]"))
    for ax, (key, scale, label) in zip(axes, keys):
        for k, m in enumerate(METHODS):
            values = [e["methods"][m].get(key, np.nan) / scale if e["methods"][m].get("completed") else np.nan
                      for e in seeds]
            ax.plot(np.arange(len(seeds)) + (k - 1) * 0.12, values, "o", color=COLOURS[m], ms=7, label=m)
            if key in ("dynamic_peak_N", "total_peak_N"):
                ax.axhline(PAPER[key][m] / scale, color=COLOURS[m], ls=":", lw=1)
        ax.set_xticks(range(len(seeds)), [f"seed {e['seed']}" for e in seeds])
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[0].set_title("dotted: the paper's values", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    plt.close(fig)
    return png


def render_3d(entry, png, exaggeration=4.0, strip=40.0):
    """pyvista render (z exaggerated) at t = 6 s: left, the irregular surface and the general
    line; right, the surface see-through, the two planes as strips along y = 0 and the three lines."""
    import pyvista

    pyvista.OFF_SCREEN = True
    grid, runs = entry["_grid"], entry["methods"]
    scale = np.array([1.0, 1.0, exaggeration])
    gx, gy = np.meshgrid(grid.x, grid.y)
    surface = pyvista.StructuredGrid(gx, gy, grid.z * exaggeration)
    surface["elevation [m]"] = grid.z.ravel(order="F")
    (x0, x1), _ = EXTENT
    plotter = pyvista.Plotter(off_screen=True, shape=(1, 2), window_size=(2000, 900), border=False)
    # looking from the anchor's side, south-west and above, at the middle of the line
    camera = [(-1100.0, -900.0, 300.0), (-300.0, 0.0, -90.0 * exaggeration), (0.0, 0.0, 1.0)]
    for column in (0, 1):
        plotter.subplot(0, column)
        plotter.set_background("white")
        plotter.add_mesh(surface.copy(), scalars="elevation [m]", cmap="gist_earth", clim=(grid.z.min(), grid.z.max()),
                         opacity=1.0 if column == 0 else 0.35, show_scalar_bar=column == 0,
                         scalar_bar_args={"title": "seabed elevation [m]", "color": "black", "vertical": True,
                                          "position_x": 0.06, "position_y": 0.25,
                                          "title_font_size": 14, "label_font_size": 12, "fmt": "%.0f"})
        shown = ("general",) if column == 0 else METHODS
        if column == 1:
            for m in ("inclined", "horizontal"):
                bed = grid.least_squares_plane() if m == "inclined" else grid.mean_depth_horizontal()
                corners = np.array([[x0, -strip], [x1, -strip], [x1, strip], [x0, strip]], dtype=float)
                quad = np.column_stack([corners, bed.elevation(corners)]) * scale
                plotter.add_mesh(pyvista.PolyData(quad, faces=[4, 0, 1, 2, 3]), color=COLOURS[m][4:],
                                 opacity=0.45)
        for m in shown:
            if runs[m].get("completed"):
                points = runs[m]["_series"]["snapshot"] * scale
                plotter.add_mesh(pyvista.lines_from_points(points), color=COLOURS[m][4:], line_width=6)
        plotter.camera_position = camera
        plotter.reset_camera()
        plotter.camera.zoom(1.3)
        text = ("irregular seabed (diamond-square) and the line on it, general projection" if column == 0 else
                "see-through: least-squares plane (green) and z-bar plane (red) strips; lines of the three models")
        plotter.add_text(f"{text}\nseed {entry['seed']}, t = {SNAPSHOT_T:g} s, z x {exaggeration:g}",
                         font_size=11, color="black")
        if column == 1:  # a legend of coloured words (add_legend's box is clipped in subplots)
            for k, m in enumerate(METHODS):
                plotter.add_text(f"line: {LABELS[m]}", position=(0.52, 0.2 - 0.05 * k), viewport=True,
                                 font_size=11, color=COLOURS[m][4:])
    plotter.screenshot(str(png))
    plotter.close()
    return png


# ---------------------------------------------------------------- settings study
#: (elements, dt [s]) of the convergence study, on the primary seed, ramp + 2 periods
CONVERGENCE = [(40, 0.02), (40, 0.01), (80, 0.01), (80, 0.005), (160, 0.005)]
CONVERGENCE_DURATION = MOTION.ramp + 2 * PERIOD


def convergence(runs_dir=None, seed=PRIMARY_SEED):
    """Peaks and touchdown of the three models against elements and dt (chooses SETTINGS)."""
    keep = runs_dir is not None
    runs_dir = Path(runs_dir) if keep else Path(tempfile.mkdtemp(prefix="irregular_seabed_conv_"))
    rows = []
    try:
        models = seabed_models(seabed_grid(seed))
        for elements, dt in CONVERGENCE:
            settings = {"elements": elements, "dt": dt, "duration": CONVERGENCE_DURATION, "every": 0.5}
            for m in METHODS:
                r = run_method(m, models[m], seed, settings, runs_dir / f"{elements}el-dt{dt:g}")
                r.pop("_series", None)
                rows.append({"elements": elements, "dt": dt, **r})
                print(f"{elements:4d} el  dt {dt:<6g} {m:<11} " + (
                    f"dyn.peak {r['dynamic_peak_N'] / 1e6:.4f}  total peak {r['total_peak_N'] / 1e6:.4f}  "
                    f"mean {r['mean_N'] / 1e6:.4f} MN  touchdown {r['touchdown_x_m']:7.1f} m  "
                    f"grounded {r['grounded_length_m']:6.1f} m  wall {r['wall_time_s']:6.1f} s"
                    if r.get("completed") else f"FAILED {r['error'] or r['status']}"), flush=True)
    finally:
        if not keep:
            shutil.rmtree(runs_dir, ignore_errors=True)
    return {"seed": seed, "duration_s": CONVERGENCE_DURATION, "rows": rows}


# ---------------------------------------------------------------- report
def print_report(results):
    """The comparison table, the findings with PASS/FAIL, and Table 6."""
    mn = 1e6
    print(f"desire2023 Sec. 5: irregular seabed, three ways ({'fast' if results['fast'] else 'full'} variant; "
          f"{results['settings']['elements']} P1 elements, dt = {results['settings']['dt']} s, "
          f"{results['settings']['duration']:g} s simulated)")
    print("\nseed  surface (rms / range about its plane)  method      dyn.peak  total peak  mean     "
          f"steady dyn.  touchdown x @{SNAPSHOT_T:g}s  grounded  wall     halved steps")
    for entry in results["seeds"]:
        surface = entry["surface"]
        for m in METHODS:
            r = entry["methods"][m]
            head = (f"{entry['seed']:>4}  {surface['roughness_rms_m']:5.2f} / {surface['roughness_range_m']:5.1f} m"
                    if m == "general" else f"{'':4}  {'':16}")
            if not r.get("completed"):
                print(f"{head}{'':23}{m:<11} FAILED: {r['error'] or r['status']}")
                continue
            print(f"{head}{'':23}{m:<11} {r['dynamic_peak_N'] / mn:6.3f}   {r['total_peak_N'] / mn:6.3f}    "
                  f"{r['mean_N'] / mn:6.3f}   {r['steady_dynamic_peak_N'] / mn:6.3f}       {r['touchdown_x_m']:8.1f} m"
                  f"          {r['grounded_length_m']:6.1f} m  {r['wall_time_s']:5.1f} s  {r['rejected_steps']:3d}")
    print("paper (Fig. 20 text)                                general    0.5      2.8\n"
          "                                                    inclined  <0.4      2.2\n"
          "                                                    horizontal<0.4      2.4   [MN]")
    print("\nfindings of desire2023 Sec. 5, per seed (primary seed first):")
    order = sorted(results["seeds"], key=lambda e: e["seed"] != results["primary_seed"])
    for name, label in (("general_highest_dynamic_peak", "general projection has the highest dynamic peak"),
                        ("horizontal_total_above_inclined", "horizontal total peak > inclined total peak"),
                        ("general_highest_total", "general projection has the highest total peak"),
                        ("touchdowns_differ", "the three touchdown points differ (> 1 m)"),
                        ("inclined_touchdown_nearer_fairlead_than_horizontal",
                         "inclined touchdown nearer the fairlead than horizontal")):
        marks = []
        for entry in order:
            f = entry["findings"].get(name)
            marks.append("n/a" if f is None else ("PASS" if f["passed"] else "FAIL"))
        passed, total = results["robustness"].get(name, (0, 0))
        print(f"  {label:<58} {' '.join(f'{x:>4}' for x in marks)}   ({passed}/{total} seeds)")
    sweep = results["static_sweep"]
    print(f"\nstatics at the largest surge (fairlead x = {sweep['fairlead_x_m']:g} m), many realisations: "
          f"inclined {sweep['inclined']['tension_N'] / mn:.3f} MN, horizontal {sweep['horizontal']['tension_N'] / mn:.3f} MN")
    print("amplitude  seeds  roughness rms    general: median  [min, max] MN    > inclined  > horizontal  > both")
    for r in sweep["amplitudes"]:
        print(f"{r['amplitude_m']:7.0f} m  {r['seeds']:5d}  {r['roughness_rms_m'][0]:4.1f}-{r['roughness_rms_m'][1]:3.1f} m"
              f"      {r['general_median_N'] / mn:6.3f}  [{r['general_range_N'][0] / mn:.3f}, {r['general_range_N'][1] / mn:.3f}]"
              f"        {r['fraction_above_inclined']:5.0%}      {r['fraction_above_horizontal']:5.0%}      "
              f"{r['fraction_above_both']:4.0%}" + (f"   ({len(r['failures'])} failed)" if r["failures"] else ""))
    if "table6" in results:
        print_table6(results["table6"])
    print(f"\ntotal wall time {results['total_wall_time_s']:.0f} s")


def print_table6(c):
    """Table 6: wall and CPU times of the two horizontal-seabed models, their ratio, the tensions."""
    print(f"\nTable 6: horizontal seabed z = -{MEAN_DEPTH} m, {c['duration_s']:g} s simulated, "
          f"{c['elements']} elements, dt = {c['dt']} s; triangulated with {c['triangles']} triangles")
    for path, data in c["paths"].items():
        print(f"  {path}: " + ("the compiled kernel, as `cablefem run` (frames and tensions.csv written)"
                               if path == "run_scene" else "the reference numpy assembly, time loop only"))
        print("  repeat  wall: Horizontal  general [s]  ratio   CPU: Horizontal  general [s]  ratio"
              "   max rel. tension diff.  load average")
        for r in data["rows"]:
            h, g = r["horizontal"], r["general"]
            if not (h["completed"] and g["completed"]):
                print(f"  {r['repeat']:>6}  FAILED: {h['error'] or g['error']}")
                continue
            print(f"  {r['repeat']:>6}  {h['wall_time_s']:16.2f}  {g['wall_time_s']:11.2f}  {r['ratio']:5.3f}"
                  f"  {h['cpu_time_s']:15.2f}  {g['cpu_time_s']:11.2f}  {r['cpu_ratio']:5.3f}"
                  f"   {r['max_relative_tension_difference']:.2e}               "
                  f"{h['load_average']:.1f} / {g['load_average']:.1f}")
        print(f"  ratio general / horizontal: wall {data['ratio_mean']:.3f} (min {data['ratio_min']:.3f}, "
              f"max {data['ratio_max']:.3f}), CPU {data['cpu_ratio_mean']:.3f} (min {data['cpu_ratio_min']:.3f}, "
              f"max {data['cpu_ratio_max']:.3f}); paper {c['paper_ratio']:.3f} (11236 s vs 13488 s)")
    print(f"one projection call ({c['elements'] + 1} points, derivatives): plane "
          f"{c['projection_call_s']['horizontal'] * 1e6:.1f} us, triangulated "
          f"{c['projection_call_s']['general'] * 1e6:.1f} us (x{c['projection_call_ratio']:.1f})")
    if c.get("tree_changed_during_measurement"):
        print("  WARNING: cablefem/ changed while Table 6 was measured; the times mix two versions")
    same = c["max_relative_tension_difference"] <= 1e-8
    print(f"same tensions on both (<= 1e-8 relative): {'PASS' if same else 'FAIL'} "
          f"({c['max_relative_tension_difference']:.1e})")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse and short: what the tests run")
    parser.add_argument("--out", help="folder for results.json and the PNGs (default: next to this script; "
                                      "with --fast, nothing is written unless --out is given)")
    parser.add_argument("--runs", help="keep the runs (VTK frames, tensions.csv) in this folder")
    parser.add_argument("--convergence", action="store_true",
                        help="instead: the element / time-step study behind SETTINGS (convergence.json)")
    parser.add_argument("--table6", action="store_true",
                        help="instead: only Table 6, merged into the results.json already in --out (or here)")
    args = parser.parse_args(argv)
    if args.table6:
        target = Path(args.out or HERE)
        settings = SETTINGS["fast" if args.fast else "full"]
        runs = Path(tempfile.mkdtemp(prefix="irregular_seabed_cost_"))
        try:
            cost = cost_study(settings, runs)
        finally:
            shutil.rmtree(runs, ignore_errors=True)
        print_table6(cost)
        if (target / "results.json").is_file() and not args.fast:
            results = json.loads((target / "results.json").read_text())
            results["table6"] = study.jsonable(cost)
            study.write_json(target / "results.json", results)
            print(f"updated table6 in {target / 'results.json'}")
        return
    if args.convergence:
        study.write_json(Path(args.out or HERE) / "convergence.json", convergence(args.runs))
        return
    results = run(fast=args.fast, runs_dir=args.runs)
    print_report(results)
    target = args.out or (None if args.fast else HERE)
    if target is not None:
        written = write_outputs(results, target)
        print(f"wrote {', '.join(written)} to {target}")


if __name__ == "__main__":
    main()
