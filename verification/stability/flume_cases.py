"""The cases of verification/stability on the flume line: 2. snap loads, 3. the steep step's convex
edge, 5. a sudden stop, 6. time steps from 1e-4 to 0.1 s through ``run_scene``."""

import csv
import json
import os
import tempfile

import numpy as np

from cablefem.errors import ConvergenceError
from cablefem.model.line import Line
from cablefem.model.motion import fairlead_motion
from cablefem.fem.system import build_system
from cablefem.runs.run import run_scene
from cablefem.model.scene import Friction, Motion, Output
from cablefem.model.builtin import FLUME_ANCHOR, FLUME_DEPTH, flume_scene
from cablefem.statics.solve import solve_static

from verification.stability.driver import flume_like, sample, series, simulate, summary

# -- 2. snap loads

SNAP_AMPLITUDE = 7.5  # m: 1.5 x the paper's dynamic motion; the upper line goes slack each period


def snap_scene(dt, duration, friction=True):
    """The flume's flat floor driven at 7.5 m / 6 s (ramped over the first period)."""
    scene = flume_scene("flat", "dynamic", duration=duration, dt=dt)
    scene.motion = Motion(kind="harmonic", amplitude=(SNAP_AMPLITUDE, 0.0, 0.0), period=6.0, ramp=6.0)
    if not friction:
        scene.friction = Friction()
    return scene


class SlackMonitor:
    """Largest fraction of the suspended elements that are slack (strain <= 0) at any step."""

    def __init__(self, depth=FLUME_DEPTH, clearance=1.0):
        self.depth, self.clearance = depth, clearance
        self.fraction = 0.0

    def __call__(self, integ):
        system = integ.system
        strain = system.tension_strain(integ.X)
        r, _ = system.fem.at_quadrature(integ.X, system.fem.reduced)
        suspended = r[2] > -self.depth + self.clearance
        if np.any(suspended):
            self.fraction = max(self.fraction, float(np.mean(strain[suspended] <= 0.0)))


def run_snap(fast):
    """Case 2: snap loads; peak tension against dt and the energy balance."""
    duration = 12.0 if fast else 24.0
    steps = (0.02, 0.01, 0.005) if fast else (0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125)
    rows, runs = [], []
    for dt in steps:
        monitor = SlackMonitor()
        run = simulate(snap_scene(dt, duration), dt, duration, monitor=monitor)
        row = summary(run)
        row["slack_fraction"] = monitor.fraction
        row["peak_per_period"] = [float(run["fairlead_tension"][(run["t"] > 6.0 * k) & (run["t"] <= 6.0 * (k + 1))].max())
                                  for k in range(int(round(duration / 6.0)))]
        rows.append(row)
        runs.append(run)
    finest = rows[-1]["peak_tension"]
    errors = [r["peak_tension"] / finest - 1.0 for r in rows[:-1]]
    for row, error in zip(rows, errors + [0.0]):
        row["peak_error_vs_finest"] = error
    return {"duration_s": duration, "amplitude_m": SNAP_AMPLITUDE, "rows": rows,
            "series": {f"dt={r['dt']:g}": series(r) for r in runs}}


# -- 3. the steep step's edge

EDGE_X = -200.0  # m, the steep step's convex top (cablefem.geometry.generators.flume_step)


class EdgeMonitor:
    """Changes of contact state per step at the quadrature points within ``reach`` [m] of the
    convex edge: chatter shows as points flipping in and out of contact every step."""

    def __init__(self, reach=25.0):
        self.reach = reach
        self.previous = None
        self.changes = 0
        self.steps = 0

    def __call__(self, integ):
        system = integ.system
        r, _ = system.fem.at_quadrature(integ.X)
        points = r.reshape(3, -1).T
        near = np.abs(points[:, 0] - EDGE_X) <= self.reach
        touching = system.seabed.gap_only(points) < 0.0
        if self.previous is not None:
            self.changes += int(np.sum((touching != self.previous) & near))
            self.steps += 1
        self.previous = touching


def run_edge(fast):
    """Case 3: the steep step's convex edge under both flume motions, three dt."""
    motions = {"quasi-static": 17.0 if fast else 34.0, "dynamic": 12.0 if fast else 18.0}
    steps = (0.02,) if fast else (0.05, 0.02, 0.01)
    rows = []
    series_out = {}
    for motion, duration in motions.items():
        for dt in steps:
            monitor = EdgeMonitor()
            run = simulate(flume_scene("steep", motion, duration=duration, dt=dt), dt, duration, monitor=monitor)
            row = summary(run)
            row.update(motion=motion, edge_contact_changes=monitor.changes,
                       edge_changes_per_step=monitor.changes / max(monitor.steps, 1))
            rows.append(row)
            series_out[f"{motion} dt={dt:g}"] = series(run)
    for motion in motions:
        mine = [r for r in rows if r["motion"] == motion]
        finest = mine[-1]["peak_tension"]
        for row in mine:
            row["peak_difference_vs_finest"] = row["peak_tension"] / finest - 1.0
    return {"durations_s": motions, "rows": rows, "series": series_out}


# -- 5. sudden stop

STOP_SPEED, STOP_DISTANCE, STOP_START = 1.0, 10.0, 2.0  # m/s, m, s


def stop_scene(dt, duration):
    """The flume line on its flat floor, frictionless (so that the static end state is unique):
    at rest for 2 s, then the fairlead moves away from the anchor at 1 m/s for 10 m and stops
    dead (a velocity jump at both ends of the stroke: a table joined by straight lines)."""
    end = STOP_START + STOP_DISTANCE / STOP_SPEED
    motion = Motion(kind="table", times=np.array([0.0, STOP_START, end, end + 1e3]),
                    positions=np.array([[0, 0, 0], [0, 0, 0], [STOP_DISTANCE, 0, 0], [STOP_DISTANCE, 0, 0]], float),
                    interpolation="linear")
    return flume_like("stop", FLUME_ANCHOR, (0.0, 0.0, 0.0), motion, friction=False, dt=dt, duration=duration), end


def run_stop(fast):
    """Case 5: ring-down after a dead stop; decay of the tension's deviation from the static value."""
    duration = 32.0 if fast else 62.0
    steps = (0.02,) if fast else (0.05, 0.01)
    rows, runs = [], []
    for dt in steps:
        scene, stop = stop_scene(dt, duration)
        run = simulate(scene, dt, duration)
        line = scene.lines[0]
        final = fairlead_motion(scene.motion, duration)[0]
        moved = Line(line.name, line.anchor, line.fairlead + final, line.segments, line.order)
        system = build_system(scene, moved, dynamic=False)
        X = solve_static(system, tolerance=scene.solver.tolerance).X
        static = float(np.linalg.norm(system.residual(X)[system.fem.fairlead_dof]))
        t, T = run["t"], run["fairlead_tension"]
        windows = []
        for k in range(int((duration - stop) // 5)):
            inside = (t > stop + 5 * k) & (t <= stop + 5 * (k + 1))
            if np.any(inside):
                windows.append({"from_s": 5.0 * k, "to_s": 5.0 * (k + 1),
                                "max_deviation_N": float(np.max(np.abs(T[inside] - static)))})
        deviations = np.array([w["max_deviation_N"] for w in windows])
        # e-folding time of the envelope: a line fitted to log(deviation) over the windows
        usable = deviations > 1e-6 * static
        rate = -np.polyfit([5.0 * k + 2.5 for k in range(len(windows))], np.log(deviations), 1)[0] \
            if usable.sum() >= 2 else None
        row = summary(run)
        row.update(static_tension=static, overshoot=float(np.max(T[t > stop]) / static - 1.0),
                   final_error=float(T[-1] / static - 1.0), windows=windows,
                   envelope_decay_time_s=(1.0 / rate) if rate and rate > 0 else None)
        rows.append(row)
        runs.append(run)
    return {"duration_s": duration, "speed_m_s": STOP_SPEED, "stroke_m": STOP_DISTANCE,
            "stop_s": STOP_START + STOP_DISTANCE / STOP_SPEED, "rows": rows,
            "series": {f"dt={r['dt']:g}": series(r) for r in runs}}


# -- 6. 1e-4 s to 0.1 s

def run_steps(fast):
    """Case 6: the snap scene from dt = 1e-4 to 0.1 s through ``run_scene`` (the user's path,
    with its output frames): every run completes or stops with a message; the files it wrote
    are read back and checked for NaN and for tensions no line can carry; error against a run
    in plain fixed steps of the finest dt (``simulate``, no output frames), and cost per dt."""
    duration = 8.0 if fast else 12.0
    steps = (0.005, 0.01, 0.05, 0.1) if fast else (1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.03, 0.1)
    finest = 0.002 if fast else 1e-4
    grid = np.arange(0.0, duration + 1e-9, 0.1)
    reference = simulate(snap_scene(finest, duration), finest, duration, energy=False)
    ref = sample(reference, grid)
    scale = float(np.mean(ref))
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for dt in steps:
            out = os.path.join(scratch, f"dt{dt:g}")
            scene = snap_scene(dt, duration)
            scene.output = Output(dir=out, every=0.5)
            row = {"dt": dt}
            try:
                run_scene(scene, out_dir=out, progress=False)
                row["status"] = "completed"
            except ConvergenceError as error:
                row["status"] = f"stopped: {error}"
            with open(os.path.join(out, "summary.json")) as handle:
                written = json.load(handle)
            with open(os.path.join(out, "tensions.csv")) as handle:
                table = np.array([[float(x) for x in r] for r in list(csv.reader(handle))[1:]])
            t, T = table[:, 0], table[:, 1]
            ok = grid <= t[-1] + 1e-9
            difference = np.interp(grid[ok], t, T) - ref[ok]
            row.update(wall_time_s=written["wall_time_s"], steps=written["steps"],
                       newton_iterations=written["newton_iterations"],
                       rejected=sum(s["rejected"] for s in written["integrator"]),
                       simulated_s=written["simulated_time_s"], summary_status=written["status"],
                       rows_written=len(table), nan_in_outputs=bool(not np.all(np.isfinite(table)))
                       or "nan" in json.dumps(written).lower(),
                       largest_tension_written=float(np.max(T)), shortest_step_written=float(np.min(np.diff(t))),
                       rms_error_vs_finest=float(np.sqrt(np.mean(difference**2)) / scale),
                       peak_error_vs_finest=float(np.max(T) / reference["peak_tension"] - 1.0))
            rows.append(row)
    return {"duration_s": duration, "reference_dt": finest, "reference_status": reference["status"],
            "reference_peak_tension": reference["peak_tension"], "rows": rows}
