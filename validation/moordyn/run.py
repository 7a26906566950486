"""cablefem against MoorDyn-C on the same MoorDyn input files: the flat flume cases of desire2023
and the three-line semi-taut system of housner2022 over flat and 12.5 % sloped seabeds.

Run ``python -m validation.moordyn.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the
numbers tests/test_validation_moordyn.py asserts on. The README has the case definitions, the
choices and the latest numbers.

1. Same scenes, one input file: each case is ONE MoorDyn v2 file (``inputs/``, written by
   ``write_inputs``) that MoorDyn runs (``peer.run_moordyn``) and cablefem reads through a TOML
   that adds the motion (``[moordyn] file = ...``). Both codes' settings are checked by doubling
   the time step and halving the segments/elements (``convergence_check``).
2. Fairlead tension series of both codes per case, differences over the last two periods
   (RMS, largest, mean and peak, relative to the mean tension) and wall times.
3. Physics differences switched off one at a time (``switches``; OPTIONS rewritten for both).

The parts: ``inputs.py`` (the files), ``runners.py`` (both codes' runs), ``comparison.py``,
``cases.py`` (one case, its switches and convergence check; the static checks), ``report.py`` and
``plots.py``.
"""

import argparse
import json
import pickle
import sys
import time
from pathlib import Path

if __package__ in (None, ""):  # python validation/moordyn/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.io import load_scene  # noqa: E402
from cablefem.study import package_version, write_json  # noqa: E402

from validation.moordyn.cases import run_case, static_checks  # noqa: E402
from validation.moordyn.inputs import FLUME_FILE_SEGMENTS, HOUSNER_SEABEDS, write_inputs  # noqa: E402,F401
from validation.moordyn.plots import figures  # noqa: E402
from validation.moordyn.report import report  # noqa: E402
# verification/work_precision/common.py imports COUPLING_DT, FLUME_FILE_SEGMENTS and run_moordyn_case from here
from validation.moordyn.runners import (COUPLING_DT, WINDOW_PERIODS, run_cablefem_case,  # noqa: E402,F401
                                        run_moordyn_case)

HERE = Path(__file__).resolve().parent


def run(fast=False, out_dir=None, log=print):
    """The whole study; returns (results dict, series for the figures)."""
    out_dir = Path(out_dir or HERE)
    inputs = write_inputs(out_dir / "inputs")
    cases = ["flume-quasi-static", "housner-flat", "housner-upslope"] if fast else \
        ["flume-quasi-static", "flume-dynamic"] + [f"housner-{kind}" for kind in HOUSNER_SEABEDS]
    results = {"fast": fast, "coupling_dt_s": COUPLING_DT, "window_periods": WINDOW_PERIODS,
               "moordyn_version": package_version("moordyn"), "cases": {}}
    series = {}
    start = time.perf_counter()
    _warm_up(inputs["flume-quasi-static"])
    for case in cases:
        results["cases"][case], series[case] = run_case(case, inputs[case], fast, log)
    results["statics"] = static_checks(out_dir / "inputs", fast, log)
    results["wall_time_s"] = time.perf_counter() - start
    return results, series


def _warm_up(toml):
    """Two steps of a small run, so that numba's compilation of cablefem's step kernel (cached on
    disk after the first run ever) is not counted in the first case's wall time."""
    run_cablefem_case(load_scene(toml), 0.1, 0.05)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse settings, short runs (~1 min): what the tests assert")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for inputs/, results.json and PNGs")
    parser.add_argument("--series", type=Path, help="also keep the time series in this pickle (for --replot)")
    parser.add_argument("--replot", type=Path, help="no runs: redraw the PNGs from --out/results.json and this pickle")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    if args.replot:
        results = json.loads((args.out / "results.json").read_text())
        with open(args.replot, "rb") as handle:
            series = pickle.load(handle)
        print(report(results))
        print(f"wrote {', '.join(figures(results, series, args.out))}")
        return
    results, series = run(fast=args.fast, out_dir=args.out)
    print(report(results))
    write_json(args.out / "results.json", results, private=True)
    if args.series:
        with open(args.series, "wb") as handle:
            pickle.dump(series, handle)
    written = figures(results, series, args.out)
    print(f"wrote {args.out / 'results.json'}, {', '.join(written)}")


if __name__ == "__main__":
    main()
