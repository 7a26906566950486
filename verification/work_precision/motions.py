"""The study of one motion of verification/work_precision: both codes' references, cablefem's sweep
(run by ``runs.py``) and MoorDyn's, their errors and ratio table, and the time order."""

from dataclasses import asdict

import numpy as np

from verification.work_precision.errors import error_against, observed_order, pareto, ratios, window_start
from verification.work_precision.runners import MoordynSettings, moordyn_candidates, run_moordyn
from verification.work_precision.runs import REPEATS, least_time

#: the looser Newton tolerance of the sweep ([solver] tolerance; the scenes' default is 1e-8); the
#: sweep runs both at the steps they share, so the tables show what it changes
LOOSE_NEWTON = 1e-4


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
