"""Marine cables against MoorDyn-C (issue 34): a lazy-wave dynamic power cable and MoorDyn's own beam.

Parts: the lazy wave (``case``: buoyancy section, touchdown, a hang-off clamped vertical on a moving
floater) in statics and under a surge-and-heave of the hang-off, in both codes at a range of meshes
(``comparison``: MoorDyn-C via ``moordyn_side``, cablefem via ``cablefem_side``), against MoorDyn-C's
finest run: the hang-off tension and the curvature peak, their convergence and their costs; and
MoorDyn's ``BeamSimplySupported.txt`` in both codes against Euler-Bernoulli and the stretched beam
(``beam``). Run ``python -m validation.cables.run [--fast] [--out DIR]``; ``run(fast=True)`` returns
what tests/test_validation_cables.py asserts.
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


def run(fast=False, out=None):
    """Both parts; the results dict (written to ``out``/results.json unless ``out`` is False or fast)."""
    started, start = provenance(), time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="cables-") as folder:
        lazy = comparison.runs(FAST_MOORDYN_LENGTHS if fast else MOORDYN_LENGTHS,
                               FAST_CABLEFEM_LENGTHS if fast else CABLEFEM_LENGTHS,
                               FAST_DURATION if fast else DURATION, folder)
    reference = lazy["moordyn"][-1]
    for entries in lazy.values():
        comparison.against(reference, entries)
    lazy["reference"] = {"code": "moordyn", "segments": reference["segments"]}
    lazy["within_tolerance"] = {code: {q: _mesh(comparison.time_to_tolerance(lazy[code], q))
                                       for q in comparison.QUANTITIES} for code in ("moordyn", "cablefem")}
    results = {"lazy_wave": lazy, "beam": beam.compare(), "duration": FAST_DURATION if fast else DURATION,
               "moordyn_version": package_version("moordyn"), "wall_time_s": time.perf_counter() - start,
               "provenance": stamp(started)}
    if out is not False and not fast:
        folder = Path(out) if out else HERE
        write_json(folder / "results.json", results)
        from validation.cables.plots import figures

        figures(results, folder)
    return results


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
    args = parser.parse_args()
    results = run(fast=args.fast, out=args.out)
    print_tables(results)
    print(f"\n{results['wall_time_s']:.0f} s")


if __name__ == "__main__":
    main()
