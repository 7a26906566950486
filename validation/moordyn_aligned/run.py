"""cablefem and MoorDyn-C with aligned physics on the frictionless flume chain (issue 16, part 2).

The flat flume chain of desire2023 Table 5 (``cablefem.model.builtin.flume_scene("flat")``; MoorDyn reads
the same line from ``validation/moordyn/inputs/flume_flat.dat``) without seabed friction, under
the paper's two fairlead motions (Sec. 4.1), each ramped in over its first period:

    snap   6 s period, 5 m surge (snap loads)          36 s, window 24-36 s (the last two periods)
    slow   17 s period, 2.5 m surge, 15 m offset       51 s, window 17-51 s

Aligned physics: cablefem's line type with ``damping_when_slack = true`` (MoorDyn-C's tension law,
issue 16 part 1), friction off in both (FrictionCoefficient 0; cablefem friction "none"), MoorDyn's
initial-condition solve skipped (TmaxIC 0: both start from their static equilibrium, 2e-4 apart,
validation/moordyn "Static check"), MoorDyn coupled every ``FINE_COUPLING`` s so that its
fairlead follows the prescribed motion as closely as cablefem's does (see the coupling switch),
MoorDyn's force with the end node's inertia subtracted (the force cablefem's reaction is).

Both codes are refined until converged (MoorDyn to 1280 segments, dtM 2e-5 s, ~13 min; cablefem
P1/P2/P3 in space and time), then the finest runs are compared, and each remaining model
difference is switched off one at a time (``SWITCHES``): the README tabulates them.

Error measure (``validation.moordyn.comparison.differences``): over the window, at the run's own output
times (the reference interpolated there), relative to the reference's mean tension: RMS, mean,
peak (max) and trough (min) differences.

Runs are cached by their settings (``--cache DIR``): a MoorDyn run at 1280 segments takes ~13 min
and the full study ~45 min without a cache. ``python -m validation.moordyn_aligned.run [--fast]
[--cache DIR] [--out DIR]``; ``run(fast=True)`` (~15 s) is what tests/test_moordyn_aligned.py asserts.
"""

import argparse
import hashlib
import json
import sys
import time
from dataclasses import asdict, replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python validation/moordyn_aligned/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.model.builtin import FLUME_MOTIONS, flume_scene, table5_chain  # noqa: E402
from cablefem.study import write_json  # noqa: E402
from validation.moordyn.comparison import differences  # noqa: E402
from validation.moordyn.inputs import FLUME_FILE_SEGMENTS  # noqa: E402
from validation.moordyn.runners import COUPLING_DT, run_cablefem_case, run_moordyn_case  # noqa: E402

HERE = Path(__file__).resolve().parent
MOORDYN_FILE = HERE.parent / "moordyn" / "inputs" / "flume_flat.dat"
MOTIONS = {"snap": "dynamic", "slow": "quasi-static"}
DURATION = {"snap": 36.0, "slow": 51.0}
WINDOW = {"snap": 24.0, "slow": 17.0}
#: MoorDyn's coupling step [s] for the aligned runs: its coupled point moves along the secant of the
#: motion between calls; at 5e-4 s the runs are within 0.02 % RMS of 2.5e-4 s (README)
FINE_COUPLING = 5e-4
#: the coupling step of MoorDyn's 1280-segment snap reference (~13 min a run on an idle machine)
SNAP_REFERENCE_COUPLING = COUPLING_DT


# ----------------------------------------------------------------------------- cached runs
def _key(**settings):
    return hashlib.sha1(json.dumps(settings, sort_keys=True).encode()).hexdigest()[:12]


def _cached(cache, settings, compute):
    """``compute()`` (a dict of arrays), kept in ``cache`` (a folder, or None) under its settings."""
    path = None if cache is None else Path(cache) / f"{settings['code']}-{_key(**settings)}.npz"
    if path is not None and path.exists():
        with np.load(path, allow_pickle=True) as data:
            return {name: data[name] for name in data.files if name != "meta"}
    result = compute()
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez(path, **result, meta=json.dumps(settings))
    return result


def moordyn(motion, segments, dtM, coupling=FINE_COUPLING, options=None, duration=None, cache=None):
    """MoorDyn-C, frictionless, IC solve skipped, on the flume file at ``segments`` and ``dtM`` [s],
    coupled every ``coupling`` [s]: dict of t (n,) [s], tension (n,) [N] on the fairlead point
    (end-node inertia subtracted), wall [s] (the peer's whole run)."""
    duration = duration or DURATION[motion]
    settings = dict(code="md", motion=motion, N=segments, dtM=dtM, friction=False, coupling=coupling,
                    options=options or {}, scheme=None, duration=duration)

    def compute():
        scene = flume_scene("flat", MOTIONS[motion])
        run = run_moordyn_case(MOORDYN_FILE, scene, duration,
                               {"segments": segments / FLUME_FILE_SEGMENTS, "dtM": dtM, "ic_dtM": None},
                               options={"TmaxIC": 0.0, "FrictionCoefficient": 0.0, **(options or {})},
                               coupling_dt=coupling)
        # t = 0 dropped: with its IC skipped MoorDyn reports no force before its first step
        return {"t": run["t"][1:], "tension": np.linalg.norm(run["forces_on_point"][1:, 0], axis=1),
                "wall": run["wall_time_s"]}
    return _cached(cache, settings, compute)


def aligned_scene(motion, order, elements, dt, duration=None, tolerance=1e-8, damping_when_slack=True,
                  damping_when_opening=False):
    """The flat flume scene, frictionless, with MoorDyn-C's damping law (``damping_when_slack``) and,
    with ``damping_when_opening``, its seabed damper (acting on points moving out too)."""
    scene = flume_scene("flat", MOTIONS[motion], elements, order, duration or DURATION[motion], dt)
    scene = replace(scene, friction=replace(scene.friction, model="none"),
                    contact=replace(scene.contact, damping_when_opening=damping_when_opening))
    line = scene.lines[0].with_types(lambda t: replace(t, damping_when_slack=damping_when_slack))
    scene = replace(scene, lines=[line])
    scene.solver = replace(scene.solver, tolerance=tolerance, newton="full")
    return scene


#: cablefem's variants: name -> run_cablefem_case's switches, or None: the aligned scene runs compiled
#: (with Eq. 11's tension law for "default-damping-law", MoorDyn-C's seabed damper for
#: "two-sided-contact-damping")
VARIANTS = {None: None,
            "default-damping-law": None,
            "numpy-hydroTrue-lumpedFalse": {"hydro_per_unstretched": True},
            "numpy-hydroFalse-lumpedTrue": {"lumped": True},
            "two-sided-contact-damping": None}


def cablefem(motion, order, elements, dt, tolerance=1e-8, variant=None, duration=None, cache=None):
    """cablefem BDF2 on the aligned scene (``variant``: one of ``VARIANTS``): dict of t (n,) [s],
    tension (n,) [N] at the fairlead, wall [s] (statics, set-up and steps)."""
    duration = duration or DURATION[motion]
    settings = dict(code="cf", motion=motion, order=order, elements=elements, dt=dt, friction=False,
                    slack=variant != "default-damping-law", tol=tolerance, newton="full", duration=duration,
                    variant=None if variant == "default-damping-law" else variant)

    def compute():
        from verification.work_precision.runs import run_cablefem_scene

        scene = aligned_scene(motion, order, elements, dt, duration, tolerance,
                              damping_when_slack=variant != "default-damping-law",
                              damping_when_opening=variant == "two-sided-contact-damping")
        switches = VARIANTS[variant]
        if switches is None:
            run = run_cablefem_scene(scene)
            if "failed" in run:
                raise RuntimeError(run["failed"])
            return {"t": run["t"], "tension": run["tension"], "wall": run["wall_time_s"]}
        run = run_cablefem_case(scene, duration, dt, **switches)
        return {"t": run["t"], "tension": run["tensions"][:, 0], "wall": run["wall_time_s"]}
    return _cached(cache, settings, compute)


def compare(run, reference, t_from):
    """``differences`` of ``run`` against ``reference`` over t >= t_from [s] (fractions)."""
    t = run["t"]
    on = np.interp(t, reference["t"], reference["tension"])
    found = differences(t, on, run["tension"], t_from)
    return {key: float(found[key]) for key in ("mean", "peak", "trough", "rms", "max")}


def smooth_part(run, reference, window, width=0.25):
    """RMS and mean [fraction] of the difference's moving average over ``width`` [s] in ``window``
    [s, s]: what is left of it without the ringing (the slack chain's 1-30 Hz waves)."""
    t = np.arange(window[0], window[1], 0.01)
    base = np.interp(t, reference["t"], reference["tension"])
    diff = (np.interp(t, run["t"], run["tension"]) - base) / base.mean()
    n = int(round(width / 0.01))
    smooth = np.convolve(diff, np.ones(n) / n, mode="same")[n:-n]
    return {"rms": float(np.sqrt(np.mean(smooth ** 2))), "mean": float(smooth.mean())}


# ----------------------------------------------------------------------------- the shortest wave
def shortest_wave(minimum_tension, frequency):
    """Transverse wave speed [m/s] and length [m] in the chain (mass plus added mass) at a
    tension [N] and frequency [Hz]: c = sqrt(T / (m + C_a rho A)), lambda = c / f."""
    chain = table5_chain()
    added = chain.Ca_normal * 1025.0 * np.pi * chain.diameter ** 2 / 4.0
    speed = np.sqrt(minimum_tension / (chain.mass + added))
    return float(speed), float(speed / frequency)


def spectrum_bands(run, t_from, edges=(0, 1, 2, 4, 8, 16, 32, 64)):
    """Share of the fairlead tension's fluctuation (RMS) per frequency band [Hz] over t >= t_from [s]."""
    keep = run["t"] >= t_from
    y = run["tension"][keep] - run["tension"][keep].mean()
    dt = float(np.median(np.diff(run["t"][keep])))
    f = np.fft.rfftfreq(len(y), dt)
    power = np.abs(np.fft.rfft(y)) ** 2
    return [{"band_Hz": [lo, hi], "share": float(np.sqrt(power[(f >= lo) & (f < hi)].sum() / power.sum()))}
            for lo, hi in zip(edges[:-1], edges[1:])]


# ----------------------------------------------------------------------------- the plan
def plan(fast):
    """Runs per motion: MoorDyn (segments, dtM, coupling), cablefem (order, elements, dt, tolerance),
    the finest of each, and the switches (name -> the runs with and without it)."""
    if fast:  # the ramp and one period
        return {"slow": {"duration": 34.0,
                         "moordyn": [(80, 2e-3, COUPLING_DT)],
                         "cablefem": [(2, 40, 0.01, 1e-8)],
                         "finest": ((80, 2e-3, COUPLING_DT), (2, 40, 0.01, 1e-8)),
                         "switches": {}},
                "snap": {"duration": 12.0,
                         "moordyn": [],
                         "cablefem": [],
                         "finest": None,
                         "switches": {"coupling": ("moordyn", (40, 2e-3, COUPLING_DT), (40, 2e-3, 1e-3))}}}
    return {
        "snap": {"duration": None,
                 "moordyn": [(80, 2e-3, FINE_COUPLING), (160, 1e-3, FINE_COUPLING), (320, 2.5e-4, FINE_COUPLING),
                             (640, 8e-5, COUPLING_DT), (640, 1e-4, FINE_COUPLING), (1280, 2e-5, COUPLING_DT)],
                 "cablefem": [(1, 160, 0.0025, 1e-8), (1, 320, 0.00125, 1e-8), (1, 640, 0.000625, 1e-8),
                              (2, 80, 0.0025, 1e-8), (2, 160, 0.00125, 1e-8),
                              (2, 320, 0.000625, 1e-8), (3, 80, 0.00125, 1e-8),
                              (1, 640, 0.00125, 1e-4), (1, 320, 0.0025, 1e-4)],
                 "finest": ((1280, 2e-5, SNAP_REFERENCE_COUPLING), (1, 640, 0.000625, 1e-8)),
                 "finest_switched": (1, 640, 0.000625, 1e-8, "two-sided-contact-damping"),
                 "switches": {
                     "coupling": ("moordyn", (320, 2.5e-4, COUPLING_DT), (320, 2.5e-4, FINE_COUPLING)),
                     "coupling_640": ("moordyn", (640, 8e-5, COUPLING_DT), (640, 1e-4, FINE_COUPLING)),
                     "damping_when_slack": ("cablefem", (1, 160, 0.0025, 1e-8, "default-damping-law"),
                                            (1, 160, 0.0025, 1e-8)),
                     "two_sided_contact_damping": ("cablefem", (1, 160, 0.0025, 1e-8, "two-sided-contact-damping"),
                                                   (1, 160, 0.0025, 1e-8))}},
        "slow": {"duration": None,
                 "moordyn": [(20, 5e-3, COUPLING_DT), (80, 2e-3, COUPLING_DT), (160, 5e-4, FINE_COUPLING),
                             (320, 2.5e-4, FINE_COUPLING), (640, 1e-4, FINE_COUPLING)],
                 "cablefem": [(2, 40, 0.01, 1e-8), (2, 80, 0.005, 1e-8), (1, 160, 0.005, 1e-8),
                              (1, 320, 0.0025, 1e-8), (3, 80, 0.0025, 1e-8), (2, 160, 0.0025, 1e-4)],
                 "finest": ((640, 1e-4, FINE_COUPLING), (1, 320, 0.0025, 1e-8)),
                 "finest_switched": (1, 320, 0.0025, 1e-8, "two-sided-contact-damping"),
                 "switches": {
                     "coupling": ("moordyn", (320, 2.5e-4, COUPLING_DT), (320, 2.5e-4, FINE_COUPLING)),
                     "hydrodynamics_per_unstretched_length": (
                         "cablefem", (1, 160, 0.005, 1e-8, "numpy-hydroTrue-lumpedFalse"), (1, 160, 0.005, 1e-8)),
                     "damping_when_slack": ("cablefem", (1, 160, 0.005, 1e-8, "default-damping-law"),
                                            (1, 160, 0.005, 1e-8)),
                     "two_sided_contact_damping": ("cablefem", (1, 160, 0.005, 1e-8, "two-sided-contact-damping"),
                                                   (1, 160, 0.005, 1e-8))}}}


def md_label(settings):
    segments, dtM, coupling = settings
    return f"MoorDyn {segments} seg, dtM {dtM:g}, coupling {coupling:g}"


def cf_label(settings):
    order, elements, dt, tolerance = settings[:4]
    variant = f", {settings[4]}" if len(settings) > 4 else ""
    newton = "" if tolerance == 1e-8 else f", Newton tol {tolerance:g}"
    return f"cablefem P{order} x {elements}, dt {dt:g}{newton}{variant}"


# ----------------------------------------------------------------------------- the study
def study_motion(motion, spec, cache, log=print):
    """Convergence of both codes, the finest runs against each other, and the switches."""
    duration = spec["duration"] or DURATION[motion]

    def md(settings):
        return moordyn(motion, *settings, duration=duration, cache=cache)

    def cf(settings):
        variant = settings[4] if len(settings) > 4 else None
        return cablefem(motion, *settings[:4], variant=variant, duration=duration, cache=cache)

    t_from = WINDOW[motion] if spec["duration"] is None else duration - FLUME_MOTIONS[MOTIONS[motion]].period
    window = (t_from, duration)
    entry = {"duration_s": duration, "window_s": list(window)}
    log(f"== {motion}: window {t_from:g}-{duration:g} s, frictionless, aligned physics")
    if spec["finest"] is not None:
        md_ref, cf_ref = md(spec["finest"][0]), cf(spec["finest"][1])
        entry["finest"] = finest_pair(md_ref, cf_ref, spec["finest"], window, log)
        if spec.get("finest_switched"):  # the same MoorDyn run against cablefem with a switch
            switched = spec["finest_switched"]
            entry["finest_switched"] = finest_pair(md_ref, cf(switched), (spec["finest"][0], switched), window,
                                                   log, "finest, switched")
        rows = []
        for code, runs, label, get in (("moordyn", spec["moordyn"], md_label, md),
                                       ("cablefem", spec["cablefem"], cf_label, cf)):
            for settings in runs:
                run = get(settings)
                row = {"code": code, "label": label(settings), "wall_s": float(run["wall"]),
                       "vs_moordyn_finest": compare(run, md_ref, t_from),
                       "vs_cablefem_finest": compare(run, cf_ref, t_from)}
                rows.append(row)
                a, b = row["vs_moordyn_finest"], row["vs_cablefem_finest"]
                log(f"  {row['label']:<58} vs MoorDyn finest: RMS {100 * a['rms']:5.2f} % peak {100 * a['peak']:+6.2f} %"
                    f" | vs cablefem finest: RMS {100 * b['rms']:5.2f} % peak {100 * b['peak']:+6.2f} %"
                    f" | {row['wall_s']:7.1f} s")
        entry["runs"] = rows
        if motion == "snap":
            entry["spectrum"] = spectrum_bands(cf_ref, t_from)
    entry["switches"] = {}
    for name, (code, switched, aligned) in spec["switches"].items():
        get, label = (md, md_label) if code == "moordyn" else (cf, cf_label)
        on, off = get(switched), get(aligned)
        d = compare(on, off, t_from)
        entry["switches"][name] = {"code": code, "with": label(switched), "without": label(aligned),
                                   "difference": d, "smooth_part": smooth_part(on, off, window)}
        log(f"  switch {name:<36} {label(switched)} - {label(aligned)}: RMS {100 * d['rms']:.2f} %, "
            f"mean {100 * d['mean']:+.2f} %, peak {100 * d['peak']:+.2f} %")
    return entry


def finest_pair(md_run, cf_run, settings, window, log=print, what="finest"):
    """A MoorDyn and a cablefem run (``settings``: theirs) against each other over ``window`` [s, s]:
    their labels, MoorDyn's mean tension there, ``compare`` and ``smooth_part``; logged as ``what``."""
    t_from = window[0]
    found = {"moordyn": md_label(settings[0]), "cablefem": cf_label(settings[1]),
             "moordyn_mean_N": float(np.mean(md_run["tension"][md_run["t"] >= t_from])),
             "cablefem_vs_moordyn": compare(cf_run, md_run, t_from),
             "smooth_part": smooth_part(cf_run, md_run, window)}
    d = found["cablefem_vs_moordyn"]
    log(f"  {what}: {found['cablefem']} - {found['moordyn']}: RMS {100 * d['rms']:.3f} %, "
        f"mean {100 * d['mean']:+.3f} %, peak {100 * d['peak']:+.3f} %, trough {100 * d['trough']:+.3f} %")
    return found


def run(fast=False, cache=None, log=print):
    """The study (``plan``): a dict per motion (see ``study_motion``)."""
    start = time.perf_counter()
    results = {"fast": fast, "fine_coupling_s": FINE_COUPLING, "file_coupling_s": COUPLING_DT,
               "motions": {name: asdict(FLUME_MOTIONS[MOTIONS[name]]) for name in MOTIONS}}
    for motion, spec in plan(fast).items():
        results[motion] = study_motion(motion, spec, cache, log)
    if not fast:
        # the slack phase's shortest transverse waves: the least tension in the suspended chain
        # (20.6 kN, at its touchdown, P1 x 640) and the tension's highest frequency band with
        # a share above 0.5 % (16-32 Hz, ``spectrum``)
        results["shortest_wave"] = {f"{tension / 1e3:g} kN, {f:g} Hz": shortest_wave(tension, f)
                                    for tension in (20.6e3, 140e3, 300e3) for f in (4.0, 16.0)}
    results["wall_time_s"] = time.perf_counter() - start
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--cache", type=Path, default=None, help="folder of cached runs (kept between runs)")
    parser.add_argument("--out", type=Path, default=HERE)
    args = parser.parse_args(argv)
    results = run(fast=args.fast, cache=args.cache)
    args.out.mkdir(parents=True, exist_ok=True)
    write_json(args.out / ("results_fast.json" if args.fast else "results.json"), results)
    print(f"done in {results['wall_time_s']:.0f} s")


if __name__ == "__main__":
    main()
