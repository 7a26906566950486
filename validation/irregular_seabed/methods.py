"""The line on each seabed model of validation/irregular_seabed: one dynamic run per model and seed,
the paper's findings checked on them and over the seeds, the static sweep over realisations, and
the element / time-step study behind ``SETTINGS``."""

import shutil
import tempfile
from pathlib import Path

import numpy as np

from cablefem.geometry import TriangulatedSurface
from cablefem.model.line import Line
from cablefem.post import read_tensions

from validation.irregular_seabed.model import (CENTRE, CONTACT, ENVIRONMENT, LENGTH, METHODS, MOTION, PERIOD,
                                               PRIMARY_SEED, SNAPSHOT_T, STEADY_FROM, frame_at, grounded_length,
                                               line_on, run_scene_quiet, scene_on, seabed_grid, seabed_models,
                                               surface_statistics, touchdown)


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


def static_tension(seabed, elements, fairlead_x):
    """(fairlead tension [N], touchdown x [m]) of the line in static equilibrium with its
    fairlead at (fairlead_x, 0, 0) [m], solved as ``cablefem static`` does with ``[solver]
    fit_touchdown = true`` (``solve_line``)."""
    from cablefem.runs.results import report
    from cablefem.statics.touchdown import solve_line

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


def robustness(seeds):
    """How many seeds satisfy each finding: dict finding -> [passed, checked]."""
    counts = {}
    for entry in seeds:
        for name, finding in entry["findings"].items():
            if isinstance(finding, dict) and "passed" in finding:
                passed, total = counts.get(name, (0, 0))
                counts[name] = (passed + int(finding["passed"]), total + 1)
    return {name: list(v) for name, v in counts.items()}


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
