"""Speed against error (work-precision) on the flat flume chain: cablefem's element orders, element
counts, time steps and integrators against MoorDyn-C's segment counts and time steps, in one run.

The case is desire2023's Table 5 chain over the flat 100 m seabed (``cablefem.scenes.flume_scene``
"flat"; MoorDyn reads the same line from ``validation/moordyn/inputs/flume_flat.dat``) under two
fairlead motions, each ramped in over its first period:

    slow-surge   17 s period, 2.5 m amplitude, 15 m offset   51 s simulated (ramp + 2 periods)
    snap          6 s period, 5 m amplitude (snap loads)      36 s simulated (6 periods)

Error of a run = RMS over the last two periods of (its fairlead tension - the reference's), at the
run's own output times (the reference interpolated there), divided by the reference's mean
tension over the window (``validation.moordyn.run.differences``). Each code is measured against
its own finest run (the README says why): cablefem against P3 elements at the finest mesh and
step, MoorDyn against 640 segments at dtM = 1e-4 s. The two finest runs' difference is the model
floor, reported apart. Wall times: cablefem's whole run (statics, set-up, steps), warmed up (numba
compiled); MoorDyn's Init plus the time spent inside ``moordyn.Step`` (the peer's Python
bookkeeping between calls is left out, in MoorDyn's favour), its initial-condition solve
skipped (TmaxIC = 0, in MoorDyn's favour: ``ic_check`` measures what that changes in the window,
< 1e-5). MoorDyn's largest stable dtM per segment count is found by trying the divisors of the
0.01 s coupling step downwards from twice the axial-wave CFL limit. Cheap runs of both codes are
repeated and their least wall time kept (``REPEATS``).

cablefem's runs are the cases of a sweep file (``sweep.toml``, ``sweep_fast.toml``; ``runs.py``)
run on Dask by ``cablefem.sweeps``: the untimed ones (references, checks, time order) in parallel,
the timed rows one at a time (``alone``); MoorDyn's runs follow in this process, alone too.

Run ``python -m verification.work_precision.run [--fast] [--out DIR] [--replot] [--runs DIR]
[--workers N | --scheduler ADDRESS]``;
``run(fast=True)`` (the snap sweep on coarse settings over 18 s and the slow-surge time order over
20 s, ~35 s) returns what tests/test_work_precision.py asserts.
"""

import argparse
import contextlib
import cProfile
import io
import json
import pstats
import sys
import time
import shutil
import tempfile
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python verification/work_precision/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.scenes import FLUME_MOTIONS, flume_scene, table5_chain  # noqa: E402
from validation.moordyn.run import (COUPLING_DT, FLUME_FILE_SEGMENTS, FLUME_LENGTH,  # noqa: E402
                                    differences, run_moordyn_case)
from verification.work_precision.runs import (REPEATS, CablefemSettings, cablefem_runs,  # noqa: E402,F401
                                              least_time, run_cablefem_scene)

HERE = Path(__file__).resolve().parent
MOORDYN_FILE = HERE.parents[1] / "validation" / "moordyn" / "inputs" / "flume_flat.dat"
#: study name -> cablefem.scenes motion name
MOTIONS = {"slow-surge": "quasi-static", "snap": "dynamic"}
WINDOW_PERIODS = 2
#: the looser Newton tolerance of the sweep ([solver] tolerance; the scenes' default is 1e-8); the
#: sweep runs both at the steps they share, so the tables show what it changes
LOOSE_NEWTON = 1e-4
#: MoorDyn time steps tried: divisors of the coupling step, so that every substep has the same dtM
DTM_DIVISORS = (1, 2, 4, 5, 8, 10, 16, 20, 25, 32, 40, 50, 64, 80, 100, 125, 160, 200)


@dataclass(frozen=True)
class MoordynSettings:
    """One MoorDyn run: segments and dtM [s]."""

    segments: int
    dtM: float

    def label(self):
        return f"{self.segments} segments, dtM {self.dtM:.3g}"


# ----------------------------------------------------------------------------- the plan
def plan(fast):
    """Per motion, MoorDyn's part of the study: its reference, the initial-condition check, the
    segment counts with how many stable steps to keep each, and the repeats of its timed runs
    (cablefem's runs are in the sweep files, ``runs.py``)."""
    if fast:
        return {"snap": {"moordyn_reference": MoordynSettings(160, 1e-3), "moordyn_segments": {20: 2, 40: 2, 80: 1},
                         "repeats": ()},  # the tests assert no timings
                "slow-surge": {}}
    full = {"moordyn_reference": MoordynSettings(640, 1e-4), "ic_check": MoordynSettings(80, 0.0025),
            "moordyn_segments": {20: 3, 40: 3, 80: 3, 160: 2, 320: 2}}
    return {"slow-surge": dict(full), "snap": dict(full)}


# ----------------------------------------------------------------------------- runners
def run_cablefem(motion, duration, settings):
    """cablefem on the flat flume scene with ``settings`` (``runs.run_cablefem_scene``: t, tension,
    wall time and counters, or ``failed``); for the warm-up and the profile, in this process."""
    s = settings
    scene = flume_scene("flat", MOTIONS[motion], s.elements, s.order, duration, s.dt)
    scene.solver = replace(scene.solver, integrator=s.integrator, adaptive=s.adaptive,
                           error_tolerance=s.error_tolerance, rho_inf=s.rho_inf, tolerance=s.tolerance,
                           newton=s.newton)
    return run_cablefem_scene(scene)


@contextlib.contextmanager
def moordyn_step_clock():
    """Inside the block, ``moordyn.Step`` adds the seconds it spends to the yielded list's item 0."""
    import moordyn

    step = moordyn.Step
    spent = [0.0]

    def timed(*args):
        begin = time.perf_counter()
        try:
            return step(*args)
        finally:
            spent[0] += time.perf_counter() - begin

    moordyn.Step = timed
    try:
        yield spent
    finally:
        moordyn.Step = step


def run_moordyn(motion, duration, settings, tension_limit=np.inf, initial_condition=False):
    """MoorDyn-C on the flat flume file with ``settings``, its initial-condition solve skipped
    (with ``initial_condition``: the file's, threshIC 1e-5): dict of t (n,) [s],
    tension (n,) [N] on the fairlead point (end-node inertia subtracted: the force cablefem
    reports), tension_raw (MoorDyn's own), wall_time_s (Init + inside Step), peer_wall_time_s
    (the peer's whole loop), or {"stable": False} when MoorDyn fails, returns a non-finite
    tension or one above ``tension_limit`` [N]."""
    scene = flume_scene("flat", MOTIONS[motion])
    factor = settings.segments / FLUME_FILE_SEGMENTS
    with moordyn_step_clock() as spent:
        try:
            result = run_moordyn_case(MOORDYN_FILE, scene, duration,
                                      {"segments": factor, "dtM": settings.dtM, "ic_dtM": None},
                                      options={} if initial_condition else {"TmaxIC": 0.0})
        except Exception:  # MoorDyn raises on NaN node positions
            return {"stable": False, "wall_time_s": spent[0]}
    tension = np.linalg.norm(result["forces_on_point"][:, 0], axis=1)
    stable = bool(np.all(np.isfinite(tension)) and tension.max() <= tension_limit)
    own = result["init_time_s"] + spent[0]
    # t = 0 dropped: with its IC skipped MoorDyn reports no force before its first step
    return {"stable": stable, "t": result["t"][1:], "tension": tension[1:],
            "tension_raw": result["tensions"][1:, 0], "wall_time_s": own,
            "peer_wall_time_s": result["wall_time_s"]}


def moordyn_candidates(segments):
    """dtM [s] to try for ``segments``, largest first: the coupling step's divisors below twice
    the time an axial wave takes to cross a segment."""
    chain = table5_chain()
    crossing = FLUME_LENGTH / segments / np.sqrt(chain.EA / chain.mass)
    return [COUPLING_DT / k for k in DTM_DIVISORS if COUPLING_DT / k <= 2.0 * crossing]


# ----------------------------------------------------------------------------- errors
def window_start(motion, duration):
    """Start [s] of the error window: the last two periods."""
    return duration - WINDOW_PERIODS * FLUME_MOTIONS[MOTIONS[motion]].period


def error_against(run, reference, t_from):
    """RMS of run - reference over t >= t_from at the run's times, relative to the reference's mean."""
    t = run["t"]
    on_run = np.interp(t, reference["t"], reference["tension"])
    return differences(t, on_run, run["tension"], t_from)["rms"]


def pareto(rows, gain=0.02):
    """The rows no other row beats in both wall time and error, cheapest first; a row joins only
    when its error is below the last one's by more than ``gain`` (a 1 % better error at twice
    the cost is no new error level). Failed runs (error None) are left out."""
    front, best = [], np.inf
    for row in sorted((r for r in rows if r["error"] is not None), key=lambda r: (r["wall_time_s"], r["error"])):
        if row["error"] < best * (1.0 - gain):
            front.append(row)
            best = row["error"]
    return front


def ratios(moordyn_rows, cablefem_rows):
    """For every MoorDyn Pareto point: the cheapest cablefem run at least as accurate, and the
    ratio of wall times (cablefem / MoorDyn); None where cablefem has no run that accurate."""
    table = []
    for md in pareto(moordyn_rows):
        good = [r for r in cablefem_rows if r["error"] is not None and r["error"] <= md["error"]]
        cf = min(good, key=lambda r: r["wall_time_s"]) if good else None
        table.append({"error": md["error"], "moordyn": md["label"], "moordyn_s": md["wall_time_s"],
                      "moordyn_peer_s": md["peer_wall_time_s"],
                      "cablefem": cf["label"] if cf else None, "cablefem_error": cf["error"] if cf else None,
                      "cablefem_s": cf["wall_time_s"] if cf else None,
                      "ratio": cf["wall_time_s"] / md["wall_time_s"] if cf else None})
    return table


def observed_order(steps, errors):
    """Least-squares slope of log(error) against log(step)."""
    return float(np.polyfit(np.log(steps), np.log(errors), 1)[0])


# ----------------------------------------------------------------------------- the study
def study_motion(motion, spec, runs, duration, log=print):
    """References, their convergence, the sweeps and the ratio table of one motion (when its runs
    have them), and the observed order of the time error alone. ``spec``: MoorDyn's part
    (``plan``); ``runs``: the motion's cablefem runs by role (``runs.cablefem_runs``)."""
    t_from = window_start(motion, duration)
    t_from = max(t_from, 0.0)
    log(f"== {motion}: {duration:g} s simulated, window {t_from:g}-{duration:g} s")
    entry = {"duration_s": duration, "window_s": [t_from, duration]}
    if "reference" in runs:
        references_and_sweeps(motion, spec, runs, entry, log)
    (fine_settings, fine), = runs["time-order-reference"]
    dts = [settings.dt for settings, _ in runs["time-order"]]
    time_errors = [error_against(run, fine, t_from) for _, run in runs["time-order"]]
    order, elements = fine_settings.order, fine_settings.elements
    entry["time_order"] = {"mesh": f"P{order} x {elements}", "dt": dts, "errors": time_errors,
                           "reference_dt": fine_settings.dt, "order": observed_order(dts, time_errors)}
    log(f"  time error alone, P{order} x {elements} BDF2 against dt {fine_settings.dt:g}: "
        + ", ".join(f"dt {dt:g}: {e:.2e}" for dt, e in zip(dts, time_errors))
        + f"; observed order {entry['time_order']['order']:.2f}")
    return entry


def references_and_sweeps(motion, spec, runs, entry, log=print):
    """Fill ``entry`` with the references, their checks, both sweeps, the Pareto fronts and ratios."""
    duration, t_from = entry["window_s"][1], entry["window_s"][0]

    (cf_settings, cf_ref), = runs["reference"]
    log(f"cablefem reference {cf_settings.label()}: {cf_ref['wall_time_s']:.1f} s")
    md_ref = run_moordyn(motion, duration, spec["moordyn_reference"])
    if not md_ref["stable"]:
        raise RuntimeError(f"MoorDyn reference {spec['moordyn_reference'].label()} failed")
    log(f"MoorDyn reference {spec['moordyn_reference'].label()}: {md_ref['wall_time_s']:.1f} s")
    raw = {"t": md_ref["t"], "tension": md_ref["tension_raw"]}
    entry["references"] = {
        "cablefem": {"settings": asdict(cf_settings), "wall_time_s": cf_ref["wall_time_s"],
                     "mean_tension_N": float(np.mean(cf_ref["tension"][cf_ref["t"] >= t_from - 1e-9]))},
        "moordyn": {"settings": asdict(spec["moordyn_reference"]), "wall_time_s": md_ref["wall_time_s"]},
        # the model floor: the two finest runs against each other, on MoorDyn's output times
        "moordyn_vs_cablefem": error_against(md_ref, cf_ref, t_from),
        "moordyn_raw_vs_cablefem": error_against(raw, cf_ref, t_from),
        "checks": []}
    for settings, check in runs["check"]:
        change = error_against(check, cf_ref, t_from)
        entry["references"]["checks"].append({"code": "cablefem", "label": settings.label(), "change": change,
                                              "wall_time_s": check["wall_time_s"]})
        log(f"  check {settings.label()}: {change:.2e} from the reference ({check['wall_time_s']:.1f} s)")
    log(f"  finest MoorDyn against finest cablefem: {entry['references']['moordyn_vs_cablefem']:.2e} "
        f"(MoorDyn's own force, end-node inertia kept: {entry['references']['moordyn_raw_vs_cablefem']:.2e})")
    if "ic_check" in spec:
        # what skipping MoorDyn's initial-condition solve changes in the window
        settings = spec["ic_check"]
        skipped, solved = (run_moordyn(motion, duration, settings, initial_condition=ic) for ic in (False, True))
        entry["references"]["moordyn_ic_check"] = {
            "settings": asdict(settings), "change": error_against(skipped, solved, t_from),
            "init_time_s": solved["wall_time_s"] - skipped["wall_time_s"]}
        log(f"  MoorDyn {settings.label()} without its IC solve against with it (threshIC 1e-5): "
            f"{entry['references']['moordyn_ic_check']['change']:.1e}")

    moordyn_rows, attempts = moordyn_sweep(motion, spec, duration, md_ref, cf_ref, t_from, log)
    entry["moordyn_attempts"] = attempts
    entry["moordyn"] = moordyn_rows
    # MoorDyn's reference against the next finest run (most segments below it, smallest dtM)
    finest = max(moordyn_rows, key=lambda r: (r["settings"]["segments"], -r["settings"]["dtM"]))
    entry["references"]["moordyn_next"] = {"label": finest["label"], "change": finest["error"]}

    cablefem_rows = []
    for settings, result in runs["row"]:
        row = {"label": settings.label(), "settings": asdict(settings), "wall_time_s": result["wall_time_s"]}
        if "failed" in result:
            row.update(error=None, failed=result["failed"])
            log(f"  cablefem {row['label']:<52} FAILED after {row['wall_time_s']:.2f} s: {result['failed']}")
        else:
            row.update(error=error_against(result, cf_ref, t_from),
                       error_vs_moordyn_reference=error_against(result, md_ref, t_from), repeats=result["repeats"],
                       **{key: result[key] for key in ("steps", "rejected", "newton_iterations", "nfev", "nlu")})
            log(f"  cablefem {row['label']:<52} error {row['error']:.2e} {row['wall_time_s']:7.2f} s "
                f"({row['newton_iterations'] / max(row['steps'], 1):.2f} Newton/step)")
        cablefem_rows.append(row)
    entry["cablefem"] = cablefem_rows
    entry["pareto"] = {"moordyn": [r["label"] for r in pareto(moordyn_rows)],
                       "cablefem": [r["label"] for r in pareto(cablefem_rows)]}
    entry["ratios"] = ratios(moordyn_rows, cablefem_rows)
    entry["series"] = {"cablefem_reference": cf_ref, "moordyn_reference": md_ref}


def moordyn_sweep(motion, spec, duration, md_ref, cf_ref, t_from, log=print):
    """MoorDyn at each segment count of ``spec``, from its largest stable dtM down, keeping as many
    stable runs as the spec says: (rows with errors against both references, every attempt)."""
    limit = 2.0 * float(np.max(cf_ref["tension"]))
    moordyn_rows, attempts = [], []
    for segments, keep in spec["moordyn_segments"].items():
        found = 0
        for dtM in moordyn_candidates(segments):
            settings = MoordynSettings(segments, dtM)
            result = run_moordyn(motion, duration, settings, tension_limit=limit)
            if result["stable"]:
                result = least_time(lambda: run_moordyn(motion, duration, settings, tension_limit=limit),
                                    spec.get("repeats", REPEATS))
            attempts.append({"segments": segments, "dtM": dtM, "stable": result["stable"],
                             "wall_time_s": result["wall_time_s"]})
            if not result["stable"]:
                continue
            row = {"label": settings.label(), "settings": asdict(settings), "wall_time_s": result["wall_time_s"],
                   "peer_wall_time_s": result["peer_wall_time_s"], "error": error_against(result, md_ref, t_from),
                   "error_vs_cablefem_reference": error_against(result, cf_ref, t_from),
                   "largest_stable_dtM": found == 0, "repeats": result["repeats"]}
            moordyn_rows.append(row)
            log(f"  MoorDyn {row['label']:<28} error {row['error']:.2e} ({row['error_vs_cablefem_reference']:.2e} "
                f"vs cablefem's) {row['wall_time_s']:7.2f} s (peer {row['peer_wall_time_s']:.2f} s)")
            found += 1
            if found == keep:
                break
    return moordyn_rows, attempts


def warm_up():
    """A few steps of every element order and of MoorDyn in this process (where MoorDyn's timed runs
    and the profile run), so that numba's compile (cached on disk after the first run ever) and
    first-call costs stay out of the timings; the Dask workers warm themselves (cablefem.sweeps)."""
    for order in (1, 2, 3):
        run_cablefem("snap", 0.1, CablefemSettings(order, 4, 0.05))
    run_moordyn("snap", 0.1, MoordynSettings(20, 0.005))


def profile_run(motion="snap", settings=CablefemSettings(2, 80, 0.01), duration=12.0, top=12):
    """cProfile of one cablefem run: wall time and the functions with the most own time."""
    profiler = cProfile.Profile()
    profiler.enable()
    result = run_cablefem(motion, duration, settings)
    profiler.disable()
    stats = pstats.Stats(profiler, stream=io.StringIO())
    total = stats.total_tt
    rows = []
    for (path, line, name), (_, calls, own, cumulative, _) in sorted(stats.stats.items(), key=lambda kv: -kv[1][2])[:top]:
        rows.append({"function": f"{Path(path).name}:{line}({name})", "calls": calls, "own_s": own,
                     "cumulative_s": cumulative, "own_fraction": own / total})
    return {"run": settings.label(), "motion": motion, "duration_s": duration, "profiled_s": total,
            "steps": result["steps"], "newton_iterations": result["newton_iterations"], "nfev": result["nfev"],
            "nlu": result["nlu"], "top": rows}


def run(fast=False, log=print, profile=True, client=None, runs_dir=None):
    """The whole study; returns (results dict, series for the figures). cablefem's runs go to Dask
    (``client``, or a LocalCluster of one worker per core) into ``runs_dir`` (default: a temporary
    folder, removed after; a kept one lets an interrupted study resume)."""
    from importlib.metadata import version

    begin = time.perf_counter()
    warm_up()
    runs_kept = runs_dir is not None
    runs_dir = Path(runs_dir) if runs_kept else Path(tempfile.mkdtemp(prefix="cablefem-work-precision-"))
    try:
        runs, durations = cablefem_runs(fast, runs_dir, client=client, log=log)
    finally:
        if not runs_kept:
            shutil.rmtree(runs_dir, ignore_errors=True)
    results = {"fast": fast, "moordyn_version": version("moordyn"), "coupling_dt_s": COUPLING_DT,
               "window_periods": WINDOW_PERIODS, "motions": {}}
    series = {}
    for motion, spec in plan(fast).items():
        entry = study_motion(motion, spec, runs[motion], durations[motion], log)
        if "series" in entry:
            series[motion] = entry.pop("series")
        results["motions"][motion] = entry
    if profile and not fast:
        results["profile"] = profile_run()
    results["study_wall_time_s"] = time.perf_counter() - begin
    return results, series


# ----------------------------------------------------------------------------- output
def report(results):
    """The tables as text: references, ratio table per motion, Pareto fronts, time order."""
    out = []
    for motion, e in results["motions"].items():
        out.append(f"{motion}: {e['duration_s']:g} s, error window {e['window_s'][0]:g}-{e['window_s'][1]:g} s")
        if "references" in e:
            out.extend(_sweep_report(e))
        t = e["time_order"]
        out.append(f"  time error alone ({t['mesh']}, BDF2, against dt {t['reference_dt']:g}): "
                   + ", ".join(f"dt {dt:g}: {err:.2e}" for dt, err in zip(t["dt"], t["errors"]))
                   + f"; order {t['order']:.2f}")
        out.append("")
    if "profile" in results:
        p = results["profile"]
        out.append(f"profile: {p['run']}, {p['motion']}, {p['duration_s']:g} s: {p['profiled_s']:.2f} s, "
                   f"{p['steps']} steps, {p['newton_iterations']} Newton iterations, {p['nfev']} evaluations, "
                   f"{p['nlu']} LU")
        for row in p["top"]:
            out.append(f"  {row['own_fraction']:6.1%} {row['own_s']:7.3f} s {row['calls']:7d} calls  {row['function']}")
    return "\n".join(out)


def _sweep_report(e):
    """Lines of the references and the ratio table of one motion."""
    out = []
    ref = e["references"]
    out.append(f"  cablefem reference {CablefemSettings(**ref['cablefem']['settings']).label()} "
               f"({ref['cablefem']['wall_time_s']:.1f} s); "
               + "; ".join(f"{c['label']}: {c['change']:.2e}" for c in ref["checks"]))
    out.append(f"  MoorDyn reference {MoordynSettings(**ref['moordyn']['settings']).label()} "
               f"({ref['moordyn']['wall_time_s']:.1f} s); model floor (finest MoorDyn vs finest cablefem) "
               f"{ref['moordyn_vs_cablefem']:.2e}; {ref['moordyn_next']['label']}: {ref['moordyn_next']['change']:.2e}"
               + (f"; IC solve skipped vs done: {ref['moordyn_ic_check']['change']:.1e}" if "moordyn_ic_check" in ref else ""))
    out.append(f"  {'MoorDyn error':>13} {'MoorDyn':<28} {'[s]':>7} {'cablefem':<46} {'error':>8} {'[s]':>7} {'ratio':>6}")
    for row in e["ratios"]:
        cf = (f"{row['cablefem']:<46} {row['cablefem_error']:8.2e} {row['cablefem_s']:7.2f} {row['ratio']:6.2f}"
              if row["cablefem"] else f"{'(none as accurate)':<46}")
        out.append(f"  {row['error']:13.2e} {row['moordyn']:<28} {row['moordyn_s']:7.2f} {cf}")
    return out


def figures(results, series, out_dir):
    """work_precision.png: error against wall time per motion (log-log, both codes, Pareto fronts);
    references.png: the two finest runs' tensions over the window and their difference."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    motions = [m for m, e in results["motions"].items() if "cablefem" in e]
    fig, axes = plt.subplots(1, len(motions), figsize=(7.2 * len(motions), 5.6), squeeze=False)
    markers = {1: "o", 2: "s", 3: "^"}
    loose = f"BDF2, Newton tol {LOOSE_NEWTON:g}"
    colours = {"BDF2": "tab:red", loose: "tab:green", f"{loose}, modified Newton": "tab:olive",
               "gen-alpha": "tab:orange", "adaptive BDF2": "tab:purple"}
    for ax, motion in zip(axes[0], motions):
        e = results["motions"][motion]
        for row in e["cablefem"]:
            s = row["settings"]
            if row["error"] is None:
                continue
            kind = ("adaptive BDF2" if s["adaptive"] else "gen-alpha" if s["integrator"] != "bdf2"
                    else "BDF2" if s["tolerance"] == 1e-8
                    else f"{loose}, modified Newton" if s.get("newton") == "modified" else loose)
            ax.scatter(row["wall_time_s"], row["error"], marker=markers[s["order"]], s=22,
                       facecolors="none", edgecolors=colours[kind], lw=0.9)
        md = e["moordyn"]
        ax.scatter([r["wall_time_s"] for r in md], [r["error"] for r in md], marker="x", color="tab:blue", s=24)
        for r in md:
            if r["largest_stable_dtM"]:
                ax.annotate(str(r["settings"]["segments"]), (r["wall_time_s"], r["error"]), fontsize=7,
                            color="tab:blue", xytext=(3, 3), textcoords="offset points")
        for rows, colour, name in ((md, "tab:blue", "MoorDyn Pareto front"),
                                   (e["cablefem"], "tab:red", "cablefem Pareto front")):
            front = pareto(rows)
            ax.step([r["wall_time_s"] for r in front], [r["error"] for r in front], where="post",
                    color=colour, lw=1.2, label=name)
        floor = e["references"]["moordyn_vs_cablefem"]
        ax.axhline(floor, color="0.4", ls=":", lw=1.0, label=f"model floor {floor:.1e} (finest vs finest)")
        check = max(c["change"] for c in e["references"]["checks"])
        ax.axhline(check, color="tab:red", ls="--", lw=0.8,
                   label=f"cablefem reference: finest vs next {check:.1e}")
        for order, marker in markers.items():
            ax.scatter([], [], marker=marker, facecolors="none", edgecolors="0.3", label=f"cablefem P{order}")
        for kind, colour in colours.items():
            ax.scatter([], [], marker="o", facecolors="none", edgecolors=colour, label=f"cablefem {kind}")
        ax.scatter([], [], marker="x", color="tab:blue", label="MoorDyn (label: segments)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time [s] (cablefem: whole run; MoorDyn: Init + Step)")
        ax.set_ylabel("RMS fairlead tension error / mean tension")
        ax.set_title(f"{motion}: {e['duration_s']:g} s, error over {e['window_s'][0]:g}-{e['window_s'][1]:g} s "
                     "(each code against its own finest run)", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(handles=ax.get_legend_handles_labels()[0][:4], fontsize=7, loc="upper right")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles[4:], labels[4:], loc="lower center", ncol=5, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    written = [out_dir / "work_precision.png"]
    fig.savefig(written[0], dpi=90)
    plt.close(fig)

    fig, axes = plt.subplots(2, len(motions), figsize=(7.2 * len(motions), 6.0), squeeze=False, sharex="col")
    for k, motion in enumerate(motions):
        e, s = results["motions"][motion], series[motion]
        t0 = e["window_s"][0]
        cf, md = s["cablefem_reference"], s["moordyn_reference"]
        window = md["t"] >= t0 - 1e-9
        axes[0, k].plot(cf["t"], cf["tension"] / 1e6, color="tab:red", lw=0.9, label="cablefem finest")
        axes[0, k].plot(md["t"], md["tension"] / 1e6, color="tab:blue", lw=0.9, ls="--", label="MoorDyn finest")
        axes[0, k].set_xlim(t0, e["window_s"][1])
        axes[0, k].set_ylabel("fairlead tension [MN]")
        axes[0, k].legend(fontsize=8)
        axes[0, k].set_title(motion, fontsize=9)
        difference = md["tension"][window] - np.interp(md["t"][window], cf["t"], cf["tension"])
        axes[1, k].plot(md["t"][window], difference / 1e3, color="0.3", lw=0.8)
        axes[1, k].set_ylabel("MoorDyn - cablefem [kN]")
        axes[1, k].set_xlabel("t [s]")
        for ax in axes[:, k]:
            ax.grid(alpha=0.3)
    fig.tight_layout()
    written.append(out_dir / "references.png")
    fig.savefig(written[1], dpi=90)
    plt.close(fig)
    return [p.name for p in written]


def write_series(path, series):
    """The references' tension series (per motion and code: t, tension) as one .npz."""
    np.savez_compressed(path, **{f"{motion}/{code}/{key}": run[key] for motion, codes in series.items()
                                 for code, run in codes.items() for key in ("t", "tension")})


def read_series(path):
    """``write_series``'s file back as {motion: {code: {"t": ..., "tension": ...}}}."""
    series = {}
    with np.load(path) as data:
        for name in data.files:
            motion, code, key = name.split("/")
            series.setdefault(motion, {}).setdefault(code, {})[key] = data[name]
    return series


def _json_ready(value):
    if isinstance(value, dict):
        return {k: _json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_ready(v) for v in value]
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="snap motion only, 18 s, coarse settings (~1 min)")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and the PNGs")
    parser.add_argument("--replot", action="store_true", help="redraw the PNGs from OUT/results.json and "
                        "OUT/references.npz without running")
    parser.add_argument("--runs", type=Path, help="keep cablefem's runs here (a re-run resumes); default: "
                        "a temporary folder")
    parser.add_argument("--workers", type=int, metavar="N", help="local Dask cluster: worker processes "
                        "(default: one per core)")
    parser.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask cluster instead")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    if args.replot:
        results = json.loads((args.out / "results.json").read_text())
        series = read_series(args.out / "references.npz")
    else:
        from cablefem.sweeps.engine import connect

        with connect(scheduler=args.scheduler, workers=args.workers) as client:
            results, series = run(fast=args.fast, client=client, runs_dir=args.runs)
        (args.out / "results.json").write_text(json.dumps(_json_ready(results), indent=1))
        write_series(args.out / "references.npz", series)
    print(report(results))
    written = figures(results, series, args.out)
    print(f"wrote {', '.join(written)}" + ("" if args.replot else f", results.json, references.npz; the study "
                                          f"took {results['study_wall_time_s']:.0f} s"))


if __name__ == "__main__":
    main()
