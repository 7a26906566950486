"""Why cablefem's error in the frictionless slow surge scatters with the element count (issue 16).

At MoorDyn's 160-segment level (0.08 % RMS) the common study's P1 rows are not monotonic in the
element count, and finer quadrature of the contact does not smooth them (README, "The error at
MoorDyn's 160-segment level scatters"). This runs P1 rows (generalised-alpha rho_inf 0.7, modified
Newton, tolerance 1e-3, dt 0.014 s: the study's rows there) on the aligned slow-surge scene against
cablefem's own P1 x 320 at dt 0.0025 s, first with Table 5's internal damping beta = 0.001 s and then
with beta times ``--beta-factor`` in rows and reference alike. The whole line's first axial mode
(1.53 Hz, ``time_error.py``) has the damping ratio omega beta / 2: 0.5 % with Table 5's beta, 5 %
with ten times it. If the scatter is that ring's, it shrinks with the larger beta.

    python -m verification.work_precision.ring_damping [--beta-factor 10] [--elements 56 60 ...]
        [--out DIR]

prints a line per beta factor and writes ``ring_damping.json`` (~7 min on the 2-core machine;
``--beta-factor 1`` would run the first pass twice under one key).
"""

import argparse
import sys
from dataclasses import replace
from pathlib import Path

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.study import write_json  # noqa: E402
from validation.moordyn_aligned.run import WINDOW, aligned_scene, compare  # noqa: E402
from verification.work_precision.runs import run_cablefem_scene  # noqa: E402

HERE = Path(__file__).resolve().parent
ELEMENTS = (56, 60, 64, 68, 72, 80, 90)
ROW_DT, REFERENCE = 0.014, (320, 0.0025)


def scene(elements, dt, beta_factor, row):
    """The aligned slow-surge scene (MoorDyn-C's damping law and seabed damper), P1 x ``elements``,
    beta times ``beta_factor``; a ``row`` in the study's solver settings, else the reference's
    (BDF2, tolerance 1e-8)."""
    s = aligned_scene("slow", 1, elements, dt, tolerance=1e-3 if row else 1e-8, damping_when_opening=True)
    s = replace(s, lines=[s.lines[0].with_types(lambda t: replace(t, damping=t.damping * beta_factor))])
    if row:
        s.solver = replace(s.solver, integrator="generalized-alpha", rho_inf=0.7, newton="modified")
    return s


def run(beta_factors=(1.0, 10.0), elements=ELEMENTS, log=print):
    """RMS error [-] of each row against the reference, per beta factor."""
    results = {"row_dt": ROW_DT, "reference": {"order": 1, "elements": REFERENCE[0], "dt": REFERENCE[1]},
               "t_from_s": WINDOW["slow"], "elements": list(elements), "rms": {}}
    for factor in beta_factors:
        reference = run_cablefem_scene(scene(REFERENCE[0], REFERENCE[1], factor, row=False))
        errors = [compare(run_cablefem_scene(scene(n, ROW_DT, factor, row=True)), reference, WINDOW["slow"])["rms"]
                  for n in elements]
        results["rms"][f"{factor:g}"] = errors
        log(f"beta x {factor:<4g} " + "  ".join(f"P1 x {n}: {100 * e:.3f} %" for n, e in zip(elements, errors)))
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--beta-factor", type=float, default=10.0, help="beta's factor of the second pass")
    parser.add_argument("--elements", type=int, nargs="+", default=list(ELEMENTS), help="P1 rows' element counts")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for ring_damping.json")
    args = parser.parse_args(argv)
    results = run((1.0, args.beta_factor), args.elements)
    write_json(args.out / "ring_damping.json", results)
    print(f"wrote {args.out / 'ring_damping.json'}")


if __name__ == "__main__":
    main()
