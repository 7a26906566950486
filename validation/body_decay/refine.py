"""Whether each side of the body decay study is converged: MoorDyn-C's period and decrement as its
segments per line (NumSegs) and its step (dtM) refine, cablefem's as its mesh and its step do.

    python -m validation.body_decay.refine                      # the study's heave (0.25 m)
    python -m validation.body_decay.refine --case heave --offset 1.0   # the taut-slack heave (README)
    python -m validation.body_decay.refine --case pitch --side moordyn

Each row releases the body as ``validation.body_decay.run`` does and measures three periods.
"""

import argparse

import numpy as np

from validation.body_decay.cases import cablefem_decay, equilibrium, moordyn_decay, period_and_decrement

#: (pose component, period [s] to size the run) of each case
CASES = {"heave": (2, 6.6), "pitch": (4, 4.0)}
#: MoorDyn-C's (NumSegs, dtM [s]): its file's, its step halved, its segments doubled twice
MOORDYN = ((20, 1e-4), (20, 5e-5), (40, 1e-4), (80, 5e-5))
#: cablefem's (integrator, element order, elements per line, step [s])
CABLEFEM = (("generalized-alpha", 2, 10, 0.05), ("generalized-alpha", 2, 20, 0.05),
            ("generalized-alpha", 2, 10, 0.025), ("generalized-alpha", 2, 10, 0.0125),
            ("bdf2", 2, 10, 0.05), ("bdf2", 2, 10, 0.025), ("bdf2", 2, 10, 0.0125))
CYCLES = 3


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", choices=sorted(CASES), default="heave")
    parser.add_argument("--offset", type=float, default=None,
                        help="the release: heave [m] (default 0.25) or pitch [deg] (default 3)")
    parser.add_argument("--side", choices=("both", "moordyn", "cablefem"), default="both")
    args = parser.parse_args(argv)
    component, period = CASES[args.case]
    offset = args.offset if args.offset is not None else (0.25 if args.case == "heave" else 3.0)
    rest = equilibrium()
    pose = rest.copy()
    pose[component] += offset if args.case == "heave" else np.radians(offset)
    duration = (CYCLES + 0.8) * period
    rows = []
    if args.side in ("both", "moordyn"):
        for numsegs, dtM in MOORDYN:
            times, poses = moordyn_decay(pose, duration, 0.005, numsegs, dtM)
            rows.append((f"MoorDyn-C NumSegs {numsegs} dtM {dtM:g}",)
                        + period_and_decrement(times, poses[:, component], rest[component], CYCLES))
            print(f"{rows[-1][0]:45} {rows[-1][1]:9.4f} {rows[-1][2]:9.4f}", flush=True)
    if args.side in ("both", "cablefem"):
        for integrator, order, elements, dt in CABLEFEM:
            times, poses, _ = cablefem_decay(pose, duration, dt, integrator, order=order, elements=elements)
            rows.append((f"cablefem {integrator} P{order} x {elements} dt {dt:g}",)
                        + period_and_decrement(times, poses[:, component], rest[component], CYCLES))
            print(f"{rows[-1][0]:45} {rows[-1][1]:9.4f} {rows[-1][2]:9.4f}", flush=True)
    return rows


if __name__ == "__main__":
    main()
