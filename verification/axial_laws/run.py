"""Axial laws of line types (issue 36, item 3): closed forms and MoorDyn-C on its own inputs.

Run ``python -m verification.axial_laws.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the
numbers tests/test_verification_axial_laws.py asserts on. The parts:

(a) a strain-tension table: a rope's free end under a steady force lies at L (1 + e), e the table's
    inverse (``cases.table_free_end``);
(b) static and dynamic stiffness: a rope stretched harmonically against the exact solution of its
    linear equation, backward Euler's observed order (``cases.viscoelastic_harmonic``);
(c) SYROPE: a load cycle past Tmax0, the tension on the original and on the new working curve
    (``cases.syrope_cycle``);
(d) MoorDyn-C on its tests/Mooring/syrope cases and polyester/visco.txt: the initial tension and a
    run's tension with the fairlead moved harmonically (``moordyn_side.compare``).
"""

import argparse
import sys
import time
from pathlib import Path

if __package__ in (None, ""):  # python verification/axial_laws/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.study import provenance, stamp, write_json  # noqa: E402

from verification.axial_laws.cases import syrope_cycle, table_free_end, viscoelastic_harmonic  # noqa: E402
from verification.axial_laws.moordyn_side import SYROPE_CASES, compare  # noqa: E402

HERE = Path(__file__).resolve().parent


def run(fast=False):
    """All of it; a dict of plain numbers (JSON-ready)."""
    started, start = provenance(), time.perf_counter()
    results = {"table_free_end": table_free_end(),
               "viscoelastic_harmonic": viscoelastic_harmonic(steps=(20, 40) if fast else (20, 40, 80, 160)),
               "syrope_cycle": [syrope_cycle(period=period, dt=period / (500 if fast else 4000))
                                for period in (4000.0, 40000.0)]}
    cases = [("linear_wc", False), ("quadratic_wc", False)] + [(case, True) for case in SYROPE_CASES]
    results["moordyn"] = [compare(case, header, duration=20.0 if fast else 40.0) for case, header in cases]
    results["moordyn"].append(compare("visco", duration=90.0, skip=45.0))
    results["wall_time_s"] = time.perf_counter() - start
    results["provenance"] = stamp(started)
    return results


def report(results):
    """The tables, as text."""
    lines = ["(a) table: free end under a force, end position against L (1 + inverse(F))",
             f"{'F [N]':>12} {'x end [m]':>14} {'exact [m]':>14} {'error [m]':>10}"]
    lines += [f"{r['force']:12.4g} {r['end_x']:14.9f} {r['exact']:14.9f} {r['error']:10.2g}"
              for r in results["table_free_end"]]
    visco = results["viscoelastic_harmonic"]
    lines += ["", "(b) EA_s|EA_d, harmonic stretching: RMS error / tension amplitude",
              f"{'steps/period':>12} {'dt [s]':>8} {'error':>10} {'amplitude [N]':>14} {'static EA amp [N]':>18}"]
    lines += [f"{r['steps_per_period']:12d} {r['dt']:8.4g} {r['rms_error_of_amplitude']:10.3e} "
              f"{r['dynamic_amplitude']:14.6g} {r['static_amplitude']:18.6g}" for r in visco["rows"]]
    lines += [f"observed order {visco['observed_order']:.2f} (backward Euler: 1)"]
    lines += ["", "(c) SYROPE load cycle past Tmax0 = 1e6 N: tension error / new Tmax (the slow strain's lag: 1 / period)",
              f"{'period [s]':>10} {'new Tmax [N]':>13} {'largest T [N]':>14} {'original curve':>15} {'working curve':>14}"]
    lines += [f"{c['period']:10.6g} {c['new_peak']:13.6g} {c['peak_reached']:14.6g} {c['original_curve_error']:15.2e} "
              f"{c['working_curve_error']:14.2e}" for c in results["syrope_cycle"]]
    lines += ["", "(d) MoorDyn-C on its own inputs: initial tension and a run (RMS difference)",
              f"{'case':>14} {'owc 3 lines':>11} {'MoorDyn T0 [N]':>15} {'cablefem T0 [N]':>16} {'diff':>9} "
              f"{'from [s]':>8} {'RMS/swing':>10} {'RMS/mean':>9}"]
    lines += [f"{r['case']:>14} {str(r['owc_header']):>11} {r['moordyn_initial']:15.8g} {r['cablefem_static']:16.8g} "
              f"{r['initial_difference']:9.2e} {r['from_s']:8.3g} {r['run_rms_over_swing']:10.2e} "
              f"{r['run_rms_over_mean']:9.2e}" for r in results["moordyn"]]
    lines += ["", f"wall time {results['wall_time_s']:.1f} s"]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="fewer steps (the tests' variant)")
    parser.add_argument("--out", default=str(HERE), help="folder for results.json")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print(report(results))
    write_json(Path(args.out) / "results.json", results)


if __name__ == "__main__":
    main()
