"""Catenary moorings of barreiro2015: single lines and a three-line spread mooring, FEM statics
against closed forms.

barreiro2015 (Sec. 2.2.1 "Static approach", after Faltinsen 1993) gives, for an inextensible
line of submerged weight w [N/m] lying on a flat seabed and rising h [m] to the fairlead,
the horizontal span X = l - h (1 + 2a/h)^(1/2) + a acosh(1 + h/a), a = T_H / w, and the
fairlead tension T = T_H + w h; for a spread mooring F = sum_i T_Hi (cos Psi_i, sin Psi_i).
Its two single lines have w = 850 and 1000 N/m, h = 20 m, l = 100 m.
Run ``python -m validation.spread_mooring.run [--fast] [--out DIR]``; ``run(fast=True)``
returns the numbers the tests assert on, in a few seconds.

(1) Single lines, fairlead tension and horizontal tension against the span X, from
    (a) Barreiro's formula solved for a at each X, (b) ``elastic_catenary`` with EA = inf
    (and with the FEM's EA), (c) cablefem FEM statics (``solve_static`` on a uniform mesh,
    reactions from ``results.end_forces``), from a line mostly on the seabed to a nearly
    taut one; and (c*) ``solve_line`` with its touchdown-fitted mesh, as ``cablefem static``
    solves a scene with ``[solver] fit_touchdown = true``, where it converges.
(2) Three identical lines at 120 deg around a floater: the horizontal restoring force,
    the sum of the three FEM fairlead forces against the sum of the closed-form ones, for
    floater offsets in the directions 0, 30, 60 and 90 deg, with the symmetry checks of the
    layout (120 deg rotations, mirrors about the 0 and 60 deg axes).

The parts: ``lines.py`` (the lines, (a) and (c)), ``single.py`` (1), ``spread.py`` (2),
``report.py`` (the tables), ``plots.py`` (the figures).
"""

import argparse
import sys
import time
from pathlib import Path

if __package__ in (None, ""):  # python validation/spread_mooring/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.study import write_json  # noqa: E402

from validation.spread_mooring.lines import (DIAMETER, DRAFT, EA, EA_START, ELEMENTS, ENVIRONMENT,  # noqa: E402,F401
                                             HEIGHT, LENGTH, ORDER, SEABED_STIFFNESS, TOLERANCE, WEIGHTS,
                                             barreiro_limit, barreiro_line, barreiro_span, line_type)
from validation.spread_mooring.plots import figures  # noqa: E402
from validation.spread_mooring.report import report  # noqa: E402
from validation.spread_mooring.single import barreiro_check, single_lines  # noqa: E402
from validation.spread_mooring.spread import (ANCHOR_RADIUS, SPREAD_WEIGHT, _mirror, _rotation,  # noqa: E402,F401
                                              _unit, spread_forces, spread_layout, spread_mooring)

HERE = Path(__file__).resolve().parent


def run(fast=False):
    """Both studies; a dict of plain numbers (JSON-ready)."""
    start = time.perf_counter()
    results = {"fast": fast,
               "settings": {"EA_N": EA, "seabed_stiffness_N_per_m3": SEABED_STIFFNESS, "diameter_m": DIAMETER,
                            "order": ORDER, "elements": ELEMENTS, "element_length_m": LENGTH / ELEMENTS,
                            "tolerance": TOLERANCE, "EA_start_N": EA_START, "draft_m": DRAFT,
                            "water_density": ENVIRONMENT.water_density, "gravity": ENVIRONMENT.gravity},
               "single_lines": single_lines(fast), "spread": spread_mooring(fast)}
    results["wall_time_s"] = time.perf_counter() - start
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="a few spans and offsets, a few seconds")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and PNGs")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print(report(results))
    args.out.mkdir(parents=True, exist_ok=True)
    write_json(args.out / "results.json", results, private=True, finite=True)
    figures(results, args.out)
    print(f"wrote {args.out / 'results.json'}, single_lines.png, spread_offset.png, spread_polar.png")


if __name__ == "__main__":
    main()
