"""Numerical stability on hard cases: stiff lines, snap loads, a convex seabed edge, lying and
taut lines, a sudden stop and time steps from 1e-4 to 0.1 s (issue 6 item 3).

Each case drives cablefem's own time-domain path (``cablefem.runs.run``: ``start_states``,
``build_system``, ``boundary_path`` and the integrators of ``cablefem.dynamics.integrator``; the
time-step sweep goes through ``run_scene`` and reads back the files it writes) and
reports an error against a closed form or a converged run, or an energy balance:

    W_fairlead = dKE + dPE + D_internal + D_seabed + D_drag + W_added_mass + E_numerical,

with W_fairlead the work of the support force on the line (the fairlead's residual row
times its velocity, integrated by the trapezoidal rule over the steps), KE = V.M V / 2,
PE = ``LineSystem.energy`` (strain, weight and seabed spring), each D the integral of a
dissipative load's power (internal damping: the damped minus the elastic flux times
dv/ds; seabed: contact damping and friction, the contact force minus its spring part,
times v; drag without current), W_added_mass the work of the added-mass force, and
E_numerical what is left: the integrator's own dissipation (> 0) or energy creation
(< 0), plus the quadrature error of the trapezoidal rule. Each dissipative power must be
>= 0 at every step and E_numerical must be small against the energy passed through the
fairlead and shrink with dt: checks that fail when a load or an integrator creates energy.

Run ``python -m verification.stability.run [--fast] [--out DIR] [--case NAME ...]``;
``run(fast=True)`` returns what tests/test_stability.py asserts. Every run stops with a
status: "completed", "stopped: <the ConvergenceError's message>" or "non-finite state"
(a NaN cablefem let through, which never happened in the runs recorded in README.md).

The parts: ``driver.py`` (the stepping and its energy ledger), ``closed_forms.py`` (cases 1, 4),
``flume_cases.py`` (2, 3, 5, 6), ``reproductions.py`` (7), ``report.py`` and ``plots.py``.
"""

import argparse
import sys
import time
from pathlib import Path

if __package__ in (None, ""):  # python verification/stability/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.study import jsonable, write_json  # noqa: E402

from verification.stability.closed_forms import STIFF_PERIOD, run_lying_taut, run_stiff, stiff_case  # noqa: E402,F401
from verification.stability.driver import simulate  # noqa: E402,F401
from verification.stability.flume_cases import run_edge, run_snap, run_steps, run_stop  # noqa: E402
from verification.stability.plots import figures  # noqa: E402
from verification.stability.report import report_text  # noqa: E402
from verification.stability.reproductions import run_reproductions, toy_scene  # noqa: E402,F401

HERE = Path(__file__).resolve().parent

CASES = ("stiff", "snap", "edge", "lying", "taut", "stop", "steps", "repro")

RUNNERS = {"stiff": run_stiff, "snap": run_snap, "edge": run_edge, "lying": run_lying_taut,
           "taut": None, "stop": run_stop, "steps": run_steps, "repro": run_reproductions}  # "taut" runs with "lying"


def run(fast=False, cases=CASES):
    """The cases named in ``cases`` (all by default); a dict of plain numbers (JSON-ready)."""
    start = time.perf_counter()
    results = {"fast": fast}
    for name in cases:
        runner = RUNNERS[name] if name != "taut" else (None if "lying" in cases else run_lying_taut)
        if runner is None:
            continue
        key = "lying_taut" if runner is run_lying_taut else name
        case_start = time.perf_counter()
        results[key] = runner(fast)
        results[key]["wall_time_s"] = time.perf_counter() - case_start
    results["wall_time_s"] = time.perf_counter() - start
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="short runs and fewer dt: what the tests assert")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and tensions.png")
    parser.add_argument("--case", nargs="+", choices=CASES, default=list(CASES), help="cases to run")
    args = parser.parse_args(argv)
    results = jsonable(run(fast=args.fast, cases=tuple(args.case)), private=True, drop=("integ",))
    write_json(args.out / "results.json", results)
    print(report_text(results))
    figures(results, args.out)
    print(f"wrote {args.out / 'results.json'} and tensions.png")


if __name__ == "__main__":
    main()
