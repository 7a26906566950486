"""The six desire2023 flume cases (Sec. 4, Figs. 12-17): three seabeds x two fairlead motions.

Run ``python -m validation.flume.run [--fast] [--out DIR] [--runs DIR] [--convergence | --sensitivity]
[--workers N | --scheduler ADDRESS]``;
``run(fast=True)`` returns the numbers tests/test_validation_flume.py asserts on.

The cases are the sweep files of this folder (``sweep.toml``, ``sweep_fast.toml``; docs/sweep.md):
the Table 5 line of ``flume.toml`` (the physics of ``cablefem.model.builtin.flume_scene``: prototype
scale, reconstructed steps, docs/seabeds.md) with each case's seabed, motion, elements and step,
run in parallel on Dask by ``cablefem.sweeps`` (``cablefem.runs.run.run_scene`` in each worker) for the
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

The parts: ``cases.py`` (the runs, their statistics, the findings), ``report.py`` (the tables),
``plots.py`` (the figures and frames).
"""

import argparse
import shutil
import sys
import tempfile
import time
from pathlib import Path

if __package__ in (None, ""):  # python validation/flume/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem import study  # noqa: E402

from validation.flume.cases import MN, PAPER_LOWEST_PEAK, findings, run_sweep  # noqa: E402,F401
from validation.flume.plots import figures, render_frames  # noqa: E402
from validation.flume.report import report, report_convergence, report_sensitivity  # noqa: E402

HERE = Path(__file__).resolve().parent


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
