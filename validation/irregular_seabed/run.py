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

The parts: ``model.py`` (the seabed, the line, the motion, what frames tell), ``methods.py`` (1, 2
and the settings study), ``cost.py`` (3), ``report.py`` (the tables), ``plots.py`` (the figures).
"""

import argparse
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

if __package__ in (None, ""):  # python validation/irregular_seabed/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem import study  # noqa: E402

from validation.irregular_seabed.cost import COST_PATHS, cost_study  # noqa: E402,F401
from validation.irregular_seabed.methods import convergence, findings, robustness, run_method, static_sweep  # noqa: E402
from validation.irregular_seabed.model import (METHODS, PAPER, PRIMARY_SEED, SETTINGS, seabed_grid,  # noqa: E402
                                               seabed_models, setup_description, surface_statistics)
from validation.irregular_seabed.plots import make_figures  # noqa: E402
from validation.irregular_seabed.report import print_report, print_table6  # noqa: E402

HERE = Path(__file__).resolve().parent


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
