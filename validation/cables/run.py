"""Marine cables against MoorDyn-C (issue 34): a lazy-wave dynamic power cable and MoorDyn's own beam.

Parts: the lazy wave (``case``: buoyancy section, touchdown, a hang-off clamped vertical on a moving
floater) in statics and under a surge-and-heave of the hang-off, in both codes at a range of meshes
(``comparison``: MoorDyn-C via ``moordyn_side``, cablefem via ``cablefem_side``), against MoorDyn-C's
finest run: the hang-off tension and the curvature peak, their convergence and their costs; and
MoorDyn's ``BeamSimplySupported.txt`` and ``BeamCantilevered.txt`` in both codes against
Euler-Bernoulli (and the stretched beam) (``beam``). Run ``python -m validation.cables.run [--fast] [--out DIR] [--reuse-moordyn]``;
``run(fast=True)`` returns what tests/test_validation_cables.py asserts. ``--reuse-moordyn`` takes
MoorDyn-C's lazy-wave runs from the results.json already in the output folder (MoorDyn-C's side does
not depend on cablefem's: it relaxes to its own equilibrium from cablefem's static shape) and runs
cablefem's side again, ~1 min instead of ~21.
"""

import argparse
import tempfile
import time
from pathlib import Path

from cablefem.study import package_version, provenance, stamp, write_json
from validation.cables import beam, comparison
from validation.cables.report import print_tables

HERE = Path(__file__).resolve().parent

#: segment lengths [m] (about: whole segments per section, ``case.segments_for``)
MOORDYN_LENGTHS, FAST_MOORDYN_LENGTHS = (5.0, 2.5, 1.25, 0.625), (5.0,)
CABLEFEM_LENGTHS, FAST_CABLEFEM_LENGTHS = (20.0, 10.0, 5.0, 2.5, 1.25), (10.0, 5.0)
#: the run: the ramp and two periods of the motion
DURATION, FAST_DURATION = 34.0, 14.0


def run(fast=False, out=None, reuse_moordyn=False):
    """Both parts; the results dict (written to ``out``/results.json unless ``out`` is False or fast).
    ``reuse_moordyn``: MoorDyn-C's lazy-wave runs read from that results.json, not run again."""
    started, start = provenance(), time.perf_counter()
    folder_out = Path(out) if out else HERE
    previous = _previous_moordyn(folder_out / "results.json") if reuse_moordyn and not fast else None
    with tempfile.TemporaryDirectory(prefix="cables-") as folder:
        lazy = comparison.runs(() if previous else FAST_MOORDYN_LENGTHS if fast else MOORDYN_LENGTHS,
                               FAST_CABLEFEM_LENGTHS if fast else CABLEFEM_LENGTHS,
                               FAST_DURATION if fast else DURATION, folder)
    if previous:
        lazy["moordyn"], results_moordyn_version = previous
    reference = lazy["moordyn"][-1]
    for entries in lazy.values():
        comparison.against(reference, entries)
    lazy["reference"] = {"code": "moordyn", "segments": reference["segments"]}
    lazy["within_tolerance"] = {code: {q: _mesh(comparison.time_to_tolerance(lazy[code], q))
                                       for q in comparison.QUANTITIES} for code in ("moordyn", "cablefem")}
    results = {"lazy_wave": lazy, "beam": beam.compare(), "cantilever": beam.compare_cantilever(), "duration": FAST_DURATION if fast else DURATION,
               "moordyn_version": results_moordyn_version if previous else package_version("moordyn"), "wall_time_s": time.perf_counter() - start,
               "provenance": stamp(started)}
    if out is not False and not fast:
        write_json(folder_out / "results.json", results)
        from validation.cables.plots import figures

        figures(results, folder_out)
    return results


def _previous_moordyn(path):
    """MoorDyn-C's lazy-wave entries (their series as arrays) and its version, from ``path``."""
    import json

    import numpy as np

    if not path.exists():
        raise SystemExit(f"--reuse-moordyn: {path} does not exist; run without it first")
    previous = json.loads(path.read_text())
    entries = previous["lazy_wave"]["moordyn"]
    for entry in entries:
        entry["series"] = {key: np.asarray(value) for key, value in entry["series"].items()}
        entry.pop("differences", None)
    return entries, previous["moordyn_version"]


def _mesh(entry):
    """What identifies an entry of ``comparison.runs`` and its cost, None for none."""
    if entry is None:
        return None
    keys = ("segments", "elements", "length", "static_wall_time_s", "run_wall_time_s")
    return {key: entry[key] for key in keys if key in entry}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="one MoorDyn mesh, a short run (what the tests run)")
    parser.add_argument("--out", help="folder for results.json and the figures (default: this folder)")
    parser.add_argument("--reuse-moordyn", action="store_true",
                        help="take MoorDyn-C's lazy-wave runs from the results.json already there; run cablefem's again")
    args = parser.parse_args()
    results = run(fast=args.fast, out=args.out, reuse_moordyn=args.reuse_moordyn)
    print_tables(results)
    print(f"\n{results['wall_time_s']:.0f} s")


if __name__ == "__main__":
    main()
