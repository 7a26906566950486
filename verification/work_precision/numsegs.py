"""What a MoorDyn file's NumSegs asks for, in cablefem's elements: the rule of cablefem's default
mesh for a MoorDyn line (``cablefem.model.defaults.moordyn_elements``), derived here.

MoorDyn's line at N segments is a chain of N straight segments with the weight lumped at its N + 1
nodes. In statics that is cablefem's P1 line on the same N elements: a P1 element's consistent load
of a uniform weight is the lumped one (w h / 2 at each end) and its tension EA e is constant in the
element, as MoorDyn's segment's. So the fairlead tension error of P1 x N against a converged line
(P2 x 320) is MoorDyn's lumped-mass statics error at NumSegs N, and the smallest P2 count n that is
at least as accurate is what N asks for. For each MoorDyn line of the systems of
``benchmarks/systems.py`` (OC4's chains, the flume chain) at N = 5 ... 80 this prints both errors,
the smallest n from which on every P2 count is at least as accurate (the error scatters with the
count as the touchdown moves through the elements), and n / N.

    python -m verification.work_precision.numsegs [--json FILE]
"""

import argparse
import json
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

ROOT = Path(__file__).resolve().parents[2]
FILES = {"oc4-semi": ROOT / "examples" / "oc4_semi.dat", "flume": ROOT / "benchmarks" / "flume_snap_20.dat"}
COUNTS = (5, 10, 20, 40, 80)
LADDER = (3, 4, 5, 7, 10, 14, 20, 28, 40, 57, 80)  # a sqrt(2) ladder
REFERENCE = (2, 320)


def fairlead_tension(scene, line, order, elements):
    """Static fairlead tension [N] of ``line`` of ``scene`` on ``elements`` elements of ``order``."""
    from cablefem.statics.scene import static_network

    one = replace(scene, lines=[line.with_order(order).with_elements(elements)], points={}, bodies={})
    reports, _, _, _ = static_network(one)
    return float(reports[0].fairlead_tension)


def fit(counts, errors):
    """(C, p) of errors ~ C counts^-p, least squares in logs."""
    slope, intercept = np.polyfit(np.log(counts), np.log(errors), 1)
    return float(np.exp(intercept)), float(-slope)


def study(name, path):
    """One file's first line: the fairlead tension errors of P1 x N (MoorDyn's lumped mass at N
    segments) and P2 x n against P2 x 320, their power-law fits, and the P2 count the fits give for
    each N: dict."""
    from cablefem.io import load_scene

    scene = load_scene(str(path))
    line = scene.lines[0]
    exact = fairlead_tension(scene, line, *REFERENCE)
    errors = {order: [abs(fairlead_tension(scene, line, order, n) / exact - 1) for n in LADDER] for order in (1, 2)}
    (c1, p1), (c2, p2) = fit(LADDER, errors[1]), fit(LADDER, errors[2])
    asked = {n: (c2 / (c1 * n ** -p1)) ** (1 / p2) for n in COUNTS}
    return {"system": name, "line": line.name, "ladder": list(LADDER), "p1_errors": errors[1], "p2_errors": errors[2],
            "p1_fit": [c1, p1], "p2_fit": [c2, p2], "p2_elements": asked}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", help="write the results to this JSON file")
    args = parser.parse_args(argv)
    results = [study(name, path) for name, path in FILES.items()]
    for result in results:
        print(f"{result['system']} {result['line']}: fairlead tension error against P2 x {REFERENCE[1]}")
        print(f"{'elements':>9s} " + " ".join(f"{n:8d}" for n in result["ladder"]))
        for order in (1, 2):
            print(f"{f'P{order}':>9s} " + " ".join(f"{e:8.1e}" for e in result[f"p{order}_errors"]))
        (c1, p1), (c2, p2) = result["p1_fit"], result["p2_fit"]
        print(f"fits: P1 {c1:.3g} N^-{p1:.2f}, P2 {c2:.3g} n^-{p2:.2f}; P2 elements as accurate as P1 x N (MoorDyn "
              "at NumSegs N): " + ", ".join(f"N {N}: {n:.1f} ({n / N:.2f} N)" for N, n in result["p2_elements"].items()))
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1) + "\n")


if __name__ == "__main__":
    main()
