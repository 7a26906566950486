"""The flume cases of validation/flume: run as the cases of a sweep file, and each case's statistics
over its last two periods (tensions, touchdown range) read from its run folder; the paper's findings
checked on them."""

import dataclasses
import json
from pathlib import Path

import numpy as np

from cablefem.post import read_tensions
from cablefem.model.builtin import FLUME_MOTIONS, FLUME_SEABEDS

HERE = Path(__file__).resolve().parent
MOTIONS = tuple(FLUME_MOTIONS)  # ("quasi-static", "dynamic")
MN = 1e6

#: desire2023 Sec. 4.2: quasi-static lowest tension peaks read off Figs. 12, 14, 16 [N]
PAPER_LOWEST_PEAK = {"flat": 2.5e6, "gentle": 2.2e6, "steep": 2.0e6}

#: the sweep files (cablefem.sweeps, docs/sweep.md) holding the cases: the six cases at the settings
#: of the convergence study ("full", README) or the cheapest that keep the findings ("fast"), the
#: convergence study itself and the sensitivity runs
SWEEPS = {"full": HERE / "sweep.toml", "fast": HERE / "sweep_fast.toml",
          "convergence": HERE / "convergence.toml", "sensitivity": HERE / "sensitivity.toml"}


def touchdown_x(points, gap):
    """x [m] of the touchdown point of one frame: the last point from the anchor with
    seabed gap <= 0, refined linearly towards the next point; NaN without contact."""
    touching = np.flatnonzero(gap <= 0.0)
    if touching.size == 0:
        return float("nan")
    k = touching[-1]
    if k == len(gap) - 1:
        return float(points[k, 0])
    g0, g1 = gap[k], gap[k + 1]
    return float(points[k, 0] + (points[k + 1, 0] - points[k, 0]) * g0 / (g0 - g1))


def read_frames(out_dir, t_from):
    """Index of the first frame at t >= t_from [s], and the times (k,), line points (k, m, 3)
    and seabed gaps (k, m) of the frames from there on."""
    import meshio

    from cablefem.io.vtk import read_collection

    pvd = next(Path(out_dir).glob("*.pvd"))
    times, files = read_collection(str(pvd))
    keep = times >= t_from - 1e-9
    meshes = [meshio.read(f) for f, k in zip(files, keep) if k]
    return (int(np.argmax(keep)), times[keep], np.array([m.points for m in meshes]),
            np.array([m.point_data["seabed_gap"] for m in meshes]))


def _motion_state(m, t):
    """Fairlead surge [m] and surge velocity [m/s] of the harmonic motion ``m`` at times t (k,)
    after the ramp."""
    omega = 2 * np.pi / m.period
    return (m.offset[0] + m.amplitude[0] * np.sin(omega * t),
            m.amplitude[0] * omega * np.cos(omega * t))


def static_tension(scene, surge):
    """Static fairlead tension [N] of the scene's line with its fairlead moved by ``surge`` [m]
    along x (no friction, drag or inertia): the quasi-static limit of a case."""
    from cablefem.model.line import Line
    from cablefem.runs.results import report as line_report
    from cablefem.fem.system import build_system
    from cablefem.statics.solve import solve_static

    line = scene.lines[0]
    moved = Line(line.name, line.anchor, line.fairlead + np.array([surge, 0.0, 0.0]), line.segments, line.order)
    system = build_system(scene, moved, dynamic=False)
    return line_report(system, solve_static(system).X).fairlead_tension


def run_sweep(name, runs_dir, frames=True, select=None, client=None):
    """Run the cases of ``SWEEPS[name]`` (those whose (seabed, motion) tags ``select`` holds, or all)
    on Dask into ``runs_dir`` (``cablefem.sweeps``: a LocalCluster unless ``client`` is given;
    cases done there before are read back, not run again), and return each case's statistics."""
    from cablefem.sweeps import read_sweep
    from cablefem.sweeps import run as run_cases

    spec = read_sweep(SWEEPS[name])
    if select is not None:
        spec = dataclasses.replace(spec, cases=[c for c in spec.cases
                                                if (c.tags["tag.seabed"], c.tags["tag.motion"]) in select])
    table = run_cases(spec, out=str(runs_dir), client=client, progress=False)
    rows = {row["case"]: row for row in table.to_dict("records")}
    return [case_statistics(spec, case, rows[case.index], Path(runs_dir), frames) for case in spec.cases]


def case_statistics(spec, case, row, runs_dir, frames=True):
    """Statistics of one case of a flume sweep over its last two periods (dict, SI units), from its
    folder (tensions.csv, summary.json and, with ``frames``, the VTK frames); the series themselves
    under the private key "_series"."""
    from cablefem.io.toml_scene import read_toml_scene

    scene = read_toml_scene(spec.base, case.data)
    moving, length = scene.motion, scene.solver.duration
    period = moving.period
    out_dir = runs_dir / row["dir"]
    error = None if row["status"] == "ok" else row["error"]
    written = out_dir / "summary.json"  # run_scene writes one unless it failed before stepping
    summary = json.loads(written.read_text()) if written.is_file() else {
        "status": f"stopped before the first step: {error}", "wall_time_s": float("nan"), "steps": 0,
        "integrator": [], "newton_iterations": 0}
    stats = {
        "seabed": case.tags["tag.seabed"], "motion": case.tags["tag.motion"],
        "elements": scene.lines[0].segments[0].elements, "dt": scene.solver.dt, "duration_s": length,
        "periods": int(round((length - moving.ramp) / period)), "friction": scene.friction.model,
        "window_s": [float(length - 2 * period), float(length)], "period_s": period,
        "status": summary["status"], "error": error,
        "wall_time_s": summary["wall_time_s"], "steps": summary["steps"],
        "rejected_steps": sum(s["rejected"] for s in summary["integrator"]),
        "newton_iterations": summary["newton_iterations"], "run_dir": str(out_dir),
    }
    if "tag.variant" in case.tags:
        stats["variant"] = case.tags["tag.variant"]
    if not (out_dir / "tensions.csv").is_file():
        return {**stats, "completed": False}
    data = read_tensions(out_dir)
    t, tension, anchor = data["t"], data["fairlead_tension"], data["anchor_tension"]
    if error is not None or not np.all(np.isfinite(tension)) or t[-1] < length - 1e-6:
        return {**stats, "completed": False}
    stats.update(window_statistics(scene, t, tension, anchor))
    series = {"t": t, "fairlead_tension": tension, "anchor_tension": anchor}
    if frames:
        stats.update(touchdown_statistics(out_dir, stats, series))
    stats["_series"] = series
    return stats


def window_statistics(scene, t, tension, anchor):
    """Fairlead tension over the last two periods of a run (t (n,) [s], tension and anchor tension
    (n,) [N]): mean, extremes and their times and surges, the static tensions at the extreme
    surges, and the extremes of each of the two periods."""
    moving, length = scene.motion, scene.solver.duration
    period = moving.period
    window = t >= length - 2 * period - 1e-9
    w_t, w_T = t[window], tension[window]
    i_max, i_min = int(np.argmax(w_T)), int(np.argmin(w_T))
    surge, velocity = _motion_state(moving, w_t)
    return {
        "completed": True,
        "mean_N": float(w_T.mean()), "max_N": float(w_T[i_max]), "min_N": float(w_T[i_min]),
        "range_N": float(w_T[i_max] - w_T[i_min]),
        "lowest_peak_N": float(w_T[i_min]),  # the minimum of the periodic tension (Figs. 12, 14, 16)
        "t_max_s": float(w_t[i_max]), "t_min_s": float(w_t[i_min]),
        "surge_at_max_m": float(surge[i_max]), "surge_velocity_at_max_m_s": float(velocity[i_max]),
        "surge_at_min_m": float(surge[i_min]),
        "anchor_max_N": float(anchor[window].max()), "anchor_min_N": float(anchor[window].min()),
        # the quasi-static limit: static equilibrium at the extreme surges
        "static_at_min_surge_N": static_tension(scene, moving.offset[0] - moving.amplitude[0]),
        "static_at_max_surge_N": static_tension(scene, moving.offset[0] + moving.amplitude[0]),
        # repeatability: the two periods of the window, max and min each
        "period_max_N": [float(w_T[w_t < length - period].max()), float(w_T[w_t >= length - period].max())],
        "period_min_N": [float(w_T[w_t < length - period].min()), float(w_T[w_t >= length - period].min())],
    }


def touchdown_statistics(out_dir, stats, series):
    """Touchdown range over the window from the run's frames, and the line at the extremes (added to
    ``series``)."""
    first, f_t, points, gaps = read_frames(out_dir, stats["window_s"][0])
    x_td = np.array([touchdown_x(p, g) for p, g in zip(points, gaps)])
    k_max, k_min = int(np.argmin(np.abs(f_t - stats["t_max_s"]))), int(np.argmin(np.abs(f_t - stats["t_min_s"])))
    series.update({"frame_t": f_t, "touchdown_x": x_td, "line_at_max": points[k_max],
                   "line_at_min": points[k_min], "frame_index_min": first + k_min})
    return {"touchdown_x_min_m": float(np.nanmin(x_td)), "touchdown_x_max_m": float(np.nanmax(x_td)),
            "touchdown_x_at_max_tension_m": float(x_td[k_max]), "touchdown_x_at_min_tension_m": float(x_td[k_min]),
            "element_length_m": 635.0 / stats["elements"]}


def _spread(values):
    """Relative spread (max - min) / mean of a sequence of tensions [-]."""
    values = np.asarray(values, dtype=float)
    return float((values.max() - values.min()) / values.mean())


def findings(cases):
    """The three qualitative findings of desire2023 Sec. 4.2, checked: a dict with the
    numbers and ``passed`` for each."""
    by = {(c["seabed"], c["motion"]): c for c in cases}
    if not all(c.get("completed") for c in cases):
        return {"error": "not every case completed; no findings checked"}
    qs_low = [by[s, "quasi-static"]["lowest_peak_N"] for s in FLUME_SEABEDS]
    qs_max = [by[s, "quasi-static"]["max_N"] for s in FLUME_SEABEDS]
    qs_mean = [by[s, "quasi-static"]["mean_N"] for s in FLUME_SEABEDS]
    dyn_max = [by[s, "dynamic"]["max_N"] for s in FLUME_SEABEDS]
    dyn_range = [by[s, "dynamic"]["range_N"] for s in FLUME_SEABEDS]
    dyn_mean = [by[s, "dynamic"]["mean_N"] for s in FLUME_SEABEDS]
    decreasing = lambda v: bool(v[0] > v[1] > v[2])  # noqa: E731  flat > gentle > steep
    paper = [PAPER_LOWEST_PEAK[s] for s in FLUME_SEABEDS]
    spreads = {"quasi_static_lowest_peak": _spread(qs_low), "quasi_static_max": _spread(qs_max),
               "quasi_static_mean": _spread(qs_mean), "dynamic_max": _spread(dyn_max),
               "dynamic_range": _spread(dyn_range), "dynamic_mean": _spread(dyn_mean)}
    return {
        "seabeds": list(FLUME_SEABEDS),
        "quasi_static_lowest_peak_ordering": {
            "passed": decreasing(qs_low), "lowest_peak_N": qs_low, "paper_N": paper,
            "relative_difference_to_paper": [float(a / b - 1) for a, b in zip(qs_low, paper)],
            "paper_spread": _spread(paper)},
        "dynamic_ordering": {
            "passed": decreasing(dyn_max), "max_N": dyn_max,
            "range_N": dyn_range, "range_ordered": decreasing(dyn_range),
            "mean_N": dyn_mean, "mean_ordered": decreasing(dyn_mean)},
        "dynamic_spread_larger": {
            # like for like (the peak in both motions) and against the quantity the paper
            # quotes for the quasi-static cases (the lowest peak): both must hold
            "passed": bool(spreads["dynamic_max"] > max(spreads["quasi_static_max"],
                                                         spreads["quasi_static_lowest_peak"])),
            "relative_spreads": spreads,
            "absolute_spreads_N": {"quasi_static_lowest_peak": float(np.ptp(qs_low)),
                                   "quasi_static_max": float(np.ptp(qs_max)),
                                   "dynamic_max": float(np.ptp(dyn_max))}},
    }
