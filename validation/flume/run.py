"""The six desire2023 flume cases (Sec. 4, Figs. 12-17): three seabeds x two fairlead motions.

Run ``python -m validation.flume.run [--fast] [--out DIR] [--runs DIR] [--convergence | --sensitivity]
[--workers N | --scheduler ADDRESS]``;
``run(fast=True)`` returns the numbers tests/test_validation_flume.py asserts on.

The cases are the sweep files of this folder (``sweep.toml``, ``sweep_fast.toml``; docs/sweep.md):
the Table 5 line of ``flume.toml`` (the physics of ``cablefem.scenes.flume_scene``: prototype
scale, reconstructed steps, docs/seabeds.md) with each case's seabed, motion, elements and step,
run in parallel on Dask by ``cablefem.sweeps`` (``cablefem.run.run_scene`` in each worker) for the
ramp (one period) plus several periods, each into its own folder; the statistics are taken
over the last two periods: mean, max and min fairlead tension, the quasi-static "lowest tension
peak" (the minimum of the periodic tension, Figs. 12, 14, 16), the dynamic peak and range
(Figs. 13, 15, 17) and the touchdown position range. Three findings of the paper are checked:

1. quasi-static lowest peaks flat > gentle > steep (paper: ~2.5, 2.2, 2.0 MN);
2. dynamic tensions highest on the flat seabed, lower on gentle, lowest on steep;
3. the seabed matters more in the dynamic cases: the relative spread across
   seabeds of the dynamic peak exceeds that of the quasi-static tensions.

``--convergence`` runs instead the time-step and element study that chose the settings
(convergence.toml); ``--sensitivity`` the runs without friction and with a 4x slower
quasi-static motion (sensitivity.toml). ``--workers N`` sets the local cluster's size,
``--scheduler ADDRESS`` uses an existing Dask cluster; with ``--runs DIR`` a study stopped
half-way resumes where it stopped.
"""

import argparse
import dataclasses
import json
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem import study
from cablefem.post import read_tensions
from cablefem.scenes import FLUME_MOTIONS, FLUME_SEABEDS

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
    from cablefem.line import Line
    from cablefem.results import report as line_report
    from cablefem.run import build_system
    from cablefem.statics import solve_static

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


def run(fast=False, runs_dir=None, frames=True, cases=None, client=None):
    """Run the six cases (or ``cases``, a list of (seabed, motion)) of the fast or full sweep file in
    parallel (``run_sweep``); a dict of plain numbers, with the series under "_series" keys."""
    keep = runs_dir is not None
    runs_dir = Path(runs_dir) if keep else Path(tempfile.mkdtemp(prefix="cablefem-flume-"))
    started = study.provenance()
    start = time.perf_counter()
    results = run_sweep("fast" if fast else "full", runs_dir, frames=frames,
                        select=None if cases is None else set(cases), client=client)
    wall = time.perf_counter() - start
    settings = {c["motion"]: {"elements": c["elements"], "dt": c["dt"], "periods": c["periods"]} for c in results}
    return {"fast": fast, "settings": settings, "cases": results, "findings": findings(results),
            "wall_time_s": wall, "runs_dir": str(runs_dir), "runs_kept": keep,
            "provenance": study.stamp(started)}


def convergence(runs_dir, client=None):
    """Peak, lowest and mean fairlead tension of every case at each (elements, dt) of
    convergence.toml, over the last two of ramp + 3 periods."""
    return _study("convergence", runs_dir, client,
                  lambda c: f"{c['elements']:4d} el dt {c['dt']:<6g}", lambda c: f", {c['rejected_steps']} rejected")


def sensitivity(runs_dir, client=None):
    """What friction and the finite period do to the tensions: each variant of sensitivity.toml for
    each seabed, with the static tensions at the extreme surges."""
    return _study("sensitivity", runs_dir, client, lambda c: f"{c['variant']:22s}", lambda c: "")


def _study(name, runs_dir, client, setting, extra):
    """The rows of ``SWEEPS[name]`` without their series, each printed on a line."""
    rows = run_sweep(name, runs_dir, frames=False, client=client)
    for c in rows:
        c.pop("_series", None)
        print(f"  {c['seabed']:6s} {c['motion']:12s} {setting(c)} "
              + (f"max {c['max_N'] / MN:.4f} min {c['min_N'] / MN:.4f} mean {c['mean_N'] / MN:.4f} MN"
                 if c.get("completed") else f"FAILED {c['error']}")
              + f"  {c['wall_time_s']:.0f} s{extra(c)}", flush=True)
    return rows


def report_sensitivity(rows):
    """The sensitivity table, as text [MN]."""
    lines = ["sensitivity (80 P1 elements): fairlead tension over the last two periods [MN]; "
             "static: equilibrium at the smallest and largest surge",
             f"{'seabed':7s} {'motion':12s} {'variant':22s} {'min':>7s} {'max':>7s} {'mean':>7s} "
             f"{'static@min':>10s} {'static@max':>10s}"]
    for r in rows:
        if not r.get("completed"):
            lines.append(f"{r['seabed']:7s} {r['motion']:12s} {r['variant']:22s} FAILED: {r['error'] or r['status']}")
            continue
        lines.append(f"{r['seabed']:7s} {r['motion']:12s} {r['variant']:22s} {r['min_N'] / MN:7.4f} "
                     f"{r['max_N'] / MN:7.4f} {r['mean_N'] / MN:7.4f} {r['static_at_min_surge_N'] / MN:10.4f} "
                     f"{r['static_at_max_surge_N'] / MN:10.4f}")
    return "\n".join(lines)


def report(results):
    """The table of the six cases and the findings, as text."""
    lines = [f"desire2023 flume cases, {'fast' if results['fast'] else 'full'} settings "
             f"({_settings_words(results['settings'])}); statistics over the last two periods",
             f"{'seabed':7s} {'motion':12s} {'mean':>6s} {'max':>6s} {'min':>6s} {'range':>6s} "
             f"{'paper':>6s} {'touchdown x [m]':>17s} {'anchor max':>10s} {'wall':>6s} {'rej':>4s}",
             f"{'':7s} {'':12s} {'[MN]':>6s} {'[MN]':>6s} {'[MN]':>6s} {'[MN]':>6s} {'[MN]':>6s} "
             f"{'from .. to':>17s} {'[MN]':>10s} {'[s]':>6s} {'':>4s}"]
    for c in results["cases"]:
        if not c.get("completed"):
            lines.append(f"{c['seabed']:7s} {c['motion']:12s} FAILED: {c['error'] or c['status']}")
            continue
        paper = f"{PAPER_LOWEST_PEAK[c['seabed']] / MN:6.2f}" if c["motion"] == "quasi-static" else f"{'-':>6s}"
        td = (f"{c['touchdown_x_min_m']:7.1f} .. {c['touchdown_x_max_m']:6.1f}"
              if "touchdown_x_min_m" in c else f"{'-':>17s}")
        lines.append(f"{c['seabed']:7s} {c['motion']:12s} {c['mean_N'] / MN:6.3f} {c['max_N'] / MN:6.3f} "
                     f"{c['min_N'] / MN:6.3f} {c['range_N'] / MN:6.3f} {paper} {td:>17s} "
                     f"{c['anchor_max_N'] / MN:10.3f} {c['wall_time_s']:6.1f} {c['rejected_steps']:4d}")
    f = results["findings"]
    if "error" in f:
        lines.append(f["error"])
        return "\n".join(lines)
    mn = lambda values: ", ".join(f"{v / MN:.3f}" for v in values)  # noqa: E731
    q, d, s = f["quasi_static_lowest_peak_ordering"], f["dynamic_ordering"], f["dynamic_spread_larger"]
    r = s["relative_spreads"]
    word = lambda ok: "PASS" if ok else "FAIL"  # noqa: E731
    lines += [
        "findings (flat, gentle, steep):",
        f"  1. quasi-static lowest peak flat > gentle > steep: {word(q['passed'])}  "
        f"{mn(q['lowest_peak_N'])} MN (paper {mn(q['paper_N'])}; "
        + ", ".join(f"{100 * x:+.0f} %" for x in q["relative_difference_to_paper"]) + ")",
        f"  2. dynamic peak flat > gentle > steep:             {word(d['passed'])}  {mn(d['max_N'])} MN "
        f"(range {mn(d['range_N'])}: {'ordered' if d['range_ordered'] else 'NOT ordered'}; "
        f"mean {mn(d['mean_N'])}: {'ordered' if d['mean_ordered'] else 'NOT ordered'})",
        f"  3. seabed matters more in the dynamic cases:       {word(s['passed'])}  relative spread "
        f"(max - min)/mean across seabeds: dynamic peak {100 * r['dynamic_max']:.1f} % "
        f"{'>' if s['passed'] else 'not >'} quasi-static peak {100 * r['quasi_static_max']:.1f} % and "
        f"lowest peak {100 * r['quasi_static_lowest_peak']:.1f} % "
        f"(dynamic range {100 * r['dynamic_range']:.1f} %, means: dynamic {100 * r['dynamic_mean']:.1f} %, "
        f"quasi-static {100 * r['quasi_static_mean']:.1f} %; paper's quasi-static lowest peaks "
        f"{100 * q['paper_spread']:.1f} %)",
        f"wall time {results['wall_time_s']:.1f} s; {_provenance_words(results['provenance'])}",
    ]
    return "\n".join(lines)


def report_convergence(rows):
    """The convergence table, as text: per case and setting, max/min/mean [MN] and the change
    relative to the finest setting."""
    last = rows[-1]
    lines = ["convergence: fairlead tension over the last two of ramp + "
             f"{last['periods']} periods; change relative to {last['elements']} el, dt {last['dt']:g} s",
             f"{'seabed':7s} {'motion':12s} {'el':>4s} {'dt':>6s} {'max':>7s} {'dmax':>7s} {'min':>7s} "
             f"{'dmin':>7s} {'mean':>7s} {'dmean':>7s} {'wall':>6s} {'rej':>4s}"]
    for seabed in FLUME_SEABEDS:
        for motion in MOTIONS:
            group = [r for r in rows if r["seabed"] == seabed and r["motion"] == motion]
            ref = group[-1]
            for r in group:
                if not r.get("completed") or not ref.get("completed"):
                    lines.append(f"{seabed:7s} {motion:12s} {r['elements']:4d} {r['dt']:6g} "
                                 f"FAILED: {r['error'] or r['status']}")
                    continue
                rel = {k: 100 * (r[k] / ref[k] - 1) for k in ("max_N", "min_N", "mean_N")}
                lines.append(f"{seabed:7s} {motion:12s} {r['elements']:4d} {r['dt']:6g} "
                             f"{r['max_N'] / MN:7.4f} {rel['max_N']:+6.1f}% {r['min_N'] / MN:7.4f} "
                             f"{rel['min_N']:+6.1f}% {r['mean_N'] / MN:7.4f} {rel['mean_N']:+6.1f}% "
                             f"{r['wall_time_s']:6.1f} {r['rejected_steps']:4d}")
    return "\n".join(lines)


def figures(results, out):
    """PNGs in ``out``: fairlead tension against time (3 x 2 panels), one period of each motion
    with the three seabeds overlaid, and the line's profile over each seabed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from cablefem.geometry.generators import flume_step

    cases = {(c["seabed"], c["motion"]): c for c in results["cases"] if c.get("completed")}
    colours = {"flat": "tab:blue", "gentle": "tab:orange", "steep": "tab:green"}
    paths = []

    fig, axes = plt.subplots(3, 2, figsize=(13, 10), sharex="col")
    legend = []
    for i, seabed in enumerate(FLUME_SEABEDS):
        for j, motion in enumerate(MOTIONS):
            ax = axes[i, j]
            c = cases.get((seabed, motion))
            if c is None:
                ax.text(0.5, 0.5, "failed", transform=ax.transAxes, ha="center")
                continue
            s = c["_series"]
            m = FLUME_MOTIONS[motion]
            surge = ax.twinx()  # behind ax: the shading and the surge under the tensions
            surge.axvspan(*c["window_s"], color="0.93", label="last two periods (statistics)")
            surge.axvspan(0, m.ramp, color="#fff2cc", label="ramp")
            surge.plot(s["t"], [_surge(motion, t) for t in s["t"]], color="0.6", lw=0.7, label="fairlead surge")
            surge.set_ylabel("fairlead surge [m]", color="0.45")
            surge.tick_params(axis="y", colors="0.45")
            ax.set_zorder(surge.get_zorder() + 1)
            ax.patch.set_visible(False)
            ax.plot(s["t"], s["fairlead_tension"] / MN, color=colours[seabed], lw=0.9, label="fairlead")
            ax.plot(s["t"], s["anchor_tension"] / MN, color="0.5", lw=0.8, ls="--", label="anchor")
            ax.plot(c["t_max_s"], c["max_N"] / MN, "v", color="k", ms=6)
            ax.plot(c["t_min_s"], c["min_N"] / MN, "^", color="k", ms=6)
            ax.annotate(f"max {c['max_N'] / MN:.2f} MN", (c["t_max_s"], c["max_N"] / MN),
                        textcoords="offset points", xytext=(-70, 2), fontsize=8)
            ax.annotate(f"min {c['min_N'] / MN:.2f} MN", (c["t_min_s"], c["min_N"] / MN),
                        textcoords="offset points", xytext=(-70, -12), fontsize=8)
            if motion == "quasi-static":
                ax.axhline(PAPER_LOWEST_PEAK[seabed] / MN, color="crimson", ls=":", lw=1.2,
                           label="paper's lowest peak (Sec. 4.2)")
            ax.set_title(f"{seabed} seabed, {motion} ({_motion_words(motion)})", fontsize=10)
            ax.set_ylabel("tension [MN]")
            ax.grid(True, alpha=0.3)
            ax.margins(y=0.15)
            if not legend:
                legend = [a.get_legend_handles_labels() for a in (ax, surge)]
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    if legend:
        fig.legend(legend[0][0] + legend[1][0], legend[0][1] + legend[1][1],
                   loc="lower center", ncol=7, fontsize=8, frameon=False)
    fig.suptitle("cablefem, desire2023 flume cases (prototype scale; cf. Figs. 12-17)\n"
                 f"{_settings_words(results['settings'])}",
                 fontsize=11)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    paths.append(out / "tensions.png")
    fig.savefig(paths[-1], dpi=110)

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    for ax, motion in zip(axes, MOTIONS):
        period = FLUME_MOTIONS[motion].period
        for seabed in FLUME_SEABEDS:
            c = cases.get((seabed, motion))
            if c is None:
                continue
            s = c["_series"]
            keep = s["t"] >= c["duration_s"] - period - 1e-9
            phase = (s["t"][keep] - (c["duration_s"] - period)) / period
            ax.plot(phase, s["fairlead_tension"][keep] / MN, color=colours[seabed], label=seabed)
        if motion == "quasi-static":
            for seabed in FLUME_SEABEDS:
                ax.axhline(PAPER_LOWEST_PEAK[seabed] / MN, color=colours[seabed], ls=":", lw=1)
        surge = ax.twinx()
        grid = np.linspace(0, 1, 200)
        surge.plot(grid, _motion_state(FLUME_MOTIONS[motion], grid * period)[0], color="0.6", lw=0.8)
        surge.set_ylabel("fairlead surge [m] (grey)", color="0.5")
        ax.set_xlabel("time in the last period, t / T")
        ax.set_ylabel("fairlead tension [MN]")
        ax.set_title(f"{motion}: the three seabeds over one period"
                     + ("  (dotted: paper's lowest peaks)" if motion == "quasi-static" else ""), fontsize=10)
        ax.set_zorder(surge.get_zorder() + 1)
        ax.patch.set_visible(False)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    paths.append(out / "tensions_by_seabed.png")
    fig.savefig(paths[-1], dpi=110)

    fig, axes = plt.subplots(3, 2, figsize=(13, 9), sharex=True, sharey=True)
    x = np.linspace(-620.0, 30.0, 1301)
    for i, seabed in enumerate(FLUME_SEABEDS):
        bed = flume_step(seabed).elevation(np.column_stack([x, np.zeros_like(x)]))
        for j, motion in enumerate(MOTIONS):
            ax = axes[i, j]
            ax.fill_between(x, bed, -110, color="tan", alpha=0.6, label="seabed (y = 0)")
            c = cases.get((seabed, motion))
            if c is not None and "line_at_max" in c["_series"]:
                s = c["_series"]
                for key, label, style in (("line_at_max", f"at max tension {c['max_N'] / MN:.2f} MN", "-"),
                                          ("line_at_min", f"at min tension {c['min_N'] / MN:.2f} MN", "--")):
                    p = s[key]
                    ax.plot(p[:, 0], p[:, 2], style, color=colours[seabed], lw=1.3, label=label)
                ax.axvspan(c["touchdown_x_min_m"], c["touchdown_x_max_m"], color="k", alpha=0.12,
                           label=f"touchdown {c['touchdown_x_min_m']:.0f} .. {c['touchdown_x_max_m']:.0f} m")
            ax.set_ylim(-106, 2)
            ax.set_title(f"{seabed} seabed, {motion}", fontsize=10)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7, loc="upper left")
            if j == 0:
                ax.set_ylabel("z [m]")
    for ax in axes[-1]:
        ax.set_xlabel("x [m] (fairlead at x = 0 + surge)")
    fig.suptitle("line profile over the seabed (vertical scale exaggerated ~3x); shaded: touchdown range "
                 "over the last two periods", fontsize=11)
    fig.tight_layout()
    paths.append(out / "profiles.png")
    fig.savefig(paths[-1], dpi=110)
    plt.close("all")
    return paths


def render_frames(results, out, vertical_scale=3.0):
    """One pyvista frame per seabed: the quasi-static case at its lowest tension peak, the line
    coloured by tension [MN] over the seabed (vertical scale exaggerated), from the run's .pvd
    frames (``cablefem.post.load_run``). Returns the PNG paths."""
    import pyvista

    from cablefem.post import load_run

    pyvista.OFF_SCREEN = True
    paths = []
    for c in results["cases"]:
        if c["motion"] != "quasi-static" or not c.get("completed") or "frame_index_min" not in c["_series"]:
            continue
        times, frames, seabed = load_run(c["run_dir"])
        index = c["_series"]["frame_index_min"]
        line = frames[index].copy()
        line["tension [MN]"] = line["tension"] / MN
        plotter = pyvista.Plotter(off_screen=True, window_size=(1600, 700))
        if seabed is not None:
            plotter.add_mesh(seabed.clip_box((-640.0, 40.0, -80.0, 80.0, -200.0, 50.0), invert=False),
                             color="tan", opacity=0.8)
        plotter.add_mesh(line, scalars="tension [MN]", line_width=6, cmap="viridis",
                         scalar_bar_args={"title": "tension [MN]", "fmt": "%.2f", "n_labels": 5,
                                          "position_x": 0.06, "position_y": 0.72, "width": 0.4})
        plotter.set_scale(zscale=vertical_scale)
        plotter.view_xz()
        plotter.camera.elevation = 15
        plotter.camera.zoom(1.8)
        plotter.add_text(f"{c['seabed']} seabed, quasi-static, t = {times[index]:.1f} s: lowest tension peak, "
                         f"fairlead {c['lowest_peak_N'] / MN:.2f} MN, surge {c['surge_at_min_m']:.1f} m; "
                         f"vertical scale x{vertical_scale:g}; anchor at x = -595 m (left)", font_size=11)
        png = out / f"frame_{c['seabed']}.png"
        plotter.screenshot(str(png))
        plotter.close()
        paths.append(png)
    return paths


def _surge(motion, t):
    from cablefem.motion import fairlead_motion

    return float(fairlead_motion(FLUME_MOTIONS[motion], t)[0][0])


def _provenance_words(stamp):
    start = stamp["start"]
    where = start["git_head"] or f"at {start['cablefem_path']}, source digest {start['cablefem_sha256']}"
    words = f"cablefem {where}{' + uncommitted changes' if start['cablefem_dirty'] else ''}"
    return words + (" (CHANGED during the run)" if stamp["cablefem_changed_during_run"] else "")


def _settings_words(settings):
    return "; ".join(f"{motion} {v['elements']} P1 elements, dt {v['dt']:g} s, ramp + {v['periods']} periods"
                     for motion, v in settings.items())


def _motion_words(motion):
    m = FLUME_MOTIONS[motion]
    return f"T = {m.period:g} s, {m.amplitude[0]:g} m amplitude, {m.offset[0]:g} m drift"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="short runs, 20 elements, under a minute")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and PNGs")
    parser.add_argument("--runs", type=Path, default=None,
                        help="keep the runs (tensions.csv, .pvd frames) here; default: a temporary folder")
    parser.add_argument("--convergence", action="store_true",
                        help="run only the element/time-step study (~25 min): a table and convergence.json")
    parser.add_argument("--sensitivity", action="store_true",
                        help="run only the friction and period study (~10 min): a table and sensitivity.json")
    parser.add_argument("--workers", type=int, metavar="N", help="local Dask cluster: worker processes "
                        "(default: one per core)")
    parser.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask cluster instead")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    from cablefem.sweeps.engine import connect

    with connect(scheduler=args.scheduler, workers=args.workers) as client:
        studies(args, client)


def studies(args, client):
    """The studies ``main``'s arguments ask for, on the Dask ``client``."""
    for wanted, measure, table, name in ((args.convergence, convergence, report_convergence, "convergence"),
                                         (args.sensitivity, sensitivity, report_sensitivity, "sensitivity")):
        if not wanted:
            continue
        runs = args.runs or Path(tempfile.mkdtemp(prefix=f"cablefem-flume-{name}-"))
        started, start = study.provenance(), time.perf_counter()
        try:
            rows = measure(runs, client=client)
        finally:
            if args.runs is None:
                shutil.rmtree(runs, ignore_errors=True)
        print(table(rows))
        print(f"wall time {time.perf_counter() - start:.0f} s")
        study.write_json(args.out / f"{name}.json",
                         {"provenance": study.stamp(started), "wall_time_s": time.perf_counter() - start, "rows": rows})
    if args.convergence or args.sensitivity:
        return
    results = run(fast=args.fast, runs_dir=args.runs, client=client)
    try:
        print(report(results))
        study.write_json(args.out / "results.json", results)
        pngs = figures(results, args.out) + render_frames(results, args.out)
        print(f"wrote {args.out / 'results.json'} and {len(pngs)} PNGs")
    finally:
        if not results["runs_kept"]:
            shutil.rmtree(results["runs_dir"], ignore_errors=True)


if __name__ == "__main__":
    main()
