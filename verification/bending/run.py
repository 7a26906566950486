"""Bending stiffness on Hermite elements against closed forms (issue 34).

Cases (``cases``, against ``closed_forms``): the cantilever under its own weight (small deflection,
w L^4 / 8 EI); the elastica under a dead tip load (Bisshopp & Drucker 1945) and under a pure end
moment (a circular arc), with observed orders in space for the tip position and the curvature; a
pinned beam's and a taut beam's natural frequencies; a cantilever's free vibration with both
integrators, compiled; the catenary limit EI -> 0 of a hanging cable. Run ``python -m
verification.bending.run [--fast] [--out DIR]``; ``run(fast=True)`` returns what
tests/test_verification_bending.py asserts.
"""

import argparse
import math
import time
from pathlib import Path

from cablefem.study import provenance, stamp, write_json
from verification.bending import cases
from verification.bending.report import print_tables

HERE = Path(__file__).resolve().parent

ALPHAS, FAST_ALPHAS = (1.0, 2.0, 5.0, 10.0), (1.0, 5.0)
ELEMENTS, FAST_ELEMENTS = (2, 4, 8, 10, 16, 32), (4, 8, 10, 16)
THETAS, FAST_THETAS = (math.pi / 2, math.pi, 1.5 * math.pi, 2.0 * math.pi), (math.pi / 2, math.pi)
ARC_ELEMENTS, FAST_ARC_ELEMENTS = (4, 8, 16, 32), (4, 8, 16)
BEAM_ELEMENTS, FAST_BEAM_ELEMENTS = (2, 4, 8, 16, 32), (4, 8, 16)
EIS = (1e4, 1e3, 1e2, 10.0, 1.0, 0.1, 0.0)
#: the issue's target: the elastica's tip within 1e-5 of the closed form at 10 elements, observed order >= 3.5
TARGET = {"elements": 10, "tip_error": 1e-5, "order": 3.5}


def run(fast=False, out=None):
    """Every case; the results dict (written to ``out``/results.json unless ``out`` is False)."""
    started, start = provenance(), time.perf_counter()
    results = {
        "cantilever": cases.cantilever((1, 2, 4, 8)),
        "elastica": cases.elastica(FAST_ALPHAS if fast else ALPHAS, FAST_ELEMENTS if fast else ELEMENTS),
        "end_moment": cases.end_moment(FAST_THETAS if fast else THETAS, FAST_ARC_ELEMENTS if fast else ARC_ELEMENTS),
        "frequencies": cases.frequencies(FAST_BEAM_ELEMENTS if fast else BEAM_ELEMENTS),
        "vibration": cases.vibration(8, periods=3 if fast else 5),
        "catenary_limit": cases.catenary_limit(EIS[::2] + (0.0,) if fast else EIS),
        "target": TARGET,
    }
    results["wall_time_s"] = time.perf_counter() - start
    results["provenance"] = stamp(started)
    if out is not False and not fast:
        folder = Path(out) if out else HERE
        write_json(folder / "results.json", results)
        from verification.bending.plots import convergence

        convergence(results, folder / "convergence.png")
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="fewer loads and meshes (what the tests run)")
    parser.add_argument("--out", help="folder for results.json and convergence.png (default: this folder)")
    args = parser.parse_args()
    results = run(fast=args.fast, out=args.out)
    print_tables(results)
    print(f"\n{results['wall_time_s']:.1f} s")


if __name__ == "__main__":
    main()
