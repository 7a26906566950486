"""cablefem against MoorDyn-C on a crowfoot: one line from a coupled fairlead down to a free junction
carrying a clump, two legs from the junction to anchors (issue 18, ``cablefem.dynamics.group``).

Run ``python -m validation.junction.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the
numbers tests/test_validation_junction.py asserts on. The README has the case, the alignment of
the physics and the latest numbers.

1. One scene, two files: ``inputs/crowfoot.dat`` (MoorDyn v2: the junction a Free point joining
   three lines, the fairlead a Coupled point moved through MoorDyn's coupling API by
   ``validation.moordyn.peer``) and ``inputs/crowfoot.toml`` (cablefem: a coupled [points] entry
   following [motion]), both written by ``write_inputs`` from the constants of ``inputs.py``.
2. Statics: the junction's position and the tensions against MoorPy's ``System`` (cablefem's
   network statics, ``cablefem.statics.network``, and MoorDyn's initial condition).
3. Dynamics: each code refined (MoorDyn's segments and dtM; cablefem's elements and dt) until it
   is converged; the fairlead tension, both anchor tensions and the junction's position of the
   finest runs compared; time per simulated second of each code.

The parts: ``inputs.py`` (1), ``statics.py`` (2), ``dynamics.py`` (3), ``report.py`` (the tables).
"""

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python validation/junction/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.io import load_scene  # noqa: E402
from cablefem.study import jsonable  # noqa: E402

from validation.junction.dynamics import QUANTITIES, run_case  # noqa: E402,F401
from validation.junction.inputs import CASES, write_inputs  # noqa: E402
from validation.junction.report import report  # noqa: E402
from validation.junction.statics import static_check  # noqa: E402
from validation.moordyn.runners import COUPLING_DT  # noqa: E402

HERE = Path(__file__).resolve().parent


def run(fast=False, log=print, cases=None):
    """The static check, both codes' ladders per case and their comparison; the results dict."""
    cases = list(cases or (("dynamic",) if fast else CASES))
    with tempfile.TemporaryDirectory(prefix="crowfoot-") as folder:
        _, tomls = write_inputs(folder)
        results = {"fast": fast, "coupling_dt_s": COUPLING_DT, "statics": static_check(load_scene(tomls["slow"]), log),
                   "cases": {}}
    initial_states = {}  # MoorDyn's initial conditions per segments, shared by the cases
    for case in cases:
        results["cases"][case] = run_case(case, fast, log, initial_states)
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse settings only (what the test asserts)")
    parser.add_argument("--out", default=str(HERE), help="folder for inputs/ and results.json")
    parser.add_argument("--series", help="also keep the finest runs' time series in this .npz")
    parser.add_argument("--report", metavar="JSON", help="print the tables of a results.json without running")
    args = parser.parse_args(argv)
    if args.report:
        print(report(json.loads(Path(args.report).read_text())))
        return
    out = Path(args.out)
    write_inputs(out / "inputs")
    start = time.perf_counter()
    results = run(fast=args.fast, log=lambda line: print(line, file=sys.stderr, flush=True))
    results["wall_time_s"] = time.perf_counter() - start
    print(report(results))
    series = {case: entry.pop("series") for case, entry in results["cases"].items()}
    (out / "results.json").write_text(json.dumps(jsonable(results), indent=1) + "\n")
    if args.series:
        np.savez_compressed(args.series, **{f"{case}_{code}_{k}": v for case, runs in series.items()
                                             for code, s in runs.items() for k, v in s.items()})


if __name__ == "__main__":
    main()
