"""Speed against error (work-precision) on the flat flume chain: cablefem's element orders, element
counts, time steps and integrators against MoorDyn-C's segment counts and time steps, in one run.

The case is desire2023's Table 5 chain over the flat 100 m seabed (``cablefem.model.builtin.flume_scene``
"flat"; MoorDyn reads the same line from ``validation/moordyn/inputs/flume_flat.dat``) under two
fairlead motions, each ramped in over its first period:

    slow-surge   17 s period, 2.5 m amplitude, 15 m offset   51 s simulated (ramp + 2 periods)
    snap          6 s period, 5 m amplitude (snap loads)      36 s simulated (6 periods)

Error of a run = RMS over the last two periods of (its fairlead tension - the reference's), at the
run's own output times (the reference interpolated there), divided by the reference's mean
tension over the window (``validation.moordyn.comparison.differences``). Each code is measured against
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
the timed rows one at a time (``alone``); MoorDyn's runs follow in this process, alone too
(``runners.py``). ``motions.py`` studies one motion, ``errors.py`` measures, ``report.py`` and
``plots.py`` show.

Run ``python -m verification.work_precision.run [--fast] [--out DIR] [--replot] [--runs DIR]
[--workers N | --scheduler ADDRESS]``;
``run(fast=True)`` (the snap sweep on coarse settings over 18 s and the slow-surge time order over
20 s, ~35 s) returns what tests/test_work_precision.py asserts.
"""

import argparse
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python verification/work_precision/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.study import write_json  # noqa: E402

from validation.moordyn.runners import COUPLING_DT  # noqa: E402
from verification.work_precision.errors import WINDOW_PERIODS, error_against, pareto, ratios  # noqa: E402,F401
from verification.work_precision.motions import plan, study_motion  # noqa: E402
from verification.work_precision.plots import figures  # noqa: E402
from verification.work_precision.report import report  # noqa: E402
from verification.work_precision.runners import profile_run, warm_up  # noqa: E402
from verification.work_precision.runs import cablefem_runs  # noqa: E402

HERE = Path(__file__).resolve().parent


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
        write_json(args.out / "results.json", results, private=True)
        write_series(args.out / "references.npz", series)
    print(report(results))
    written = figures(results, series, args.out)
    print(f"wrote {', '.join(written)}" + ("" if args.replot else f", results.json, references.npz; the study "
                                          f"took {results['study_wall_time_s']:.0f} s"))


if __name__ == "__main__":
    main()
