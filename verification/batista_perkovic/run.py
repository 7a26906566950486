"""Batista & Perkovic: a chain on a 15 deg seabed, FEM against the closed form (desire2023 Sec. 3).

desire2023 Sec. 3, Tables 2-4 and Fig. 8 compare their FEM (32 nodes) with
the inextensible catenary on an inclined seabed of Batista & Perkovic (2019)
for five fairlead pulls H. Run ``python -m verification.batista_perkovic.run
[--fast] [--out DIR] [--force H] [--stiffness G_K]``; ``run(fast=True)``
returns the numbers tests/test_verification_statics.py asserts on.

Geometry (the finding of ``cablefem.statics.catenary``'s docstring): H is the
horizontal tension at the fairlead, the fairlead sits a fixed h = 83.766 m
above the anchor, the seabed falls 15 deg from the anchor towards the
fairlead (slope = -15 deg), the line weighs (835.4 - 1025 pi d^2/4) 9.8 N/m
in water, and Table 4's H column is read in reverse order. For each H the
inextensible closed form gives the fairlead's span X; the FEM line (EA =
5.055e11 N as the text says, G_K = 3e14 N/m^3, frictionless) is solved with
its fairlead there, and compared with

- the inextensible closed form (what the paper compares with), and
- the elastic closed form through the same two points (EA = 5.055e11 N, what
  the FEM solves): the difference isolates the discretisation error.

(a) Table 3: |Delta| [m] at the paper's percentile nodes 2, 6, ..., 29 of 32;
(b) Table 4: T_N, T_A, |T_N - T_A| and dT for both references;
(c) convergence of fairlead tension and node positions with the element count
    for P1, P2, P3 on a uniform mesh, on the mesh cablefem fits to the
    touchdown (``solve_line``) and on a mesh with a vertex at the exact
    touchdown, with observed orders and the wall time of each solve;
(d) the accuracy targets of issue 2.

The parts: ``case.py`` (the data, the closed forms, one FEM solve and its errors),
``analysis.py`` (a-d), ``report.py`` (the tables), ``plots.py`` (the figures).
"""

import argparse
import math
import sys
import time
from pathlib import Path

if __package__ in (None, ""):  # python verification/batista_perkovic/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.study import write_json  # noqa: E402

from verification.batista_perkovic.analysis import convergence, evidence, p1_diagnosis, table_rows, targets  # noqa: E402
from verification.batista_perkovic.case import (EA, GRAVITY, HEIGHT, PAPER_STIFFNESS, SLOPE,  # noqa: E402
                                                STUDY_STIFFNESS, weight)
from verification.batista_perkovic.plots import figures  # noqa: E402
from verification.batista_perkovic.report import report_text  # noqa: E402

HERE = Path(__file__).resolve().parent


def run(fast=False, force=3.5e6, stiffness=STUDY_STIFFNESS):
    """All of it; a dict of plain numbers (JSON-ready)."""
    start = time.perf_counter()
    setups = [{"name": "P1 x 31 uniform (the paper's 32 nodes)", "order": 1, "elements": 31, "mesh": "uniform"},
              {"name": "P2 x 16 fitted (33 nodes)", "order": 2, "elements": 16, "mesh": "fitted"}]
    if fast:
        setups = setups[:1]
    for setup in setups:
        setup["stiffness"] = PAPER_STIFFNESS
        setup["rows"] = table_rows(setup)
    study = convergence(force, stiffness, fast)
    results = {"fast": fast, "slope_deg": math.degrees(SLOPE), "height_m": HEIGHT, "gravity": GRAVITY,
               "EA": EA, "weight_N_per_m": weight(), "paper_stiffness": PAPER_STIFFNESS,
               "evidence": evidence(), "setups": setups, "convergence": study}
    results["p1_diagnosis"] = p1_diagnosis(setups[0]["rows"])
    results["targets"] = targets(setups, study)
    results["wall_time_s"] = time.perf_counter() - start
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="one setup, three element counts: a few seconds")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and PNGs")
    parser.add_argument("--force", type=float, default=3.5e6, help="H [N] of the convergence study")
    parser.add_argument("--stiffness", type=float, default=STUDY_STIFFNESS,
                        help="G_K [N/m^3] of the convergence study (the tables use the paper's 3e14)")
    args = parser.parse_args(argv)
    results = run(fast=args.fast, force=args.force, stiffness=args.stiffness)
    print(report_text(results))
    args.out.mkdir(parents=True, exist_ok=True)
    write_json(args.out / "results.json", results, private=True)
    figures(results, args.out)
    print(f"wrote {args.out / 'results.json'}, fig8.png and convergence.png")


if __name__ == "__main__":
    main()
